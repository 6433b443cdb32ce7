//! Gałaj et al.'s (2021) spline transmittance on the GPU: the mesh pass
//! (`shaders/galaj_spline/mesh.wgsl`), then the spline's way to the sun tabulated, the moving
//! sky built from it and the sky pass of the table-free single-scattering sky
//! (`shaders/shared/single_scattering_sky.wgsl`), whose way to the sun integrates the spline
//! over that mesh (`shaders/galaj_spline/columns.wgsl`); its `-ms` row adds Hillaire's Ψ_ms
//! table as the higher orders. Its f64 twin is `atmoscope_model::methods::galaj_spline`.

use super::{
    Dispatch, EXPONENTIAL, GpuMethod, HILLAIRE_HIGHER_ORDERS, HILLAIRE_MS, MOVING_SKY,
    MULTIPLE_SCATTERING_PASS, NESTED_MARCH_MOVING_SKY_FILES, NO_HIGHER_ORDERS, PassSpec, Repeat,
    Resource, SINGLE_SCATTERING_SKY_FILES, SUN_ROUTE_TABLE, Shader, TRANSMITTANCE_PASS, Table,
    moving_sky_pass, read, shader, sun_route_pass,
};
use atmoscope_model::methods::galaj_spline::MESH;
use atmoscope_model::methods::shared::single_scattering_sky::{self, Way};
use atmoscope_model::scene::Method;

/// The spline's columns, in place of the closed forms'.
const COLUMNS: Shader = shader!("galaj_spline/columns.wgsl");

const MESH_TABLE: Resource = Resource::table(&MESH);

/// The mesh of the integrand, rebuilt with the atmosphere.
pub const MESH_PASS: PassSpec = PassSpec::table(
    "galaj-spline-mesh",
    &[shader!("galaj_spline/mesh.wgsl")],
    &[],
    &[MESH_TABLE],
    Dispatch::Table(Table(&MESH)),
    Repeat::Once,
);

pub const METHODS: &[GpuMethod] = &[
    GpuMethod {
        method: Method::GalajSpline,
        lowest_table_mu_s: None,
        common: &[NO_HIGHER_ORDERS, EXPONENTIAL, COLUMNS],
        constants: |p| single_scattering_sky::constants(p, Way::GalajSpline),
        batch_rows: None,
        passes: &[
            MESH_PASS,
            sun_route_pass(&[read(MESH_TABLE)]),
            moving_sky_pass(&NESTED_MARCH_MOVING_SKY_FILES, &[read(SUN_ROUTE_TABLE)]),
            PassSpec::sky(
                &SINGLE_SCATTERING_SKY_FILES,
                &[read(MESH_TABLE), read(MOVING_SKY).in_motion()],
            ),
        ],
    },
    GpuMethod {
        method: Method::GalajSplineMs,
        lowest_table_mu_s: None,
        common: &[
            HILLAIRE_HIGHER_ORDERS[0],
            HILLAIRE_HIGHER_ORDERS[1],
            HILLAIRE_HIGHER_ORDERS[2],
            EXPONENTIAL,
            COLUMNS,
        ],
        constants: |p| single_scattering_sky::constants(p, Way::GalajSpline),
        batch_rows: None,
        passes: &[
            MESH_PASS,
            TRANSMITTANCE_PASS,
            MULTIPLE_SCATTERING_PASS,
            sun_route_pass(&[read(MESH_TABLE)]),
            moving_sky_pass(
                &NESTED_MARCH_MOVING_SKY_FILES,
                &[read(HILLAIRE_MS), read(SUN_ROUTE_TABLE)],
            ),
            PassSpec::sky(
                &SINGLE_SCATTERING_SKY_FILES,
                &[
                    read(MESH_TABLE),
                    read(HILLAIRE_MS),
                    read(MOVING_SKY).in_motion(),
                ],
            ),
        ],
    },
];
