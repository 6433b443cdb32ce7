//! `atmoscope reference`: path-traced references of a scene or of views of the suite, written as
//! linear EXR plus a PNG preview, with a progress bar showing samples per second and the noise.
//! Results are cached under a hash of the scene and settings, so asking again is instant.

use super::SceneArgs;
use crate::images::{write_exr, write_png};
use anyhow::{Context, bail};
use atmoscope_model::Scene;
use atmoscope_model::camera::Projection;
use atmoscope_model::methods::path_tracer::PathTracerSettings;
use atmoscope_model::reference::ReferenceRender;
use atmoscope_model::views::{self, View};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ProjectionArg {
    Perspective,
    Fisheye,
    Panorama,
}

impl From<ProjectionArg> for Projection {
    fn from(p: ProjectionArg) -> Projection {
        match p {
            ProjectionArg::Perspective => Projection::Perspective,
            ProjectionArg::Fisheye => Projection::Fisheye,
            ProjectionArg::Panorama => Projection::Panorama,
        }
    }
}

#[derive(Args, Debug)]
pub struct ReferenceArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// A named view of the suite (see `atmoscope reference --list-views`), applied on top of the scene.
    #[arg(long, value_name = "NAME", conflicts_with = "suite")]
    pub view: Option<String>,
    /// Render every view of the suite into --out-dir.
    #[arg(long, requires = "out_dir")]
    pub suite: bool,
    /// List the views of the suite and exit.
    #[arg(long)]
    pub list_views: bool,
    /// Image size WxH (default: the view's size, or 320x180 for a scene).
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Use each view's small CI size.
    #[arg(long)]
    pub ci_size: bool,
    /// Projection for a scene without --view.
    #[arg(long, value_enum, default_value = "perspective")]
    pub projection: ProjectionArg,
    /// Paths per pixel.
    #[arg(long, value_name = "N", conflicts_with = "noise", value_parser = clap::value_parser!(u64).range(1..))]
    pub spp: Option<u64>,
    /// Stop when the mean relative standard error of pixel luminance falls to REL (e.g. 0.01).
    #[arg(long, value_name = "REL", value_parser = super::parse_positive, allow_hyphen_values = true)]
    pub noise: Option<f64>,
    /// Highest scattering order (1 = single scattering); default all.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub max_order: Option<u32>,
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output EXR file (a PNG preview is written beside it).
    #[arg(long, value_name = "FILE.exr", required_unless_present_any = ["suite", "list_views"])]
    pub out: Option<PathBuf>,
    /// Output directory for --suite.
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,
    /// Ignore and overwrite the cache.
    #[arg(long)]
    pub no_cache: bool,
}

pub(crate) fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or("expected WxH, e.g. 320x180")?;
    let w: u32 = w.parse().map_err(|_| format!("bad width {w:?}"))?;
    let h: u32 = h.parse().map_err(|_| format!("bad height {h:?}"))?;
    if w == 0 || h == 0 || w > 8192 || h > 8192 {
        return Err("width and height must be 1 to 8192".into());
    }
    Ok((w, h))
}

/// What to render.
struct Job {
    scene: Scene,
    projection: Projection,
    size: (u32, u32),
    out: PathBuf,
}

pub fn run(args: &ReferenceArgs) -> anyhow::Result<ExitCode> {
    if args.list_views {
        for v in views::suite() {
            println!(
                "{:20} {:?} {}x{} (CI {}x{})  {}",
                v.name, v.projection, v.size.0, v.size.1, v.ci_size.0, v.ci_size.1, v.description
            );
        }
        return Ok(ExitCode::SUCCESS);
    }
    if let Some(n) = args.noise
        && !(n > 0.0 && n < 1.0)
    {
        bail!("--noise: {n} is outside (0, 1); e.g. 0.01 for 1 %");
    }
    let base = args.scene.scene()?;
    let view_size = |v: &View| {
        args.size
            .unwrap_or(if args.ci_size { v.ci_size } else { v.size })
    };
    let jobs: Vec<Job> = if args.suite {
        let dir = args.out_dir.as_ref().context("--suite needs --out-dir")?;
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        views::suite()
            .iter()
            .map(|v| Job {
                scene: v.apply(&base),
                projection: v.projection,
                size: view_size(v),
                out: dir.join(format!("{}.exr", v.name)),
            })
            .collect()
    } else {
        let out = args.out.clone().context("--out FILE.exr is required")?;
        if out
            .extension()
            .is_none_or(|e| !e.eq_ignore_ascii_case("exr"))
        {
            bail!(
                "--out {}: the file name must end in .exr (linear radiance; a PNG preview is written beside it)",
                out.display()
            );
        }
        super::check_writable(&out)?;
        match &args.view {
            Some(name) => {
                let v = views::find(name).with_context(|| {
                    let names: Vec<_> = views::suite().iter().map(|v| v.name.as_str()).collect();
                    format!(
                        "--view {name}: no such view; the suite has {}",
                        names.join(", ")
                    )
                })?;
                vec![Job {
                    scene: v.apply(&base),
                    projection: v.projection,
                    size: view_size(v),
                    out,
                }]
            }
            None => vec![Job {
                scene: base,
                projection: args.projection.into(),
                size: args.size.unwrap_or((320, 180)),
                out,
            }],
        }
    };
    for job in &jobs {
        render_job(job, args)?;
    }
    Ok(ExitCode::SUCCESS)
}

fn render_job(job: &Job, args: &ReferenceArgs) -> anyhow::Result<()> {
    let (w, h) = job.size;
    let settings = PathTrace {
        spp: args.spp,
        noise: args.noise,
        max_order: args.max_order,
        seed: args.seed,
        no_cache: args.no_cache,
    };
    let label = job
        .out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let rgb = path_traced(&job.scene, job.projection, job.size, &settings, &label)?;
    let png = job.out.with_extension("png");
    write_exr(&job.out, &rgb, w, h)?;
    write_png(&png, &rgb, w, h, &job.scene)?;
    eprintln!("{}: preview {}", job.out.display(), png.display());
    Ok(())
}

/// How a path-traced reference is rendered.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PathTrace {
    /// Paths per pixel (default 64, or until `noise` is reached).
    pub spp: Option<u64>,
    /// Stop at this mean relative standard error of pixel luminance.
    pub noise: Option<f64>,
    /// Highest scattering order (None: all).
    pub max_order: Option<u32>,
    pub seed: u64,
    /// Ignore and overwrite the cache.
    pub no_cache: bool,
}

/// The path-traced linear sRGB image (W·m⁻²·sr⁻¹, row-major) of `scene` through `projection`
/// at `size`: from the cache when an entry reads back whole, else rendered with a progress bar
/// labelled `label` and cached.
pub(crate) fn path_traced(
    scene: &Scene,
    projection: Projection,
    (w, h): (u32, u32),
    pt: &PathTrace,
    label: &str,
) -> anyhow::Result<Vec<[f64; 3]>> {
    let key = format!(
        "{}|{}|{:?}|{w}x{h}|{:?}|{:?}|{:?}|{}",
        env!("ATMOSCOPE_MODEL_SOURCES"),
        scene.to_ron(),
        projection,
        pt.spp,
        pt.noise,
        pt.max_order,
        pt.seed
    );
    let cached = crate::cache::dir("references")
        .join(format!("{:016x}.exr", crate::cache::key(key.as_bytes())));
    // A cache entry that does not read back whole (cut short, corrupted, another size) is
    // ignored and replaced.
    let hit = (cached.exists() && !pt.no_cache)
        .then(|| crate::images::read_exr(&cached))
        .and_then(|r| match r {
            Ok((rgb, cw, ch)) if (cw, ch) == (w, h) => Some(rgb),
            Ok(_) | Err(_) => {
                eprintln!(
                    "{}: unreadable cache entry, rendering anew",
                    cached.display()
                );
                None
            }
        });
    if let Some(rgb) = hit {
        eprintln!("{label}: from the cache ({})", cached.display());
        return Ok(rgb);
    }
    let settings = PathTracerSettings {
        max_order: pt.max_order,
        ..PathTracerSettings::default()
    };
    let mut render = ReferenceRender::new(scene, projection, w, h, pt.seed, settings);
    let target_spp = pt
        .spp
        .unwrap_or(if pt.noise.is_some() { 1 << 20 } else { 64 });
    let bar = ProgressBar::new(target_spp);
    bar.set_style(
        ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} spp  {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_prefix(label.to_string());
    let never = AtomicBool::new(false);
    let start = Instant::now();
    let mut pass = 1u64;
    loop {
        let done = render.samples_per_pixel();
        if done >= target_spp {
            break;
        }
        let step = pass.min(target_spp - done);
        render.run_pass(step as u32, &never);
        pass = (pass * 2).min(64);
        let noise = render.mean_relative_error();
        let rate =
            render.samples_per_pixel() as f64 * (w * h) as f64 / start.elapsed().as_secs_f64();
        bar.set_position(render.samples_per_pixel());
        bar.set_message(format!("noise {:.2} %  {:.0} paths/s", noise * 100.0, rate));
        if pt
            .noise
            .is_some_and(|target| noise <= target && render.samples_per_pixel() >= 16)
        {
            break;
        }
    }
    bar.finish();
    let rgb = render.linear_srgb();
    if let Some(dir) = cached.parent()
        && std::fs::create_dir_all(dir).is_ok()
    {
        // The cache is an optimisation: failing to fill it loses nothing.
        let _ = write_exr(&cached, &rgb, w, h);
    }
    eprintln!(
        "{label}: {} spp, noise {:.2} % (mean per-pixel relative standard error of luminance), {:.1} s",
        render.samples_per_pixel(),
        render.mean_relative_error() * 100.0,
        start.elapsed().as_secs_f64(),
    );
    Ok(rgb)
}
