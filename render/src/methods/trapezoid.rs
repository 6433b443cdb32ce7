//! Single scattering with the trapezoid rule towards the sun on the GPU: one pass, the
//! table-free single-scattering sky (`shaders/shared/single_scattering_sky.wgsl`). Its f64
//! twin is `atmoscope_model::methods::trapezoid`.

use super::{GpuMethod, SINGLE_SCATTERING_SKY_PASS};
use atmoscope_model::methods::shared::single_scattering_sky::{self, Rule};
use atmoscope_model::scene::Method;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Trapezoid,
    common: &[],
    constants: |p| single_scattering_sky::constants(p, Rule::Trapezoid),
    passes: &[SINGLE_SCATTERING_SKY_PASS],
};
