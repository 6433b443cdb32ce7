//! Nishita (1993) on the GPU: one pass, the table-free single-scattering sky
//! (`shaders/shared/single_scattering_sky.wgsl`) with the midpoint rule towards the sun. Its
//! f64 twin is `atmoscope_model::methods::nishita`.

use super::{GpuMethod, SINGLE_SCATTERING_SKY_PASS};
use atmoscope_model::methods::shared::single_scattering_sky::{self, Rule};
use atmoscope_model::scene::Method;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Nishita,
    common: &[],
    constants: |p| single_scattering_sky::constants(p, Rule::Midpoint),
    passes: &[SINGLE_SCATTERING_SKY_PASS],
};
