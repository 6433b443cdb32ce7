//! The baseline without an atmosphere on the GPU: one pass, the sky (`shaders/empty/`). Its
//! f64 twin is `atmoscope_model::methods::empty::sky`.

use super::{GpuMethod, PassSpec, shader};
use atmoscope_model::scene::Method;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Empty,
    lowest_table_mu_s: None,
    common: &[],
    constants: |_| [0.0; 12],
    passes: &[PassSpec::sky(shader!("empty/sky.wgsl"), &[])],
};
