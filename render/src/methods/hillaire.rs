//! Hillaire (2020) on the GPU: the passes of `shaders/hillaire/` as data. The f64 twin of every
//! pass is `atmoscope_model::methods::hillaire::<pass>`.

use super::{
    Dispatch, GpuMethod, HILLAIRE_MS, MU_S_AXIS, MULTIPLE_SCATTERING_PASS, PassSpec, Repeat,
    Resource, SKY_ENTRY_POINT, SUN_DISK_FROM_TABLE, TONE, TRANSMITTANCE, TRANSMITTANCE_PASS, Table,
    VIEW_RADIANCE, no_constants, read, shader,
};
use atmoscope_model::methods::hillaire::{aerial_perspective, ground_irradiance, sky_view};
use atmoscope_model::scene::Method;

const GROUND_IRRADIANCE: Resource = Resource::table(&ground_irradiance::TABLE);
const SKY_VIEW: Resource = Resource::table(&sky_view::TABLE);
const AP_INSCATTERING: Resource = Resource::table(&aerial_perspective::INSCATTERING);
const AP_TRANSMITTANCE: Resource = Resource::table(&aerial_perspective::TRANSMITTANCE);

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Hillaire,
    lowest_table_mu_s: None,
    common: &[
        SUN_DISK_FROM_TABLE,
        shader!("common/march.wgsl"),
        MU_S_AXIS,
        shader!("hillaire/common.wgsl"),
    ],
    constants: no_constants,
    batch_rows: None,
    passes: &[
        TRANSMITTANCE_PASS,
        MULTIPLE_SCATTERING_PASS,
        PassSpec::table(
            "ground-irradiance",
            &[shader!("hillaire/ground_irradiance.wgsl")],
            &[read(TRANSMITTANCE), read(HILLAIRE_MS)],
            &[GROUND_IRRADIANCE],
            Dispatch::TexelGroups(Table(&ground_irradiance::TABLE)),
            Repeat::Once,
        ),
        PassSpec::table(
            "sky-view",
            &[shader!("hillaire/sky_view.wgsl")],
            &[read(TRANSMITTANCE), read(HILLAIRE_MS)],
            &[SKY_VIEW],
            Dispatch::Table(Table(&sky_view::TABLE)),
            Repeat::Once,
        ),
        PassSpec::table(
            "aerial-perspective",
            &[shader!("hillaire/aerial_perspective.wgsl")],
            &[read(TRANSMITTANCE), read(HILLAIRE_MS)],
            &[AP_INSCATTERING, AP_TRANSMITTANCE],
            Dispatch::TexelGroups(Table(&aerial_perspective::INSCATTERING)),
            Repeat::Once,
        ),
        // Above the atmosphere each pixel is marched: no sky view, no aerial perspective; the
        // sky's pixels read the sky view, only the ground's the rest.
        PassSpec::sky(
            &[
                TONE,
                shader!("hillaire/sky.wgsl"),
                VIEW_RADIANCE,
                SKY_ENTRY_POINT,
            ],
            &[
                read(TRANSMITTANCE),
                read(HILLAIRE_MS),
                read(GROUND_IRRADIANCE).for_ground(),
                read(SKY_VIEW).inside_atmosphere(),
                read(AP_INSCATTERING).inside_atmosphere().for_ground(),
                read(AP_TRANSMITTANCE).inside_atmosphere().for_ground(),
            ],
        ),
    ],
};

pub const METHODS: &[GpuMethod] = &[METHOD];
