//! What a frame ran and how long it took, how it was timed, and the engine's errors.

use super::*;

/// How a pass's time was measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimingSource {
    /// GPU timestamp queries around the pass.
    GpuTimestamps,
    /// Wall time from submission to completion, each pass submitted and waited for alone.
    CpuFenced,
}

impl TimingSource {
    pub fn label(self) -> &'static str {
        match self {
            TimingSource::GpuTimestamps => "GPU timestamps",
            TimingSource::CpuFenced => "CPU-fenced wall time",
        }
    }
}

/// A frame's time from end to end, its passes free to overlap where no barrier parts them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spans {
    pub tables_ms: Option<f64>,
    pub frame_ms: f64,
}

/// What the last frame did; passes by name, in the order of the model's passes.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FrameStats {
    pub method: Method,
    /// Every pass of the model on screen the engine runs, the view passes last.
    pub passes: Vec<&'static str>,
    pub run: Vec<&'static str>,
    pub skipped: Vec<&'static str>,
    /// Table passes among those run.
    pub tables_run: Vec<&'static str>,
    /// Dispatches encoded: the passes run, the order loop's once per order.
    pub dispatched: usize,
    /// Milliseconds per pass run, when timing is on (and not in spans).
    pub timings_ms: Vec<(&'static str, f64)>,
    /// With span timing on (`Engine::set_span_timing`), the milliseconds from the start of
    /// the frame's first table pass to the end of its last (None when no table ran), and from
    /// the start of its first pass to the end of its last.
    pub spans_ms: Option<Spans>,
    pub timing_source: Option<TimingSource>,
    /// How far a rebuild in slices has come (`Engine::set_rebuild_slices`; 0 of 1 while held
    /// before it starts); the frame drew the previous atmosphere, or nothing before the first.
    pub rebuild: Option<RebuildProgress>,
    /// The frame put on screen a rebuild finished in slices (new images, whatever it ran).
    pub rebuild_done: bool,
    /// Pixels on a side of the tiles the frame drew its sky in (`Engine::set_sky_tile`), where
    /// more than 1; 1 (0 in a frame that failed) where it drew every pixel or no sky.
    pub sky_tile: u32,
    /// What the frame did to a moving sky being built in slices.
    pub moving_sky: MovingSkyStep,
}

/// What a frame did to the next moving sky of a march per pixel, built in slices where the
/// engine slices its work (`Engine::set_rebuild_slices`) and a moving sky is complete.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MovingSkyStep {
    /// None is being built.
    #[default]
    None,
    /// One is being built; its last slice is still on the GPU.
    Waiting,
    /// It submitted a slice of it.
    Slice,
    /// Every slice had finished: it copied the new one over the one the sky pass reads.
    Published,
}

/// Progress of a rebuild in slices, in units of work (MiB of its tables zeroed, then
/// workgroups of its passes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RebuildProgress {
    pub done: u64,
    pub total: u64,
}

impl FrameStats {
    pub fn ran(&self, pass: &str) -> bool {
        self.run.contains(&pass)
    }

    pub fn ran_any_lut(&self) -> bool {
        !self.tables_run.is_empty()
    }

    /// Milliseconds of a pass run this frame, when timed.
    pub fn ms(&self, pass: &str) -> Option<f64> {
        self.timings_ms
            .iter()
            .find(|(p, _)| *p == pass)
            .map(|(_, ms)| *ms)
    }
}

/// Why the engine could not do what was asked.
#[derive(Debug, thiserror::Error)]
pub enum EngineError {
    #[error("nothing has been rendered yet")]
    NotRendered,
    #[error("the view is in motion: its radiance comes with the next still frame")]
    InMotion,
    #[error("the model has no table `{0}`")]
    NoSuchTable(String),
    /// The model is offline, or refuses this view (a message says why).
    #[error(transparent)]
    CannotDraw(#[from] CannotDraw),
    #[error(transparent)]
    Readback(#[from] ReadbackError),
    #[error("a {0}×{1} view is larger than this GPU allows ({2} pixels on a side at most)")]
    ViewTooLarge(u32, u32, u32),
    /// A wgpu validation, out-of-memory or internal error, or a lost device, caught by the
    /// error scopes around the frame; the engine starts afresh on the next frame.
    #[error("the GPU refused the frame: {0}")]
    Gpu(String),
}

impl EngineError {
    /// Whether this is a browser's read-back still on its way (`readback::ReadbackError::
    /// Pending`): not a failure, the answer of a later frame.
    pub fn is_pending(&self) -> bool {
        matches!(self, EngineError::Readback(ReadbackError::Pending))
    }
}

/// Runs `f` inside wgpu error scopes for validation, out-of-memory and internal errors, so that
/// a fault (an absurd size, a lost device, a driver failure) is an error for the caller instead
/// of wgpu's default handler, which panics.
#[cfg(not(target_arch = "wasm32"))]
pub fn capture<T>(device: &wgpu::Device, f: impl FnOnce() -> T) -> Result<T, EngineError> {
    let scopes = [
        wgpu::ErrorFilter::Validation,
        wgpu::ErrorFilter::OutOfMemory,
        wgpu::ErrorFilter::Internal,
    ]
    .map(|filter| device.push_error_scope(filter));
    let value = f();
    let mut fault = None;
    for scope in scopes.into_iter().rev() {
        if let Some(e) = pollster::block_on(scope.pop()) {
            fault.get_or_insert(e.to_string());
        }
    }
    match fault {
        Some(e) => Err(EngineError::Gpu(e)),
        None => Ok(value),
    }
}

/// In the browser an error scope's verdict arrives only after the frame has returned to the
/// event loop, so nothing can be caught here: faults go to the device's uncaptured-error
/// handler, which the web explorer logs to the console (`app/src/web`).
#[cfg(target_arch = "wasm32")]
pub fn capture<T>(_device: &wgpu::Device, f: impl FnOnce() -> T) -> Result<T, EngineError> {
    Ok(f())
}
