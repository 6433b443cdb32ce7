//! Nishita (1993) on the GPU: one pass, the table-free single-scattering sky
//! (`shaders/shared/single_scattering_sky.wgsl`) with the nested march towards the sun of
//! `shaders/nishita/common.wgsl`. Its f64 twin is `atmoscope_model::methods::nishita`.

use super::{GpuMethod, SINGLE_SCATTERING_SKY_PASS, shader};
use atmoscope_model::methods::shared::single_scattering_sky;
use atmoscope_model::scene::Method;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Nishita,
    common: &[shader!("nishita/common.wgsl")],
    constants: single_scattering_sky::constants,
    passes: &[SINGLE_SCATTERING_SKY_PASS],
};
