//! Nishita (1996) on the GPU: the transmittance table, the intensity volume of the light
//! scattered once (`shaders/nishita_96/intensity_volume.wgsl`), the way to the sun tabulated
//! for the moving sky, and the table-free sky pass (`shaders/shared/single_scattering_sky.wgsl`)
//! with the volume gathered as its higher orders (`shaders/shared/intensity_volume.wgsl`). Its
//! f64 twin is `atmoscope_model::methods::nishita_96`.

use super::{
    CLOSED_FORM_COLUMNS, Dispatch, EXPONENTIAL, GpuMethod, MOVING_SKY, MU_S_AXIS,
    NESTED_MARCH_MOVING_SKY_FILES, PassSpec, Repeat, Resource, SINGLE_SCATTERING_SKY_FILES,
    SUN_ROUTE_TABLE, Shader, TRANSMITTANCE, TRANSMITTANCE_PASS, Table, moving_sky_pass, read,
    shader, sun_route_pass,
};
use atmoscope_model::methods::nishita_96;
use atmoscope_model::methods::shared::intensity_volume;
use atmoscope_model::scene::Method;

pub const INTENSITY_VOLUME: Resource = Resource::table(&intensity_volume::TABLE);

/// What every pass of the intensity-volume models includes: the twilight-dense μ_s axis, the
/// volume's look-ups and gather, and the table-free sky's exponential medium and its columns.
pub const INTENSITY_VOLUME_COMMON: [Shader; 4] = [
    MU_S_AXIS,
    shader!("shared/intensity_volume.wgsl"),
    EXPONENTIAL,
    CLOSED_FORM_COLUMNS,
];

/// The source of order 1 (the sunlight through the transmittance table) for the march of a
/// volume's texels.
pub const ORDER_1: Shader = shader!("shared/intensity_volume_order1.wgsl");

/// The march of a volume's texels, on the source its pass defines.
pub const INTENSITY_MARCH: Shader = shader!("shared/intensity_volume_march.wgsl");

/// The way to the sun tabulated, the moving sky and the sky pass, all reading the volume.
pub const SKY_PASSES: [PassSpec; 3] = [
    sun_route_pass(&[]),
    moving_sky_pass(
        &NESTED_MARCH_MOVING_SKY_FILES,
        &[read(INTENSITY_VOLUME), read(SUN_ROUTE_TABLE)],
    ),
    PassSpec::sky(
        &SINGLE_SCATTERING_SKY_FILES,
        &[read(INTENSITY_VOLUME), read(MOVING_SKY).in_motion()],
    ),
];

pub const METHODS: &[GpuMethod] = &[GpuMethod {
    method: Method::Nishita96,
    lowest_table_mu_s: None,
    common: &INTENSITY_VOLUME_COMMON,
    constants: nishita_96::constants,
    batch_rows: None,
    passes: &[
        TRANSMITTANCE_PASS,
        PassSpec::table(
            "intensity-volume",
            &[
                ORDER_1,
                INTENSITY_MARCH,
                shader!("nishita_96/intensity_volume.wgsl"),
            ],
            &[read(TRANSMITTANCE)],
            &[INTENSITY_VOLUME],
            Dispatch::Volume(Table(&intensity_volume::TABLE)),
            Repeat::Once,
        ),
        SKY_PASSES[0],
        SKY_PASSES[1],
        SKY_PASSES[2],
    ],
}];
