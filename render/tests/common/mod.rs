//! Shared by the GPU tests: a headless device that must exist in CI.

use atmoscope_render::GpuContext;

/// Whether a missing adapter must fail the run (CI, or ATMOSCOPE_REQUIRE_GPU=1).
pub fn gpu_required() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true" || v == "1")
        || std::env::var("ATMOSCOPE_REQUIRE_GPU").is_ok_and(|v| v == "1")
}

/// A headless device, or None (with a SKIPPED line) where there is none and none is required.
pub fn context() -> Option<GpuContext> {
    match GpuContext::headless() {
        Ok(c) => Some(c),
        Err(e) if gpu_required() => panic!("GPU required in CI: {e}"),
        Err(e) => {
            eprintln!("SKIPPED: {e}");
            None
        }
    }
}
