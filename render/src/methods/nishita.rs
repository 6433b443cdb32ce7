//! Nishita (1993) on the GPU: one pass, the sky, marching each pixel with no table
//! (`shaders/nishita/`). Its f64 twin is `atmoscope_model::methods::nishita::sky`.

use super::{GpuMethod, PassSpec, shader};
use atmoscope_model::methods::nishita;
use atmoscope_model::scene::Method;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Nishita,
    common: &[shader!("nishita/common.wgsl")],
    constants: nishita::constants,
    passes: &[PassSpec::sky(shader!("nishita/sky.wgsl"), &[])],
};
