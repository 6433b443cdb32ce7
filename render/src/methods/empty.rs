//! The baseline without an atmosphere on the GPU: one pass, the sky (`shaders/empty/`). Its
//! f64 twin is `atmoscope_model::methods::empty::sky`.

use super::{ENGINE_TILE, GpuMethod, PassSpec, shader};
use atmoscope_model::scene::Method;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Empty,
    moving_tile: ENGINE_TILE,
    common: &[],
    constants: |_| [0.0; 12],
    passes: &[PassSpec::sky(shader!("empty/sky.wgsl"), &[])],
};
