//! García Liñán (2023) on the GPU: the passes of `shaders/garcia_linan/` as data. The f64 twin
//! of every pass is `atmoscope_model::methods::garcia_linan::<pass>`.

use super::{
    Constant, Dispatch, GpuMethod, PassSpec, RADIANCE, Repeat, SKY_INPUTS, TRANSMITTANCE_PASS,
    shader,
};
use atmoscope_model::methods::Inputs;
use atmoscope_model::methods::garcia_linan::Constants;
use atmoscope_model::scene::Method;

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::GarciaLinan,
    common: &[
        shader!("common/march.wgsl"),
        shader!("garcia_linan/common.wgsl"),
    ],
    constants: |p| Constants::chosen(p.fitted_constants).uniform(),
    passes: &[
        TRANSMITTANCE_PASS,
        PassSpec {
            name: "sky-texture",
            shader: shader!("garcia_linan/sky_texture.wgsl"),
            reads: &["transmittance"],
            writes: &["sky-texture"],
            inputs: Inputs::NONE,
            dispatch: Dispatch::Table("sky-texture"),
            constants: &[],
            repeat: Repeat::Once,
        },
        PassSpec {
            name: "sky",
            shader: shader!("garcia_linan/sky.wgsl"),
            reads: &["transmittance", "sky-texture"],
            writes: &[RADIANCE],
            inputs: SKY_INPUTS,
            dispatch: Dispatch::View,
            constants: &[Constant::Projection, Constant::AboveAtmosphere],
            repeat: Repeat::Once,
        },
    ],
};
