//! The engine: GPU resources for one scene and one view, the passes of the scene's model with
//! dirty tracking, and per-pass timing. It takes a `wgpu::Device` and `Queue` from its caller (a
//! window, the command line or a test) and renders into textures. It knows no model: the passes
//! come as data from `crate::methods` and the tables from the model registry.
//!
//! A frame compares the scene's inputs with the previous frame's and runs exactly the passes
//! that read an input that changed or a table rewritten earlier in the same frame (see
//! docs/ARCHITECTURE.md): physics rebuilds the whole chain, the sun or the camera's altitude
//! rebuilds the view tables, turning the camera redraws the view, exposure re-runs only the
//! display pass, an unchanged frame runs nothing. Passes marked `Repeat::PerOrder` (an order
//! loop) are encoded once per scattering order from 2 to the scene's count.

use crate::DisplayMode;
use crate::methods::{
    Constant, Dispatch, GpuMethod, HISTOGRAM, METER_PASS, PassSpec, RADIANCE, Repeat, gpu_method,
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
use std::time::{Duration, Instant};

/// Most passes a model may have (the size of the timestamp query set is twice this).
pub const MAX_PASSES: usize = 64;

/// Bytes before the list of `ExactTiles` in `shaders/common/bindings.wgsl`: the indirect
/// dispatch's three workgroup counts and the number of tiles.
const EXACT_TILES_HEADER_BYTES: u64 = 16;

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
    /// How far a rebuild in slices has come (`Engine::set_rebuild_slices`); the frame drew
    /// the previous atmosphere.
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

/// Runs `f` inside wgpu error scopes for validation, out-of-memory and internal errors, so that
/// a fault (an absurd size, a lost device, a driver failure) is an error for the caller instead
/// of wgpu's default handler, which panics.
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

#[derive(Debug, Clone, PartialEq)]
struct AtmosphereKey {
    settings: AtmosphereSettings,
    method: Method,
    wavelengths: WavelengthSet,
    quality: Quality,
    scattering_orders: u32,
    fitted_constants: FittedConstants,
}

impl AtmosphereKey {
    /// The key with the ground albedo left out (`Inputs::GROUND_ALBEDO` apart).
    fn without_albedo(&self) -> AtmosphereKey {
        let mut k = self.clone();
        k.settings.ground_albedo = 0.0;
        k
    }
}

#[derive(Debug, Clone, PartialEq)]
struct Snapshot {
    /// The atmosphere's key without the ground albedo, which is apart.
    atmosphere: AtmosphereKey,
    ground_albedo: f64,
    viewpoint: [f64; 2],
    /// The sun's direction and the scale of its light (`SunSettings::sunlight_scale`).
    sun: [f64; 4],
    camera: (CameraSettings, Projection),
    size: [u32; 2],
    display: (f64, ToneMap, DisplayMode, bool, WhiteBalance, bool),
}

impl Snapshot {
    fn changes_from(&self, previous: Option<&Snapshot>) -> Inputs {
        let Some(p) = previous else {
            return Inputs::ALL;
        };
        let mut c = Inputs::NONE;
        let mut mark = |changed: bool, i: Inputs| {
            if changed {
                c = c.union(i);
            }
        };
        mark(self.atmosphere != p.atmosphere, Inputs::ATMOSPHERE);
        mark(self.ground_albedo != p.ground_albedo, Inputs::GROUND_ALBEDO);
        mark(self.viewpoint != p.viewpoint, Inputs::VIEWPOINT);
        mark(self.sun != p.sun, Inputs::SUN);
        mark(self.camera != p.camera, Inputs::CAMERA);
        mark(self.size != p.size, Inputs::VIEW_SIZE);
        mark(self.display != p.display, Inputs::DISPLAY);
        c
    }
}

/// What a frame draws, from the scene and the atmosphere on screen.
struct FrameSetup {
    snapshot: Snapshot,
    globals: Globals,
    sun: DVec3,
    size: [u32; 2],
    camera: Camera,
    bottom_radius_m: f64,
    /// Whether the camera is above the top of the atmosphere.
    above: bool,
    /// Whether a view ray may start with the sun below Bruneton's tables (from above the
    /// atmosphere, or with the sun that low at the camera).
    sun_below_tables: bool,
    /// Pixels on a side of the sky pass's interpolated tiles this frame (1: every pixel).
    sky_tile: u32,
    /// Whether the sky pass writes the radiance image: all but a frame in tiles that nothing
    /// meters.
    write_radiance: bool,
    /// Whether the sky pass runs in bands of what the rows see, the sun's disk apart
    /// (`Engine::set_view_bands`), or as one dispatch.
    bands: bool,
}

impl FrameSetup {
    fn new(scene: &Scene, view: &View, state: &AtmosphereState, gpu: &GpuMethod) -> FrameSetup {
        let params = &state.params;
        let camera = Camera::new(&scene.camera, params.bottom_radius_m, view.projection);
        let a = scene.sun.angles();
        let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
        let viewpoint = viewpoint(scene, &camera);
        let size = [view.width.max(1), view.height.max(1)];
        let snapshot = Snapshot {
            atmosphere: state.key.without_albedo(),
            ground_albedo: state.key.settings.ground_albedo,
            viewpoint: [viewpoint.h, viewpoint.mu_s],
            sun: sun.extend(scene.sun.sunlight_scale()).to_array(),
            camera: (scene.camera.clone(), view.projection),
            size,
            display: (
                scene.display.exposure_ev,
                scene.display.tone_map,
                view.mode,
                scene.display.dither,
                scene.display.white_balance,
                scene.display.glare,
            ),
        };
        let globals = Globals::from(&FrameInputs {
            scene,
            params,
            camera: &camera,
            sun,
            viewpoint,
            size,
            mode: view.mode,
            model: (gpu.constants)(params),
            // Only a display that shows glare pays for its source.
            glare: (scene.display.glare && view.mode == DisplayMode::Colour).then(|| {
                atmoscope_model::display::sun_irradiance_rgb(params, viewpoint.h, viewpoint.mu_s)
            }),
            balance: white_balance::matrix_with(scene, || {
                *state.noon_white.get_or_init(|| {
                    white_balance::noon_sun_white(&Atmosphere::new(&state.key.settings))
                })
            }),
        });
        let above = viewpoint.h > params.thickness_m();
        FrameSetup {
            snapshot,
            globals,
            sun,
            size,
            camera,
            bottom_radius_m: params.bottom_radius_m,
            above,
            sun_below_tables: above
                || viewpoint.mu_s < atmoscope_model::methods::bruneton::MU_S_MIN,
            sky_tile: 1,
            write_radiance: true,
            bands: true,
        }
    }

    fn shows_ground(&self, view: &View) -> bool {
        self.camera
            .shows_ground(self.bottom_radius_m, view.width, view.height)
    }

    /// A pipeline constant's value in this frame; a dispatch over the whole view draws the
    /// sun's disk and decides sky or ground per pixel.
    fn value(&self, c: Constant, scene: &Scene, view: &View) -> u32 {
        match c {
            Constant::Projection => uniforms::projection_code(view.projection),
            Constant::AboveAtmosphere => u32::from(self.above),
            Constant::DisplayMode => uniforms::display_code(view.mode),
            Constant::ToneMap => uniforms::tone_map_code(scene.display.tone_map),
            Constant::SunDisk => 1,
            Constant::ViewRegion => uniforms::region_code(Sees::Both),
            Constant::SkyTile => 1,
            Constant::SkyTileExact => 0,
            Constant::Glare => u32::from(scene.display.glare && view.mode == DisplayMode::Colour),
            Constant::WriteRadiance => u32::from(self.write_radiance),
            Constant::FirstOrder => 1,
            Constant::SunBelowTables => u32::from(self.sun_below_tables),
        }
    }

    /// Each pass's pipeline constants for a dispatch over all of it.
    fn variants(&self, pipelines: &Pipelines, scene: &Scene, view: &View) -> Vec<Variant> {
        (0..pipelines.len())
            .map(|i| pipelines.variant(i, |c| self.value(c, scene, view)))
            .collect()
    }

    /// The dispatches of pass `i` this frame. A view pass that takes the region runs in bands
    /// of rows that see sky alone, ground alone or both (`Camera::rows_see`), and one that
    /// takes the sun's disk draws it in one more dispatch over the pixels the disk reaches
    /// (`SunInView::pixel_box`), so that no pixel runs the code of what it cannot see (a
    /// software GPU runs both sides of every branch). A frame with tiles (`sky_tile` > 1)
    /// runs the sky pass as one dispatch of tiles, which decides sky or ground per corner and
    /// lists the tiles it cannot interpolate, an indirect dispatch over those, then the sun's
    /// disk pixel by pixel. Without bands (`Engine::set_view_bands`) a frame at full
    /// resolution is one dispatch, as is any other pass.
    fn work(
        &self,
        pipelines: &Pipelines,
        step: Step,
        layers: u32,
        scene: &Scene,
        view: &View,
    ) -> Vec<Work> {
        let i = step.pass;
        let grid = grid(pipelines, i, layers, self.size);
        let constants = pipelines.specs().nth(i).map_or(&[][..], |s| s.constants);
        let variant = |region: Sees, sun: bool, tile: u32, exact: bool| {
            pipelines.variant(i, |c| match c {
                Constant::SunDisk => u32::from(sun),
                Constant::ViewRegion => uniforms::region_code(region),
                Constant::SkyTile => tile,
                Constant::SkyTileExact => u32::from(exact),
                Constant::FirstOrder => step.first_order(),
                other => self.value(other, scene, view),
            })
        };
        let takes = |c: Constant| constants.contains(&c);
        let tile = self.sky_tile;
        let tiled = takes(Constant::SkyTile) && tile > 1;
        if (!takes(Constant::ViewRegion) && !takes(Constant::SunDisk)) || (!self.bands && !tiled) {
            return vec![Work::whole(i, variant(Sees::Both, true, 1, false), grid)];
        }
        let [w, h] = self.size;
        let mut work = Vec::new();
        if tiled {
            let span = WORKGROUP_SIZE * tile;
            work.push(Work {
                tiles: TilePhase::Fill,
                ..Work::whole(
                    i,
                    variant(Sees::Both, false, tile, false),
                    [w.div_ceil(span), h.div_ceil(span), 1],
                )
            });
            work.push(Work {
                tiles: TilePhase::Compute,
                ..Work::whole(i, variant(Sees::Both, false, tile, true), [0; 3])
            });
        } else if takes(Constant::ViewRegion) && !self.above {
            let rows = self.camera.rows_see(self.bottom_radius_m, w, h);
            let group_rows: Vec<Sees> = rows
                .chunks(WORKGROUP_SIZE as usize)
                .map(|c| {
                    if c.iter().all(|&s| s == c[0]) {
                        c[0]
                    } else {
                        Sees::Both
                    }
                })
                .collect();
            let mut start = 0;
            for (g, &seen) in group_rows.iter().enumerate() {
                if group_rows.get(g + 1) != Some(&seen) {
                    work.push(Work {
                        pass: i,
                        variant: variant(seen, false, 1, false),
                        origin: [0, start as u32 * WORKGROUP_SIZE, 0],
                        groups: [grid[0], (g + 1 - start) as u32, 1],
                        tiles: TilePhase::None,
                    });
                    start = g + 1;
                }
            }
        } else {
            work.push(Work::whole(i, variant(Sees::Both, false, 1, false), grid));
        }
        let sun_box = self
            .camera
            .sun_in_view(self.sun, w, h)
            .and_then(|s| s.pixel_box(w, h));
        if let (true, Some([x0, y0, x1, y1])) = (takes(Constant::SunDisk), sun_box) {
            work.push(Work {
                pass: i,
                variant: variant(Sees::Both, true, 1, false),
                origin: [x0, y0, 0],
                groups: [groups(x1 - x0), groups(y1 - y0), 1],
                tiles: TilePhase::None,
            });
        }
        work
    }
}

/// The passes to run (indices in order) when `changed` inputs changed: a pass is stale when an
/// input it reads changed, a table it reads was just rewritten or it was left stale before
/// (`deferred`); it runs when the view needs what it writes (from above the atmosphere a
/// marching sky pass reads fewer tables, Bruneton's and Elek's skies no camera slices there,
/// Bruneton's none with the sun below its tables, a view without ground none of those only the
/// ground's pixels read, and a frame not `in_motion` (drawn in tiles) no moving sky), and
/// otherwise stays marked in `deferred`.
fn plan(
    pipelines: &Pipelines,
    changed: Inputs,
    above: bool,
    sun_below_tables: bool,
    ground: bool,
    in_motion: bool,
    unwanted: &[&str],
    deferred: &mut [bool],
) -> Vec<usize> {
    let info = pipelines.method.info();
    let specs: Vec<&PassSpec> = pipelines.specs().collect();
    let mut needed = vec![false; specs.len()];
    let mut needed_resources: Vec<&str> = Vec::new();
    for (i, spec) in specs.iter().enumerate().rev() {
        let wanted = !spec.is_table() && !unwanted.contains(&spec.name);
        if wanted || spec.writes.iter().any(|w| needed_resources.contains(w)) {
            needed[i] = true;
            needed_resources.extend(spec.reads_where(above, sun_below_tables, ground, in_motion));
        }
    }
    let mut written: Vec<&str> = Vec::new();
    let mut run = Vec::new();
    for (i, spec) in specs.iter().enumerate() {
        let stale = deferred[i]
            || spec.direct_inputs(info).intersects(changed)
            || spec.reads.iter().any(|r| written.contains(r));
        // A view pass whose every output an earlier pass of this frame wrote with the frame's
        // inputs (the sky pass draws the display image too) has nothing left to do.
        let covered = !spec.is_table() && spec.writes.iter().all(|w| written.contains(w));
        if covered {
            deferred[i] = false;
        } else if stale {
            deferred[i] = !needed[i];
            // A pass left stale rewrites nothing: its readers are not stale for it.
            if needed[i] {
                written.extend(spec.writes);
                run.push(i);
            }
        }
    }
    run
}

/// Workgroups of the whole dispatch of pass `i`.
fn grid(pipelines: &Pipelines, i: usize, layers: u32, size: [u32; 2]) -> [u32; 3] {
    let Some(spec) = pipelines.specs().nth(i) else {
        return [0; 3];
    };
    let info = pipelines.method.info();
    match spec.dispatch {
        Dispatch::View => [groups(size[0]), groups(size[1]), 1],
        Dispatch::Table(id) => {
            let [w, h, _] = info.table(id).map_or([1, 1, 1], |t| t.size);
            [groups(w), groups(h), layers]
        }
        Dispatch::TexelGroups(id) => {
            let [w, h, _] = info.table(id).map_or([1, 1, 1], |t| t.size);
            [w, h, layers]
        }
        Dispatch::TexelRuns(id) => {
            let [w, h, _] = info.table(id).map_or([1, 1, 1], |t| t.size);
            [w.div_ceil(texel_run(pipelines.texel_group_size)), h, layers]
        }
        Dispatch::Volume(id) => {
            let [w, h, d] = info.table(id).map_or([1, 1, 1], |t| t.size);
            [groups(w), groups(h), d * layers]
        }
    }
}

/// Units of work a pass is cut into when it runs in slices: its workgroups (a layer of a 3D
/// table being one of its slices of one batch; workgroups are one deep in z). Not rows: one
/// row of Bruneton's scattering density takes 60–117 ms on lavapipe, longer than a frame may.
fn units(grid: [u32; 3]) -> u32 {
    grid[0] * grid[1] * grid[2]
}

/// Where a slice of `count` units from unit `start` of a pass's `grid` lies: its origin
/// (invocations), its workgroups and the units it covers. A slice stays within one row of
/// workgroups when it starts inside one or is smaller than one, within one layer likewise;
/// otherwise it covers whole rows, or whole layers.
fn slice(grid: [u32; 3], start: u32, count: u32) -> ([u32; 3], [u32; 3], u32) {
    let row = grid[0].max(1);
    let layer = row * grid[1].max(1);
    let (z, x, y) = (start / layer, start % row, start % layer / row);
    if x != 0 || count < row {
        let n = count.clamp(1, row - x);
        ([x * WORKGROUP_SIZE, y * WORKGROUP_SIZE, z], [n, 1, 1], n)
    } else if y != 0 || count < layer {
        let rows = (count / row).clamp(1, grid[1] - y);
        ([0, y * WORKGROUP_SIZE, z], [row, rows, 1], rows * row)
    } else {
        let layers = (count / layer).clamp(1, grid[2] - z);
        ([0, 0, z], [row, grid[1], layers], layers * layer)
    }
}

/// Bytes a unit of the clearing of a rebuild's tables covers.
const CLEAR_UNIT_BYTES: u64 = 1 << 20;

/// How a rebuild runs in slices.
#[derive(Debug, Clone, Copy)]
struct Slicing {
    /// GPU time each slice aims at (zero: half a row of workgroups each, so that slices also
    /// start inside rows, and 16 MiB of the tables' zeroing).
    target: Duration,
    /// Whether each slice is timed alone, waited for with the GPU idle before it (a CPU
    /// adapter, `Engine::new`), rather than by the interval until a later frame sees it done.
    alone: bool,
}

/// Share of the target a slice timed alone aims at. Its time is its own, where an interval
/// until a later frame saw it done also held a share of that frame's work, which had left
/// room for a slice costing more per workgroup than the last (rows of the sky with the sun or
/// the horizon in them, Bruneton's scattering density): aimed at the whole target, Hillaire's
/// Spectral32 still frame after a turn took up to 104 ms a frame on lavapipe.
const ALONE_AIM: f64 = 0.75;

/// How long a slice took: timed alone ([`Slicing::alone`]), or from its submission to the
/// frame that sees it finished (the flag set once the GPU has), that frame's own work included.
#[derive(Debug, Clone)]
enum SliceClock {
    Alone(f64),
    Since(Instant, Arc<AtomicBool>),
}

impl SliceClock {
    /// Submits a slice through `submit` and starts its clock. Timed alone, it waits for the
    /// GPU to be idle, then for the slice: on a CPU adapter the GPU is the CPU's other threads,
    /// so waiting costs the frame nothing, and the interval until a later frame saw a slice
    /// done was mostly that frame's own work, whose spread from frame to frame (20–40 ms on
    /// lavapipe) the steering took for the slice's cost and held slices to a workgroup.
    fn start(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        alone: bool,
        submit: impl FnOnce(),
    ) -> SliceClock {
        if !alone {
            submit();
            return SliceClock::Since(Instant::now(), when_done(queue));
        }
        let _ = device.poll(wgpu::PollType::wait_indefinitely());
        let start = Instant::now();
        submit();
        let _ = device.poll(wgpu::PollType::wait_indefinitely());
        SliceClock::Alone(start.elapsed().as_secs_f64())
    }

    /// Units for the next slice of the same work after this one of `count` units, aimed at
    /// `target_s`; `shortest_s` is the shortest interval the job has seen (`steered_units`),
    /// which a slice timed alone neither needs nor changes.
    fn steer(&self, count: u32, shortest_s: &mut f64, target_s: f64) -> u32 {
        match *self {
            SliceClock::Alone(took) => steered_units(count, took, 0.0, ALONE_AIM * target_s),
            SliceClock::Since(started, _) => {
                let took = started.elapsed().as_secs_f64();
                *shortest_s = shortest_s.min(took);
                steered_units(count, took, *shortest_s, target_s)
            }
        }
    }

    /// Whether the slice has finished (one timed alone has).
    fn finished(&self) -> bool {
        match self {
            SliceClock::Alone(_) => true,
            SliceClock::Since(_, done) => done.load(Ordering::Acquire),
        }
    }
}

/// One dispatch of a pass: its pipeline constants, where it starts in the pass's grid
/// (invocations) and its workgroups.
#[derive(Debug, Clone, Copy)]
struct Work {
    pass: usize,
    variant: Variant,
    origin: [u32; 3],
    groups: [u32; 3],
    tiles: TilePhase,
}

/// What a dispatch does with the list of tiles a sky drawn in tiles computes exactly.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum TilePhase {
    /// Nothing.
    None,
    /// Empties it, then fills it (the tiles' corners and their interpolation).
    Fill,
    /// Computes its tiles: an indirect dispatch of as many workgroups as it says.
    Compute,
}

impl Work {
    fn whole(pass: usize, variant: Variant, grid: [u32; 3]) -> Work {
        Work {
            pass,
            variant,
            origin: [0; 3],
            groups: grid,
            tiles: TilePhase::None,
        }
    }
}

/// A new atmosphere built a slice per frame while the previous one stays on screen.
struct Rebuild {
    state: AtmosphereState,
    target: Target,
    /// The frame the rebuild draws, and the passes it left stale (as a frame's).
    snapshot: Snapshot,
    deferred: Vec<bool>,
    variants: Vec<Variant>,
    /// The passes to run, in order, the order loop unrolled.
    run: Vec<Step>,
    /// The next slice: index into `run`, and its first unit (workgroups counted along rows,
    /// then rows, then layers).
    next: (usize, u32),
    /// Bytes of the new tables zeroed so far: the first slices clear them
    /// (`TableBuffers::clear`), `CLEAR_UNIT_BYTES` a unit.
    cleared: u64,
    /// Units per slice of each pass, and last those of the clearing, steered towards the
    /// target time (passes differ in cost per unit by a thousandfold, so a pass not met
    /// before starts with one unit; the engine keeps what it learnt for the model's next
    /// rebuild).
    units: Vec<u32>,
    /// The slice on the GPU: its clock, its pass (the
    /// last slot of `units` for the zeroing) and units, and the slice a zero target asks for
    /// (half a row of the pass's workgroups; 16 MiB of zeroing).
    in_flight: Option<(SliceClock, usize, u32, u32)>,
    done_units: u64,
    total_units: u64,
    /// The shortest interval from a slice's submission to seeing it finished, s.
    shortest_s: f64,
}

impl Rebuild {
    fn progress(&self) -> RebuildProgress {
        RebuildProgress {
            done: self.done_units,
            total: self.total_units,
        }
    }
}

/// Units for a pass's next slice: `count` units took `took_s` from submission to being seen
/// finished. That end is seen a frame later, so `took_s` holds the frame's own work too: most
/// of `shortest_s`, the shortest such interval of the job, is taken for that and set aside,
/// or a cheap pass would grow its slices by little more than target / frame per frame.
fn steered_units(count: u32, took_s: f64, shortest_s: f64, target_s: f64) -> u32 {
    let own = (took_s - 0.8 * shortest_s).max(0.1 * took_s).max(1e-4);
    let scaled = f64::from(count) * target_s / own;
    scaled.clamp(1.0, f64::from(count) * 16.0) as u32
}

/// Dispatches run a slice per frame where the engine slices its work
/// (`Engine::set_rebuild_slices`): the still frame after frames in tiles, drawn at full
/// resolution (a march per pixel takes seconds on a software adapter; the image in tiles stays
/// on screen and sharpens from the top down), and the next moving sky of a march per pixel
/// (`MovingSky`). Slices are counted in workgroups along rows, as a rebuild's ([`units`],
/// [`slice`]): one row of workgroups 1280 pixels wide takes about 105 ms of Nishita's march on
/// lavapipe and 230 ms of Gałaj's spline, longer than a frame may.
struct Slices {
    /// The frame's dispatches at full resolution, in order.
    work: Vec<Work>,
    /// The next slice: index into `work`, and its first workgroup (counted along rows).
    next: (usize, u32),
    /// Workgroups per slice, steered towards the target time.
    units: u32,
    /// The slice on the GPU: its clock and workgroups.
    in_flight: Option<(SliceClock, u32)>,
    /// The shortest interval from a slice's submission to seeing it finished, s.
    shortest_s: f64,
}

impl Slices {
    /// Slices of `work`, the first of one workgroup.
    fn new(work: Vec<Work>) -> Slices {
        Slices::steered(work, 1, f64::INFINITY)
    }

    /// Slices of `work` steered on from where earlier slices of the same dispatches left off:
    /// `units` workgroups first, `shortest_s` the shortest interval seen. Without the latter
    /// the first slice's whole interval, the frame's own work included, would be taken for
    /// the shortest, and the second slice sized five times too large.
    fn steered(work: Vec<Work>, units: u32, shortest_s: f64) -> Slices {
        Slices {
            work,
            next: (0, 0),
            units: units.max(1),
            in_flight: None,
            shortest_s,
        }
    }

    /// The next slice's dispatches: none while the last slice is on the GPU, None once every
    /// slice has finished. A slice runs on across rows (the rest of one, whole rows, the
    /// start of the next: up to three dispatches) so that it holds the units asked for, but
    /// stops at the end of a dispatch of the frame. A zero target takes half a row of
    /// workgroups a slice, so that slices also start inside rows.
    fn next_slice(&mut self, slicing: Slicing) -> Option<Vec<Work>> {
        let target = slicing.target.as_secs_f64();
        if let Some((clock, count)) = &self.in_flight {
            if !clock.finished() {
                return Some(Vec::new());
            }
            let steered = clock.steer(*count, &mut self.shortest_s, target);
            // A slice cut short at the end of a dispatch says little of the cost per
            // workgroup (the frame's own work can be most of its time): the size stays.
            if target > 0.0 && *count >= self.units {
                self.units = steered;
            }
            self.in_flight = None;
        }
        let (k, mut unit) = self.next;
        let w = *self.work.get(k)?;
        if target <= 0.0 {
            self.units = w.groups[0].div_ceil(2);
        }
        let (total, mut left) = (units(w.groups), self.units);
        let mut slice_work = Vec::new();
        while left > 0 && unit < total {
            let (origin, groups, count) = slice(w.groups, unit, left);
            slice_work.push(Work {
                origin: [
                    w.origin[0] + origin[0],
                    w.origin[1] + origin[1],
                    w.origin[2] + origin[2],
                ],
                groups,
                ..w
            });
            unit += count;
            left = left.saturating_sub(count);
        }
        self.next = if unit >= total { (k + 1, 0) } else { (k, unit) };
        Some(slice_work)
    }

    /// Marks the slice just submitted, with its `clock`, as on the GPU.
    fn submitted(&mut self, clock: SliceClock, work: &[Work]) {
        if !work.is_empty() {
            let count = work.iter().map(|w| units(w.groups)).sum();
            self.in_flight = Some((clock, count));
        }
    }
}

/// A flag set once the GPU has finished the work submitted to `queue` so far.
fn when_done(queue: &wgpu::Queue) -> Arc<AtomicBool> {
    let done = Arc::new(AtomicBool::new(false));
    let flag = done.clone();
    queue.on_submitted_work_done(move || flag.store(true, Ordering::Release));
    done
}

/// Encodes dispatches of one model over one atmosphere's tables and one view's images.
struct Encoder<'a> {
    device: &'a wgpu::Device,
    queue: &'a wgpu::Queue,
    pipelines: &'a Pipelines,
    tables: &'a TableBuffers,
    target: &'a Target,
    /// Where the work is a slice of the next moving sky, what it binds instead of the
    /// frame's globals and the table the sky pass reads.
    next_moving_sky: Option<&'a NextMovingSky>,
}

impl Encoder<'_> {
    /// Encodes and submits `work` (each at its origin) and returns per-pass times when
    /// `timer` is given: GPU timestamps, or fenced CPU time (one submission per pass). With
    /// `spans`, GPU timestamps are written only where the tables begin and end and where the
    /// last dispatch ends; fenced CPU time sums the passes. Untimed or in spans, consecutive
    /// dispatches share a compute pass: on an H100 dispatches in separate compute passes ran
    /// one after another even with no barrier between them, in one they overlap.
    fn submit(&self, work: &[Work], timer: Option<&Timer>, spans: bool) -> Timings {
        let gpu_timer = match timer {
            Some(Timer::Gpu(t)) => Some(t),
            _ => None,
        };
        let fenced = matches!(timer, Some(Timer::Cpu));
        let work = &work[..work.len().min(MAX_PASSES).min(ORIGIN_SLOTS)];
        let next = self.next_moving_sky;
        let group0 = next.map_or(&self.tables.group0, |n| &n.group0);
        let mut origins = vec![0u8; self.tables.origin_stride as usize * work.len()];
        for (slot, w) in work.iter().enumerate() {
            let origin = [w.origin[0], w.origin[1], w.origin[2], 0];
            let at = slot * self.tables.origin_stride as usize;
            origins[at..at + 16].copy_from_slice(bytemuck::cast_slice(&origin));
        }
        self.queue.write_buffer(&self.tables.origins, 0, &origins);
        let specs: Vec<_> = self.pipelines.specs().copied().collect();
        let last_table = work.iter().rposition(|w| specs[w.pass].is_table());
        let last = work.len().saturating_sub(1);
        // Span queries: 0 the first pass's start, 1 the end of the tables (or of the frame
        // when no table runs), 2 the frame's end when view passes follow the tables.
        let frame_end: u32 = match last_table {
            Some(t) if t != last => 2,
            _ => 1,
        };
        let mut timings = Vec::new();
        // Whether work needs the encoder itself before its dispatch (clears and copies,
        // which no compute pass may hold).
        // Histogram counts start from zero with the dispatch (or the first slice) that covers
        // the view's first pixel.
        let clears_histogram =
            |w: &Work| specs[w.pass].writes.contains(&HISTOGRAM) && w.origin == [0; 3];
        let needs_encoder = |w: &Work| clears_histogram(w) || w.tiles != TilePhase::None;
        // Untimed, or timed in spans, consecutive dispatches share one compute pass (wgpu
        // still puts a barrier wherever one reads what another wrote); the tables end theirs.
        let merge = !fenced && (spans || gpu_timer.is_none());
        let starts_pass =
            |s: usize| !merge || s == 0 || needs_encoder(&work[s]) || Some(s - 1) == last_table;
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let mut pass: Option<wgpu::ComputePass<'static>> = None;
        for (slot, w) in work.iter().enumerate() {
            let i = w.pass;
            let spec = &specs[i];
            let start = Instant::now();
            if starts_pass(slot) {
                drop(pass.take());
                if clears_histogram(w) {
                    encoder.clear_buffer(&self.target.histogram, 0, None);
                }
                match w.tiles {
                    TilePhase::Fill => encoder.clear_buffer(
                        &self.target.exact_tiles,
                        0,
                        Some(EXACT_TILES_HEADER_BYTES),
                    ),
                    // A dispatch may not bind the buffer that holds its own workgroup counts.
                    TilePhase::Compute => encoder.copy_buffer_to_buffer(
                        &self.target.exact_tiles,
                        0,
                        &self.target.exact_groups,
                        0,
                        Some(12),
                    ),
                    TilePhase::None => {}
                }
                // The last slot of this compute pass.
                let ends = (slot + 1..work.len())
                    .find(|&s| starts_pass(s))
                    .map_or(last, |s| s - 1);
                let timestamp_writes = gpu_timer.and_then(|t| {
                    if spans {
                        let end = if Some(ends) == last_table {
                            Some(1)
                        } else {
                            (ends == last).then_some(frame_end)
                        };
                        t.span_writes(slot == 0, end)
                    } else {
                        Some(t.writes(slot as u32))
                    }
                });
                pass = Some(
                    encoder
                        .begin_compute_pass(&wgpu::ComputePassDescriptor {
                            label: Some(spec.name),
                            timestamp_writes,
                        })
                        .forget_lifetime(),
                );
            }
            if let Some(cpass) = pass.as_mut() {
                let group = match (spec.dispatch, next) {
                    (Dispatch::View, _) => self.target.groups[i].as_ref(),
                    (_, Some(n)) => Some(&n.group1),
                    (_, None) => self.tables.group(i),
                };
                let dispatch = w.groups;
                if let (Some(group), Some(pipeline)) =
                    (group, self.pipelines.pipeline(i, w.variant))
                {
                    let offset = (slot as u64 * self.tables.origin_stride) as u32;
                    cpass.set_pipeline(pipeline);
                    cpass.set_bind_group(0, group0, &[offset]);
                    cpass.set_bind_group(1, group, &[]);
                    if w.tiles == TilePhase::Compute {
                        cpass.dispatch_workgroups_indirect(&self.target.exact_groups, 0);
                    } else {
                        cpass.dispatch_workgroups(dispatch[0], dispatch[1], dispatch[2]);
                    }
                }
            }
            if fenced {
                drop(pass.take());
                self.queue.submit([encoder.finish()]);
                let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
                timings.push((i, start.elapsed().as_secs_f64() * 1e3));
                encoder = self.device.create_command_encoder(&Default::default());
            }
        }
        drop(pass.take());
        match gpu_timer {
            Some(t) if spans => {
                // Only queries written this frame: resolving one never written waits forever.
                t.resolve(&mut encoder, frame_end + 1);
                self.queue.submit([encoder.finish()]);
                let ticks = t.read_ticks(self.device, frame_end + 1);
                let ms = |from: usize, to: u32| match (ticks.get(from), ticks.get(to as usize)) {
                    (Some(&a), Some(&b)) => b.saturating_sub(a) as f64 * t.period_ns * 1e-6,
                    _ => f64::NAN,
                };
                return Timings {
                    passes: Vec::new(),
                    spans: Some(Spans {
                        tables_ms: last_table.map(|_| ms(0, 1)),
                        frame_ms: ms(0, frame_end),
                    }),
                };
            }
            Some(t) => {
                t.resolve(&mut encoder, 2 * work.len() as u32);
                self.queue.submit([encoder.finish()]);
                timings.extend(
                    work.iter()
                        .map(|w| w.pass)
                        .zip(t.read_ms(self.device, work.len())),
                );
            }
            None => {
                self.queue.submit([encoder.finish()]);
            }
        }
        let spans = (spans && fenced).then(|| {
            let sum = |tables_only: bool| -> f64 {
                timings
                    .iter()
                    .filter(|(i, _)| !tables_only || specs[*i].is_table())
                    .map(|(_, ms)| ms)
                    .sum()
            };
            Spans {
                tables_ms: last_table.map(|_| sum(true)),
                frame_ms: sum(false),
            }
        });
        Timings {
            passes: if spans.is_some() { Vec::new() } else { timings },
            spans,
        }
    }
}

struct AtmosphereState {
    key: AtmosphereKey,
    params: Params,
    tables: TableBuffers,
    /// The white of the noon sun through this atmosphere, once a white balance asks for it.
    noon_white: std::sync::OnceLock<Xyz>,
    moving_sky: MovingSky,
}

/// The moving sky of a march per pixel (`methods::MOVING_SKY`) where the engine slices its
/// work. Built whole, it cost a frame 216–599 ms on lavapipe at Spectral4 (1.6 s for Nishita
/// at Spectral32) each time the sun moved in motion. Once one is complete, a new one is built
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

struct Target {
    size: [u32; 2],
    radiance: wgpu::Texture,
    display: wgpu::Texture,
    /// The view's luminance histogram (`METER_PASS`).
    histogram: wgpu::Buffer,
    /// The tiles a sky drawn in tiles computes pixel by pixel (`methods::EXACT_TILES`).
    exact_tiles: wgpu::Buffer,
    /// The workgroups of the dispatch that computes them, copied from `exact_tiles`.
    exact_groups: wgpu::Buffer,
    /// Group 1 of each view pass, by pass index (None for table passes).
    groups: Vec<Option<wgpu::BindGroup>>,
}

/// GPU timestamp queries around up to `passes` compute passes, and their read-back.
pub struct Timestamps {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    period_ns: f64,
}

impl Timestamps {
    /// Queries for `passes` passes (the device must have `TIMESTAMP_QUERY`).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, passes: u32) -> Timestamps {
        let count = 2 * passes;
        let bytes = u64::from(count) * 8;
        let buffer = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        Timestamps {
            queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: buffer(
                "timestamp resolve",
                wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            ),
            readback: buffer(
                "timestamp read-back",
                wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            ),
            period_ns: f64::from(queue.get_timestamp_period()),
        }
    }

    /// The timestamp writes of the pass in `slot`.
    pub fn writes(&self, slot: u32) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(2 * slot),
            end_of_pass_write_index: Some(2 * slot + 1),
        }
    }

    /// The stamps of a pass in a frame timed in spans, if any: query 0 at its start where it
    /// is the frame's first pass, query `end` at its end.
    fn span_writes(
        &self,
        first: bool,
        end: Option<u32>,
    ) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        (first || end.is_some()).then(|| wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: first.then_some(0),
            end_of_pass_write_index: end,
        })
    }

    /// Encodes the copy of the first `count` queries for [`Timestamps::read_ticks`].
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder, count: u32) {
        encoder.resolve_query_set(&self.queries, 0..count, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, 8 * u64::from(count));
    }

    /// The first `count` queries in ticks, once the resolving submission has run (waits for
    /// it); empty if the read-back failed.
    pub fn read_ticks(&self, device: &wgpu::Device, count: u32) -> Vec<u64> {
        map_u64(device, &self.readback).map_or_else(Vec::new, |mut ticks| {
            ticks.truncate(count as usize);
            ticks
        })
    }

    /// Milliseconds of the first `passes` slots (each a pass's start and end), once the
    /// resolving submission has run; empty if the read-back failed.
    pub fn read_ms(&self, device: &wgpu::Device, passes: usize) -> Vec<f64> {
        let ticks = self.read_ticks(device, 2 * passes as u32);
        ticks
            .chunks_exact(2)
            .map(|t| t[1].saturating_sub(t[0]) as f64 * self.period_ns * 1e-6)
            .collect()
    }
}

enum Timer {
    Gpu(Timestamps),
    Cpu,
}

/// What `Encoder::submit` measured: per-pass times (pass index, ms), or the frame's spans.
#[derive(Default)]
struct Timings {
    passes: Vec<(usize, f64)>,
    spans: Option<Spans>,
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
        self.pipelines.clear();
        self.atmosphere = None;
        self.rebuild = None;
        self.refine = None;
        self.target = None;
        self.last = None;
        self.deferred.clear();
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

    /// How a new atmosphere is built once one is on screen: `None` (the default) builds
    /// everything in the frame that asks for it; `Some(t)` builds it in slices of about `t`
    /// each, one slice in flight at a time, across as many frames as it takes, while the
    /// previous atmosphere stays on screen and the view keeps responding (for a window).
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
            Ok(Ok(())) => Ok(&self.stats),
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
                self.pipelines.clear();
                self.atmosphere = None;
                self.rebuild = None;
                self.refine = None;
                self.target = None;
                self.last = None;
                Err(fault)
            }
        }
    }

    fn render_frame(&mut self, scene: &Scene, view: &View) -> Result<(), EngineError> {
        let max = self.device.limits().max_texture_dimension_2d;
        if view.width > max || view.height > max {
            return Err(EngineError::ViewTooLarge(view.width, view.height, max));
        }
        let method = scene.render.method;
        if let Some(why) = methods::info(method).cannot_draw(scene) {
            return Err(why.into());
        }
        let gpu = gpu_method(method).ok_or_else(|| {
            CannotDraw::NotRealtime(methods::info(method).id, methods::realtime_ids())
        })?;
        let key = AtmosphereKey {
            settings: scene.atmosphere.clone(),
            method,
            wavelengths: scene.render.wavelengths,
            quality: scene.render.quality,
            scattering_orders: scene.render.scattering_orders,
            fitted_constants: scene.render.fitted_constants,
        };
        let size = [view.width.max(1), view.height.max(1)];
        let current = self.atmosphere.as_ref().is_some_and(|a| a.key == key);
        // Where no table holds the ground albedo, a change of it alone redraws the view with
        // the tables on screen (Elek's ground reflects nothing into his tables).
        let albedo_only = !current
            && !gpu.info().tables_hold_the_albedo()
            && self
                .atmosphere
                .as_ref()
                .is_some_and(|a| a.key.without_albedo() == key.without_albedo());
        let mut rebuilt = false;
        let mut progress = None;
        let mut rebuild_done = false;
        if current {
            // The scene went back to what is on screen: a rebuild under way is moot.
            self.rebuild = None;
        } else if albedo_only {
            self.rebuild = None;
            // A moving sky under way would be published half with the old albedo.
            self.drop_moving_sky_job();
            if let Some(state) = self.atmosphere.as_mut() {
                state.params = state_params(scene, &key);
                upload_batches(&self.queue, &state.tables, &state.params);
                state.key = key;
            }
        } else if let (Some(slice), Some(_), Some(_)) =
            (self.slicing, &self.atmosphere, &self.target)
        {
            // Build the new tables and view a slice per frame; the old ones stay on screen.
            if self.rebuild.as_ref().is_none_or(|r| r.state.key != key) {
                self.rebuild = Some(self.start_rebuild(scene, view, gpu, key, size));
            }
            match self.advance_rebuild(slice) {
                Some(p) => progress = Some(p),
                None => {
                    if let Some(r) = self.rebuild.take() {
                        rebuild_done = true;
                        self.slice_units.retain(|(m, _)| *m != r.state.key.method);
                        self.slice_units.push((r.state.key.method, r.units));
                        self.atmosphere = Some(r.state);
                        self.target = Some(r.target);
                        self.last = Some(r.snapshot);
                        self.deferred = r.deferred;
                    }
                }
            }
        } else {
            self.rebuild = None;
            self.refine = None;
            self.select(gpu);
            self.atmosphere = Some(self.build_state(scene, key));
            rebuilt = true;
        }
        // The model on screen: the scene's, or the previous one while a rebuild is under way.
        let Some(gpu) = self
            .atmosphere
            .as_ref()
            .and_then(|a| gpu_method(a.key.method))
        else {
            unreachable!("the atmosphere was just built, by a real-time model");
        };
        self.select(gpu);
        let Some(state) = self.atmosphere.as_ref() else {
            unreachable!("the atmosphere was just built");
        };
        let mut frame = FrameSetup::new(scene, view, state, gpu);
        let mut changed = frame
            .snapshot
            .changes_from(self.last.as_ref())
            .union(std::mem::replace(&mut self.forced, Inputs::NONE));
        if rebuilt {
            // New tables, empty: every pass runs, whatever of the atmosphere changed (the
            // ground albedo alone, for a model whose tables hold it).
            changed = changed.union(Inputs::ATMOSPHERE);
        }
        if rebuild_done {
            // The rebuild drew its view at full resolution.
            self.tiled_on_screen = false;
            self.radiance_current = true;
        }
        // The view is drawn again at full resolution by a still frame after one in tiles, and
        // by a frame that changes only the display or meters while the radiance image is not
        // the one on screen (a frame in tiles left it unwritten): the display and meter passes
        // would read it. The latter holds during a rebuild in slices too.
        let display_only = Inputs::DISPLAY.union(changed) == Inputs::DISPLAY;
        let still_after_tiles = self.tiled_on_screen && progress.is_none() && changed.is_empty();
        let radiance_read =
            !self.radiance_current && (changed.intersects(Inputs::DISPLAY) || self.metering);
        let refine = display_only && (still_after_tiles || radiance_read);
        if refine {
            changed = changed.union(Inputs::VIEW_SIZE);
        }
        // Where the engine slices its work, a still frame after tiles is drawn a slice per
        // frame; anything else that happens meanwhile drops it (a frame in motion draws in
        // tiles again, a change of the display needs the whole radiance now).
        let refine_in_slices = match self.slicing {
            Some(slicing) if still_after_tiles && !radiance_read && !rebuilt => Some(slicing),
            _ => None,
        };
        if refine_in_slices.is_none() {
            self.refine = None;
        }
        // A frame whose inputs did not change is a still one (the frame that swaps in a
        // rebuild's tables and view, drawn at full resolution, and those after it): it builds
        // no moving sky.
        frame.sky_tile = if refine || changed.is_empty() {
            1
        } else {
            self.sky_tile
        };
        frame.write_radiance = frame.sky_tile <= 1 || self.metering;
        frame.bands = self.view_bands;
        if rebuilt || self.target.as_ref().is_none_or(|t| t.size != size) {
            // New images: every pass that writes them must run.
            changed = changed.union(Inputs::VIEW_SIZE);
            self.target = Some(Target::new(
                &self.device,
                &self.pipelines[0],
                &state.tables,
                size,
                self.sky_tile,
            ));
        }
        if !changed.is_empty() {
            self.queue
                .write_buffer(&state.tables.globals, 0, bytemuck::bytes_of(&frame.globals));
        }
        let pipelines = &self.pipelines[0];
        if rebuilt || self.deferred.len() != pipelines.len() {
            self.deferred = vec![false; pipelines.len()];
        }
        // Whether the view shows the ground matters only to a frame with stale passes.
        let stale = !changed.is_empty() || self.deferred.iter().any(|&d| d);
        let ground = stale && frame.shows_ground(view);
        let mut run = plan(
            pipelines,
            changed,
            frame.above,
            frame.sun_below_tables,
            ground,
            frame.sky_tile > 1,
            self.unwanted(),
            &mut self.deferred,
        );
        let layers = state.params.batches.len() as u32;
        // Where the engine slices its work and a moving sky is complete, a new one is built in
        // slices (`MovingSky`) and the frame reads the complete one: in motion, where the frame
        // would build it, and in a still frame where one was left stale (the sun let go while
        // the last was being built), so that the next motion finds it caught up. While one is
        // being built the pass stays stale, to start again once it is complete.
        let moving_sky_pass = pipelines.moving_sky_pass();
        let mut start_moving_sky = None;
        let in_slices = self.slicing.is_some()
            && state.moving_sky.complete
            && state.tables.next_moving_sky.is_some();
        if let Some(m) = moving_sky_pass.filter(|&m| {
            in_slices
                && (run.contains(&m) || (self.deferred[m] && self.sky_tile > 1 && !frame.above))
        }) {
            run.retain(|&i| i != m);
            if state.moving_sky.job.is_some() {
                self.deferred[m] = true;
            } else {
                self.deferred[m] = false;
                start_moving_sky = Some(
                    with_order_loop(&[m], pipelines, state.params.scattering_orders)
                        .into_iter()
                        .flat_map(|step| frame.work(pipelines, step, layers, scene, view))
                        .collect::<Vec<Work>>(),
                );
            }
        }
        let steps = with_order_loop(&run, pipelines, state.params.scattering_orders);
        let work: Vec<Work> = steps
            .iter()
            .flat_map(|&step| frame.work(pipelines, step, layers, scene, view))
            .collect();
        // A still frame in slices submits its next slice, or nothing while one is on the GPU;
        // `refined` once every slice has finished.
        let mut refined = false;
        let work = match refine_in_slices {
            Some(slicing) => {
                // Runs the callback that marks the slice in flight finished.
                let _ = self.device.poll(wgpu::PollType::Poll);
                let job = self.refine.get_or_insert_with(|| Slices::new(work));
                job.next_slice(slicing).unwrap_or_else(|| {
                    refined = true;
                    self.refine = None;
                    Vec::new()
                })
            }
            None => work,
        };
        // The steps that run this frame (all of them, but while a still frame is in slices).
        let steps: Vec<Step> = steps
            .into_iter()
            .filter(|s| work.iter().any(|w| w.pass == s.pass))
            .collect();
        let ran_pass = |i: usize| steps.iter().any(|s| s.pass == i);
        for w in &work {
            self.pipelines[0].ensure(&self.device, w.pass, w.variant);
        }
        let timings = match (&self.atmosphere, &self.target) {
            (Some(state), Some(target)) if !work.is_empty() => {
                let measure = self.measure.then_some(&self.timer);
                let encoder = Encoder {
                    device: &self.device,
                    queue: &self.queue,
                    pipelines: &self.pipelines[0],
                    tables: &state.tables,
                    target,
                    next_moving_sky: None,
                };
                let mut timings = Timings::default();
                let alone = refine_in_slices.is_some_and(|s| s.alone);
                let clock = SliceClock::start(&self.device, &self.queue, alone, || {
                    timings = encoder.submit(&work, measure, self.spans);
                });
                if let Some(job) = &mut self.refine {
                    job.submitted(clock, &work);
                }
                timings
            }
            _ => Timings::default(),
        };
        let timings_ms = timings.passes;
        let method_on_screen = state.key.method;
        let moving_sky = self.advance_moving_sky(
            start_moving_sky,
            &frame.globals,
            moving_sky_pass.is_some_and(ran_pass),
        );
        let pipelines = &self.pipelines[0];
        if pipelines
            .specs()
            .enumerate()
            .any(|(i, s)| s.writes.contains(&RADIANCE) && ran_pass(i))
            && self.refine.is_none()
        {
            self.tiled_on_screen = frame.sky_tile > 1;
            self.radiance_current = frame.write_radiance;
        }
        if refined {
            self.tiled_on_screen = false;
            self.radiance_current = true;
        }
        let names: Vec<&'static str> = pipelines.specs().map(|s| s.name).collect();
        let unwanted = self.unwanted();
        let is_table: Vec<bool> = pipelines.specs().map(|s| s.is_table()).collect();
        // Each pass once, in order, however often the order loop ran it; its times summed.
        let ran: Vec<usize> = (0..names.len()).filter(|&i| ran_pass(i)).collect();
        let timings_ms: Vec<(&'static str, f64)> = ran
            .iter()
            .filter(|&&i| timings_ms.iter().any(|(j, _)| *j == i))
            .map(|&i| {
                let total = timings_ms
                    .iter()
                    .filter(|(j, _)| *j == i)
                    .map(|(_, ms)| ms)
                    .sum();
                (names[i], total)
            })
            .collect();
        self.last = Some(frame.snapshot);
        self.stats = FrameStats {
            method: method_on_screen,
            sky_tile: if ran.iter().any(|&i| names[i] == "sky") {
                frame.sky_tile
            } else {
                1
            },
            timing_source: (self.measure && !steps.is_empty()).then(|| self.timing_source()),
            skipped: (0..names.len())
                .filter(|i| !ran.contains(i) && !unwanted.contains(&names[*i]))
                .map(|i| names[i])
                .collect(),
            tables_run: ran
                .iter()
                .filter(|&&i| is_table[i])
                .map(|&i| names[i])
                .collect(),
            run: ran.iter().map(|&i| names[i]).collect(),
            dispatched: steps.len(),
            passes: names
                .iter()
                .copied()
                .filter(|n| !unwanted.contains(n))
                .collect(),
            timings_ms,
            spans_ms: timings.spans,
            rebuild: progress,
            rebuild_done,
            moving_sky,
        };
        Ok(())
    }

    /// The next moving sky of the model on screen (`MovingSky`): started from `globals` when
    /// `start` holds its dispatches, its next slice submitted once the last has finished, and
    /// once every slice has, copied over the one the sky pass reads. `built_whole`: the frame
    /// built the moving sky itself.
    fn advance_moving_sky(
        &mut self,
        start: Option<Vec<Work>>,
        globals: &Globals,
        built_whole: bool,
    ) -> MovingSkyStep {
        let (Some(state), Some(target)) = (self.atmosphere.as_mut(), self.target.as_ref()) else {
            return MovingSkyStep::None;
        };
        let moving = &mut state.moving_sky;
        moving.complete |= built_whole;
        let next = state.tables.next_moving_sky.as_ref();
        if let (Some(work), Some(next)) = (start, next) {
            self.queue
                .write_buffer(&next.globals, 0, bytemuck::bytes_of(globals));
            moving.job = Some(Slices::steered(work, moving.units, moving.shortest_s));
        }
        let (Some(slicing), Some(job), Some(next)) = (self.slicing, moving.job.as_mut(), next)
        else {
            return MovingSkyStep::None;
        };
        // Runs the callback that marks the slice in flight finished.
        let _ = self.device.poll(wgpu::PollType::Poll);
        match job.next_slice(slicing) {
            Some(work) if work.is_empty() => MovingSkyStep::Waiting,
            Some(work) => {
                for w in &work {
                    self.pipelines[0].ensure(&self.device, w.pass, w.variant);
                }
                let encoder = Encoder {
                    device: &self.device,
                    queue: &self.queue,
                    pipelines: &self.pipelines[0],
                    tables: &state.tables,
                    target,
                    next_moving_sky: Some(next),
                };
                let clock = SliceClock::start(&self.device, &self.queue, slicing.alone, || {
                    encoder.submit(&work, None, false);
                });
                job.submitted(clock, &work);
                MovingSkyStep::Slice
            }
            None => {
                (moving.units, moving.shortest_s) = (job.units, job.shortest_s);
                moving.job = None;
                let mut encoder = self.device.create_command_encoder(&Default::default());
                state.tables.publish_next_moving_sky(&mut encoder);
                self.queue.submit([encoder.finish()]);
                MovingSkyStep::Published
            }
        }
    }

    /// Forgets the next moving sky being built, leaving the pass stale so that the next frame
    /// in motion builds it.
    fn drop_moving_sky_job(&mut self) {
        let job = self
            .atmosphere
            .as_mut()
            .and_then(|a| a.moving_sky.job.take());
        if let (Some(_), Some(m)) = (
            job,
            self.pipelines.first().and_then(Pipelines::moving_sky_pass),
        ) {
            if let Some(d) = self.deferred.get_mut(m) {
                *d = true;
            }
        }
    }

    /// The tables' buffers of a new atmosphere for `key`, its inputs uploaded.
    fn build_state(&mut self, scene: &Scene, key: AtmosphereKey) -> AtmosphereState {
        let Some(gpu) = gpu_method(key.method) else {
            unreachable!("the caller checked the model is a real-time one");
        };
        let params = state_params(scene, &key);
        let i = self.pipelines_of(gpu);
        let tables = TableBuffers::new(&self.device, &self.pipelines[i], gpu.info(), &params);
        upload_batches(&self.queue, &tables, &params);
        self.queue.write_buffer(
            &tables.profile,
            0,
            bytemuck::cast_slice(&uniforms::profile(&params)),
        );
        self.queue.write_buffer(
            &tables.mie_phase,
            0,
            bytemuck::cast_slice(&uniforms::mie_phase_rows(&params)),
        );
        AtmosphereState {
            key,
            params,
            tables,
            noon_white: std::sync::OnceLock::new(),
            moving_sky: MovingSky::default(),
        }
    }

    /// A rebuild of everything `scene` draws with its new atmosphere `key`, to run in slices.
    fn start_rebuild(
        &mut self,
        scene: &Scene,
        view: &View,
        gpu: &'static GpuMethod,
        key: AtmosphereKey,
        size: [u32; 2],
    ) -> Rebuild {
        let method = key.method;
        let mut state = self.build_state(scene, key);
        let frame = FrameSetup::new(scene, view, &state, gpu);
        self.queue
            .write_buffer(&state.tables.globals, 0, bytemuck::bytes_of(&frame.globals));
        let p = self.pipelines_of(gpu);
        let pipelines = &self.pipelines[p];
        let target = Target::new(&self.device, pipelines, &state.tables, size, self.sky_tile);
        let mut deferred = vec![false; pipelines.len()];
        let ground = frame.shows_ground(view);
        let run = plan(
            pipelines,
            Inputs::ALL,
            frame.above,
            frame.sun_below_tables,
            ground,
            // A rebuild draws its view at full resolution, and builds the moving sky of a
            // march per pixel where frames in motion are drawn in tiles: the first of them
            // would build it whole (216 ms for Nishita on lavapipe at Spectral4, 1.6 s at
            // Spectral32), a few percent of the still frame the rebuild draws.
            self.sky_tile > 1,
            self.unwanted(),
            &mut deferred,
        );
        state.moving_sky.complete = pipelines
            .moving_sky_pass()
            .is_some_and(|m| run.contains(&m));
        let run = with_order_loop(&run, pipelines, state.params.scattering_orders);
        let variants = frame.variants(pipelines, scene, view);
        let layers = state.params.batches.len() as u32;
        let total_units = state.tables.bytes().div_ceil(CLEAR_UNIT_BYTES)
            + run
                .iter()
                .map(|s| u64::from(units(grid(pipelines, s.pass, layers, size))))
                .sum::<u64>();
        Rebuild {
            state,
            target,
            snapshot: frame.snapshot,
            deferred,
            variants,
            run,
            next: (0, 0),
            cleared: 0,
            units: self
                .slice_units
                .iter()
                .find(|(m, u)| *m == method && u.len() == pipelines.len() + 1)
                .map_or_else(|| vec![1; pipelines.len() + 1], |(_, u)| u.clone()),
            in_flight: None,
            done_units: 0,
            total_units,
            shortest_s: f64::INFINITY,
        }
    }

    /// Runs the next slice of the rebuild under way once the last one has finished. Returns
    /// its progress, or None when every slice has finished.
    fn advance_rebuild(&mut self, slicing: Slicing) -> Option<RebuildProgress> {
        let _ = self.device.poll(wgpu::PollType::Poll);
        let gpu = gpu_method(self.rebuild.as_ref()?.state.key.method)?;
        let p = self.pipelines_of(gpu);
        let r = self.rebuild.as_mut()?;
        if let Some((clock, pass, count, half_row)) = &r.in_flight {
            if !clock.finished() {
                return Some(r.progress());
            }
            // Aim the pass's next slice at the target time from how long this one took.
            let target = slicing.target.as_secs_f64();
            let steered = clock.steer(*count, &mut r.shortest_s, target);
            r.units[*pass] = if target <= 0.0 { *half_row } else { steered };
            r.in_flight = None;
        }
        let clearing = r.units.len() - 1;
        let table_bytes = r.state.tables.bytes();
        if r.cleared < table_bytes {
            let count = r.units[clearing];
            let mut encoder = self.device.create_command_encoder(&Default::default());
            let cleared =
                r.state
                    .tables
                    .clear(&mut encoder, r.cleared, u64::from(count) * CLEAR_UNIT_BYTES);
            let clock = SliceClock::start(&self.device, &self.queue, slicing.alone, || {
                self.queue.submit([encoder.finish()]);
            });
            r.cleared += cleared;
            // The units zeroed, not those asked for: the last piece is usually short, and the
            // next slice is sized from what this one did.
            let units = cleared.div_ceil(CLEAR_UNIT_BYTES);
            r.in_flight = Some((clock, clearing, u32::try_from(units).unwrap_or(count), 16));
            r.done_units += units;
            return Some(r.progress());
        }
        let (k, unit) = r.next;
        let &step = r.run.get(k)?;
        let pass = step.pass;
        let variant = self.pipelines[p].with_constant(
            pass,
            r.variants[pass],
            Constant::FirstOrder,
            step.first_order(),
        );
        self.pipelines[p].ensure(&self.device, pass, variant);
        let layers = r.state.params.batches.len() as u32;
        let pipelines = &self.pipelines[p];
        let grid = grid(pipelines, pass, layers, r.target.size);
        let (_, _, count) = slice(grid, unit, r.units[pass]);
        let encoder = Encoder {
            device: &self.device,
            queue: &self.queue,
            pipelines,
            tables: &r.state.tables,
            target: &r.target,
            next_moving_sky: None,
        };
        let (origin, groups, _) = slice(grid, unit, count);
        let work = Work {
            pass,
            variant,
            origin,
            groups,
            tiles: TilePhase::None,
        };
        let clock = SliceClock::start(&self.device, &self.queue, slicing.alone, || {
            encoder.submit(&[work], None, false);
        });
        r.in_flight = Some((clock, pass, count, grid[0].div_ceil(2)));
        r.done_units += u64::from(count);
        r.next = if unit + count >= units(grid) {
            (k + 1, 0)
        } else {
            (k, unit + count)
        };
        Some(r.progress())
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
        self.try_render(scene, view)?;
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

    /// A sampled view of the displayed image that decodes its sRGB bytes to linear colour, for
    /// compositors that work in linear light (egui-wgpu). Recreated when the view's size changes.
    pub fn display_view_srgb(&self) -> Option<wgpu::TextureView> {
        self.display_texture().map(|t| {
            t.create_view(&wgpu::TextureViewDescriptor {
                label: Some("display (sRGB view)"),
                format: Some(wgpu::TextureFormat::Rgba8UnormSrgb),
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

/// The optics of an atmosphere for `key`. Sunlight at 1 AU: the sky pass scales the view to
/// the scene's distance (`SunSettings::sunlight_scale`), so a sun placed by date keeps its
/// tables all year.
fn state_params(scene: &Scene, key: &AtmosphereKey) -> Params {
    Params::new(
        &Atmosphere::new(&key.settings),
        key.wavelengths,
        key.quality,
    )
    .with_render(&scene.render)
}

/// Uploads the optics of every batch of four wavelengths (`batches` in the shaders).
fn upload_batches(queue: &wgpu::Queue, tables: &TableBuffers, params: &Params) {
    let batches: Vec<uniforms::Batch> = params.batches.iter().map(Into::into).collect();
    queue.write_buffer(&tables.batches, 0, bytemuck::cast_slice(&batches));
}

fn map_u64(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Option<Vec<u64>> {
    let (tx, rx) = std::sync::mpsc::channel();
    buffer.slice(..).map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).ok()?;
    rx.recv().ok()?.ok()?;
    let ticks = {
        let data = buffer.slice(..).get_mapped_range().ok()?;
        bytemuck::pod_collect_to_vec(&data)
    };
    buffer.unmap();
    Some(ticks)
}

/// One pass to encode, and the scattering order it computes when it is in an order loop (0
/// when it is not).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Step {
    pass: usize,
    order: u32,
}

impl Step {
    /// The value of [`Constant::FirstOrder`]: whether the deltas this step reads are single
    /// scattering (outside an order loop, or at its order 2).
    fn first_order(self) -> u32 {
        u32::from(self.order <= 2)
    }
}

/// The passes to encode: `run` (pass indices in order) with each stretch of consecutive
/// order-loop passes repeated once per scattering order from 2 to `orders`.
fn with_order_loop(run: &[usize], pipelines: &Pipelines, orders: u32) -> Vec<Step> {
    let specs: Vec<&PassSpec> = pipelines.specs().collect();
    let mut out = Vec::with_capacity(run.len());
    let mut group: Vec<usize> = Vec::new();
    let flush = |group: &mut Vec<usize>, out: &mut Vec<Step>| {
        for order in 2..=orders {
            out.extend(group.iter().map(|&pass| Step { pass, order }));
        }
        group.clear();
    };
    for &i in run {
        if specs[i].repeat == Repeat::PerOrder {
            group.push(i);
        } else {
            flush(&mut group, &mut out);
            out.push(Step { pass: i, order: 0 });
        }
    }
    flush(&mut group, &mut out);
    out
}

fn groups(n: u32) -> u32 {
    n.div_ceil(crate::prelude::WORKGROUP_SIZE)
}

impl Target {
    fn new(
        device: &wgpu::Device,
        pipelines: &Pipelines,
        tables: &TableBuffers,
        size: [u32; 2],
        sky_tile: u32,
    ) -> Target {
        let texture = |label, format, view_formats: &[wgpu::TextureFormat]| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: size[0],
                    height: size[1],
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats,
            })
        };
        let radiance = texture("radiance", wgpu::TextureFormat::Rgba32Float, &[]);
        // The sRGB view lets a UI sample the encoded bytes as linear colour (egui decodes).
        let display = texture(
            "display",
            wgpu::TextureFormat::Rgba8Unorm,
            &[wgpu::TextureFormat::Rgba8UnormSrgb],
        );
        let radiance_view = radiance.create_view(&Default::default());
        let display_view = display.create_view(&Default::default());
        let histogram = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("histogram"),
            size: 4 * HISTOGRAM_BINS as u64,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        // Room for every tile of the view; one word when frames are not drawn in tiles.
        let tiles = if sky_tile > 1 {
            u64::from(size[0].div_ceil(sky_tile)) * u64::from(size[1].div_ceil(sky_tile))
        } else {
            1
        };
        let exact_tiles = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("exact tiles"),
            size: EXACT_TILES_HEADER_BYTES + 4 * tiles,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let exact_groups = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("exact tiles' workgroups"),
            size: 12,
            usage: wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let groups = pipelines
            .specs()
            .enumerate()
            .map(|(i, spec)| {
                if spec.is_table() {
                    return None;
                }
                pipelines.bind(device, i, |id| match id {
                    crate::methods::RADIANCE => {
                        Some(wgpu::BindingResource::TextureView(&radiance_view))
                    }
                    crate::methods::DISPLAY => {
                        Some(wgpu::BindingResource::TextureView(&display_view))
                    }
                    crate::methods::HISTOGRAM => Some(histogram.as_entire_binding()),
                    crate::methods::EXACT_TILES => Some(exact_tiles.as_entire_binding()),
                    table => tables.buffer(table).map(|b| b.as_entire_binding()),
                })
            })
            .collect();
        Target {
            size,
            radiance,
            display,
            histogram,
            exact_tiles,
            exact_groups,
            groups,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{SliceClock, WORKGROUP_SIZE, slice, units};
    use std::sync::Arc;
    use std::sync::atomic::AtomicBool;
    use std::time::{Duration, Instant};

    /// A slice timed alone is steered by its own time, whatever frames came between: 4
    /// workgroups in 5 ms ask for 12 at a 20 ms target (aiming at 15 ms), and the shortest
    /// interval is left as it was. One seen done 40 ms after its submission, with 20 ms the
    /// shortest interval, sets most of that aside as the frame's own work.
    #[test]
    fn slices_timed_alone_are_steered_by_their_own_time() {
        let mut shortest = 0.020;
        assert_eq!(SliceClock::Alone(0.005).steer(4, &mut shortest, 0.020), 12);
        assert_eq!(SliceClock::Alone(0.080).steer(4, &mut shortest, 0.020), 1);
        // Growth stays within 16 times a slice.
        assert_eq!(SliceClock::Alone(1e-6).steer(4, &mut shortest, 0.020), 64);
        assert_eq!(shortest, 0.020);
        let submitted = Instant::now() - Duration::from_millis(40);
        let seen = Arc::new(AtomicBool::new(true));
        let steered = SliceClock::Since(submitted, seen).steer(4, &mut shortest, 0.020);
        // own = 40 − 0.8 × 20 = 24 ms (a little more, as time passed since): 4 × 20 / 24 → 3.
        assert_eq!(steered, 3);
        assert_eq!(shortest, 0.020);
    }

    /// Slices of any size, taken one after another, cover every workgroup of a pass exactly
    /// once, each slice a box inside the grid.
    #[test]
    fn slices_tile_the_grid_exactly_once() {
        for grid in [[3, 4, 5], [1, 1, 1], [16, 8, 16], [2, 7, 1]] {
            for size in [1, 2, 3, 4, 7, 8, 9, 30, 1000] {
                let mut hits = vec![0u32; (grid[0] * grid[1] * grid[2]) as usize];
                let mut start = 0;
                while start < units(grid) {
                    let (origin, groups, n) = slice(grid, start, size);
                    assert!(n >= 1 && n <= size, "{grid:?} {size}: {n}");
                    assert_eq!(n, groups[0] * groups[1] * groups[2]);
                    let x0 = origin[0] / WORKGROUP_SIZE;
                    let (y0, z0) = (origin[1] / WORKGROUP_SIZE, origin[2]);
                    for z in z0..z0 + groups[2] {
                        for y in y0..y0 + groups[1] {
                            for x in x0..x0 + groups[0] {
                                hits[((z * grid[1] + y) * grid[0] + x) as usize] += 1;
                            }
                        }
                    }
                    start += n;
                }
                assert!(hits.iter().all(|&h| h == 1), "{grid:?} in slices of {size}");
            }
        }
    }
}
