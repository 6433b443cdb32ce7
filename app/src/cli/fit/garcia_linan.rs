//! `atmoscope fit-garcia-linan`: refits the constants of García Liñán's (2023) logistic
//! multiple-scattering term L_ms = s·(λ_ref/λ)⁴/(1 + a·e^(−b·μ_s)) against path-traced
//! references of the view suite (`atmoscope reference --suite`), over the views in the model's
//! domain, and reports the error before and after. The thesis fitted them at 10 km against its
//! own path tracer; this refits them for the scene's atmosphere.
//!
//! Each sampled pixel's radiance is the model's own (the sky texture's in-scattering marched
//! along the pixel's ray, `garcia_linan::sky::radiance_marched`), so the fit measures the
//! model and not the texture's interpolation. The objective is the mean squared log ratio of
//! luminance, which weighs a dark view as much as a bright one.

use crate::args::parse_wavelengths;
use crate::cli::common::suite_reference;

use anyhow::bail;
use atmoscope_eval::optimize::nelder_mead;
use atmoscope_model::camera::Camera;
use atmoscope_model::colour::linear_srgb_to_xyz;
use atmoscope_model::geometry::direction_from_angles;
use atmoscope_model::methods::garcia_linan::{Constants, DOMAIN, sky::radiance_marched};
use atmoscope_model::methods::shared::sun_disk::in_sun_disk;
use atmoscope_model::methods::shared::transmittance::compute_transmittance_lut;
use atmoscope_model::methods::shared::{Lut, Params};
use atmoscope_model::scene::WavelengthSet;
use atmoscope_model::wavelengths::to_linear_srgb;
use atmoscope_model::{Atmosphere, Scene, views};
use clap::Args;
use glam::DVec3;
use rayon::prelude::*;
use std::fmt::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct FitGarciaLinanArgs {
    /// Directory of path-traced references named `<view>.exr`
    /// (from `atmoscope reference --suite --out-dir DIR`); default: the repository's
    /// tests/data/references, under the working directory or above the program.
    #[arg(long, value_name = "DIR")]
    pub refs: Option<PathBuf>,
    /// Views of the suite, comma-separated (default: every view in the model's domain with a
    /// reference in --refs).
    #[arg(long, value_delimiter = ',')]
    pub views: Vec<String>,
    /// Pixels per view: a GRID × GRID raster (1–64).
    #[arg(long, default_value_t = 12)]
    pub grid: u32,
    /// Wavelength set the model is evaluated with (a dense one measures the model, not the set).
    #[arg(long, value_parser = parse_wavelengths, default_value = "spectral16")]
    pub wavelengths: WavelengthSet,
    /// Most evaluations of the objective.
    #[arg(long, default_value_t = 200)]
    pub max_evaluations: usize,
    /// Write the fitted constants as CSV here.
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
}

/// One view's optics and sampled pixels: (ray origin, direction, reference luminance).
struct ViewSamples {
    name: String,
    params: Params,
    transmittance: Lut,
    altitude_m: f64,
    sun: DVec3,
    pixels: Vec<(DVec3, DVec3, f64)>,
}

fn luminance(rgb: [f64; 3]) -> f64 {
    linear_srgb_to_xyz(rgb).y
}

impl ViewSamples {
    /// Log ratios of the model's luminance over the reference's, per pixel.
    fn log_ratios(&self, c: &Constants) -> Vec<f64> {
        let colours: Vec<_> = self
            .params
            .batches
            .iter()
            .map(|b| b.colour.clone())
            .collect();
        self.pixels
            .par_iter()
            .map(|&(origin, dir, reference)| {
                let lanes: Vec<_> = (0..self.params.batches.len())
                    .map(|layer| {
                        radiance_marched(
                            &self.params,
                            &self.transmittance,
                            c,
                            layer,
                            (origin, self.altitude_m),
                            dir,
                            self.sun,
                        )
                    })
                    .collect();
                let y = luminance(to_linear_srgb(&colours, &lanes));
                (y.max(1e-30) / reference).ln()
            })
            .collect()
    }
}

/// Root mean square and mean of `v`.
fn rms_and_mean(v: &[f64]) -> (f64, f64) {
    let n = v.len().max(1) as f64;
    (
        (v.iter().map(|x| x * x).sum::<f64>() / n).sqrt(),
        v.iter().sum::<f64>() / n,
    )
}

fn load(args: &FitGarciaLinanArgs, refs: &std::path::Path) -> anyhow::Result<Vec<ViewSamples>> {
    let mut out = Vec::new();
    for v in views::suite() {
        let named = args.views.iter().any(|n| n == v.name.as_str());
        if !args.views.is_empty() && !named {
            continue;
        }
        let scene: Scene = v.apply(&Scene::default());
        let sun_elevation = scene.sun.angles().elevation_deg;
        if let Some(why) = DOMAIN.excludes(scene.camera.altitude_m, sun_elevation) {
            if named {
                bail!("--views {}: {why}", v.name);
            }
            continue;
        }
        let Some((reference, w, h)) = suite_reference(refs, &v.name, named)? else {
            continue;
        };
        let atm = Atmosphere::for_scene(&scene);
        let params = Params::new(&atm, args.wavelengths, scene.render.quality);
        let transmittance = compute_transmittance_lut(&params);
        let camera = Camera::new(&scene.camera, atm.bottom_radius_m, v.projection);
        let a = scene.sun.angles();
        let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
        let g = args.grid;
        let pixels = (0..g * g)
            .filter_map(|i| {
                let (x, y) = (
                    (f64::from(i % g) + 0.5) * f64::from(w) / f64::from(g),
                    (f64::from(i / g) + 0.5) * f64::from(h) / f64::from(g),
                );
                let ray = camera.ray(x, y, w, h)?;
                let reference = luminance(reference[y as usize * w as usize + x as usize]);
                let usable =
                    reference.is_finite() && reference > 0.0 && !in_sun_disk(ray.direction, sun);
                usable.then_some((ray.origin, ray.direction, reference))
            })
            .collect();
        out.push(ViewSamples {
            name: v.name.clone(),
            params,
            transmittance,
            altitude_m: scene.camera.altitude_m,
            sun,
            pixels,
        });
    }
    if out.is_empty() {
        bail!(
            "no reference of a view in the model's domain ({}) in {}",
            DOMAIN.note,
            refs.display()
        );
    }
    Ok(out)
}

fn constants(x: &[f64], reference_wavelength_nm: f64) -> Constants {
    Constants {
        ms_scale: x[0].exp(),
        ms_a: x[1].exp(),
        ms_b: x[2],
        reference_wavelength_nm,
    }
}

pub fn run(args: &FitGarciaLinanArgs) -> anyhow::Result<ExitCode> {
    if !(1..=64).contains(&args.grid) {
        bail!("--grid: {} is outside 1 to 64", args.grid);
    }
    if let Some(out) = &args.out {
        crate::files::check_writable(out)?;
    }
    let refs = crate::shipped::references(args.refs.as_deref())?;
    let views = load(args, &refs)?;
    let published = Constants::published();
    let objective = |c: &Constants| -> f64 {
        let all: Vec<f64> = views.iter().flat_map(|v| v.log_ratios(c)).collect();
        rms_and_mean(&all).0.powi(2)
    };
    let start = [published.ms_scale.ln(), published.ms_a.ln(), published.ms_b];
    eprintln!(
        "fitting on {} views, {} pixels",
        views.len(),
        views.iter().map(|v| v.pixels.len()).sum::<usize>()
    );
    let (x, _) = nelder_mead(
        |x| objective(&constants(x, published.reference_wavelength_nm)),
        &start,
        &[0.5, 0.5, 4.0],
        1e-6,
        args.max_evaluations,
    );
    let fitted = constants(&x, published.reference_wavelength_nm);
    println!(
        "L_ms constants    published                 fitted\n  scale (sr⁻¹)    {:<25.5} {:.5}\n  a               {:<25.4} {:.4}\n  b               {:<25.4} {:.4}",
        published.ms_scale,
        fitted.ms_scale,
        published.ms_a,
        fitted.ms_a,
        published.ms_b,
        fitted.ms_b
    );
    println!("\nluminance error per view (RMS of ln(model/reference); mean signed)");
    println!(
        "{:22} {:>8} {:>20} {:>20}",
        "view", "pixels", "published", "fitted"
    );
    let (mut before, mut after) = (Vec::new(), Vec::new());
    for v in &views {
        let b = v.log_ratios(&published);
        let a = v.log_ratios(&fitted);
        let ((rb, mb), (ra, ma)) = (rms_and_mean(&b), rms_and_mean(&a));
        println!(
            "{:22} {:>8} {:>11.1} % {:>+6.1} % {:>11.1} % {:>+6.1} %",
            v.name,
            v.pixels.len(),
            100.0 * rb,
            100.0 * mb,
            100.0 * ra,
            100.0 * ma
        );
        before.extend(b);
        after.extend(a);
    }
    let ((rb, mb), (ra, ma)) = (rms_and_mean(&before), rms_and_mean(&after));
    println!(
        "{:22} {:>8} {:>11.1} % {:>+6.1} % {:>11.1} % {:>+6.1} %",
        "all",
        before.len(),
        100.0 * rb,
        100.0 * mb,
        100.0 * ra,
        100.0 * ma
    );
    if let Some(path) = &args.out {
        let mut csv = String::new();
        writeln!(
            csv,
            "# García Liñán (2023) L_ms constants refitted by `atmoscope fit-garcia-linan` against path-traced references ({}) of {} suite views ({}×{} pixels each, {:?}); RMS log luminance error {:.3} -> {:.3}.\nname,value\nms_scale,{}\nms_a,{}\nms_b,{}\nreference_wavelength_nm,{}",
            refs.display(),
            views.len(),
            args.grid,
            args.grid,
            args.wavelengths,
            rb,
            ra,
            fitted.ms_scale,
            fitted.ms_a,
            fitted.ms_b,
            fitted.reference_wavelength_nm
        )?;
        crate::files::write_atomic(path, csv.as_bytes())?;
        eprintln!("wrote {}", path.display());
    }
    Ok(ExitCode::SUCCESS)
}
