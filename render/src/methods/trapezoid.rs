//! Single scattering with the trapezoid rule towards the sun on the GPU: its way to the sun
//! tabulated, the moving sky built from it and the sky pass of the table-free
//! single-scattering sky (`shaders/shared/single_scattering_sky.wgsl`); its `-ms` row adds
//! Hillaire's Ψ_ms table as the higher orders. Its f64 twin is
//! `atmoscope_model::methods::trapezoid`.

use super::{GpuMethod, single_scattering_rows};
use atmoscope_model::methods::shared::single_scattering_sky::{self, Rule, Way};
use atmoscope_model::scene::Method;

pub const METHODS: &[GpuMethod] =
    &single_scattering_rows(Method::Trapezoid, Method::TrapezoidMs, true, |p| {
        single_scattering_sky::constants(p, Way::March(Rule::Trapezoid))
    });
