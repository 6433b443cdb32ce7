//! Gałaj et al.'s (2021) Taylor-series transmittance on the GPU: the moving sky and the sky
//! pass of the table-free single-scattering sky (`shaders/shared/single_scattering_sky.wgsl`)
//! with the Taylor integral towards the sun (`shaders/shared/exponential.wgsl`). Its f64 twin
//! is `atmoscope_model::methods::galaj_taylor`.

use super::{
    GpuMethod, SINGLE_SCATTERING_COMMON, SINGLE_SCATTERING_MS_COMMON, SINGLE_SCATTERING_MS_PASSES,
    SINGLE_SCATTERING_PASSES,
};
use atmoscope_model::methods::shared::single_scattering_sky::{self, Way};
use atmoscope_model::scene::Method;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::GalajTaylor,
    lowest_table_mu_s: None,
    common: &SINGLE_SCATTERING_COMMON,
    constants: |p| single_scattering_sky::constants(p, Way::GalajTaylor),
    passes: &SINGLE_SCATTERING_PASSES,
};

/// With Hillaire's Ψ_ms table as the higher orders (the `galaj-taylor-ms` row).
pub const METHOD_MS: GpuMethod = GpuMethod {
    method: Method::GalajTaylorMs,
    lowest_table_mu_s: None,
    common: &SINGLE_SCATTERING_MS_COMMON,
    constants: |p| single_scattering_sky::constants(p, Way::GalajTaylor),
    passes: &SINGLE_SCATTERING_MS_PASSES,
};
