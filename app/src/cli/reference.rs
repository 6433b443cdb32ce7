//! `atmoscope reference`: path-traced references of a scene or of views of the suite, written as
//! linear EXR plus a PNG preview, with a progress bar showing samples per second and the noise.
//! Results are cached under a hash of the scene and settings, so asking again is instant.

use crate::args::parse_size;
use crate::cli::common::{PathTrace, path_traced, path_traced_stokes};
use crate::images::{write_exr, write_exr_with_stokes, write_png};
use crate::scene_args::SceneArgs;
use anyhow::{Context, bail};
use atmoscope_model::Scene;
use atmoscope_model::camera::Projection;
use atmoscope_model::views::{self, View};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use std::process::ExitCode;

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
    #[arg(long, value_name = "REL", value_parser = crate::args::parse_positive, allow_hyphen_values = true)]
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
    /// Trace in the vector mode and add the photometric Stokes vector as channels I, Q, U, V
    /// (ȳ-weighted like Y, W·m⁻²·sr⁻¹; Q and U referred to "up" in the picture at each
    /// pixel). Not cached.
    #[arg(long)]
    pub stokes: bool,
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
        crate::files::check_writable(&out)?;
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
    let png = job.out.with_extension("png");
    let rgb = if args.stokes {
        let (rgb, stokes) =
            path_traced_stokes(&job.scene, job.projection, job.size, &settings, &label);
        write_exr_with_stokes(&job.out, &rgb, Some(&stokes), w, h)?;
        rgb
    } else {
        let rgb = path_traced(&job.scene, job.projection, job.size, &settings, &label)?;
        write_exr(&job.out, &rgb, w, h)?;
        rgb
    };
    write_png(&png, &rgb, w, h, &job.scene)?;
    eprintln!("{}: preview {}", job.out.display(), png.display());
    Ok(())
}
