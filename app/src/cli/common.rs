//! What several subcommands share: the headless GPU, the path-traced references and their
//! cache, medians and the sun's disk in a view. No subcommand imports another; they import this.

use crate::images::{read_exr, write_exr};
use anyhow::Context;
use atmoscope_model::Scene;
use atmoscope_model::camera::{Camera, Projection};
use atmoscope_model::geometry::direction_from_angles;
use atmoscope_model::methods::path_tracer::PathTracerSettings;
use atmoscope_model::reference::ReferenceRender;
use atmoscope_render::{DisplayMode, GpuContext};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// Opens the headless GPU the engine renders on.
pub fn gpu() -> anyhow::Result<GpuContext> {
    GpuContext::headless().context("the real-time engine needs a GPU adapter")
}

/// The median (the mean of the middle two of an even count; NaN of none).
pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => v[n / 2],
        n => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}

/// Which pixels of a `w`×`h` view of `scene` the sun's disk does not touch.
pub fn outside_sun_disk(scene: &Scene, projection: Projection, w: u32, h: u32) -> Vec<bool> {
    let camera = Camera::new(
        &scene.camera,
        scene.atmosphere.planet_radius_km * 1000.0,
        projection,
    );
    let a = scene.sun.angles();
    let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
    let disk = camera.sun_in_view(sun, w, h);
    (0..w * h)
        .map(|i| {
            disk.as_ref().is_none_or(|d| {
                d.pixel((i % w) as f64 + 0.5, (i / w) as f64 + 0.5)
                    .is_none()
            })
        })
        .collect()
}

/// How a path-traced reference is rendered.
#[derive(Debug, Clone, Copy)]
pub struct PathTrace {
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
pub fn path_traced(
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
    let mut render = ReferenceRender::new(scene, projection, w, h, pt.seed, pt.settings());
    run_to_target(&mut render, pt, label);
    let rgb = render.linear_srgb();
    if let Some(dir) = cached.parent()
        && std::fs::create_dir_all(dir).is_ok()
    {
        // The cache is an optimisation: failing to fill it loses nothing.
        let _ = write_exr(&cached, &rgb, w, h);
    }
    Ok(rgb)
}

/// The path tracer's vector mode over `scene` through `projection` at `size`: linear sRGB
/// and, per pixel, the photometric Stokes vector in the image frame
/// (`ReferenceRender::stokes_y`). Not cached: the cache holds colour images only.
pub fn path_traced_stokes(
    scene: &Scene,
    projection: Projection,
    (w, h): (u32, u32),
    pt: &PathTrace,
    label: &str,
) -> (Vec<[f64; 3]>, Vec<[f64; 4]>) {
    let mut render =
        ReferenceRender::new(scene, projection, w, h, pt.seed, pt.settings()).with_stokes();
    run_to_target(&mut render, pt, label);
    let stokes = render.stokes_y().unwrap_or_default();
    (render.linear_srgb(), stokes)
}

impl PathTrace {
    fn settings(&self) -> PathTracerSettings {
        PathTracerSettings {
            max_order: self.max_order,
            ..PathTracerSettings::default()
        }
    }
}

/// Runs `render` in passes to `pt`'s paths per pixel or noise, with a progress bar labelled
/// `label`, and reports what it reached.
fn run_to_target(render: &mut ReferenceRender, pt: &PathTrace, label: &str) {
    let (w, h) = (render.width, render.height);
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
    eprintln!(
        "{label}: {} spp, noise {:.2} % (mean per-pixel relative standard error of luminance), {:.1} s",
        render.samples_per_pixel(),
        render.mean_relative_error() * 100.0,
        start.elapsed().as_secs_f64(),
    );
}

/// `--projection`: what a rendered view shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ViewArg {
    Perspective,
    Fisheye,
    Panorama,
    /// Luminance in cd/m², log scale in false colour, on the fisheye sky dome.
    Luminance,
    /// The degree of polarisation in false colour, 0–100 %, on the fisheye sky dome (PNG).
    Polarisation,
}

impl ViewArg {
    /// The projection and display mode the argument asks for.
    pub fn projection_and_mode(self) -> (Projection, DisplayMode) {
        match self {
            ViewArg::Perspective => (Projection::Perspective, DisplayMode::Colour),
            ViewArg::Fisheye => (Projection::Fisheye, DisplayMode::Colour),
            ViewArg::Panorama => (Projection::Panorama, DisplayMode::Colour),
            ViewArg::Luminance => (Projection::Fisheye, DisplayMode::LUMINANCE),
            ViewArg::Polarisation => (Projection::Fisheye, DisplayMode::Polarisation),
        }
    }
}

/// Linear sRGB radiance, row-major, with its width and height.
pub type LinearImage = (Vec<[f64; 3]>, u32, u32);

/// The path-traced reference of suite view `view` in `refs` (`<view>.exr`: linear sRGB,
/// width, height). A missing file is skipped (None) unless the user `named` the view, when it
/// is an error that says how to render the references.
pub fn suite_reference(
    refs: &Path,
    view: &str,
    named: bool,
) -> anyhow::Result<Option<LinearImage>> {
    let path = refs.join(format!("{view}.exr"));
    if !path.exists() {
        if named {
            anyhow::bail!(
                "{}: no reference (run `atmoscope reference --suite --out-dir {}`)",
                path.display(),
                refs.display()
            );
        }
        return Ok(None);
    }
    read_exr(&path)
        .with_context(|| format!("reference of {view}"))
        .map(Some)
}
