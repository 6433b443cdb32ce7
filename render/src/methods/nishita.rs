//! Nishita (1993) on the GPU: its way to the sun tabulated, the moving sky built from it and
//! the sky pass of the table-free single-scattering sky
//! (`shaders/shared/single_scattering_sky.wgsl`) with the midpoint rule towards the sun. Its f64 twin is `atmoscope_model::methods::nishita`.

use super::{
    GpuMethod, NESTED_MARCH_MS_PASSES, NESTED_MARCH_PASSES, SINGLE_SCATTERING_COMMON,
    SINGLE_SCATTERING_MS_COMMON,
};
use atmoscope_model::methods::shared::single_scattering_sky::{self, Rule, Way};
use atmoscope_model::scene::Method;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Nishita,
    lowest_table_mu_s: None,
    common: &SINGLE_SCATTERING_COMMON,
    constants: |p| single_scattering_sky::constants(p, Way::March(Rule::Midpoint)),
    passes: &NESTED_MARCH_PASSES,
};

/// With Hillaire's Ψ_ms table as the higher orders (the `nishita-ms` row).
pub const METHOD_MS: GpuMethod = GpuMethod {
    method: Method::NishitaMs,
    lowest_table_mu_s: None,
    common: &SINGLE_SCATTERING_MS_COMMON,
    constants: |p| single_scattering_sky::constants(p, Way::March(Rule::Midpoint)),
    passes: &NESTED_MARCH_MS_PASSES,
};
