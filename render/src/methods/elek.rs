//! Elek (2009) on the GPU: the passes of `shaders/elek/` as data. The gather, multiple
//! scattering and accumulate passes run once per scattering order from 2 to the scene's count, each order
//! reading the last one's tables. The f64 twin of every pass is
//! `atmoscope_model::methods::elek::<pass>`.

use super::{
    Constant, Dispatch, GpuMethod, PassSpec, RADIANCE, Repeat, SKY_INPUTS, TRANSMITTANCE_PASS,
    shader,
};
use atmoscope_model::methods::Inputs;
use atmoscope_model::scene::Method;

const T: &str = "transmittance";
const DELTA_RAYLEIGH: &str = "delta-rayleigh";
const DELTA_MIE: &str = "delta-mie";
const RAYLEIGH: &str = "rayleigh-scattering";
const MIE: &str = "mie-scattering";
const GATHERED_RAYLEIGH: &str = "gathered-rayleigh";
const GATHERED_MIE: &str = "gathered-mie";

const fn table_pass(
    name: &'static str,
    shader: super::Shader,
    reads: &'static [&'static str],
    writes: &'static [&'static str],
    repeat: Repeat,
) -> PassSpec {
    PassSpec {
        name,
        shader,
        reads,
        writes,
        inputs: Inputs::NONE,
        dispatch: Dispatch::Volume(RAYLEIGH),
        constants: &[],
        repeat,
    }
}

pub const METHOD: GpuMethod = GpuMethod {
    method: Method::Elek,
    common: &[shader!("elek/common.wgsl")],
    constants: |_| [0.0; 4],
    passes: &[
        TRANSMITTANCE_PASS,
        table_pass(
            "single-scattering",
            shader!("elek/single_scattering.wgsl"),
            &[T],
            &[DELTA_RAYLEIGH, DELTA_MIE, RAYLEIGH, MIE],
            Repeat::Once,
        ),
        table_pass(
            "gather",
            shader!("elek/gather.wgsl"),
            &[DELTA_RAYLEIGH, DELTA_MIE],
            &[GATHERED_RAYLEIGH, GATHERED_MIE],
            Repeat::PerOrder,
        ),
        table_pass(
            "multiple-scattering",
            shader!("elek/multiple_scattering.wgsl"),
            &[T, GATHERED_RAYLEIGH, GATHERED_MIE],
            &[DELTA_RAYLEIGH, DELTA_MIE],
            Repeat::PerOrder,
        ),
        table_pass(
            "accumulate",
            shader!("elek/accumulate.wgsl"),
            &[DELTA_RAYLEIGH, DELTA_MIE, RAYLEIGH, MIE],
            &[RAYLEIGH, MIE],
            Repeat::PerOrder,
        ),
        PassSpec {
            name: "sky",
            shader: shader!("elek/sky.wgsl"),
            reads: &[T, RAYLEIGH, MIE],
            writes: &[RADIANCE],
            inputs: SKY_INPUTS,
            dispatch: Dispatch::View,
            constants: &[Constant::Projection, Constant::AboveAtmosphere],
            repeat: Repeat::Once,
        },
    ],
};
