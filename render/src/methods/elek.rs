//! Elek (2009) on the GPU: the passes of `shaders/elek/` as data. The gather, multiple
//! scattering and accumulate passes run once per scattering order from 2 to the scene's count,
//! each order reading the last one's tables; the camera slice, the tables' rows at the camera,
//! runs again when the sun or the camera's altitude moves. The f64 twin of every pass is
//! `atmoscope_model::methods::elek::<pass>`.

use super::{
    Dispatch, GpuMethod, PassSpec, Repeat, Resource, SKY_ENTRY_POINT, SUN_DISK_FROM_TABLE, TONE,
    TRANSMITTANCE as T, TRANSMITTANCE_PASS, Table, VIEW_RADIANCE, no_constants, read, shader,
};
use atmoscope_model::methods::elek::{self as model, camera_slice};
use atmoscope_model::scene::Method;

const DELTA_RAYLEIGH: Resource = Resource::table(&model::DELTA_RAYLEIGH);
const DELTA_MIE: Resource = Resource::table(&model::DELTA_MIE);
const RAYLEIGH: Resource = Resource::table(&model::RAYLEIGH);
const MIE: Resource = Resource::table(&model::MIE);
const GATHERED_RAYLEIGH: Resource = Resource::table(&model::GATHERED_RAYLEIGH);
const GATHERED_MIE: Resource = Resource::table(&model::GATHERED_MIE);
const CAMERA_RAYLEIGH: Resource = Resource::table(&camera_slice::CAMERA_RAYLEIGH);
const CAMERA_MIE: Resource = Resource::table(&camera_slice::CAMERA_MIE);
/// Every table pass runs one invocation per texel of the (equally sized) scattering tables.
const VOLUME: Dispatch = Dispatch::Volume(Table(&model::RAYLEIGH));

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Elek,
    lowest_table_mu_s: None,
    common: &[SUN_DISK_FROM_TABLE, shader!("elek/common.wgsl")],
    constants: no_constants,
    batch_rows: None,
    passes: &[
        TRANSMITTANCE_PASS,
        PassSpec::table(
            "single-scattering",
            &[shader!("elek/single_scattering.wgsl")],
            &[read(T)],
            &[DELTA_RAYLEIGH, DELTA_MIE, RAYLEIGH, MIE],
            VOLUME,
            Repeat::Once,
        ),
        PassSpec::table(
            "gather",
            &[shader!("elek/gather.wgsl")],
            &[read(DELTA_RAYLEIGH), read(DELTA_MIE)],
            &[GATHERED_RAYLEIGH, GATHERED_MIE],
            VOLUME,
            Repeat::PerOrder,
        ),
        PassSpec::table(
            "multiple-scattering",
            &[shader!("elek/multiple_scattering.wgsl")],
            &[read(T), read(GATHERED_RAYLEIGH), read(GATHERED_MIE)],
            &[DELTA_RAYLEIGH, DELTA_MIE],
            VOLUME,
            Repeat::PerOrder,
        ),
        PassSpec::table(
            "accumulate",
            &[shader!("elek/accumulate.wgsl")],
            &[
                read(DELTA_RAYLEIGH),
                read(DELTA_MIE),
                read(RAYLEIGH),
                read(MIE),
            ],
            &[RAYLEIGH, MIE],
            VOLUME,
            Repeat::PerOrder,
        ),
        PassSpec::table(
            "camera-slice",
            &[shader!("elek/camera_slice.wgsl")],
            &[read(RAYLEIGH), read(MIE)],
            &[CAMERA_RAYLEIGH, CAMERA_MIE],
            Dispatch::Table(Table(&camera_slice::CAMERA_RAYLEIGH)),
            Repeat::Once,
        ),
        // Above the atmosphere rays start where they enter it: no camera slices there.
        PassSpec::sky(
            &[
                TONE,
                shader!("elek/sky.wgsl"),
                VIEW_RADIANCE,
                SKY_ENTRY_POINT,
            ],
            &[
                read(T),
                read(RAYLEIGH),
                read(MIE),
                read(CAMERA_RAYLEIGH).inside_atmosphere(),
                read(CAMERA_MIE).inside_atmosphere(),
            ],
        ),
    ],
};

pub const METHODS: &[GpuMethod] = &[METHOD];
