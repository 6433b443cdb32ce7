//! Benchmarks of the real-time engine: `bench gpu` times every pass (GPU timestamps where the
//! adapter has them, fenced CPU wall time otherwise) and whole frames per wavelength set;
//! `bench accuracy` measures ΔE2000 against path-traced references of the view suite.

use super::SceneArgs;
use super::progress::Progress;
use super::render::{gpu, parse_wavelengths};
use crate::images::read_exr;
use anyhow::Context;
use atmoscope_model::Scene;
use atmoscope_model::camera::Projection;
use atmoscope_model::metrics::{DisplaySetup, compare};
use atmoscope_model::scene::Method;
use atmoscope_model::scene::{SunSettings, WavelengthSet};
use atmoscope_model::views;
use atmoscope_render::{Engine, View};
use clap::Args;
use serde::Serialize;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Args, Debug)]
pub struct GpuBench {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Frame size WxH.
    #[arg(long, value_name = "WxH", value_parser = super::reference::parse_size, default_value = "1280x720")]
    pub size: (u32, u32),
    /// Wavelength sets, comma-separated.
    #[arg(long, value_delimiter = ',', value_parser = parse_wavelengths, default_value = "rgb3,spectral4,spectral32")]
    pub sets: Vec<WavelengthSet>,
    /// Sky models, comma-separated registry ids, or `all` (default: the scene's).
    #[arg(long, value_name = "IDS", value_parser = super::parse_methods)]
    pub methods: Option<super::MethodList>,
    /// Repetitions of each measurement (the median is reported).
    #[arg(long, default_value_t = 10)]
    pub repeats: usize,
    /// Time passes by fenced CPU wall time even where GPU timestamps exist.
    #[arg(long)]
    pub cpu_timing: bool,
    /// Tile of the sky pass in moving frames (1: every pixel, the marches per pixel included;
    /// `sky_still_ms` is always every pixel; above 1 the marches per pixel draw moving frames
    /// from their moving sky). Default: the explorer's for the adapter, 4 on a software
    /// adapter, 1 on a GPU.
    #[arg(long, value_name = "PIXELS", value_parser = clap::value_parser!(u32).range(1..=16))]
    pub sky_tile: Option<u32>,
    /// Whether the sky pass runs in bands of what the rows see, the sun's disk apart, or as
    /// one dispatch. Default: the explorer's for the adapter, bands on a software adapter.
    #[arg(long, value_name = "true|false")]
    pub bands: Option<bool>,
    /// Time only what the explorer draws in slices: the change of the atmosphere and the still
    /// frame after a turn (the `rebuild_ui_*`, `rebuild_sliced_ms` and `still_*` keys, beside
    /// `floor_ms`; the frame, sun-move, table and whole-rebuild timings are null): for models
    /// whose whole rebuilds take minutes on a software adapter.
    #[arg(long)]
    pub rebuild_only: bool,
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize, Debug)]
struct GpuRow {
    method: String,
    wavelengths: String,
    timing: String,
    /// Median milliseconds of each table pass in a full rebuild.
    lut_ms: Vec<(String, f64)>,
    lut_total_ms: f64,
    /// Tile of the sky pass in the moving frames: `--sky-tile`.
    sky_tile: u32,
    /// Whether the sky pass ran in bands (`--bands`).
    view_bands: bool,
    /// Median milliseconds of the sky pass of a frame with the camera turning (it draws the
    /// display image too), and of the display pass in a frame that changes only the exposure.
    sky_ms: f64,
    display_ms: f64,
    /// Median milliseconds of the sky pass at full resolution, as in the first still frame
    /// after a move.
    sky_still_ms: f64,
    /// Median of every pass a frame with the camera turning runs.
    frame_gpu_ms: f64,
    /// Median wall time of a turning-camera frame from `render` to the GPU being idle.
    frame_wall_ms: f64,
    /// Median of every pass a change of the sun's elevation runs (the tables it invalidates,
    /// and the sky, which draws the display image too).
    sun_move_ms: f64,
    /// Median of the floor pass: a trivial full-screen pass of the same size and output
    /// format, timed the same way in the same run.
    floor_ms: f64,
    /// Median spans, from the start of the first pass to the end of the last (GPU
    /// timestamps only there, so that passes free of barriers overlap as they do untimed;
    /// with fenced CPU time, the sums of the passes): a turning-camera frame, a sun move, and
    /// the table passes of a full rebuild.
    frame_span_ms: f64,
    sun_move_span_ms: f64,
    tables_span_ms: f64,
    /// The frame, a sun move and a full table rebuild (their spans) as multiples of the floor.
    frame_floors: f64,
    sun_move_floors: f64,
    tables_floors: f64,
    /// A change of the atmosphere as the explorer runs it: the wall time of the one frame
    /// that rebuilds everything at once, and, built in slices across frames (one floor pass
    /// standing for the UI's own drawing in each, and a wait for the GPU as a window's
    /// present does), the longest, 99th-percentile and mean frame interval and the time until
    /// the new image.
    rebuild_whole_ms: f64,
    rebuild_ui_max_ms: f64,
    rebuild_ui_p99_ms: f64,
    rebuild_ui_mean_ms: f64,
    /// The interval of the frame that swaps in the new tables and the view drawn with them
    /// (the view passes run in slices too).
    rebuild_ui_last_ms: f64,
    rebuild_sliced_ms: f64,
    /// The still frame after a turn of the camera as the explorer draws it: where the turn
    /// was drawn in tiles, every pixel again, a run of workgroups per frame, each frame
    /// drawing the floor pass and waiting as above. The longest, 99th-percentile and mean
    /// frame interval, the time until the frame that finds the last slice finished, and the
    /// frames until then (one, drawing nothing, where the turn was not drawn in tiles).
    still_ui_max_ms: f64,
    still_ui_p99_ms: f64,
    still_ui_mean_ms: f64,
    still_sliced_ms: f64,
    still_frames: usize,
    /// The sun dragged as the explorer draws it (`SUN_DRAG_FRAMES` frames, each moving it
    /// `SUN_DRAG_STEP_DEG` and drawing the floor pass and waiting as above): the longest,
    /// 99th-percentile and mean frame interval, the mean as a multiple of the floor, and the
    /// frames after the last step until the moving sky of a march per pixel, built in slices,
    /// has caught up with it (0 for the other models).
    sun_drag_ui_max_ms: f64,
    sun_drag_ui_p99_ms: f64,
    sun_drag_ui_mean_ms: f64,
    sun_drag_floors: f64,
    sun_drag_catch_up_frames: usize,
}

/// Frames of the sun drag of `bench gpu`, and the step of the sun's elevation in each, degrees.
const SUN_DRAG_FRAMES: usize = 24;
const SUN_DRAG_STEP_DEG: f64 = 0.25;

/// Frame intervals while the engine finishes work in slices, ms.
struct SlicedFrames {
    longest: f64,
    /// The 99th percentile (nearest rank): a single long frame on a busy machine moves the
    /// longest but not this.
    p99: f64,
    mean: f64,
    /// The last frame: the one that swaps in the new tables (a rebuild), or the one that
    /// finds the still image's last slice finished.
    last: f64,
    /// From the first frame to the end of the last.
    total: f64,
    frames: usize,
}

/// Frame intervals of frames drawn as the explorer draws them, its work in slices, each
/// frame also drawing the floor pass (the UI) and waiting for the GPU (a window's present):
/// frame `i` draws `scene(i)`, for as long as `more(engine, i)` says there is work left.
/// `lead`, when given, is drawn first, untimed, with slicing already on (the frame whose work
/// the timed ones finish). Returns the intervals, ms, and the time from the first frame to the
/// end of the last.
fn sliced_frames(
    engine: &mut Engine,
    lead: Option<&Scene>,
    scene: &dyn Fn(usize) -> Scene,
    view: &View,
    ui: &atmoscope_render::floor::FloorPass,
    context: &atmoscope_render::gpu::GpuContext,
    more: &dyn Fn(&Engine, usize) -> bool,
) -> anyhow::Result<(Vec<f64>, f64)> {
    engine.set_timing(false);
    engine.set_rebuild_slices(Some(crate::gui::REBUILD_SLICE));
    if let Some(lead) = lead {
        engine.try_render(lead, view)?;
        engine.wait();
    }
    let start = Instant::now();
    let mut intervals = Vec::new();
    for i in 0.. {
        let frame = Instant::now();
        engine.try_render(&scene(i), view)?;
        // The UI's drawing, submitted behind the frame; it returns once the GPU is idle.
        ui.time_ms(
            &context.device,
            &context.queue,
            [view.width, view.height],
            atmoscope_render::engine::TimingSource::CpuFenced,
            1,
        );
        intervals.push(frame.elapsed().as_secs_f64() * 1e3);
        if !more(engine, i) {
            break;
        }
    }
    engine.set_rebuild_slices(None);
    engine.set_timing(true);
    Ok((intervals, start.elapsed().as_secs_f64() * 1e3))
}

impl SlicedFrames {
    /// The figures of frame `intervals` (ms) that took `total` ms from first to last.
    fn of(intervals: &[f64], total: f64) -> SlicedFrames {
        let last = intervals.last().copied().unwrap_or(f64::NAN);
        let mean = intervals.iter().sum::<f64>() / intervals.len() as f64;
        let mut sorted = intervals.to_vec();
        sorted.sort_by(f64::total_cmp);
        let rank = (0.99 * sorted.len() as f64).ceil() as usize;
        SlicedFrames {
            frames: sorted.len(),
            longest: sorted.last().copied().unwrap_or(f64::NAN),
            p99: sorted.get(rank.max(1) - 1).copied().unwrap_or(f64::NAN),
            mean,
            last,
            total,
        }
    }
}

/// The median (the mean of the middle two of an even count; NaN of none).
pub(super) fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => v[n / 2],
        n => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}

pub(super) fn set_name(s: WavelengthSet) -> String {
    match s {
        WavelengthSet::Rgb3 => "rgb3".into(),
        WavelengthSet::Spectral4 => "spectral4".into(),
        WavelengthSet::SpectralN(n) => format!("spectral{n}"),
    }
}

pub fn gpu_bench(args: &GpuBench) -> anyhow::Result<ExitCode> {
    let base = args.scene.scene()?;
    let context = gpu()?;
    eprintln!("adapter: {}", context.describe());
    let device_type = context.device.adapter_info().device_type;
    let sky_tile = args
        .sky_tile
        .unwrap_or_else(|| atmoscope_render::views::moving_sky_tile(device_type));
    let view_bands = args
        .bands
        .unwrap_or_else(|| atmoscope_render::views::view_bands(device_type));
    let (w, h) = args.size;
    let view = View::new(Projection::Perspective, w, h);
    let repeats = args.repeats.max(1);
    let mut rows = Vec::new();
    let floor = atmoscope_render::floor::FloorPass::new(&context.device);
    let methods = args
        .methods
        .clone()
        .map_or(vec![base.render.method], |m| m.0);
    // A run over the registry takes many minutes on a software adapter: say where it is.
    let progress = Progress::new((methods.len() * args.sets.len()) as u64);
    for (method, &set) in methods
        .iter()
        .flat_map(|&m| args.sets.iter().map(move |s| (m, s)))
    {
        let case_start = Instant::now();
        let case = format!("{}/{}", super::method_id(method), set_name(set));
        let mut scene = base.clone();
        scene.render.method = method;
        scene.render.wavelengths = set;
        if let Some(why) = atmoscope_model::methods::info(method).cannot_draw(&scene) {
            eprintln!("{case}: {why}; left out");
            progress.step(&format!("{case} left out"));
            continue;
        }
        let mut engine = Engine::new(&context.device, &context.queue);
        engine.set_timing(true);
        engine.set_sky_tile(sky_tile);
        engine.set_view_bands(view_bands);
        if args.cpu_timing {
            engine.force_cpu_timing();
        }
        let first = engine.try_render(&scene, &view)?.clone();
        engine.wait();
        // Repetitions of the frame, sun-move and table timings (none with --rebuild-only:
        // their medians are NaN, written as null).
        let timed = if args.rebuild_only { 0 } else { repeats };
        if args.rebuild_only {
            // A turning frame, then a still one, as the timed frames would: the pipelines they
            // compile on first use are not the rebuild's cost.
            let mut turned = scene.clone();
            turned.camera.heading_deg = (base.camera.heading_deg + 1.0) % 360.0;
            engine.try_render(&turned, &view)?;
            engine.try_render(&turned, &view)?;
            engine.try_render(&scene, &view)?;
            engine.try_render(&scene, &view)?;
            engine.wait();
        }
        let mut lut: Vec<(&str, Vec<f64>)> =
            first.tables_run.iter().map(|&p| (p, Vec::new())).collect();
        for _ in 0..timed {
            engine.invalidate();
            let stats = engine.render(&scene, &view).clone();
            for (pass, times) in &mut lut {
                times.extend(stats.ms(pass));
            }
        }
        let (mut sky, mut frame, mut wall) = (Vec::new(), Vec::new(), Vec::new());
        let mut sky_still = Vec::new();
        for i in 0..timed {
            scene.camera.heading_deg = (base.camera.heading_deg + 1.0 + i as f64) % 360.0;
            let start = Instant::now();
            let stats = engine.render(&scene, &view).clone();
            engine.wait();
            wall.push(start.elapsed().as_secs_f64() * 1e3);
            sky.extend(stats.ms("sky"));
            frame.push(stats.timings_ms.iter().map(|(_, ms)| ms).sum::<f64>());
            // The scene holds still: a frame in tiles is redrawn at full resolution.
            let still = engine.render(&scene, &view).clone();
            sky_still.extend(still.ms("sky").or(stats.ms("sky")));
        }
        let mut display = Vec::new();
        for i in 0..timed {
            scene.display.exposure_ev = base.display.exposure_ev + 0.01 * (i + 1) as f64;
            display.extend(engine.render(&scene, &view).ms("display"));
        }
        scene.display.exposure_ev = base.display.exposure_ev;
        let sun = base.sun.angles();
        let mut sun_moves = Vec::new();
        for i in 0..timed {
            scene.sun = SunSettings::Angles {
                elevation_deg: (sun.elevation_deg + 0.5 * (i + 1) as f64).min(90.0),
                azimuth_deg: sun.azimuth_deg,
            };
            let stats = engine.render(&scene, &view).clone();
            sun_moves.push(stats.timings_ms.iter().map(|(_, ms)| ms).sum::<f64>());
        }
        // The same three, timed in spans.
        engine.set_span_timing(true);
        let (mut frame_spans, mut sun_spans, mut table_spans) =
            (Vec::new(), Vec::new(), Vec::new());
        for i in 0..timed {
            engine.invalidate();
            if let Some(s) = engine.render(&scene, &view).spans_ms {
                table_spans.extend(s.tables_ms);
            }
            scene.camera.heading_deg = (base.camera.heading_deg + 1.5 + i as f64) % 360.0;
            frame_spans.extend(engine.render(&scene, &view).spans_ms.map(|s| s.frame_ms));
            scene.sun = SunSettings::Angles {
                elevation_deg: (sun.elevation_deg + 0.25 + 0.5 * i as f64).min(90.0),
                azimuth_deg: sun.azimuth_deg,
            };
            sun_spans.extend(engine.render(&scene, &view).spans_ms.map(|s| s.frame_ms));
        }
        engine.set_span_timing(false);
        // A change of the atmosphere, in one frame, then in slices: of its aerosol, which
        // every table holds (a change of the ground albedo alone keeps the tables of the
        // models whose tables do not hold it).
        let mut changed = scene.clone();
        let aod = &mut changed.atmosphere.aerosol.aod550;
        *aod = if *aod < 4.9 { *aod + 0.01 } else { *aod - 0.01 };
        let rebuild_whole_ms = if args.rebuild_only {
            f64::NAN
        } else {
            let whole = Instant::now();
            engine.try_render(&changed, &view)?;
            engine.wait();
            let ms = whole.elapsed().as_secs_f64() * 1e3;
            engine.try_render(&scene, &view)?;
            engine.wait();
            ms
        };
        let (intervals, total) = sliced_frames(
            &mut engine,
            None,
            &|_| changed.clone(),
            &view,
            &floor,
            &context,
            &|e, _| e.rebuilding(),
        )?;
        let sliced = SlicedFrames::of(&intervals, total);
        // The still frame after a turn of the camera, drawn a slice at a time where the
        // turn was drawn in tiles.
        let mut turned = changed.clone();
        turned.camera.heading_deg = (changed.camera.heading_deg + 2.0) % 360.0;
        let (intervals, total) = sliced_frames(
            &mut engine,
            Some(&turned),
            &|_| turned.clone(),
            &view,
            &floor,
            &context,
            &|e, _| e.settling(),
        )?;
        let still = SlicedFrames::of(&intervals, total);
        // The sun dragged, a step a frame, then let go: the frames of the drag, and those
        // until a moving sky built in slices has caught up with the last step.
        let from = turned.sun.angles();
        let dragged = |i: usize| {
            let mut s = turned.clone();
            s.sun = SunSettings::Angles {
                elevation_deg: (from.elevation_deg
                    + SUN_DRAG_STEP_DEG * (i.min(SUN_DRAG_FRAMES - 1) + 1) as f64)
                    .min(90.0),
                azimuth_deg: from.azimuth_deg,
            };
            s
        };
        let intervals = if args.rebuild_only {
            Vec::new()
        } else {
            sliced_frames(
                &mut engine,
                None,
                &dragged,
                &view,
                &floor,
                &context,
                &|e, i| i + 1 < SUN_DRAG_FRAMES || e.building_moving_sky(),
            )?
            .0
        };
        let drag = SlicedFrames::of(&intervals[..SUN_DRAG_FRAMES.min(intervals.len())], f64::NAN);
        let sun_drag_catch_up_frames = intervals.len().saturating_sub(SUN_DRAG_FRAMES);
        let floor_ms = median(floor.time_ms(
            &context.device,
            &context.queue,
            [w, h],
            engine.timing_source(),
            // A few milliseconds each: enough runs for a steady median.
            repeats.max(20),
        ));
        let lut_ms: Vec<(String, f64)> = lut
            .into_iter()
            .map(|(p, v)| (p.to_string(), median(v)))
            .collect();
        let (sky_ms, display_ms, frame_ms) = (median(sky), median(display), median(frame));
        // + 0.0: an empty sum is −0.0, which would print as "-0.00" for a table-free model.
        let lut_total_ms: f64 = lut_ms.iter().map(|(_, ms)| ms).sum::<f64>() + 0.0;
        let sun_move_ms = median(sun_moves);
        // A model without tables rebuilds nothing: 0, as the sum above.
        let tables_span_ms = if args.rebuild_only {
            f64::NAN
        } else if table_spans.is_empty() {
            0.0
        } else {
            median(table_spans)
        };
        let (frame_span_ms, sun_move_span_ms) = (median(frame_spans), median(sun_spans));
        rows.push(GpuRow {
            method: super::method_id(method).into(),
            wavelengths: set_name(set),
            timing: engine.timing_source().label().into(),
            lut_total_ms,
            lut_ms,
            sky_tile,
            view_bands,
            sky_ms,
            display_ms,
            sky_still_ms: median(sky_still),
            frame_gpu_ms: frame_ms,
            frame_wall_ms: median(wall),
            sun_move_ms,
            floor_ms,
            frame_span_ms,
            sun_move_span_ms,
            tables_span_ms,
            frame_floors: frame_span_ms / floor_ms,
            sun_move_floors: sun_move_span_ms / floor_ms,
            tables_floors: tables_span_ms / floor_ms,
            rebuild_whole_ms,
            rebuild_ui_max_ms: sliced.longest,
            rebuild_ui_p99_ms: sliced.p99,
            rebuild_ui_mean_ms: sliced.mean,
            rebuild_ui_last_ms: sliced.last,
            rebuild_sliced_ms: sliced.total,
            still_ui_max_ms: still.longest,
            still_ui_p99_ms: still.p99,
            still_ui_mean_ms: still.mean,
            still_sliced_ms: still.total,
            still_frames: still.frames,
            sun_drag_ui_max_ms: drag.longest,
            sun_drag_ui_p99_ms: drag.p99,
            sun_drag_ui_mean_ms: drag.mean,
            sun_drag_floors: drag.mean / floor_ms,
            sun_drag_catch_up_frames,
        });
        progress.step(&format!(
            "{case} in {:.1} s",
            case_start.elapsed().as_secs_f64()
        ));
    }
    progress.finish();
    if args.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
        return Ok(ExitCode::SUCCESS);
    }
    let measured = if args.rebuild_only {
        "the rebuild in slices only".to_string()
    } else {
        format!("median of {repeats}")
    };
    println!(
        "{w}x{h} perspective, {measured}; times from {}; moving frames draw the sky in {t}×{t} tiles (a march per pixel from its moving sky where tiles are on), a still frame every pixel; the sky pass {}",
        rows.first().map_or("", |r| r.timing.as_str()),
        if view_bands {
            "in bands, the sun's disk apart"
        } else {
            "in one dispatch"
        },
        t = sky_tile
    );
    println!(
        "{:14} {:12} {:>10} {:>8} {:>10} {:>8} {:>12} {:>12} {:>9} {:>8}   spans: {:>8} {:>8} {:>8}   ×floor: {:>6} {:>6} {:>7}   rebuild: {:>9} {:>28} {:>9}   still: {:>16}   sun drag: {:>20}   table passes",
        "method",
        "set",
        "tables",
        "sky",
        "still sky",
        "display",
        "frame (GPU)",
        "frame (wall)",
        "sun move",
        "floor",
        "frame",
        "sun",
        "tables",
        "frame",
        "sun",
        "tables",
        "one frame",
        "sliced: UI max/p99/mean/last",
        "done in",
        "UI max/done in",
        "UI max/mean/×floor/+"
    );
    for r in &rows {
        let passes: Vec<String> = r
            .lut_ms
            .iter()
            .map(|(name, ms)| format!("{name} {ms:.2}"))
            .collect();
        println!(
            "{:14} {:12} {:>7.2} ms {:>5.2} ms {:>7.2} ms {:>5.2} ms {:>9.2} ms {:>9.2} ms {:>6.2} ms {:>5.2} ms   {:>5.2} ms {:>5.2} ms {:>5.2} ms          {:>6.1} {:>6.1} {:>7.1}            {:>6.0} ms {:>6.0}/{:>5.0}/{:>5.0}/{:>5.0} ms {:>6.0} ms          {:>6.0}/{:>6.0} ms   {:>5.0}/{:>5.0} ms/{:>4.1}/{:>3}   {}",
            r.method,
            r.wavelengths,
            r.lut_total_ms,
            r.sky_ms,
            r.sky_still_ms,
            r.display_ms,
            r.frame_gpu_ms,
            r.frame_wall_ms,
            r.sun_move_ms,
            r.floor_ms,
            r.frame_span_ms,
            r.sun_move_span_ms,
            r.tables_span_ms,
            r.frame_floors,
            r.sun_move_floors,
            r.tables_floors,
            r.rebuild_whole_ms,
            r.rebuild_ui_max_ms,
            r.rebuild_ui_p99_ms,
            r.rebuild_ui_mean_ms,
            r.rebuild_ui_last_ms,
            r.rebuild_sliced_ms,
            r.still_ui_max_ms,
            r.still_sliced_ms,
            r.sun_drag_ui_max_ms,
            r.sun_drag_ui_mean_ms,
            r.sun_drag_floors,
            r.sun_drag_catch_up_frames,
            passes.join(", ")
        );
    }
    Ok(ExitCode::SUCCESS)
}

#[derive(Args, Debug)]
pub struct AccuracyBench {
    /// Directory of path-traced references named `<view>.exr`
    /// (from `atmoscope reference --suite --out-dir DIR`).
    #[arg(long, value_name = "DIR")]
    pub refs: PathBuf,
    /// Views of the suite, comma-separated (default: every view with a reference in --refs).
    #[arg(long, value_delimiter = ',')]
    pub views: Vec<String>,
    /// The spectral set the others are compared with.
    #[arg(long, value_parser = parse_wavelengths, default_value = "spectral32")]
    pub spectral: WavelengthSet,
    /// Wavelength sets to measure, comma-separated, the first being the one the others are
    /// compared with (default: the --spectral set, spectral4, rgb3).
    #[arg(long, value_delimiter = ',', value_parser = parse_wavelengths)]
    pub sets: Vec<WavelengthSet>,
    /// Sky models, comma-separated registry ids, or `all`.
    #[arg(long, value_name = "IDS", value_parser = super::parse_methods, default_value = "hillaire")]
    pub methods: super::MethodList,
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize, Debug)]
struct AccuracyRow {
    view: String,
    sun_elevation_deg: f64,
    exposure_ev: f64,
    /// (model/set, mean, p95) ΔE2000 against the path-traced reference, per model and set.
    vs_reference: Vec<(String, f64, f64)>,
    /// (model/set, mean, p95) ΔE2000 of Spectral4 and RGB3 against the model's spectral set.
    vs_spectral: Vec<(String, f64, f64)>,
}

pub fn accuracy(args: &AccuracyBench) -> anyhow::Result<ExitCode> {
    let context = gpu()?;
    let sets = if args.sets.is_empty() {
        vec![args.spectral, WavelengthSet::Spectral4, WavelengthSet::Rgb3]
    } else {
        args.sets.clone()
    };
    let runs: Vec<(Method, WavelengthSet)> = args
        .methods
        .0
        .iter()
        .flat_map(|&m| sets.iter().map(move |&s| (m, s)))
        .collect();
    let name = |(m, s): (Method, WavelengthSet)| format!("{}/{}", super::method_id(m), set_name(s));
    let mut rows = Vec::new();
    // One engine per run, kept across views: a table whose inputs a view leaves unchanged is
    // not rebuilt (Bruneton's 4D tables, which depend on the atmosphere alone, are built once).
    let mut engines: Vec<Engine> = runs
        .iter()
        .map(|_| Engine::new(&context.device, &context.queue))
        .collect();
    for v in views::suite() {
        if !args.views.is_empty() && !args.views.iter().any(|n| n == v.name.as_str()) {
            continue;
        }
        let path = args.refs.join(format!("{}.exr", v.name));
        if !path.exists() {
            if !args.views.is_empty() {
                anyhow::bail!(
                    "{}: no reference (run `atmoscope reference --suite --out-dir {}`)",
                    path.display(),
                    args.refs.display()
                );
            }
            continue;
        }
        let (reference, w, h) =
            read_exr(&path).with_context(|| format!("reference of {}", v.name))?;
        let scene: Scene = v.apply(&Scene::default());
        let setup = DisplaySetup {
            exposure_ev: scene.display.exposure_ev,
            tone_map: scene.display.tone_map,
            ..DisplaySetup::default()
        };
        // None where the model refuses the view (its figures are then NaN, null in JSON).
        let images: Vec<Option<Vec<[f64; 3]>>> = runs
            .iter()
            .zip(engines.iter_mut())
            .map(|(&(method, set), engine)| {
                let mut s = scene.clone();
                s.render.method = method;
                s.render.wavelengths = set;
                if atmoscope_model::methods::info(method)
                    .cannot_draw(&s)
                    .is_some()
                {
                    return Ok(None);
                }
                engine.try_render(&s, &View::new(v.projection, w, h))?;
                Ok(Some(
                    engine
                        .read_radiance()?
                        .iter()
                        .map(|p| [p[0], p[1], p[2]].map(f64::from))
                        .collect(),
                ))
            })
            .collect::<anyhow::Result<_>>()?;
        let de = |a: &Option<Vec<[f64; 3]>>, b: &[[f64; 3]]| match a {
            Some(a) => {
                let (c, _) = compare(a, b, w, h, setup);
                (c.delta_e2000_mean, c.delta_e2000_p95)
            }
            None => (f64::NAN, f64::NAN),
        };
        let vs_reference = runs
            .iter()
            .zip(&images)
            .map(|(&run, img)| {
                let (m, p) = de(img, &reference);
                (name(run), m, p)
            })
            .collect();
        // Each model's other sets against its first (by default Spectral4 and RGB3 against
        // the spectral set).
        let vs_spectral = runs
            .iter()
            .enumerate()
            .filter(|(i, _)| i % sets.len() != 0)
            .map(|(i, &run)| {
                let (m, p) = match &images[i - i % sets.len()] {
                    Some(first) => de(&images[i], first),
                    None => (f64::NAN, f64::NAN),
                };
                (name(run), m, p)
            })
            .collect();
        rows.push(AccuracyRow {
            view: v.name.clone(),
            sun_elevation_deg: scene.sun.angles().elevation_deg,
            exposure_ev: scene.display.exposure_ev,
            vs_reference,
            vs_spectral,
        });
        eprintln!("{} done", v.name);
    }
    if rows.is_empty() {
        anyhow::bail!("no references found in {}", args.refs.display());
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
        return Ok(ExitCode::SUCCESS);
    }
    let s = set_name(sets[0]);
    println!("ΔE2000 mean / p95, display-referred at each view's exposure");
    print!("{:20} {:>6} ", "view", "sun°");
    let first = &rows[0];
    for (n, _, _) in &first.vs_reference {
        print!(" {:>17}", format!("{n} vs ref"));
    }
    for (n, _, _) in &first.vs_spectral {
        print!(" {:>17}", format!("{n} vs {s}"));
    }
    println!();
    for r in &rows {
        print!("{:20} {:>6.1} ", r.view, r.sun_elevation_deg);
        for (_, m, p) in r.vs_reference.iter().chain(&r.vs_spectral) {
            if m.is_nan() {
                print!(" {:>17}", "refused");
            } else {
                print!(" {:>9.2} / {:>5.2}", m, p);
            }
        }
        println!();
    }
    for (label, daylight) in [
        ("daylight (sun ≥ 0°)", true),
        ("twilight (sun < 0°)", false),
    ] {
        let group: Vec<&AccuracyRow> = rows
            .iter()
            .filter(|r| (r.sun_elevation_deg >= 0.0) == daylight)
            .collect();
        if group.is_empty() {
            continue;
        }
        // Over the views each run draws (a refusing model's are fewer).
        let mean = |f: &dyn Fn(&AccuracyRow) -> f64| {
            let drawn: Vec<f64> = group.iter().map(|r| f(r)).filter(|v| !v.is_nan()).collect();
            drawn.iter().sum::<f64>() / drawn.len() as f64
        };
        println!("{label}, {} views, mean ΔE2000 (mean / p95):", group.len());
        for (i, (n, _, _)) in first.vs_reference.iter().enumerate() {
            let drawn = group
                .iter()
                .filter(|r| !r.vs_reference[i].1.is_nan())
                .count();
            if drawn == 0 {
                println!("  {n} vs ref: refuses these views");
                continue;
            }
            println!(
                "  {n} vs ref {:.2} / {:.2}{}",
                mean(&|r| r.vs_reference[i].1),
                mean(&|r| r.vs_reference[i].2),
                if drawn < group.len() {
                    format!(" (over the {drawn} views it draws)")
                } else {
                    String::new()
                }
            );
        }
        for (i, (n, _, _)) in first.vs_spectral.iter().enumerate() {
            let m = mean(&|r| r.vs_spectral[i].1);
            if m.is_nan() {
                println!("  {n} vs {s}: refuses these views");
            } else {
                println!("  {n} vs {s} {m:.2}");
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}
