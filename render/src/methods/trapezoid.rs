//! Single scattering with the trapezoid rule towards the sun on the GPU: its way to the sun
//! tabulated, the moving sky built from it and the sky pass of the table-free
//! single-scattering sky
//! (`shaders/shared/single_scattering_sky.wgsl`). Its f64 twin is
//! `atmoscope_model::methods::trapezoid`.

use super::{
    GpuMethod, NESTED_MARCH_MS_PASSES, NESTED_MARCH_PASSES, SINGLE_SCATTERING_COMMON,
    SINGLE_SCATTERING_MS_COMMON,
};
use atmoscope_model::methods::shared::single_scattering_sky::{self, Rule, Way};
use atmoscope_model::scene::Method;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Trapezoid,
    lowest_table_mu_s: None,
    common: &SINGLE_SCATTERING_COMMON,
    constants: |p| single_scattering_sky::constants(p, Way::March(Rule::Trapezoid)),
    passes: &NESTED_MARCH_PASSES,
};

/// With Hillaire's Ψ_ms table as the higher orders (the `trapezoid-ms` row).
pub const METHOD_MS: GpuMethod = GpuMethod {
    method: Method::TrapezoidMs,
    lowest_table_mu_s: None,
    common: &SINGLE_SCATTERING_MS_COMMON,
    constants: |p| single_scattering_sky::constants(p, Way::March(Rule::Trapezoid)),
    passes: &NESTED_MARCH_MS_PASSES,
};
