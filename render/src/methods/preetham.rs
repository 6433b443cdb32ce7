//! Preetham et al. (1999) on the GPU: one pass, the sky (`shaders/preetham/sky.wgsl`), with the
//! turbidity as its one model constant. Its f64 twin is `atmoscope_model::methods::preetham`.

use super::{GpuMethod, PassSpec, SKY_ENTRY_POINT, TONE, VIEW_RADIANCE, shader};
use atmoscope_model::methods::preetham;
use atmoscope_model::scene::Method;

pub const METHODS: &[GpuMethod] = &[GpuMethod {
    method: Method::Preetham,
    lowest_table_mu_s: None,
    common: &[],
    constants: preetham::constants,
    batch_rows: None,
    passes: &[PassSpec::sky(
        &[
            TONE,
            shader!("preetham/sky.wgsl"),
            VIEW_RADIANCE,
            SKY_ENTRY_POINT,
        ],
        &[],
    )],
}];
