//! `atmoscope fit-wavelengths`: refits the Spectral4 matrix (García Liñán 2023's method, done by
//! this project) against SpectralN renders of the Hillaire method over the view suite, and
//! writes it as the CSV the model embeds (`model/data/spectral4_fitted_matrix.csv`); with
//! `--hold-out` it judges the fit out of sample instead, each half of the views under the matrix
//! fitted on the other.

use super::render::parse_wavelengths;
use anyhow::{Context, bail};
use atmoscope_model::Atmosphere;
use atmoscope_model::Scene;
use atmoscope_model::camera::Camera;
use atmoscope_model::colour::linear_srgb_to_xyz;
use atmoscope_model::geometry::direction_from_angles;
use atmoscope_model::methods::hillaire::{self, Params, Tables};
use atmoscope_model::methods::shared::sun::in_sun_disk;
use atmoscope_model::metrics::{DisplaySetup, delta_e2000_map, percentile};
use atmoscope_model::optimize::nelder_mead;
use atmoscope_model::scene::WavelengthSet;
use atmoscope_model::views;
use atmoscope_model::wavelengths::{fit_matrix, garcia_linan_spectral4, to_linear_srgb};
use clap::{Args, ValueEnum};
use rayon::prelude::*;
use serde::Serialize;
use std::fmt::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct FitArgs {
    /// The spectral set the fit targets.
    #[arg(long, value_parser = parse_wavelengths, default_value = "spectral32")]
    pub spectral: WavelengthSet,
    /// Directions per view: a GRID × GRID raster of the view's own projection.
    #[arg(long, default_value_t = 16)]
    pub grid: u32,
    /// Views of the suite to fit on, comma-separated (default: all 21).
    #[arg(long, value_delimiter = ',')]
    pub views: Vec<String>,
    /// Write the matrix as CSV here (the model embeds model/data/spectral4_fitted_matrix.csv).
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
    /// Judge the fit out of sample instead of writing a matrix: fit on every other view of
    /// the chosen ones (half A: the 1st, 3rd, …) and report each view's ΔE2000 under the
    /// matrix of the half it is not in, beside the matrix fitted on all of them.
    #[arg(long, conflicts_with = "out")]
    pub hold_out: bool,
    /// With --hold-out: the rows as JSON.
    #[arg(long, requires = "hold_out")]
    pub json: bool,
    /// What the fit minimises.
    #[arg(long, value_enum, default_value = "least-squares")]
    pub objective: Objective,
}

/// What `fit-wavelengths` minimises.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Objective {
    /// Colour error relative to luminance, squared (weights 1/Y²): a linear solve.
    LeastSquares,
    /// ΔE2000 itself, as each view is displayed: every view's mean over 0.5 plus its 95th
    /// percentile over 1.5 (the bounds the issue set), summed over the views; Nelder–Mead from
    /// the least-squares matrix.
    De2000,
}

/// The matrix of `objective` over `views`.
fn fit(views: &[&ViewSamples], objective: Objective) -> Option<[[f64; 4]; 3]> {
    let all: Vec<Sample> = views
        .iter()
        .flat_map(|v| v.samples.iter().copied())
        .collect();
    let m = fit_matrix(&all)?;
    if objective == Objective::LeastSquares {
        return Some(m);
    }
    let unflatten = |x: &[f64]| -> [[f64; 4]; 3] {
        std::array::from_fn(|r| std::array::from_fn(|k| x[4 * r + k]))
    };
    let cost = |x: &[f64]| -> f64 {
        let m = unflatten(x);
        views
            .par_iter()
            .map(|v| {
                let [mean, p95] = delta_e(&m, &v.samples, v.setup);
                mean / 0.5 + p95 / 1.5
            })
            .sum()
    };
    let start: Vec<f64> = m.iter().flatten().copied().collect();
    let step: Vec<f64> = start.iter().map(|v| 0.05 * v.abs() + 1e-4).collect();
    let (x, _) = nelder_mead(cost, &start, &step, 1e-9, 6000);
    Some(unflatten(&x))
}

type Sample = ([f64; 4], [f64; 3]);

/// (Spectral4 lanes, SpectralN linear sRGB) for every covered direction of the raster.
fn samples(
    scene: &Scene,
    projection: atmoscope_model::camera::Projection,
    grid: u32,
    set: WavelengthSet,
) -> Vec<Sample> {
    let atm = Atmosphere::for_scene(&scene);
    let p4 = Params::new(&atm, WavelengthSet::Spectral4, scene.render.quality);
    let pn = Params::new(&atm, set, scene.render.quality);
    let camera = Camera::new(&scene.camera, atm.bottom_radius_m, projection);
    let vp = hillaire::viewpoint(scene, &camera);
    let (t4, tn) = (Tables::compute(&p4, vp), Tables::compute(&pn, vp));
    let a = scene.sun.angles();
    let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
    let colours: Vec<_> = pn.batches.iter().map(|b| b.colour.clone()).collect();
    (0..grid * grid)
        .into_par_iter()
        .filter_map(|i| {
            let ray = camera.ray(
                f64::from(i % grid) + 0.5,
                f64::from(i / grid) + 0.5,
                grid,
                grid,
            )?;
            // Pixels on the sun's disk are left out, so none below carries it.
            if in_sun_disk(ray.direction, sun) {
                return None;
            }
            let at = (ray.origin, scene.camera.altitude_m);
            let l4 = hillaire::radiance(&p4, &t4, 0, at, ray.direction, sun);
            let ln: Vec<[f64; 4]> = (0..pn.batches.len())
                .map(|b| hillaire::radiance(&pn, &tn, b, at, ray.direction, sun))
                .collect();
            Some((l4, to_linear_srgb(&colours, &ln)))
        })
        .collect()
}

/// The matrix applied to one direction's four lanes: linear sRGB.
fn apply(m: &[[f64; 4]; 3], l: &[f64; 4]) -> [f64; 3] {
    std::array::from_fn(|r| (0..4).map(|k| m[r][k] * l[k]).sum())
}

/// Mean and 95th percentile of ΔE2000 between the matrix's colours and SpectralN's over the
/// samples, display-referred as the view shows them.
fn delta_e(m: &[[f64; 4]; 3], samples: &[Sample], setup: DisplaySetup) -> [f64; 2] {
    let test: Vec<[f64; 3]> = samples.iter().map(|(l, _)| apply(m, l)).collect();
    let reference: Vec<[f64; 3]> = samples.iter().map(|&(_, c)| c).collect();
    let de = delta_e2000_map(&test, &reference, setup);
    [
        de.iter().sum::<f64>() / de.len().max(1) as f64,
        percentile(&de, 0.95),
    ]
}

/// One view's samples and how it is displayed.
struct ViewSamples {
    name: String,
    setup: DisplaySetup,
    samples: Vec<Sample>,
}

#[derive(Serialize)]
struct HoldOutRow {
    view: String,
    /// "A" or "B": the half the view belongs to; its ΔE is under the other half's matrix.
    half: &'static str,
    /// [mean, p95] ΔE2000 under the matrix fitted on the other half.
    held_out: [f64; 2],
    /// [mean, p95] ΔE2000 under the matrix fitted on every chosen view.
    fitted_on_all: [f64; 2],
}

/// Fits on each half of `views`, reports each view under the other half's matrix.
fn hold_out(
    views: &[ViewSamples],
    all: &[[f64; 4]; 3],
    objective: Objective,
    json: bool,
) -> anyhow::Result<ExitCode> {
    if views.len() < 2 {
        bail!("--hold-out needs at least two views (one per half)");
    }
    let half = |h: usize| -> anyhow::Result<[[f64; 4]; 3]> {
        let chosen: Vec<&ViewSamples> = views.iter().skip(h).step_by(2).collect();
        fit(&chosen, objective)
            .with_context(|| format!("half {} alone does not determine a matrix", ["A", "B"][h]))
    };
    let matrices = [half(0)?, half(1)?];
    let rows: Vec<HoldOutRow> = views
        .iter()
        .enumerate()
        .map(|(i, v)| HoldOutRow {
            view: v.name.clone(),
            half: ["A", "B"][i % 2],
            held_out: delta_e(&matrices[1 - i % 2], &v.samples, v.setup),
            fitted_on_all: delta_e(all, &v.samples, v.setup),
        })
        .collect();
    if json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "ΔE2000 mean / p95 of Spectral4 against the spectral set, display-referred at each view's exposure:\n\
         under the matrix fitted on the other half of the views (held out), and on all of them"
    );
    println!(
        "{:20} half  {:>15}  {:>15}",
        "view", "held out", "fitted on all"
    );
    for r in &rows {
        println!(
            "{:20} {:4}  {:>6.2} / {:>6.2}  {:>6.2} / {:>6.2}",
            r.view, r.half, r.held_out[0], r.held_out[1], r.fitted_on_all[0], r.fitted_on_all[1]
        );
    }
    let worst = |k: usize| rows.iter().map(|r| r.held_out[k]).fold(0.0f64, f64::max);
    println!(
        "held out: worst view mean {:.2}, worst view p95 {:.2}, mean over views {:.2}",
        worst(0),
        worst(1),
        rows.iter().map(|r| r.held_out[0]).sum::<f64>() / rows.len() as f64
    );
    Ok(ExitCode::SUCCESS)
}

/// Mean relative error of luminance-weighted colour: |M·l − c| / Y(c).
fn mean_error(m: &[[f64; 4]; 3], samples: &[Sample]) -> f64 {
    let errors: Vec<f64> = samples
        .iter()
        .map(|(l, c)| {
            let v = apply(m, l);
            let e: f64 = (0..3).map(|r| (v[r] - c[r]).powi(2)).sum();
            e.sqrt() / linear_srgb_to_xyz(*c).y
        })
        .collect();
    errors.iter().sum::<f64>() / errors.len().max(1) as f64
}

pub fn run(args: &FitArgs) -> anyhow::Result<ExitCode> {
    if !matches!(args.spectral, WavelengthSet::SpectralN(_)) {
        bail!("--spectral must be a spectralN set, e.g. spectral32");
    }
    for name in &args.views {
        views::find(name).with_context(|| format!("--views: no view {name}"))?;
    }
    let chosen = views::suite()
        .iter()
        .filter(|v| args.views.is_empty() || args.views.contains(&v.name));
    let mut per_view = Vec::new();
    for v in chosen {
        let scene = v.apply(&Scene::default());
        let s = samples(&scene, v.projection, args.grid.max(2), args.spectral);
        eprintln!("{}: {} samples", v.name, s.len());
        per_view.push(ViewSamples {
            name: v.name.clone(),
            setup: DisplaySetup {
                exposure_ev: scene.display.exposure_ev,
                tone_map: scene.display.tone_map,
                ..DisplaySetup::default()
            },
            samples: s
                .into_iter()
                .filter(|(_, c)| linear_srgb_to_xyz(*c).y > 0.0)
                .collect(),
        });
    }
    let all: Vec<Sample> = per_view
        .iter()
        .flat_map(|v| v.samples.iter().copied())
        .collect();
    let chosen: Vec<&ViewSamples> = per_view.iter().collect();
    let m = fit(&chosen, args.objective).context("the samples do not determine a matrix")?;
    if args.hold_out {
        return hold_out(&per_view, &m, args.objective, args.json);
    }
    let (_, published) = garcia_linan_spectral4();
    println!(
        "{} samples; mean relative colour error against {:?}: published matrix {:.4}, fitted {:.4}",
        all.len(),
        args.spectral,
        mean_error(&published, &all),
        mean_error(&m, &all)
    );
    let mut csv = String::from(
        "# Spectral4 matrix: linear sRGB (rows R, G, B) from spectral radiance at 630/560/490/430 nm (lanes 0-3).\n",
    );
    let (flag, how) = match args.objective {
        Objective::LeastSquares => ("", "weighted least squares (weights 1/Y²)"),
        Objective::De2000 => (
            " --objective de2000",
            "ΔE2000 as each view is displayed (Nelder–Mead from weighted least squares)",
        ),
    };
    writeln!(
        csv,
        "# Fitted by Atmoscope (`atmoscope fit-wavelengths --spectral spectral{} --grid {}{flag}`): {how}\n\
         # against Hillaire-method {:?} renders of views of presets/views/suite.ron ({}; sun disk excluded), as García Liñán (2023) did against full spectral renders.",
        match args.spectral {
            WavelengthSet::SpectralN(n) => n,
            _ => 0,
        },
        args.grid,
        args.spectral,
        if args.views.is_empty() {
            "all 21".to_string()
        } else {
            args.views.join(", ")
        }
    )?;
    csv.push_str("row,lane,value\n");
    for (r, row) in m.iter().enumerate() {
        for (k, v) in row.iter().enumerate() {
            writeln!(csv, "{r},{k},{v:.9}")?;
        }
    }
    match &args.out {
        Some(path) => {
            super::write_atomic(path, csv.as_bytes())?;
            eprintln!("wrote {}", path.display());
        }
        None => print!("{csv}"),
    }
    Ok(ExitCode::SUCCESS)
}
