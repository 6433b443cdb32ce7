//! O'Neil (2005) on the GPU: one pass, the sky (`shaders/oneil/sky.wgsl`), with the refitted
//! scale function, the shared scale height and the ground densities in `globals.model`. Its
//! f64 twin is `atmoscope_model::methods::oneil`.

use super::{GpuMethod, PassSpec, SKY_ENTRY_POINT, TONE, VIEW_RADIANCE, shader};
use atmoscope_model::methods::oneil;
use atmoscope_model::scene::Method;

pub const METHODS: &[GpuMethod] = &[GpuMethod {
    method: Method::ONeil,
    lowest_table_mu_s: None,
    common: &[],
    constants: oneil::constants,
    batch_rows: None,
    passes: &[PassSpec::sky(
        &[
            TONE,
            shader!("oneil/sky.wgsl"),
            VIEW_RADIANCE,
            SKY_ENTRY_POINT,
        ],
        &[],
    )],
}];
