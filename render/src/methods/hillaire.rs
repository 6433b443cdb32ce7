//! Hillaire (2020) on the GPU: the passes of `shaders/hillaire/` as data. The f64 twin of every
//! pass is `atmoscope_model::methods::hillaire::<pass>`.

use super::{
    Dispatch, GpuMethod, PassSpec, Repeat, SUN_DISK_FROM_TABLE, TRANSMITTANCE_PASS, shader,
};
use atmoscope_model::scene::Method;

const AP_INSCATTERING: &str = "aerial-perspective-inscattering";
const AP_TRANSMITTANCE: &str = "aerial-perspective-transmittance";

/// The Ψ_ms table's pass, which the single-scattering `-ms` rows share.
pub const MULTIPLE_SCATTERING_PASS: PassSpec = PassSpec::table(
    "multiple-scattering",
    shader!("hillaire/multiple_scattering.wgsl"),
    &["transmittance"],
    &["multiple-scattering"],
    Dispatch::TexelRuns("multiple-scattering"),
    Repeat::Once,
);

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Hillaire,
    lowest_table_mu_s: None,
    common: &[
        SUN_DISK_FROM_TABLE,
        shader!("common/march.wgsl"),
        shader!("hillaire/common.wgsl"),
    ],
    constants: |_| [0.0; 12],
    passes: &[
        TRANSMITTANCE_PASS,
        MULTIPLE_SCATTERING_PASS,
        PassSpec::table(
            "ground-irradiance",
            shader!("hillaire/ground_irradiance.wgsl"),
            &["transmittance", "multiple-scattering"],
            &["ground-irradiance"],
            Dispatch::TexelGroups("ground-irradiance"),
            Repeat::Once,
        ),
        PassSpec::table(
            "sky-view",
            shader!("hillaire/sky_view.wgsl"),
            &["transmittance", "multiple-scattering"],
            &["sky-view"],
            Dispatch::Table("sky-view"),
            Repeat::Once,
        ),
        PassSpec::table(
            "aerial-perspective",
            shader!("hillaire/aerial_perspective.wgsl"),
            &["transmittance", "multiple-scattering"],
            &[AP_INSCATTERING, AP_TRANSMITTANCE],
            Dispatch::TexelGroups(AP_INSCATTERING),
            Repeat::Once,
        ),
        PassSpec::sky_marching_from_space(
            shader!("hillaire/sky.wgsl"),
            &[
                "transmittance",
                "multiple-scattering",
                "ground-irradiance",
                "sky-view",
                AP_INSCATTERING,
                AP_TRANSMITTANCE,
            ],
            // Above the atmosphere each pixel is marched: no sky view, no aerial perspective.
            &["transmittance", "multiple-scattering", "ground-irradiance"],
        )
        // The sky's pixels read the sky view; only the ground's read these.
        .with_reads_for_ground(&["ground-irradiance", AP_INSCATTERING, AP_TRANSMITTANCE]),
    ],
};
