//! Single scattering with the trapezoid rule towards the sun on the GPU: one pass, the
//! table-free single-scattering sky (`shaders/shared/single_scattering_sky.wgsl`). Its f64
//! twin is `atmoscope_model::methods::trapezoid`.

use super::{
    ENGINE_TILE, GpuMethod, SINGLE_SCATTERING_COMMON, SINGLE_SCATTERING_MS_COMMON,
    SINGLE_SCATTERING_MS_PASSES, SINGLE_SCATTERING_SKY_PASS,
};
use atmoscope_model::methods::shared::single_scattering_sky::{self, Rule, Way};
use atmoscope_model::scene::Method;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Trapezoid,
    moving_tile: ENGINE_TILE,
    common: &SINGLE_SCATTERING_COMMON,
    constants: |p| single_scattering_sky::constants(p, Way::March(Rule::Trapezoid)),
    passes: &[SINGLE_SCATTERING_SKY_PASS],
};

/// With Hillaire's Ψ_ms table as the higher orders (the `trapezoid-ms` row).
pub const METHOD_MS: GpuMethod = GpuMethod {
    method: Method::TrapezoidMs,
    moving_tile: ENGINE_TILE,
    common: &SINGLE_SCATTERING_MS_COMMON,
    constants: |p| single_scattering_sky::constants(p, Way::March(Rule::Trapezoid)),
    passes: &SINGLE_SCATTERING_MS_PASSES,
};
