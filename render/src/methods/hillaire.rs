//! Hillaire (2020) on the GPU: the passes of `shaders/hillaire/` as data. The f64 twin of every
//! pass is `atmoscope_model::methods::hillaire::<pass>`.

use super::{Dispatch, GpuMethod, PassSpec, Repeat, TRANSMITTANCE_PASS, shader};
use atmoscope_model::methods::Inputs;
use atmoscope_model::scene::Method;

const AP_INSCATTERING: &str = "aerial-perspective-inscattering";
const AP_TRANSMITTANCE: &str = "aerial-perspective-transmittance";

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Hillaire,
    common: &[
        shader!("common/march.wgsl"),
        shader!("hillaire/common.wgsl"),
    ],
    constants: |_| [0.0; 4],
    passes: &[
        TRANSMITTANCE_PASS,
        PassSpec {
            name: "multiple-scattering",
            shader: shader!("hillaire/multiple_scattering.wgsl"),
            reads: &["transmittance"],
            writes: &["multiple-scattering"],
            inputs: Inputs::NONE,
            dispatch: Dispatch::Table("multiple-scattering"),
            constants: &[],
            repeat: Repeat::Once,
        },
        PassSpec {
            name: "ground-irradiance",
            shader: shader!("hillaire/ground_irradiance.wgsl"),
            reads: &["transmittance", "multiple-scattering"],
            writes: &["ground-irradiance"],
            inputs: Inputs::NONE,
            dispatch: Dispatch::Table("ground-irradiance"),
            constants: &[],
            repeat: Repeat::Once,
        },
        PassSpec {
            name: "sky-view",
            shader: shader!("hillaire/sky_view.wgsl"),
            reads: &["transmittance", "multiple-scattering"],
            writes: &["sky-view"],
            inputs: Inputs::NONE,
            dispatch: Dispatch::Table("sky-view"),
            constants: &[],
            repeat: Repeat::Once,
        },
        PassSpec {
            name: "aerial-perspective",
            shader: shader!("hillaire/aerial_perspective.wgsl"),
            reads: &["transmittance", "multiple-scattering"],
            writes: &[AP_INSCATTERING, AP_TRANSMITTANCE],
            inputs: Inputs::NONE,
            dispatch: Dispatch::Table(AP_INSCATTERING),
            constants: &[],
            repeat: Repeat::Once,
        },
        PassSpec::sky(
            shader!("hillaire/sky.wgsl"),
            &[
                "transmittance",
                "multiple-scattering",
                "ground-irradiance",
                "sky-view",
                AP_INSCATTERING,
                AP_TRANSMITTANCE,
            ],
        ),
    ],
};
