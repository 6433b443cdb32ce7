//! `atmoscope timelapse`: a sweep of the sun as a PNG sequence and an animated PNG.

use crate::cli::common::{ViewArg, gpu};
use crate::scene_args::SceneArgs;
use crate::timelapse::{self, Sweep};
use anyhow::Context;
use atmoscope_render::View;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct TimelapseArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Sweep the sun's elevation from FROM to TO degrees, its azimuth kept (default: from the
    /// scene's sun, or 10° if lower, to −8°: a sunset).
    #[arg(long, value_name = "FROM,TO", value_parser = parse_pair, allow_hyphen_values = true, conflicts_with = "hours")]
    pub elevations: Option<(f64, f64)>,
    /// Sweep the local clock time of the scene's date and place from FROM to TO hours (the
    /// scene's sun must be placed by date, time and place: a preset's `sun: Date(...)`, as in
    /// `zurich-solstice-evening`).
    #[arg(long, value_name = "FROM,TO", value_parser = parse_pair)]
    pub hours: Option<(f64, f64)>,
    /// Number of frames (1 to 1000).
    #[arg(long, default_value_t = 48)]
    pub frames: u32,
    /// Frames a second of the animation (1 to 120).
    #[arg(long, default_value_t = 12)]
    pub fps: u16,
    /// Projection, or `luminance` for a false-colour luminance map of the sky dome.
    #[arg(long, value_enum, default_value = "perspective")]
    pub projection: ViewArg,
    /// Frame size WxH.
    #[arg(long, value_name = "WxH", value_parser = crate::args::parse_size, default_value = "640x360")]
    pub size: (u32, u32),
    /// Output folder: frame_0000.png, frame_0001.png, … and timelapse.png (the animation).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

fn parse_pair(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s.split_once(',').ok_or("expected FROM,TO, e.g. 10,-8")?;
    let num = |v: &str| {
        v.trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or(format!("bad number {v:?}"))
    };
    Ok((num(a)?, num(b)?))
}

pub fn run(args: &TimelapseArgs) -> anyhow::Result<ExitCode> {
    let scene = args.scene.scene()?;
    let sweep = match (args.elevations, args.hours) {
        (Some((from_deg, to_deg)), _) => Sweep::Elevation { from_deg, to_deg },
        (None, Some((from_h, to_h))) => Sweep::Hours { from_h, to_h },
        (None, None) => Sweep::sunset_or_day(&scene),
    };
    sweep.validate()?;
    // Every frame's scene is checked before the GPU starts.
    for i in 0..args.frames.min(timelapse::MAX_FRAMES) {
        sweep.scene(&scene, i, args.frames)?;
    }
    let (projection, mode) = args.projection.projection_and_mode();
    let (width, height) = args.size;
    let view = View {
        projection,
        mode,
        width,
        height,
    };
    let gpu = gpu()?;
    let bar = ProgressBar::new(u64::from(args.frames));
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} frames, {eta} left")
            .context("progress style")?,
    );
    let animation = args.out.join("timelapse.png");
    let written = timelapse::render(
        &mut atmoscope_render::Engine::new(&gpu.device, &gpu.queue),
        &scene,
        sweep,
        args.frames,
        view,
        args.fps,
        &args.out,
        &animation,
        &|f| {
            bar.set_position((f64::from(f) * f64::from(args.frames)).round() as u64);
            true
        },
    )?;
    bar.finish_and_clear();
    if let Some(w) = written {
        eprintln!(
            "wrote {} frames in {} and the animation {} ({width}x{height}, {} fps) on {}",
            w.frames.len(),
            args.out.display(),
            w.animation.display(),
            args.fps,
            gpu.describe()
        );
    }
    Ok(ExitCode::SUCCESS)
}
