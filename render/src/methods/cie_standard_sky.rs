//! The CIE standard general sky on the GPU: one pass, the sky
//! (`shaders/cie_standard_sky/sky.wgsl`), reading the type's parameters and the scales the CPU
//! computes for the frame's sun (`cie_standard_sky::batch_rows`, `batches[layer].model`). Its
//! f64 twin is `atmoscope_model::methods::cie_standard_sky`.

use super::{GpuMethod, PassSpec, SKY_ENTRY_POINT, TONE, VIEW_RADIANCE, no_constants, shader};
use atmoscope_model::methods::cie_standard_sky;
use atmoscope_model::scene::Method;

pub const METHODS: &[GpuMethod] = &[GpuMethod {
    method: Method::CieStandardSky,
    lowest_table_mu_s: None,
    common: &[],
    constants: no_constants,
    batch_rows: Some(cie_standard_sky::batch_rows),
    passes: &[PassSpec::sky(
        &[
            TONE,
            shader!("cie_standard_sky/sky.wgsl"),
            VIEW_RADIANCE,
            SKY_ENTRY_POINT,
        ],
        &[],
    )],
}];
