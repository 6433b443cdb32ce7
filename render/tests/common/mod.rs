//! Shared by the GPU tests (the render crate's, and the command line's in `tests/cli.rs`): a
//! headless device that must exist in CI or wherever a software driver is installed, and a
//! count of the tests that skipped for want of one.
#![allow(dead_code)]

use atmoscope_render::GpuContext;
use std::io::Write;
use std::path::Path;

/// Where Debian installs the Vulkan drivers' manifests; lavapipe's starts with `lvp_icd`.
const VULKAN_ICD_DIR: &str = "/usr/share/vulkan/icd.d";

/// Whether a missing adapter must fail the run: in CI (`CI=true`), with
/// `ATMOSCOPE_REQUIRE_GPU=1`, and wherever Mesa's software driver is installed (an adapter
/// that should be there and is not is a fault, not a reason to skip).
pub fn gpu_required() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true" || v == "1")
        || std::env::var("ATMOSCOPE_REQUIRE_GPU").is_ok_and(|v| v == "1")
        || software_driver_installed()
}

fn software_driver_installed() -> bool {
    std::fs::read_dir(Path::new(VULKAN_ICD_DIR)).is_ok_and(|entries| {
        entries
            .flatten()
            .any(|e| e.file_name().to_string_lossy().starts_with("lvp_icd"))
    })
}

/// Says SKIPPED with `why`, and adds the test's name to the file `ATMOSCOPE_GPU_SKIPS` names
/// (tests/run.sh counts them at the end of the run, where the runner hides a passing test's
/// output).
pub fn skip(why: &str) {
    let test = std::thread::current()
        .name()
        .unwrap_or("a GPU test")
        .to_string();
    eprintln!("SKIPPED: {why}");
    if let Some(path) = std::env::var_os("ATMOSCOPE_GPU_SKIPS") {
        let line = format!("{test}: {}\n", why.lines().next().unwrap_or(""));
        let appended = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .and_then(|mut f| f.write_all(line.as_bytes()));
        if let Err(e) = appended {
            eprintln!("the skip could not be counted: {e}");
        }
    }
}

/// A headless device, or None (counted by [`skip`]) where there is none and none is required.
pub fn context() -> Option<GpuContext> {
    match GpuContext::headless() {
        Ok(c) => Some(c),
        Err(e) if gpu_required() => panic!("GPU required (CI, or lavapipe installed): {e}"),
        Err(e) => {
            skip(&e.to_string());
            None
        }
    }
}
