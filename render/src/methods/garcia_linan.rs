//! García Liñán (2023) on the GPU: the passes of `shaders/garcia_linan/` as data. The f64 twin
//! of every pass is `atmoscope_model::methods::garcia_linan::<pass>`.

use super::{
    Dispatch, GpuMethod, PassSpec, Repeat, SUN_DISK_FROM_TABLE, TRANSMITTANCE_PASS, shader,
};
use atmoscope_model::methods::garcia_linan::Constants;
use atmoscope_model::scene::Method;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::GarciaLinan,
    lowest_table_mu_s: None,
    common: &[
        SUN_DISK_FROM_TABLE,
        shader!("common/march.wgsl"),
        shader!("garcia_linan/common.wgsl"),
    ],
    constants: |p| super::first_row(Constants::chosen(p.fitted_constants).uniform()),
    passes: &[
        TRANSMITTANCE_PASS,
        PassSpec::table(
            "sky-texture",
            shader!("garcia_linan/sky_texture.wgsl"),
            &["transmittance"],
            &["sky-texture"],
            Dispatch::Table("sky-texture"),
            Repeat::Once,
        ),
        PassSpec::sky_marching_from_space(
            shader!("garcia_linan/sky.wgsl"),
            &["transmittance", "sky-texture"],
            // Above the atmosphere each pixel is marched with the model's integrand.
            &["transmittance"],
        ),
    ],
};
