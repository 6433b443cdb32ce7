//! `atmoscope bench methods`: every model × wavelength set × quality over views of the suite,
//! run time against error on one chart. Per view it measures the table precompute (the table
//! passes of a full rebuild: those of the atmosphere timed once per configuration, the view
//! tables per view), a frame with the camera turning (the passes it runs), the tables' memory,
//! and the error of the view against its path-traced reference (ΔE2000 mean and p95, HDR-FLIP,
//! relative RMSE of luminance outside the sun's disk); it writes `results.csv`, `summary.md` and the Pareto chart
//! (`pareto.svg`, `pareto.png`) of frame time against mean ΔE2000.

use crate::args::parse_wavelengths;
use crate::args::set_name;
use crate::args::{parse_quality, quality_name};
use crate::bench_results::{Config, Row, summarise, to_csv};
use crate::cli::common::{gpu, median, outside_sun_disk};
use crate::cli::progress::Progress;
use crate::images::read_exr;
use anyhow::{Context, anyhow, bail};
use atmoscope_eval::metrics::{DisplaySetup, compare, luminance_relative_rmse_where};
use atmoscope_model::Scene;
use atmoscope_model::methods::Inputs;
use atmoscope_model::scene::{Quality, WavelengthSet};
use atmoscope_model::views;
use atmoscope_render::{Engine, View};
use clap::Args;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// The views `--quick` measures: ground, plane and space, high and low sun, one twilight.
pub const QUICK_VIEWS: [&str; 6] = [
    "ground-noon",
    "ground-sunrise",
    "fisheye-sun5",
    "plane-noon",
    "orbit-sunrise",
    "twilight-6",
];

/// Wall time after which a view's frame timing, or a configuration's precompute timing, stops,
/// however few it has timed (one at least).
const TIMING_BUDGET: std::time::Duration = std::time::Duration::from_secs(2);

#[derive(Args, Debug)]
pub struct MethodsBench {
    /// A quick run (six views, RGB3 and Spectral4, medium quality, up to 3 frames of 480x270
    /// each).
    #[arg(long, conflicts_with = "full")]
    pub quick: bool,
    /// The whole run (every view with a reference; RGB3, Spectral4 and Spectral32; low,
    /// medium and high quality; frames of 320x180 timed on the quick views, 10 each).
    #[arg(long)]
    pub full: bool,
    /// Sky models, comma-separated registry ids, or `all` (default: all).
    #[arg(long, value_name = "IDS", value_parser = crate::args::parse_methods)]
    pub methods: Option<crate::args::MethodList>,
    /// Wavelength sets, comma-separated (overrides --quick/--full).
    #[arg(long, value_delimiter = ',', value_parser = parse_wavelengths)]
    pub sets: Vec<WavelengthSet>,
    /// Qualities, comma-separated: low, medium, high (overrides --quick/--full).
    #[arg(long, value_delimiter = ',', value_parser = parse_quality)]
    pub qualities: Vec<Quality>,
    /// Views of the suite, comma-separated (overrides --quick/--full).
    #[arg(long, value_delimiter = ',')]
    pub views: Vec<String>,
    /// Directory of path-traced references `<view>.exr`
    /// (`atmoscope reference --suite --ci-size --out-dir DIR`, which caches what it renders);
    /// default: the repository's tests/data/references, under the working directory or above
    /// the program.
    #[arg(long, value_name = "DIR")]
    pub refs: Option<PathBuf>,
    /// Size WxH of the frames that are timed (errors are measured at the references' size);
    /// default 480x270, or 320x180 with --full.
    #[arg(long, value_name = "WxH", value_parser = crate::args::parse_size)]
    pub frame_size: Option<(u32, u32)>,
    /// Most frames timed per view (median reported; default 3 quick, 10 full); fewer once
    /// they have taken two seconds, as the nested marches of a table-free model can.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub repeats: Option<u32>,
    /// Time passes by fenced CPU wall time even where GPU timestamps exist (always on a
    /// software adapter, whose timestamps do not time passes).
    #[arg(long)]
    pub cpu_timing: bool,
    /// Output folder (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

/// What one run measures, from the flags.
struct Plan {
    /// Where the references are (`--refs`, or the shipped ones).
    refs: PathBuf,
    methods: Vec<atmoscope_model::scene::Method>,
    sets: Vec<WavelengthSet>,
    qualities: Vec<Quality>,
    views: Vec<&'static views::View>,
    /// The views whose frames are timed: with --full the quick views among `views` (a frame
    /// of a nested march at Spectral32 High takes 40 s at 640×360 here, and a model's frame
    /// time varies less across views than across models), else all.
    frame_views: Vec<&'static str>,
    frame_size: (u32, u32),
    repeats: usize,
}

fn plan(args: &MethodsBench) -> anyhow::Result<Plan> {
    let full = args.full;
    let methods = args.methods.clone().map_or_else(
        || {
            atmoscope_model::methods::realtime()
                .map(|m| m.method)
                .collect()
        },
        |m| m.0,
    );
    let sets = match (args.sets.is_empty(), full) {
        (false, _) => args.sets.clone(),
        (true, false) => vec![WavelengthSet::Rgb3, WavelengthSet::Spectral4],
        (true, true) => vec![
            WavelengthSet::Rgb3,
            WavelengthSet::Spectral4,
            WavelengthSet::SpectralN(32),
        ],
    };
    let qualities = match (args.qualities.is_empty(), full) {
        (false, _) => args.qualities.clone(),
        (true, false) => vec![Quality::Medium],
        (true, true) => vec![Quality::Low, Quality::Medium, Quality::High],
    };
    let refs = crate::shipped::references(args.refs.as_deref())?;
    let has_ref = |v: &views::View| refs.join(format!("{}.exr", v.name)).is_file();
    let views: Vec<&'static views::View> = if !args.views.is_empty() {
        args.views
            .iter()
            .map(|n| views::find(n).with_context(|| format!("--views: no view {n} in the suite")))
            .collect::<anyhow::Result<_>>()?
    } else if full {
        views::suite().iter().filter(|v| has_ref(v)).collect()
    } else {
        QUICK_VIEWS.iter().filter_map(|n| views::find(n)).collect()
    };
    if let Some(v) = views.iter().find(|v| !has_ref(v)) {
        bail!(
            "{}: no reference for view {} (render them with `atmoscope reference --suite --ci-size --out-dir {}`; results are cached)",
            refs.join(format!("{}.exr", v.name)).display(),
            v.name,
            refs.display()
        );
    }
    if views.is_empty() {
        bail!("no references in {}", refs.display());
    }
    let repeats = args
        .repeats
        .map_or(if full { 10 } else { 3 }, |r| r as usize);
    let quick_ones: Vec<&'static str> = views
        .iter()
        .map(|v| v.name.as_str())
        .filter(|n| QUICK_VIEWS.contains(n))
        .collect();
    let frame_views = if full && !quick_ones.is_empty() {
        quick_ones
    } else {
        views.iter().map(|v| v.name.as_str()).collect()
    };
    let frame_size = args
        .frame_size
        .unwrap_or(if full { (320, 180) } else { (480, 270) });
    Ok(Plan {
        refs,
        methods,
        sets,
        qualities,
        views,
        frame_views,
        frame_size,
        repeats,
    })
}

pub fn run(args: &MethodsBench) -> anyhow::Result<ExitCode> {
    let plan = plan(args)?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let references: Vec<(Vec<[f64; 3]>, u32, u32)> = plan
        .views
        .iter()
        .map(|v| {
            let path = plan.refs.join(format!("{}.exr", v.name));
            read_exr(&path).with_context(|| format!("reference {}", path.display()))
        })
        .collect::<anyhow::Result<_>>()?;
    let context = gpu()?;
    let mut configs = Vec::new();
    for &m in &plan.methods {
        for &s in &plan.sets {
            for &q in &plan.qualities {
                configs.push((m, s, q));
            }
        }
    }
    let total = (configs.len() * plan.views.len()) as u64;
    let progress = Progress::new(total);
    let start = Instant::now();
    let mut rows = Vec::new();
    let mut timing = String::new();
    let mut failures = Vec::new();
    let mut refused = Vec::new();
    for &(method, set, quality) in &configs {
        let mut engine = Engine::new(&context.device, &context.queue);
        engine.set_timing(true);
        if args.cpu_timing || context.is_software() {
            engine.force_cpu_timing();
        }
        let info = atmoscope_model::methods::info(method);
        let mut state = ConfigState::default();
        for (v, (reference, w, h)) in plan.views.iter().zip(&references) {
            let label = format!(
                "{}/{}/{} {}",
                info.id,
                set_name(set),
                quality_name(quality),
                v.name
            );
            progress.step(&label);
            let mut scene = v.apply(&Scene::default());
            scene.render.method = method;
            scene.render.wavelengths = set;
            scene.render.quality = quality;
            if let Some(why) = info.cannot_draw(&scene) {
                refused.push(format!("{label}: {why}"));
                continue;
            }
            let case = Case {
                view: v,
                scene,
                reference,
                size: (*w, *h),
            };
            let frames = plan
                .frame_views
                .contains(&v.name.as_str())
                .then_some(plan.frame_size);
            // A failure (a GPU error, say) leaves this case out and the run goes on.
            match measure(&mut engine, info, case, frames, plan.repeats, &mut state) {
                Ok(row) => {
                    timing = engine.timing_source().label().to_string();
                    rows.push(row);
                }
                Err(e) => {
                    eprintln!("{label}: {e:#}; left out");
                    failures.push(format!("{label}: {e:#}"));
                }
            }
        }
    }
    progress.finish();
    if rows.is_empty() {
        bail!("every case failed:\n{}", failures.join("\n"));
    }
    let configs = summarise(&rows);
    let header = Header {
        left_out: &failures,
        refused: &refused,
        adapter: context.describe(),
        timing,
        frame_size: plan.frame_size,
        repeats: plan.repeats,
        views: plan.views.iter().map(|v| v.name.as_str()).collect(),
        frame_views: plan.frame_views.clone(),
        seconds: start.elapsed().as_secs_f64(),
    };
    crate::files::write_atomic(&args.out.join("results.csv"), to_csv(&rows).as_bytes())?;
    crate::files::write_atomic(
        &args.out.join("summary.md"),
        summary_markdown(&configs, &header).as_bytes(),
    )?;
    write_charts(&args.out, &configs, &header)?;
    print!("{}", summary_markdown(&configs, &header));
    if !failures.is_empty() {
        eprintln!(
            "{} case(s) left out:\n{}",
            failures.len(),
            failures.join("\n")
        );
    }
    eprintln!(
        "wrote results.csv, summary.md, pareto.svg and pareto.png to {}",
        args.out.display()
    );
    // Results are written either way; a run with cases left out says so in its status.
    Ok(if failures.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// One view of one configuration: its scene and its path-traced reference.
struct Case<'a> {
    view: &'a views::View,
    scene: Scene,
    reference: &'a [[f64; 3]],
    size: (u32, u32),
}

/// What the views of one configuration share: whether its pipelines are compiled, and the
/// part of its precompute that no view changes (the tables of the atmosphere alone).
#[derive(Default)]
struct ConfigState {
    warmed: bool,
    atmosphere_ms: Option<f64>,
}

/// Measures one case with `engine` (the configuration's): frames of size `frames` are timed,
/// or none where it is None.
fn measure(
    engine: &mut Engine,
    info: &atmoscope_model::methods::ModelInfo,
    case: Case,
    frames: Option<(u32, u32)>,
    repeats: usize,
    state: &mut ConfigState,
) -> anyhow::Result<Row> {
    let Case {
        view: v,
        mut scene,
        reference,
        size: (w, h),
    } = case;
    // A full rebuild, pass by pass (each table pass's time, summed); a model whose
    // tables do not read the viewpoint builds the same tables for every view, so once
    // is enough.
    let ref_view = View::new(v.projection, w, h);
    if !state.warmed {
        // Compiles the model's pipelines outside the timing.
        engine.try_render(&scene, &ref_view)?;
        engine.wait();
        state.warmed = true;
    }
    // The precompute of this view: the tables of the atmosphere, timed once per configuration
    // (no view changes them or their cost), and the view tables it needs (Hillaire's sky view
    // and aerial perspective, none from space; Bruneton's and Elek's camera slices), timed per
    // view.
    let time_tables = |engine: &mut Engine, full: bool| -> anyhow::Result<f64> {
        let mut times = Vec::new();
        let start = Instant::now();
        for _ in 0..repeats.min(3) {
            if full {
                engine.invalidate();
            } else {
                engine.invalidate_inputs(Inputs::VIEWPOINT);
            }
            let stats = engine.try_render(&scene, &ref_view)?;
            times.push(stats.tables_run.iter().filter_map(|p| stats.ms(p)).sum());
            engine.wait();
            if start.elapsed() > TIMING_BUDGET {
                break;
            }
        }
        Ok(median(times))
    };
    let precompute_ms = if info.tables.is_empty() {
        0.0
    } else {
        let view_ms = if info.reads_viewpoint() {
            time_tables(engine, false)?
        } else {
            0.0
        };
        let atmosphere_ms = match state.atmosphere_ms {
            Some(ms) => ms,
            None => {
                let ms = (time_tables(engine, true)? - view_ms).max(0.0);
                state.atmosphere_ms = Some(ms);
                ms
            }
        };
        atmosphere_ms + view_ms
    };
    engine.try_render(&scene, &ref_view)?;
    let image: Vec<[f64; 3]> = engine
        .read_radiance()?
        .iter()
        .map(|p| [p[0], p[1], p[2]].map(f64::from))
        .collect();
    let setup = DisplaySetup {
        exposure_ev: scene.display.exposure_ev,
        tone_map: scene.display.tone_map,
        ..DisplaySetup::default()
    };
    let (c, _) = compare(&image, reference, w, h, setup);
    let outside_sun = outside_sun_disk(&scene, v.projection, w, h);
    let mut times = Vec::new();
    if let Some((fw, fh)) = frames {
        let frame_view = View::new(v.projection, fw, fh);
        let timing_start = Instant::now();
        for i in 0..repeats {
            scene.camera.heading_deg = (scene.camera.heading_deg + 1.0 + i as f64) % 360.0;
            let stats = engine.try_render(&scene, &frame_view)?;
            // A frame whose passes were not timed (none ran) is left out.
            if stats.ms("sky").is_some() {
                times.push(stats.timings_ms.iter().map(|(_, ms)| ms).sum::<f64>());
            }
            engine.wait();
            if timing_start.elapsed() > TIMING_BUDGET {
                break;
            }
        }
    }
    Ok(Row {
        method: info.id.into(),
        wavelengths: set_name(scene.render.wavelengths),
        quality: quality_name(scene.render.quality).into(),
        view: v.name.clone(),
        precompute_ms,
        // None where no frame was timed (or none of them ran its passes).
        frame_ms: (!times.is_empty()).then(|| median(times)),
        table_bytes: engine.table_bytes(),
        de2000_mean: c.delta_e2000_mean,
        de2000_p95: c.delta_e2000_p95,
        flip: c.hdr_flip_mean,
        rel_rmse: luminance_relative_rmse_where(&image, reference, &outside_sun),
    })
}

/// What the summary and the chart say about the run itself.
struct Header<'a> {
    /// Cases that failed and were left out, each with why.
    left_out: &'a [String],
    /// Cases outside the domain of a model that refuses them, each with why.
    refused: &'a [String],
    adapter: String,
    timing: String,
    frame_size: (u32, u32),
    repeats: usize,
    views: Vec<&'a str>,
    /// The views whose frames were timed.
    frame_views: Vec<&'a str>,
    seconds: f64,
}

fn summary_markdown(configs: &[Config], h: &Header) -> String {
    let mut s = String::from("# Sky models: run time against error\n\n");
    s += &format!(
        "Adapter: {}. Frame time: the passes of a {}×{} frame with the camera turning (the sky pass draws the displayed image too), median of up to {} (fewer after 2 s; {}){}. \
         Precompute: the table passes of a full rebuild, timed the same way (median of up to 3, fewer after 2 s). \
         Error against path-traced references of {} view(s): {}. Measured in {:.0} s.\n\n",
        h.adapter,
        h.frame_size.0,
        h.frame_size.1,
        h.repeats,
        h.timing,
        if h.frame_views.len() < h.views.len() {
            format!(", timed on {}", h.frame_views.join(", "))
        } else {
            String::new()
        },
        h.views.len(),
        h.views.join(", "),
        h.seconds
    );
    s += "Means over the views; ★ marks the Pareto front of frame time against mean ΔE2000.\n\n";
    s += "| | model | set | quality | precompute ms | frame ms | tables MiB | ΔE2000 mean | ΔE2000 p95 | HDR-FLIP | rel. RMSE L |\n";
    s += "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
    let mut sorted: Vec<&Config> = configs.iter().collect();
    sorted.sort_by(|a, b| a.frame_ms.total_cmp(&b.frame_ms));
    let most_views = configs.iter().map(|c| c.views).max().unwrap_or(0);
    for c in &sorted {
        s += &format!(
            "| {} | {}{} | {} | {} | {:.1} | {} | {:.2} | {:.2} | {:.2} | {:.3} | {:.3} |\n",
            if c.on_front { "★" } else { "" },
            c.method,
            if c.views < most_views {
                format!(" ({} of {most_views} views)", c.views)
            } else {
                String::new()
            },
            c.wavelengths,
            c.quality,
            c.precompute_ms,
            if c.timed() {
                format!("{:.2}", c.frame_ms)
            } else {
                "—".into()
            },
            c.table_bytes as f64 / (1024.0 * 1024.0),
            c.de2000_mean,
            c.de2000_p95,
            c.flip,
            c.rel_rmse
        );
    }
    s += "\n## What to pick for a frame budget\n\n";
    let front: Vec<&&Config> = sorted.iter().filter(|c| c.on_front).collect();
    for (i, c) in front.iter().enumerate() {
        let until = front.get(i + 1).map_or(String::from("and more"), |n| {
            format!("to {:.2} ms", n.frame_ms)
        });
        s += &format!(
            "- {:.2} ms {until}: **{}** (mean ΔE2000 {:.2})\n",
            c.frame_ms,
            c.name(),
            c.de2000_mean
        );
    }
    if !h.refused.is_empty() {
        s += "\n## Refused\n\nViews outside the domain of a model that refuses them; that \
              model's figures are means over the views it draws.\n\n";
        for f in h.refused {
            s += &format!("- {f}\n");
        }
    }
    if !h.left_out.is_empty() {
        s += "\n## Left out\n\n";
        for f in h.left_out {
            s += &format!("- {f}\n");
        }
    }
    s
}

/// The Pareto chart as `pareto.svg` and `pareto.png`.
fn write_charts(out: &Path, configs: &[Config], header: &Header) -> anyhow::Result<()> {
    crate::images::register_font();
    // A configuration without a timed frame has no place on the time axis.
    let timed: Vec<Config> = configs.iter().filter(|c| c.timed()).cloned().collect();
    let configs = &timed[..];
    crate::images::chart_files!(out, "pareto", (960u32, 640u32), |backend| draw_chart(
        backend, configs, header
    ))
}

/// Axis ticks at 1, 2 and 5 times the powers of ten inside `range` (a log axis of less than a
/// decade would otherwise show one label or none).
fn ticks(range: std::ops::Range<f64>) -> Vec<f64> {
    let (lo, hi) = (
        range.start.log10().floor() as i32,
        range.end.log10().ceil() as i32,
    );
    (lo..=hi)
        .flat_map(|d| [1.0, 2.0, 5.0].map(|m| m * 10f64.powi(d)))
        .filter(|v| range.contains(v))
        .collect()
}

fn draw_chart<B: plotters::prelude::DrawingBackend>(
    backend: B,
    configs: &[Config],
    header: &Header,
) -> anyhow::Result<()> {
    use plotters::prelude::*;
    let err = |e: plotters::drawing::DrawingAreaErrorKind<B::ErrorType>| anyhow!("chart: {e}");
    let root = backend.into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    // `room`: how far past the largest value the axis goes (the labels sit right of points).
    let range = |f: fn(&Config) -> f64, room: f64| {
        let (lo, hi) = configs
            .iter()
            .map(f)
            .filter(|v| *v > 0.0 && v.is_finite())
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        if lo.is_finite() {
            (lo / 1.5)..(hi * room)
        } else {
            0.01..1.0
        }
    };
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!(
                "Frame time against error ({} views, {}×{}, {})",
                header.views.len(),
                header.frame_size.0,
                header.frame_size.1,
                header.timing
            ),
            ("sans-serif", 20),
        )
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(56)
        .build_cartesian_2d(
            {
                // Room on the right for the legend (in the upper right corner), so that it
                // hides none of the slowest models' points.
                let r = range(|c| c.frame_ms, 25.0);
                r.clone().log_scale().with_key_points(ticks(r))
            },
            {
                let r = range(|c| c.de2000_mean, 1.5);
                r.clone().log_scale().with_key_points(ticks(r))
            },
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("frame time, ms (log)")
        .y_desc("mean ΔE2000 against the path tracer (log)")
        .label_style(("sans-serif", 14))
        .x_label_formatter(&|v| format!("{}", (v * 1e6).round() / 1e6))
        .y_label_formatter(&|v| format!("{}", (v * 1e6).round() / 1e6))
        .draw()
        .map_err(err)?;
    let mut front: Vec<(f64, f64)> = configs
        .iter()
        .filter(|c| c.on_front)
        .map(|c| (c.frame_ms, c.de2000_mean))
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    // The front as a staircase: each point is the best error until the next one's time.
    let mut steps = Vec::new();
    for (i, p) in front.iter().enumerate() {
        steps.push(*p);
        if let Some(n) = front.get(i + 1) {
            steps.push((n.0, p.1));
        }
    }
    chart
        .draw_series(LineSeries::new(steps, BLACK.stroke_width(2)))
        .map_err(err)?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.stroke_width(2)));
    let models = crate::bench_results::models_in_order(configs);
    for (i, model) in models.iter().enumerate() {
        // The family's colour, the model's marker within it (`chart_style`).
        let style = crate::chart_style::style(model, i);
        let [r, g, b] = style.colour;
        let colour = RGBColor(r, g, b);
        let points: Vec<(f64, f64)> = configs
            .iter()
            .filter(|c| c.method == *model)
            .map(|c| (c.frame_ms, c.de2000_mean))
            .collect();
        // Each marker drawn at a point's pixel, and the same in the legend.
        macro_rules! series {
            ($shape:expr) => {
                chart
                    .draw_series(points.iter().map(|&p| EmptyElement::at(p) + $shape))
                    .map_err(err)?
                    .label(*model)
                    .legend(move |(x, y)| EmptyElement::at((x + 9, y)) + $shape)
            };
        }
        use crate::chart_style::Marker;
        let (filled, open) = (colour.filled(), colour.stroke_width(2));
        match style.marker {
            Marker::Circle => series!(Circle::new((0, 0), 6, filled)),
            Marker::Ring => series!(Circle::new((0, 0), 6, open)),
            Marker::Triangle => series!(TriangleMarker::new((0, 0), 7, filled)),
            Marker::OpenTriangle => series!(TriangleMarker::new((0, 0), 7, open)),
            Marker::Square => series!(Rectangle::new([(-5, -5), (5, 5)], filled)),
            Marker::OpenSquare => series!(Rectangle::new([(-5, -5), (5, 5)], open)),
            Marker::Cross => series!(Cross::new((0, 0), 6, open)),
        };
    }
    // Each point's wavelength set and quality beside it where that covers no other label or
    // marker; in a crowd some are left out (the legend and summary.md name every one).
    let at: Vec<(i32, i32)> = configs
        .iter()
        .map(|c| chart.backend_coord(&(c.frame_ms, c.de2000_mean)))
        .collect();
    let texts: Vec<String> = configs
        .iter()
        .map(|c| format!("{} {}", c.wavelengths, c.quality))
        .collect();
    // 12 px sans-serif: about 6.5 px a character.
    let sizes: Vec<(i32, i32)> = texts
        .iter()
        .map(|t| ((t.chars().count() as f64 * 6.5).ceil() as i32, 13))
        .collect();
    let (xs, ys) = chart.plotting_area().get_pixel_range();
    let area = crate::chart_style::PixelBox {
        x: xs.start,
        y: ys.start,
        w: xs.end - xs.start,
        h: ys.end - ys.start,
    };
    for (text, place) in texts
        .iter()
        .zip(crate::chart_style::place_labels(&at, &sizes, 7, area))
    {
        if let Some(b) = place {
            root.draw(&Text::new(text.clone(), (b.x, b.y), ("sans-serif", 12)))
                .map_err(err)?;
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 14))
        .draw()
        .map_err(err)?;
    root.present().map_err(err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(full: bool, views: &[&str]) -> MethodsBench {
        MethodsBench {
            quick: !full,
            full,
            methods: None,
            sets: Vec::new(),
            qualities: Vec::new(),
            views: views.iter().map(|v| v.to_string()).collect(),
            refs: Some(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../tests/data/references")),
            frame_size: None,
            repeats: None,
            cpu_timing: false,
            out: std::env::temp_dir(),
        }
    }

    /// `--full` measures every view with a reference but times 320×180 frames on the quick
    /// views alone; a run without a quick view times all its views, as `--quick` does.
    #[test]
    fn full_times_frames_on_the_quick_views_only() {
        let full = plan(&args(true, &[])).expect("plan");
        assert!(full.views.len() > QUICK_VIEWS.len());
        let mut timed = full.frame_views.clone();
        timed.sort_unstable();
        let mut quick_views = QUICK_VIEWS.to_vec();
        quick_views.sort_unstable();
        assert_eq!(timed, quick_views);
        assert_eq!(full.frame_size, (320, 180));
        assert_eq!(full.sets.len() * full.qualities.len(), 9);
        let quick = plan(&args(false, &[])).expect("plan");
        assert_eq!(quick.frame_views.len(), quick.views.len());
        assert_eq!(quick.frame_size, (480, 270));
        let elsewhere = plan(&args(true, &["space", "twilight-12"])).expect("plan");
        assert_eq!(elsewhere.frame_views, vec!["space", "twilight-12"]);
    }
}
