//! Schuler (2012) on the GPU: the moving sky and the sky pass of the table-free
//! single-scattering sky (`shaders/shared/single_scattering_sky.wgsl`) with Schuler's Chapman
//! function towards the sun (`shaders/shared/exponential.wgsl`). Its f64 twin is
//! `atmoscope_model::methods::schuler`.

use super::{
    GpuMethod, SINGLE_SCATTERING_COMMON, SINGLE_SCATTERING_MS_COMMON, SINGLE_SCATTERING_MS_PASSES,
    SINGLE_SCATTERING_PASSES,
};
use atmoscope_model::methods::shared::single_scattering_sky::{self, Way};
use atmoscope_model::scene::Method;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Schuler,
    lowest_table_mu_s: None,
    common: &SINGLE_SCATTERING_COMMON,
    constants: |p| single_scattering_sky::constants(p, Way::SchulerChapman),
    passes: &SINGLE_SCATTERING_PASSES,
};

/// With Hillaire's Ψ_ms table as the higher orders (the `schuler-ms` row).
pub const METHOD_MS: GpuMethod = GpuMethod {
    method: Method::SchulerMs,
    lowest_table_mu_s: None,
    common: &SINGLE_SCATTERING_MS_COMMON,
    constants: |p| single_scattering_sky::constants(p, Way::SchulerChapman),
    passes: &SINGLE_SCATTERING_MS_PASSES,
};
