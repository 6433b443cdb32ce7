//! `atmoscope bench path-tracer`: renders views of the suite progressively and reports paths
//! per second and the time each takes to reach a noise level, both for the mean per-pixel
//! relative standard error of luminance and for the relative standard error of the image's
//! mean luminance.

use anyhow::{Context, bail};
use atmoscope_model::Scene;
use atmoscope_model::methods::path_tracer::PathTracerSettings;
use atmoscope_model::reference::ReferenceRender;
use atmoscope_model::views;
use clap::Args;
use serde::Serialize;
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

#[derive(Args, Debug)]
pub struct PathTracerBench {
    /// Views of the suite, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "fisheye-sun90,fisheye-sun2"
    )]
    pub views: Vec<String>,
    /// Square image size, pixels.
    #[arg(long, default_value_t = 128, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub size: u32,
    /// Target relative standard error of luminance.
    #[arg(long, default_value_t = 0.01, value_parser = crate::args::parse_positive, allow_hyphen_values = true)]
    pub noise: f64,
    /// Give up on a view after this many seconds.
    #[arg(long, default_value_t = 600.0, value_parser = crate::args::parse_positive, allow_hyphen_values = true)]
    pub max_seconds: f64,
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize, Debug)]
struct Row {
    view: String,
    size: u32,
    threads: usize,
    paths_per_second: f64,
    /// Seconds until the image's mean luminance reached the target error (None: not within the limit).
    seconds_to_image_noise: Option<f64>,
    /// Seconds until the mean per-pixel error reached the target.
    seconds_to_pixel_noise: Option<f64>,
    spp_at_end: u64,
    pixel_noise_at_end: f64,
}

pub fn run(args: &PathTracerBench) -> anyhow::Result<ExitCode> {
    if !(args.noise > 0.0 && args.noise < 1.0) {
        bail!("--noise: {} is outside (0, 1)", args.noise);
    }
    let mut rows = Vec::new();
    for name in &args.views {
        let view = views::find(name).with_context(|| format!("--views: no view {name}"))?;
        let scene = view.apply(&Scene::default());
        let mut render = ReferenceRender::new(
            &scene,
            view.projection,
            args.size,
            args.size,
            1,
            PathTracerSettings::default(),
        );
        let never = AtomicBool::new(false);
        let start = Instant::now();
        let (mut image_t, mut pixel_t) = (None, None);
        let mut pass = 1;
        while start.elapsed().as_secs_f64() < args.max_seconds && pixel_t.is_none() {
            render.run_pass(pass, &never);
            pass = (pass * 2).min(32);
            let t = start.elapsed().as_secs_f64();
            if image_t.is_none()
                && render.samples_per_pixel() >= 4
                && render.image_relative_error() <= args.noise
            {
                image_t = Some(t);
            }
            if render.samples_per_pixel() >= 16 && render.mean_relative_error() <= args.noise {
                pixel_t = Some(t);
            }
            eprint!(
                "\r{name}: {} spp, pixel noise {:.2} %, {:.0} s   ",
                render.samples_per_pixel(),
                render.mean_relative_error() * 100.0,
                t
            );
        }
        eprintln!();
        let covered = render.pixels().iter().filter(|p| p.covered).count() as f64;
        rows.push(Row {
            view: name.clone(),
            size: args.size,
            threads: rayon::current_num_threads(),
            paths_per_second: covered * render.samples_per_pixel() as f64
                / start.elapsed().as_secs_f64(),
            seconds_to_image_noise: image_t,
            seconds_to_pixel_noise: pixel_t,
            spp_at_end: render.samples_per_pixel(),
            pixel_noise_at_end: render.mean_relative_error(),
        });
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
    } else {
        println!(
            "view                 size  threads  paths/s    to {0:.1}% (image mean)  to {0:.1}% (per pixel)  spp",
            args.noise * 100.0
        );
        let fmt = |t: Option<f64>| t.map_or("not reached".to_string(), |t| format!("{t:.1} s"));
        for r in rows {
            println!(
                "{:20} {:4}  {:7}  {:9.0}  {:>22}  {:>21}  {}",
                r.view,
                r.size,
                r.threads,
                r.paths_per_second,
                fmt(r.seconds_to_image_noise),
                fmt(r.seconds_to_pixel_noise),
                r.spp_at_end
            );
        }
    }
    Ok(ExitCode::SUCCESS)
}
