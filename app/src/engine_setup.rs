//! The one place an engine is set up to draw as the explorer draws: the explorer's views and
//! the benchmarks that measure what a user of the explorer meets (`bench gpu`) both start here,
//! so a benchmark times the same slicing, tiling and bands as the window.

use atmoscope_render::wgpu;
use atmoscope_render::{Engine, views};
use std::time::Duration;

/// GPU time a slice of a rebuild aims at: well inside the 100 ms a window may take per frame
/// and still feel live, leaving room for the frame's own work and for a slice that costs three
/// times what the last one promised (slices of Bruneton's scattering density can, on a CPU
/// adapter). docs/measurements/speed.md has the frame times that chose it.
pub const REBUILD_SLICE: Duration = Duration::from_millis(20);

/// How an engine draws on one adapter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EngineSetup {
    /// Side of the tiles a view in motion draws its sky in, pixels (1: every pixel).
    pub sky_tile: u32,
    /// Whether the sky pass runs in bands of rows with the sun's disk apart.
    pub view_bands: bool,
    /// Time per pass from fenced CPU wall time instead of GPU timestamps (a CPU adapter's
    /// timestamps are taken at recording and do not time passes).
    pub cpu_timing: bool,
    /// Time budget of one slice of a rebuild (`None`: every rebuild in the frame that asks).
    pub rebuild_slice: Option<Duration>,
}

impl EngineSetup {
    /// The explorer's settings on `device`'s adapter: on a software adapter a view in motion
    /// draws its sky in tiles (it sharpens in the first still frame) and in bands, and passes
    /// are timed by fenced wall time; on a GPU every pixel, in one dispatch, by timestamps.
    pub fn explorer(device: &wgpu::Device) -> EngineSetup {
        let device_type = device.adapter_info().device_type;
        EngineSetup {
            sky_tile: views::moving_sky_tile(device_type),
            view_bands: views::view_bands(device_type),
            cpu_timing: device_type == wgpu::DeviceType::Cpu,
            rebuild_slice: Some(REBUILD_SLICE),
        }
    }

    /// A timed engine on `device` with these settings.
    pub fn engine(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Engine {
        let mut engine = Engine::new(device, queue);
        engine.set_timing(true);
        engine.set_rebuild_slices(self.rebuild_slice);
        engine.set_sky_tile(self.sky_tile);
        engine.set_view_bands(self.view_bands);
        if self.cpu_timing {
            engine.force_cpu_timing();
        }
        engine
    }
}

/// Time left to a window between two slices of work done beside it (thumbnails, exports) on
/// the window's GPU queue: about a frame.
pub const BESIDE_A_WINDOW_PAUSE: Duration = Duration::from_millis(16);

/// An engine for work beside a window on the window's device: it builds its tables in slices
/// of [`REBUILD_SLICE`], so that the window's frames, queued behind its work, wait a slice at
/// most ([`render_still_beside_a_window`]).
pub fn engine_beside_a_window(device: &wgpu::Device, queue: &wgpu::Queue) -> Engine {
    let mut engine = Engine::new(device, queue);
    engine.set_rebuild_slices(Some(REBUILD_SLICE));
    engine
}

/// Draws `scene` with an engine beside a window: a new atmosphere is built a slice at a time
/// with [`BESIDE_A_WINDOW_PAUSE`] between slices. Returns false when `cancelled` says so
/// between slices.
pub fn render_beside_a_window(
    engine: &mut Engine,
    scene: &atmoscope_model::Scene,
    view: &atmoscope_render::View,
    cancelled: &dyn Fn() -> bool,
) -> Result<bool, atmoscope_render::EngineError> {
    engine.try_render(scene, view)?;
    while engine.rebuilding() {
        if cancelled() {
            return Ok(false);
        }
        std::thread::sleep(BESIDE_A_WINDOW_PAUSE);
        engine.try_render(scene, view)?;
    }
    Ok(true)
}

/// [`Engine::render_still`] after [`render_beside_a_window`]; None when cancelled.
pub fn render_still_beside_a_window(
    engine: &mut Engine,
    scene: &atmoscope_model::Scene,
    view: &atmoscope_render::View,
    cancelled: &dyn Fn() -> bool,
) -> Result<Option<(atmoscope_model::Scene, Option<f64>)>, atmoscope_render::EngineError> {
    if !render_beside_a_window(engine, scene, view, cancelled)? {
        return Ok(None);
    }
    engine.render_still(scene, view).map(Some)
}
