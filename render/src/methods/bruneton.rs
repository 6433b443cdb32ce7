//! Bruneton (2017) on the GPU: the passes of `shaders/bruneton/` as data. The three passes of
//! the order loop run once per scattering order from 2 to the scene's count, each order reading
//! the deltas the previous one wrote. The f64 twin of every pass is
//! `atmoscope_model::methods::bruneton::<pass>`.

use super::{
    Constant, Dispatch, GpuMethod, PassSpec, Repeat, SKY_CONSTANTS, SUN_DISK_FROM_TABLE,
    TRANSMITTANCE_PASS, shader,
};
use atmoscope_model::scene::Method;

const T: &str = "transmittance";
const DELTA_IRRADIANCE: &str = "delta-irradiance";
const IRRADIANCE: &str = "irradiance";
const DELTA_RAYLEIGH: &str = "delta-rayleigh";
const DELTA_MIE: &str = "delta-mie";
const SCATTERING: &str = "scattering";
const SINGLE_MIE: &str = "single-mie";
const DENSITY: &str = "scattering-density";
const CAMERA_SCATTERING: &str = "camera-scattering";
const CAMERA_SINGLE_MIE: &str = "camera-single-mie";

/// What the sky pass reads where no view ray starts at the camera with the sun in the tables.
const WITHOUT_CAMERA_SLICES: &[&str] = &[T, SCATTERING, SINGLE_MIE, IRRADIANCE];

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
    lowest_table_mu_s: Some(atmoscope_model::methods::bruneton::MU_S_MIN),
    common: &[SUN_DISK_FROM_TABLE, shader!("bruneton/common.wgsl")],
    constants: |_| [0.0; 12],
    passes: &[
        TRANSMITTANCE_PASS,
        PassSpec::table(
            "direct-irradiance",
            shader!("bruneton/direct_irradiance.wgsl"),
            &[T],
            &[DELTA_IRRADIANCE, IRRADIANCE],
            Dispatch::Table(IRRADIANCE),
            Repeat::Once,
        ),
        PassSpec::table(
            "single-scattering",
            shader!("bruneton/single_scattering.wgsl"),
            &[T],
            &[DELTA_RAYLEIGH, DELTA_MIE, SCATTERING, SINGLE_MIE],
            Dispatch::Volume(SCATTERING),
            Repeat::Once,
        ),
        PassSpec {
            constants: &[Constant::FirstOrder],
            ..PassSpec::table(
                "scattering-density",
                shader!("bruneton/scattering_density.wgsl"),
                &[T, DELTA_RAYLEIGH, DELTA_MIE, DELTA_IRRADIANCE],
                &[DENSITY],
                Dispatch::Volume(DENSITY),
                Repeat::PerOrder,
            )
        },
        PassSpec {
            constants: &[Constant::FirstOrder],
            ..PassSpec::table(
                "indirect-irradiance",
                shader!("bruneton/indirect_irradiance.wgsl"),
                &[DELTA_RAYLEIGH, DELTA_MIE, IRRADIANCE],
                &[DELTA_IRRADIANCE, IRRADIANCE],
                Dispatch::Table(IRRADIANCE),
                Repeat::PerOrder,
            )
        },
        PassSpec::table(
            "multiple-scattering",
            shader!("bruneton/multiple_scattering.wgsl"),
            &[T, DENSITY, SCATTERING],
            &[DELTA_RAYLEIGH, DELTA_MIE, SCATTERING],
            Dispatch::Volume(SCATTERING),
            Repeat::PerOrder,
        ),
        PassSpec::table(
            "camera-slice",
            shader!("bruneton/camera_slice.wgsl"),
            &[SCATTERING, SINGLE_MIE],
            &[CAMERA_SCATTERING, CAMERA_SINGLE_MIE],
            Dispatch::Table(CAMERA_SCATTERING),
            Repeat::Once,
        ),
        PassSpec {
            constants: &SKY_CONSTANTS_BELOW_TABLES,
            // Above the atmosphere rays start where they enter it, and with the sun below the
            // tables at the camera they read past the tables' edge: no camera slices in either.
            reads_above_atmosphere: Some(WITHOUT_CAMERA_SLICES),
            reads_with_sun_below_tables: Some(WITHOUT_CAMERA_SLICES),
            ..PassSpec::sky(
                shader!("bruneton/sky.wgsl"),
                &[
                    T,
                    SCATTERING,
                    SINGLE_MIE,
                    IRRADIANCE,
                    CAMERA_SCATTERING,
                    CAMERA_SINGLE_MIE,
                ],
            )
        },
    ],
};
