//! The baseline without an atmosphere on the GPU: one pass, the sky (`shaders/empty/`). Its
//! f64 twin is `atmoscope_model::methods::empty::sky`.

use super::{GpuMethod, PassSpec, SKY_ENTRY_POINT, TONE, VIEW_RADIANCE, no_constants, shader};
use atmoscope_model::scene::Method;

pub const METHODS: &[GpuMethod] = &[GpuMethod {
    method: Method::Empty,
    lowest_table_mu_s: None,
    common: &[],
    constants: no_constants,
    batch_rows: None,
    passes: &[PassSpec::sky(
        &[
            TONE,
            shader!("empty/sky.wgsl"),
            VIEW_RADIANCE,
            SKY_ENTRY_POINT,
        ],
        &[],
    )],
}];
