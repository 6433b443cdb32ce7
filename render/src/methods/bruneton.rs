//! Bruneton (2017) on the GPU: the passes of `shaders/bruneton/` as data. The three passes of
//! the order loop run once per scattering order from 2 to the scene's count, each order reading
//! the deltas the previous one wrote. The f64 twin of every pass is
//! `atmoscope_model::methods::bruneton::<pass>`.

use super::{
    Constant, Dispatch, GpuMethod, PassSpec, Repeat, Resource, SKY_CONSTANTS, SKY_ENTRY_POINT,
    SUN_DISK_FROM_TABLE, TONE, TRANSMITTANCE as T, TRANSMITTANCE_PASS, Table, VIEW_RADIANCE,
    no_constants, read, shader,
};
use atmoscope_model::methods::bruneton::{self as model, camera_slice};
use atmoscope_model::scene::Method;

const DELTA_IRRADIANCE: Resource = Resource::table(&model::DELTA_IRRADIANCE);
const IRRADIANCE: Resource = Resource::table(&model::IRRADIANCE);
const DELTA_RAYLEIGH: Resource = Resource::table(&model::DELTA_RAYLEIGH);
const DELTA_MIE: Resource = Resource::table(&model::DELTA_MIE);
const SCATTERING: Resource = Resource::table(&model::SCATTERING);
const SINGLE_MIE: Resource = Resource::table(&model::SINGLE_MIE);
const DENSITY: Resource = Resource::table(&model::SCATTERING_DENSITY);
const CAMERA_SCATTERING: Resource = Resource::table(&camera_slice::CAMERA_SCATTERING);
const CAMERA_SINGLE_MIE: Resource = Resource::table(&camera_slice::CAMERA_SINGLE_MIE);

/// The sky pass's constants, and whether a ray may start with the sun below the tables.
const SKY_CONSTANTS_BELOW_TABLES: [Constant; 11] = {
    let mut c = [Constant::SunBelowTables; 11];
    let mut i = 0;
    while i < SKY_CONSTANTS.len() {
        c[i] = SKY_CONSTANTS[i];
        i += 1;
    }
    c
};

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Bruneton,
    lowest_table_mu_s: Some(model::MU_S_MIN),
    common: &[SUN_DISK_FROM_TABLE, shader!("bruneton/common.wgsl")],
    constants: no_constants,
    batch_rows: None,
    passes: &[
        TRANSMITTANCE_PASS,
        PassSpec::table(
            "direct-irradiance",
            &[shader!("bruneton/direct_irradiance.wgsl")],
            &[read(T)],
            &[DELTA_IRRADIANCE, IRRADIANCE],
            Dispatch::Table(Table(&model::IRRADIANCE)),
            Repeat::Once,
        ),
        PassSpec::table(
            "single-scattering",
            &[shader!("bruneton/single_scattering.wgsl")],
            &[read(T)],
            &[DELTA_RAYLEIGH, DELTA_MIE, SCATTERING, SINGLE_MIE],
            Dispatch::Volume(Table(&model::SCATTERING)),
            Repeat::Once,
        ),
        PassSpec {
            constants: &[Constant::FirstOrder],
            ..PassSpec::table(
                "scattering-density",
                &[shader!("bruneton/scattering_density.wgsl")],
                &[
                    read(T),
                    read(DELTA_RAYLEIGH),
                    read(DELTA_MIE),
                    read(DELTA_IRRADIANCE),
                ],
                &[DENSITY],
                Dispatch::Volume(Table(&model::SCATTERING_DENSITY)),
                Repeat::PerOrder,
            )
        },
        PassSpec {
            constants: &[Constant::FirstOrder],
            ..PassSpec::table(
                "indirect-irradiance",
                &[shader!("bruneton/indirect_irradiance.wgsl")],
                &[read(DELTA_RAYLEIGH), read(DELTA_MIE), read(IRRADIANCE)],
                &[DELTA_IRRADIANCE, IRRADIANCE],
                Dispatch::Table(Table(&model::IRRADIANCE)),
                Repeat::PerOrder,
            )
        },
        PassSpec::table(
            "multiple-scattering",
            &[shader!("bruneton/multiple_scattering.wgsl")],
            &[read(T), read(DENSITY), read(SCATTERING)],
            &[DELTA_RAYLEIGH, DELTA_MIE, SCATTERING],
            Dispatch::Volume(Table(&model::SCATTERING)),
            Repeat::PerOrder,
        ),
        PassSpec::table(
            "camera-slice",
            &[shader!("bruneton/camera_slice.wgsl")],
            &[read(SCATTERING), read(SINGLE_MIE)],
            &[CAMERA_SCATTERING, CAMERA_SINGLE_MIE],
            Dispatch::Table(Table(&camera_slice::CAMERA_SCATTERING)),
            Repeat::Once,
        ),
        PassSpec {
            constants: &SKY_CONSTANTS_BELOW_TABLES,
            // Above the atmosphere rays start where they enter it, and with the sun below the
            // tables at the camera they read past the tables' edge: no camera slices in either.
            ..PassSpec::sky(
                &[
                    TONE,
                    shader!("bruneton/sky.wgsl"),
                    VIEW_RADIANCE,
                    SKY_ENTRY_POINT,
                ],
                &[
                    read(T),
                    read(SCATTERING),
                    read(SINGLE_MIE),
                    read(IRRADIANCE),
                    read(CAMERA_SCATTERING)
                        .inside_atmosphere()
                        .with_sun_in_tables(),
                    read(CAMERA_SINGLE_MIE)
                        .inside_atmosphere()
                        .with_sun_in_tables(),
                ],
            )
        },
    ],
};

pub const METHODS: &[GpuMethod] = &[METHOD];
