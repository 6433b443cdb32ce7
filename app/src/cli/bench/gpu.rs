//! Benchmarks of the real-time engine: `bench gpu` times every pass (GPU timestamps where the
//! adapter has them, fenced CPU wall time otherwise) and whole frames per wavelength set;
//! the sliced rebuilds, still frames and sun drags as the explorer draws them.

use crate::args::parse_wavelengths;
use crate::args::set_name;
use crate::cli::common::{gpu, median};
use crate::cli::progress::Progress;
use crate::engine_setup::EngineSetup;
use crate::scene_args::SceneArgs;
use atmoscope_model::Scene;
use atmoscope_model::camera::Projection;
use atmoscope_model::scene::{SunSettings, WavelengthSet};
use atmoscope_render::{Engine, View};
use clap::Args;
use serde::Serialize;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Args, Debug)]
pub struct GpuBench {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Frame size WxH.
    #[arg(long, value_name = "WxH", value_parser = crate::args::parse_size, default_value = "1280x720")]
    pub size: (u32, u32),
    /// Wavelength sets, comma-separated.
    #[arg(long, value_delimiter = ',', value_parser = parse_wavelengths, default_value = "rgb3,spectral4,spectral32")]
    pub sets: Vec<WavelengthSet>,
    /// Sky models, comma-separated registry ids, or `all` (default: the scene's).
    #[arg(long, value_name = "IDS", value_parser = crate::args::parse_methods)]
    pub methods: Option<crate::args::MethodList>,
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
    engine.set_rebuild_slices(Some(crate::engine_setup::REBUILD_SLICE));
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

pub fn run(args: &GpuBench) -> anyhow::Result<ExitCode> {
    let base = args.scene.scene()?;
    let context = gpu()?;
    eprintln!("adapter: {}", context.describe());
    // The explorer's settings, but for what the flags set: a whole rebuild is timed built in
    // one frame, and the sliced frames turn slicing on themselves.
    let explorer = EngineSetup::explorer(&context.device);
    let setup = EngineSetup {
        sky_tile: args.sky_tile.unwrap_or(explorer.sky_tile),
        view_bands: args.bands.unwrap_or(explorer.view_bands),
        cpu_timing: args.cpu_timing,
        rebuild_slice: None,
    };
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
        let case = format!("{}/{}", crate::args::method_id(method), set_name(set));
        let mut scene = base.clone();
        scene.render.method = method;
        scene.render.wavelengths = set;
        if let Some(why) = atmoscope_model::methods::info(method).cannot_draw(&scene) {
            eprintln!("{case}: {why}; left out");
            progress.step(&format!("{case} left out"));
            continue;
        }
        let mut engine = setup.engine(&context.device, &context.queue);
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
            method: crate::args::method_id(method).into(),
            wavelengths: set_name(set),
            timing: engine.timing_source().label().into(),
            lut_total_ms,
            lut_ms,
            sky_tile: setup.sky_tile,
            view_bands: setup.view_bands,
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
        if setup.view_bands {
            "in bands, the sun's disk apart"
        } else {
            "in one dispatch"
        },
        t = setup.sky_tile
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
