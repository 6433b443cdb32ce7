//! Gałaj et al.'s (2021) Taylor-series transmittance on the GPU: the moving sky and the sky
//! pass of the table-free single-scattering sky (`shaders/shared/single_scattering_sky.wgsl`)
//! with the Taylor integral towards the sun (`shaders/shared/exponential.wgsl`); its `-ms` row
//! adds Hillaire's Ψ_ms table as the higher orders. Its f64 twin is
//! `atmoscope_model::methods::galaj_taylor`.

use super::{GpuMethod, single_scattering_rows};
use atmoscope_model::methods::shared::single_scattering_sky::{self, Way};
use atmoscope_model::scene::Method;

pub const METHODS: &[GpuMethod] =
    &single_scattering_rows(Method::GalajTaylor, Method::GalajTaylorMs, false, |p| {
        single_scattering_sky::constants(p, Way::GalajTaylor)
    });
