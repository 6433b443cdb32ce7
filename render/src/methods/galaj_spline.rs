//! Gałaj et al.'s (2021) spline transmittance on the GPU: the mesh pass
//! (`shaders/galaj_spline/mesh.wgsl`), then the spline's way to the sun tabulated, the moving
//! sky built from it and the sky pass of the table-free
//! single-scattering sky
//! (`shaders/shared/single_scattering_sky.wgsl`) whose way to the sun integrates the spline over
//! that mesh (`shaders/galaj_spline/columns.wgsl`). Its f64 twin is
//! `atmoscope_model::methods::galaj_spline`.

use super::{
    Dispatch, EXPONENTIAL, GpuMethod, HIGHER_ORDERS_PASSES, HILLAIRE_HIGHER_ORDERS, MOVING_SKY,
    NO_HIGHER_ORDERS, PassSpec, Repeat, SINGLE_SCATTERING_SKY, SUN_ROUTE, SUN_ROUTE_TABLE, Shader,
    moving_sky_pass, shader, sun_route_pass,
};
use atmoscope_model::methods::galaj_spline::MESH;
use atmoscope_model::methods::shared::single_scattering_sky::{self, Way};
use atmoscope_model::scene::Method;

/// The spline's columns, in place of the closed forms'.
const COLUMNS: Shader = shader!("galaj_spline/columns.wgsl");

/// The mesh of the integrand, rebuilt with the atmosphere.
pub const MESH_PASS: PassSpec = PassSpec::table(
    "galaj-spline-mesh",
    shader!("galaj_spline/mesh.wgsl"),
    &[],
    &[MESH.id],
    Dispatch::Table(MESH.id),
    Repeat::Once,
);

const SKY_SHADER: Shader = SINGLE_SCATTERING_SKY;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::GalajSpline,
    lowest_table_mu_s: None,
    common: &[NO_HIGHER_ORDERS, EXPONENTIAL, COLUMNS, SUN_ROUTE],
    constants: |p| single_scattering_sky::constants(p, Way::GalajSpline),
    passes: &[
        MESH_PASS,
        sun_route_pass(&[MESH.id]),
        moving_sky_pass(SKY_SHADER, &[SUN_ROUTE_TABLE]),
        PassSpec::sky(SKY_SHADER, &[MESH.id, MOVING_SKY]).with_moving_sky(),
    ],
};

/// With Hillaire's Ψ_ms table as the higher orders (the `galaj-spline-ms` row).
pub const METHOD_MS: GpuMethod = GpuMethod {
    method: Method::GalajSplineMs,
    lowest_table_mu_s: None,
    common: &[HILLAIRE_HIGHER_ORDERS, EXPONENTIAL, COLUMNS, SUN_ROUTE],
    constants: |p| single_scattering_sky::constants(p, Way::GalajSpline),
    passes: &[
        MESH_PASS,
        HIGHER_ORDERS_PASSES[0],
        HIGHER_ORDERS_PASSES[1],
        sun_route_pass(&[MESH.id]),
        moving_sky_pass(SKY_SHADER, &["multiple-scattering", SUN_ROUTE_TABLE]),
        PassSpec::sky(SKY_SHADER, &[MESH.id, "multiple-scattering", MOVING_SKY]).with_moving_sky(),
    ],
};
