//! The engine: GPU resources for one scene and one view, the passes of the scene's model with
//! dirty tracking, and per-pass timing. It takes a `wgpu::Device` and `Queue` from its caller (a
//! window, the command line or a test) and renders into textures. It knows no model: the passes
//! come as data from `crate::methods` and the tables from the model registry.
//!
//! A frame compares the scene's inputs with the previous frame's and runs exactly the passes
//! that read an input that changed or a table rewritten earlier in the same frame (see
//! docs/architecture.md): physics rebuilds the whole chain, the sun or the camera's altitude
//! rebuilds the view tables, turning the camera redraws the view, exposure re-runs only the
//! display pass, an unchanged frame runs nothing. Passes marked `Repeat::PerOrder` (an order
//! loop) are encoded once per scattering order from 2 to the scene's count.

mod changes;
mod dispatch;
mod encoder;
mod frame;
mod rebuild;
mod schedule;
mod slices;
mod stats;
mod target;
mod timing;

use crate::DisplayMode;
use crate::methods::{
    Constant, Dispatch, GpuMethod, HISTOGRAM, METER_PASS, PassSpec, RADIANCE, Repeat, Resource,
    Situation, gpu_method,
};
use crate::passes::{NextMovingSky, ORIGIN_SLOTS, Pipelines, TableBuffers, Variant};
use crate::prelude::{WORKGROUP_SIZE, texel_group_size, texel_run};
use crate::readback::{
    ReadbackError, read_buffer_f32x4, read_buffer_u32, read_texture, read_texture_f32x4,
};
use crate::uniforms::{self, FrameInputs, Globals};
use crate::views::{self, View};
use atmoscope_model::Atmosphere;
use atmoscope_model::camera::{Camera, Projection, Sees};
use atmoscope_model::colour::Xyz;
use atmoscope_model::display::{HISTOGRAM_BINS, Histogram};
use atmoscope_model::geometry::direction_from_angles;
use atmoscope_model::methods::shared::{Params, viewpoint};
use atmoscope_model::methods::{self, CannotDraw, Inputs};
use atmoscope_model::scene::{
    AtmosphereSettings, CameraSettings, FittedConstants, Method, Quality, Scene, ToneMap,
    WavelengthSet, WhiteBalance,
};
use atmoscope_model::white_balance;
use glam::DVec3;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;
use web_time::Instant;

use changes::*;
use dispatch::*;
use encoder::*;
use rebuild::*;
use schedule::*;
use slices::*;
pub use stats::{
    EngineError, FrameStats, MovingSkyStep, RebuildProgress, Spans, TimingSource, capture,
};
use target::*;
pub use timing::Timestamps;
use timing::*;

/// Most passes a model may have (the size of the timestamp query set is twice this).
pub const MAX_PASSES: usize = 64;

/// Bytes before the list of `ExactTiles` in `shaders/common/bindings.wgsl`: the indirect
/// dispatch's three workgroup counts and the number of tiles.
const EXACT_TILES_HEADER_BYTES: u64 = 16;

struct AtmosphereState {
    key: AtmosphereKey,
    params: Params,
    tables: TableBuffers,
    /// The white of the noon sun through this atmosphere, once a white balance asks for it.
    noon_white: std::sync::OnceLock<Xyz>,
    /// The model's constants for these optics (`GpuMethod::constants`, `globals.model`),
    /// computed once: some fit the medium (O'Neil's scale function, the exponential fits).
    model_constants: crate::methods::ModelConstants,
    moving_sky: MovingSky,
}

/// The moving sky of a march per pixel (`methods::MOVING_SKY`) where the engine slices its
/// work. Built whole it would cost a frame many times its budget each time the sun moves in
/// motion, so once one is complete, a new one is built
/// in slices across frames in `TableBuffers::next_moving_sky`, from the globals of the frame
/// that started it, while the sky pass reads the last complete one (the sky of a slightly
/// earlier sun or altitude, turned to the sun's azimuth of the moment), then copied over it.
/// A change while one is being built waits for it to finish, then starts the next.
struct MovingSky {
    /// Whether the table the sky pass reads holds a complete moving sky (of any inputs).
    complete: bool,
    /// The next one, being built.
    job: Option<Slices>,
    /// Workgroups per slice the last one reached, and the shortest interval it saw from a
    /// slice's submission to seeing it finished, s (`Slices::steered`).
    units: u32,
    shortest_s: f64,
}

impl Default for MovingSky {
    fn default() -> MovingSky {
        MovingSky {
            complete: false,
            job: None,
            units: 1,
            shortest_s: f64::INFINITY,
        }
    }
}

/// Renders views of scenes with any real-time model of the registry.
pub struct Engine {
    device: wgpu::Device,
    queue: wgpu::Queue,
    /// Compiled passes of every model used so far; the last one used is first.
    pipelines: Vec<Pipelines>,
    atmosphere: Option<AtmosphereState>,
    /// A new atmosphere being built in slices while `atmosphere` stays on screen.
    rebuild: Option<Rebuild>,
    /// The still frame after frames in tiles, being drawn in slices.
    refine: Option<Slices>,
    slicing: Option<Slicing>,
    /// Whether a rebuild in slices waits this frame (`Engine::hold_rebuild`).
    rebuild_held: bool,
    /// Whether slices are timed alone ([`Slicing::alone`]): on a CPU adapter.
    slices_alone: bool,
    metering: bool,
    /// Units per slice each pass of a model reached in its last rebuild in slices.
    slice_units: Vec<(Method, Vec<u32>)>,
    target: Option<Target>,
    last: Option<Snapshot>,
    /// Inputs the next frame treats as changed whatever the scene (`invalidate_inputs`).
    forced: Inputs,
    timer: Timer,
    measure: bool,
    /// Timing in spans rather than per pass (`Engine::set_span_timing`).
    spans: bool,
    stats: FrameStats,
    /// Passes left stale because the last frames did not need them (by pass index of the
    /// model on screen); they run as soon as a frame needs them.
    deferred: Vec<bool>,
    /// Invocations of a workgroup that shares a texel (`prelude::texel_group_size`).
    texel_group_size: u32,
    /// Tile of the sky pass in frames that redraw because something changed (1: none).
    sky_tile: u32,
    /// Whether the view on screen was drawn in tiles (the next still frame redraws it).
    tiled_on_screen: bool,
    /// Whether the radiance image holds the view on screen (a frame in tiles that nothing
    /// meters draws the display image alone).
    radiance_current: bool,
    /// Whether the sky pass runs in bands (`set_view_bands`).
    view_bands: bool,
}

impl Engine {
    /// Compiles the passes on `device`. Timestamp queries are used when the device has the
    /// `TIMESTAMP_QUERY` feature; otherwise timing falls back to fenced CPU wall time.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Engine {
        let timer = if device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            Timer::Gpu(Timestamps::new(device, queue, MAX_PASSES as u32))
        } else {
            Timer::Cpu
        };
        Engine {
            device: device.clone(),
            queue: queue.clone(),
            pipelines: Vec::new(),
            atmosphere: None,
            rebuild: None,
            refine: None,
            slicing: None,
            rebuild_held: false,
            slices_alone: device.adapter_info().device_type == wgpu::DeviceType::Cpu,
            metering: false,
            slice_units: Vec::new(),
            target: None,
            last: None,
            forced: Inputs::NONE,
            timer,
            measure: false,
            spans: false,
            stats: FrameStats::default(),
            deferred: Vec::new(),
            texel_group_size: texel_group_size(device.adapter_info().device_type),
            sky_tile: 1,
            tiled_on_screen: false,
            radiance_current: true,
            view_bands: true,
        }
    }

    /// Draws the sky of a frame that redraws because its inputs changed (a view in motion) at
    /// the corners of `tile` × `tile` tiles, interpolated inside those that are smooth
    /// (`shaders/views/sky.wgsl`), and the first frame after it whose inputs did not change at
    /// full resolution, so a still view is exact. Such a frame writes the displayed image
    /// alone unless the engine meters (`set_metering`): a frame that changes only the display
    /// after it redraws the view at full resolution too, and `read_radiance` waits for that.
    /// 1 (the default) draws every frame at full resolution; at most 16.
    pub fn set_sky_tile(&mut self, tile: u32) {
        let tile = tile.clamp(1, views::MAX_SKY_TILE);
        if tile != self.sky_tile {
            self.sky_tile = tile;
            // The list of tiles is sized for the tile: new images, redrawn (a rebuild under
            // way would bring images sized for the old one).
            self.target = None;
            self.rebuild = None;
            self.refine = None;
            self.tiled_on_screen = false;
            self.drop_moving_sky_job();
        }
    }

    /// Draws the sky pass in bands of rows that see sky alone, ground alone or both, and the
    /// sun's disk in a dispatch of its own, each compiled without the code its pixels cannot
    /// need (on, the default: a software GPU runs both sides of every branch), or as one
    /// dispatch that decides per pixel (a GPU, where a branch costs a warp that takes both
    /// sides and each dispatch a fixed time: `views::view_bands`). The images are the same.
    pub fn set_view_bands(&mut self, on: bool) {
        self.view_bands = on;
    }

    /// Whether a frame of an unchanged scene would still draw: a rebuild in slices is under
    /// way, the frame on screen was drawn in tiles and awaits its full resolution, or a moving
    /// sky is being built in slices.
    pub fn settling(&self) -> bool {
        self.rebuilding() || self.tiled_on_screen || self.building_moving_sky()
    }

    /// Whether a moving sky is being built in slices (`FrameStats::moving_sky`).
    pub fn building_moving_sky(&self) -> bool {
        self.atmosphere
            .as_ref()
            .is_some_and(|a| a.moving_sky.job.is_some())
    }

    /// Compiles passes that share a texel among a workgroup with workgroups of `n` invocations
    /// (a power of two, 1–256) instead of the adapter's choice, and splits marches as that size
    /// does (`prelude::march_split`); the tables come out the same up to f32 rounding, only the
    /// speed differs. Forgets every compiled pass and table.
    pub fn set_texel_group_size(&mut self, n: u32) {
        self.texel_group_size = n.clamp(1, 256).next_power_of_two();
        self.forget_gpu_state();
        self.deferred.clear();
    }

    /// Drops every compiled pass, table and target and the last frame's inputs, so that the
    /// next frame builds everything anew.
    fn forget_gpu_state(&mut self) {
        self.pipelines.clear();
        self.atmosphere = None;
        self.rebuild = None;
        self.refine = None;
        self.target = None;
        self.last = None;
    }

    /// Forgets the previous frame, so the next one runs every pass (a full rebuild).
    pub fn invalidate(&mut self) {
        self.last = None;
    }

    /// Makes the next frame run what it would if `inputs` had changed (e.g. the viewpoint:
    /// the view tables), whatever the scene.
    pub fn invalidate_inputs(&mut self, inputs: Inputs) {
        self.forced = self.forced.union(inputs);
    }

    /// How a new atmosphere is built: `None` (the default) builds everything in the frame that
    /// asks for it; `Some(t)` builds it in slices of about `t` each, one slice in flight at a
    /// time, across as many frames as it takes, while the previous atmosphere stays on screen
    /// (or, for the first, nothing is drawn and `FrameStats::rebuild` says how far it has
    /// come) and the view keeps responding (for a window).
    /// `Duration::ZERO` makes every slice after a pass's first half a row of its workgroups
    /// (and of the tables' zeroing 16 MiB).
    pub fn set_rebuild_slices(&mut self, target: Option<Duration>) {
        let alone = self.slices_alone;
        self.slicing = target.map(|target| Slicing { target, alone });
        if self.slicing.is_none() {
            self.rebuild = None;
            self.refine = None;
            self.drop_moving_sky_job();
        }
    }

    /// The time budget of a slice of a rebuild, None where rebuilds are built whole
    /// (`set_rebuild_slices`).
    pub fn rebuild_slices(&self) -> Option<Duration> {
        self.slicing.map(|s| s.target)
    }

    /// Holds a rebuild in slices where it is (`true`) or lets it go on (`false`, the default):
    /// a window whose engines share one budget of GPU time per frame lets one of them build at
    /// a time. A held engine keeps drawing what is on screen.
    pub fn hold_rebuild(&mut self, hold: bool) {
        self.rebuild_held = hold;
    }

    /// Turns the luminance histogram of the view on or off (`METER_PASS`; off by default, as
    /// no frame should count what nobody reads). While on, every frame that redraws the view
    /// counts it; `histogram` reads the last count.
    pub fn set_metering(&mut self, on: bool) {
        self.metering = on;
    }

    /// View passes this engine leaves out.
    fn unwanted(&self) -> &'static [&'static str] {
        if self.metering {
            &[]
        } else {
            &[METER_PASS.name]
        }
    }

    /// The luminance histogram of the last view drawn while metering.
    pub fn histogram(&self) -> Result<Histogram, EngineError> {
        let target = self.target.as_ref().ok_or(EngineError::NotRendered)?;
        let words = capture(&self.device, || {
            read_buffer_u32(&self.device, &self.queue, &target.histogram)
        })??;
        Ok(Histogram { counts: words })
    }

    /// Whether a rebuild in slices is under way (the caller should keep drawing frames).
    pub fn rebuilding(&self) -> bool {
        self.rebuild.is_some()
    }

    /// Turns per-pass timing on or off. Timing waits for the GPU at the end of each frame.
    pub fn set_timing(&mut self, on: bool) {
        self.measure = on;
    }

    /// With timing on, measures each frame's span (`FrameStats::spans_ms`) instead of each
    /// pass: the frame runs as it does untimed (its dispatches sharing compute passes, those
    /// that only read the same tables side by side on a GPU), stamped only at its ends and
    /// where its tables end. Timed per pass, each dispatch has a compute pass and stamps of
    /// its own, and runs alone. Fenced CPU time sums the passes either way.
    pub fn set_span_timing(&mut self, on: bool) {
        self.spans = on;
    }

    /// Measures with fenced CPU wall time even where timestamp queries exist (software
    /// drivers such as lavapipe stamp commands when they are recorded, not when they run).
    pub fn force_cpu_timing(&mut self) {
        self.timer = Timer::Cpu;
    }

    /// Where per-pass times come from on this device.
    pub fn timing_source(&self) -> TimingSource {
        match self.timer {
            Timer::Gpu(_) => TimingSource::GpuTimestamps,
            Timer::Cpu => TimingSource::CpuFenced,
        }
    }

    /// What the last frame ran, skipped and measured.
    pub fn stats(&self) -> &FrameStats {
        &self.stats
    }

    /// The optics of the current atmosphere.
    pub fn params(&self) -> Option<&Params> {
        self.atmosphere.as_ref().map(|a| &a.params)
    }

    /// The passes of the model last rendered.
    pub fn method(&self) -> Option<&GpuMethod> {
        self.pipelines.first().map(|p| &p.method)
    }

    /// Bytes of the current model's tables on the GPU.
    pub fn table_bytes(&self) -> u64 {
        self.atmosphere.as_ref().map_or(0, |a| a.tables.bytes())
    }

    /// Makes the pipelines of `method` the first, compiling them on first use.
    fn select(&mut self, method: &GpuMethod) {
        let i = self.pipelines_of(method);
        if i > 0 {
            let p = self.pipelines.remove(i);
            self.pipelines.insert(0, p);
        }
    }

    /// Index of the pipelines of `method`, compiled on first use.
    fn pipelines_of(&mut self, method: &GpuMethod) -> usize {
        match self
            .pipelines
            .iter()
            .position(|p| p.method.method == method.method)
        {
            Some(i) => i,
            None => {
                self.pipelines
                    .push(Pipelines::new(&self.device, method, self.texel_group_size));
                self.pipelines.len() - 1
            }
        }
    }

    /// Renders `view` of `scene` with the scene's model, running only the passes whose inputs
    /// changed since the last frame. Returns the frame's statistics. The work is submitted; it
    /// finishes on the GPU. A model with no real-time passes (the path tracer) is refused.
    /// GPU faults come back as [`EngineError::Gpu`]; the next frame then rebuilds everything.
    pub fn try_render(&mut self, scene: &Scene, view: &View) -> Result<&FrameStats, EngineError> {
        let device = self.device.clone();
        match capture(&device, || self.render_frame(scene, view)) {
            Ok(Ok(())) => {
                // What a web page reads back must show this frame (`readback::written`).
                #[cfg(target_arch = "wasm32")]
                if self.stats.dispatched > 0
                    || !self.stats.run.is_empty()
                    || self.stats.rebuild_done
                    || self.refine.is_some()
                {
                    self.forget_reads();
                }
                Ok(&self.stats)
            }
            Ok(Err(e)) => {
                if matches!(e, EngineError::CannotDraw(_)) {
                    // Nothing ran for this scene: no earlier model's passes on show.
                    self.stats = FrameStats {
                        method: scene.render.method,
                        ..FrameStats::default()
                    };
                }
                Err(e)
            }
            Err(fault) => {
                // Whatever the frame created may be invalid: start from nothing.
                self.forget_gpu_state();
                Err(fault)
            }
        }
    }

    /// Renders `scene` as a still: with automatic exposure (`display.auto_exposure`) the view is
    /// metered and shown at once at the metered exposure (a window adapts over frames
    /// instead). Returns the scene as shown (its exposure the one used) and the metered
    /// log-average luminance, cd/m².
    pub fn render_still(
        &mut self,
        scene: &Scene,
        view: &View,
    ) -> Result<(Scene, Option<f64>), EngineError> {
        let auto = scene.display.auto_exposure;
        self.set_metering(auto);
        // A still shows the scene as it is: a rebuild in slices is finished first, held or not.
        let held = std::mem::replace(&mut self.rebuild_held, false);
        let mut drawn = self.try_render(scene, view).map(|_| ());
        while drawn.is_ok() && self.rebuilding() {
            self.wait();
            drawn = self.try_render(scene, view).map(|_| ());
        }
        self.rebuild_held = held;
        drawn?;
        let mut shown = scene.clone();
        let metered = if auto {
            self.histogram()?.log_average_cd_m2()
        } else {
            None
        };
        if let Some(l) = metered {
            shown.display.exposure_ev =
                atmoscope_model::display::metered_exposure_ev(l, scene.display.compensation_ev);
            // Only the display pass runs again (with tiles, after one at full resolution).
            self.try_render(&shown, view)?;
        }
        Ok((shown, metered))
    }

    /// [`Engine::try_render`] for callers that have already checked the scene's model draws
    /// it (`ModelInfo::cannot_draw`); a path-tracer scene or a refused view renders nothing and
    /// reports no pass.
    pub fn render(&mut self, scene: &Scene, view: &View) -> &FrameStats {
        if self.try_render(scene, view).is_err() {
            self.stats = FrameStats {
                method: scene.render.method,
                ..FrameStats::default()
            };
        }
        &self.stats
    }

    /// In a browser: forgets the read-backs of this engine's images and tables, which its
    /// frame may have written.
    #[cfg(target_arch = "wasm32")]
    fn forget_reads(&self) {
        use crate::readback::Source;
        let mut sources = Vec::new();
        if let Some(t) = &self.target {
            sources.extend([
                Source::Texture(&t.radiance),
                Source::Texture(&t.display),
                Source::Buffer(&t.histogram),
            ]);
        }
        if let Some(a) = &self.atmosphere {
            sources.extend(a.tables.table_buffers().map(Source::Buffer));
        }
        crate::readback::written(&sources);
    }

    /// Blocks until the GPU has finished all submitted work.
    pub fn wait(&self) {
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
    }

    /// The view's linear radiance: linear sRGB with Y = ∫ȳL dλ (W·m⁻²·sr⁻¹), alpha 1 where the
    /// projection shows the sky and 0 outside (the fisheye's corners). Rgba32Float.
    pub fn radiance_texture(&self) -> Option<&wgpu::Texture> {
        self.target.as_ref().map(|t| &t.radiance)
    }

    /// The view as displayed: sRGB-encoded Rgba8Unorm.
    pub fn display_texture(&self) -> Option<&wgpu::Texture> {
        self.target.as_ref().map(|t| &t.display)
    }

    /// A sampled view of the displayed image, its sRGB-encoded bytes as they are: what egui-wgpu
    /// takes for an image of the UI (Rgba8Unorm, not an sRGB view, which would decode the
    /// bytes once more and darken the picture). Recreated when the view's size changes.
    pub fn display_view(&self) -> Option<wgpu::TextureView> {
        self.display_texture().map(|t| {
            t.create_view(&wgpu::TextureViewDescriptor {
                label: Some("display (sampled)"),
                usage: Some(wgpu::TextureUsages::TEXTURE_BINDING),
                ..Default::default()
            })
        })
    }

    /// Reads the linear radiance back, row-major from the top row; [`EngineError::InMotion`]
    /// while the view on screen was drawn in tiles without it (the next frame, still, draws
    /// it).
    pub fn read_radiance(&self) -> Result<Vec<[f32; 4]>, EngineError> {
        let t = self.radiance_texture().ok_or(EngineError::NotRendered)?;
        if !self.radiance_current {
            return Err(EngineError::InMotion);
        }
        Ok(capture(&self.device, || {
            read_texture_f32x4(&self.device, &self.queue, t)
        })??)
    }

    /// Reads the displayed image back as RGBA8, row-major from the top row.
    pub fn read_display(&self) -> Result<Vec<u8>, EngineError> {
        let t = self.display_texture().ok_or(EngineError::NotRendered)?;
        Ok(capture(&self.device, || {
            read_texture(&self.device, &self.queue, t)
        })??)
    }

    /// Reads one lookup table back: every texel of every layer (batch), in the order of
    /// `model::methods::shared::Lut`.
    pub fn read_table(&self, id: &str) -> Result<Vec<[f32; 4]>, EngineError> {
        let buffer = self
            .atmosphere
            .as_ref()
            .ok_or(EngineError::NotRendered)?
            .tables
            .buffer(id)
            .ok_or_else(|| EngineError::NoSuchTable(id.to_string()))?;
        Ok(capture(&self.device, || {
            read_buffer_f32x4(&self.device, &self.queue, buffer)
        })??)
    }
}
