//! García Liñán (2023) on the GPU: the passes of `shaders/garcia_linan/` as data. The f64 twin
//! of every pass is `atmoscope_model::methods::garcia_linan::<pass>`.

use super::{
    Dispatch, GpuMethod, PassSpec, Repeat, Resource, SKY_ENTRY_POINT, SUN_DISK_FROM_TABLE, TONE,
    TRANSMITTANCE, TRANSMITTANCE_PASS, Table, VIEW_RADIANCE, first_row, read, shader,
};
use atmoscope_model::methods::garcia_linan::{Constants, sky_texture};
use atmoscope_model::scene::Method;

const SKY_TEXTURE: Resource = Resource::table(&sky_texture::TABLE);

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::GarciaLinan,
    lowest_table_mu_s: None,
    common: &[
        SUN_DISK_FROM_TABLE,
        shader!("common/march.wgsl"),
        shader!("garcia_linan/common.wgsl"),
    ],
    constants: |p| first_row(Constants::chosen(p.fitted_constants).uniform()),
    batch_rows: None,
    passes: &[
        TRANSMITTANCE_PASS,
        PassSpec::table(
            "sky-texture",
            &[shader!("garcia_linan/sky_texture.wgsl")],
            &[read(TRANSMITTANCE)],
            &[SKY_TEXTURE],
            Dispatch::Table(Table(&sky_texture::TABLE)),
            Repeat::Once,
        ),
        // Above the atmosphere each pixel is marched with the model's integrand.
        PassSpec::sky(
            &[
                TONE,
                shader!("garcia_linan/sky.wgsl"),
                VIEW_RADIANCE,
                SKY_ENTRY_POINT,
            ],
            &[read(TRANSMITTANCE), read(SKY_TEXTURE).inside_atmosphere()],
        ),
    ],
};

pub const METHODS: &[GpuMethod] = &[METHOD];
