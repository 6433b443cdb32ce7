//! Elek (2009) on the GPU: the passes of `shaders/elek/` as data. The gather, multiple
//! scattering and accumulate passes run once per scattering order from 2 to the scene's count,
//! each order reading the last one's tables; the camera slice, the tables' rows at the camera,
//! runs again when the sun or the camera's altitude moves. The f64 twin of every pass is
//! `atmoscope_model::methods::elek::<pass>`.

use super::{
    Dispatch, GpuMethod, PassSpec, Repeat, SUN_DISK_FROM_TABLE, TRANSMITTANCE_PASS, shader,
};
use atmoscope_model::scene::Method;

const T: &str = "transmittance";
const DELTA_RAYLEIGH: &str = "delta-rayleigh";
const DELTA_MIE: &str = "delta-mie";
const RAYLEIGH: &str = "rayleigh-scattering";
const MIE: &str = "mie-scattering";
const GATHERED_RAYLEIGH: &str = "gathered-rayleigh";
const GATHERED_MIE: &str = "gathered-mie";
const CAMERA_RAYLEIGH: &str = "camera-rayleigh";
const CAMERA_MIE: &str = "camera-mie";
/// What the sky pass reads from above the atmosphere, where rays start where they enter it.
const WITHOUT_CAMERA_SLICES: &[&str] = &[T, RAYLEIGH, MIE];
/// Every table pass runs one invocation per texel of the (equally sized) scattering tables.
const VOLUME: Dispatch = Dispatch::Volume(RAYLEIGH);

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Elek,
    lowest_table_mu_s: None,
    common: &[SUN_DISK_FROM_TABLE, shader!("elek/common.wgsl")],
    constants: |_| [0.0; 12],
    passes: &[
        TRANSMITTANCE_PASS,
        PassSpec::table(
            "single-scattering",
            shader!("elek/single_scattering.wgsl"),
            &[T],
            &[DELTA_RAYLEIGH, DELTA_MIE, RAYLEIGH, MIE],
            VOLUME,
            Repeat::Once,
        ),
        PassSpec::table(
            "gather",
            shader!("elek/gather.wgsl"),
            &[DELTA_RAYLEIGH, DELTA_MIE],
            &[GATHERED_RAYLEIGH, GATHERED_MIE],
            VOLUME,
            Repeat::PerOrder,
        ),
        PassSpec::table(
            "multiple-scattering",
            shader!("elek/multiple_scattering.wgsl"),
            &[T, GATHERED_RAYLEIGH, GATHERED_MIE],
            &[DELTA_RAYLEIGH, DELTA_MIE],
            VOLUME,
            Repeat::PerOrder,
        ),
        PassSpec::table(
            "accumulate",
            shader!("elek/accumulate.wgsl"),
            &[DELTA_RAYLEIGH, DELTA_MIE, RAYLEIGH, MIE],
            &[RAYLEIGH, MIE],
            VOLUME,
            Repeat::PerOrder,
        ),
        PassSpec::table(
            "camera-slice",
            shader!("elek/camera_slice.wgsl"),
            &[RAYLEIGH, MIE],
            &[CAMERA_RAYLEIGH, CAMERA_MIE],
            Dispatch::Table(CAMERA_RAYLEIGH),
            Repeat::Once,
        ),
        PassSpec {
            reads_above_atmosphere: Some(WITHOUT_CAMERA_SLICES),
            ..PassSpec::sky(
                shader!("elek/sky.wgsl"),
                &[T, RAYLEIGH, MIE, CAMERA_RAYLEIGH, CAMERA_MIE],
            )
        },
    ],
};
