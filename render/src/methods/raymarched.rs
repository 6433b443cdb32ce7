//! Leenman (2025)'s raymarched model on the GPU: one pass, the segment-integral sky
//! (`shaders/shared/segments_sky.wgsl`) with five segments. Its f64 twin is
//! `atmoscope_model::methods::raymarched`.

use super::{GpuMethod, SEGMENTS_COMMON, SEGMENTS_SKY_PASS};
use atmoscope_model::methods::shared::segments_sky::{self, RAYMARCHED_SEGMENTS};
use atmoscope_model::scene::Method;

pub const METHODS: &[GpuMethod] = &[GpuMethod {
    method: Method::Raymarched,
    lowest_table_mu_s: None,
    common: &SEGMENTS_COMMON,
    constants: |p| segments_sky::constants(p, RAYMARCHED_SEGMENTS),
    batch_rows: None,
    passes: &[SEGMENTS_SKY_PASS],
}];
