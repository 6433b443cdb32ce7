//! Hosek & Wilkie (2012) on the GPU: one pass, the sky (`shaders/hosek_wilkie/sky.wgsl`),
//! reading the coefficients the CPU blends for the frame's sun
//! (`hosek_wilkie::batch_rows`, `batches[layer].model`). Its f64 twin is
//! `atmoscope_model::methods::hosek_wilkie`.

use super::{GpuMethod, PassSpec, SKY_ENTRY_POINT, TONE, VIEW_RADIANCE, no_constants, shader};
use atmoscope_model::methods::hosek_wilkie;
use atmoscope_model::scene::Method;

pub const METHODS: &[GpuMethod] = &[GpuMethod {
    method: Method::HosekWilkie,
    lowest_table_mu_s: None,
    common: &[],
    constants: no_constants,
    batch_rows: Some(hosek_wilkie::batch_rows),
    passes: &[PassSpec::sky(
        &[
            TONE,
            shader!("hosek_wilkie/sky.wgsl"),
            VIEW_RADIANCE,
            SKY_ENTRY_POINT,
        ],
        &[],
    )],
}];
