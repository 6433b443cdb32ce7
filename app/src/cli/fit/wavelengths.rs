//! `atmoscope fit-wavelengths`: fits Spectral4's matrix (García Liñán 2023's method, done by this
//! project) and, with `--choose-lanes`, its four wavelengths, against SpectralN renders of the
//! Hillaire method over the view suite, and writes them as the CSV the model embeds
//! (`model/data/spectral4_fitted.csv`); with `--hold-out` it judges the fit out of sample
//! instead, each half of the views under the fit made on the other.

use crate::args::parse_wavelengths;
use anyhow::{Context, bail};
use atmoscope_eval::metrics::{DisplaySetup, delta_e2000_map, percentile};
use atmoscope_eval::optimize::nelder_mead;
use atmoscope_model::Atmosphere;
use atmoscope_model::Scene;
use atmoscope_model::camera::Camera;
use atmoscope_model::colour::linear_srgb_to_xyz;
use atmoscope_model::constants::{VISIBLE_MAX_NM, VISIBLE_MIN_NM};
use atmoscope_model::geometry::direction_from_angles;
use atmoscope_model::methods::hillaire::{self, Params, Tables};
use atmoscope_model::methods::shared::sun_disk::in_sun_disk;
use atmoscope_model::scene::WavelengthSet;
use atmoscope_model::views;
use atmoscope_model::wavelengths::{
    POINT_SET_SOLAR_BAND_NM, batches_at, fit_matrix, garcia_linan_spectral4, spectral4_fitted,
    to_linear_srgb,
};
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
    /// The four wavelengths to fit the matrix at, nm, longest first, comma-separated
    /// (default: the shipped Spectral4's; García Liñán's are 630,560,490,430).
    #[arg(long, value_delimiter = ',', conflicts_with = "choose_lanes")]
    pub lanes_nm: Option<Vec<f64>>,
    /// Choose the four wavelengths too: on a 10 nm grid, one in each of 570–680, 510–600,
    /// 450–530 and 400–470 nm, the four under whose least-squares matrix the worst view is
    /// furthest within its bounds (the smallest largest ratio of a view's mean ΔE2000 to 0.5,
    /// or of its p95 to 1.5).
    #[arg(long)]
    pub choose_lanes: bool,
    /// Write the wavelengths and matrix as CSV here (the model embeds
    /// model/data/spectral4_fitted.csv).
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
    /// Judge the fit out of sample instead of writing wavelengths and a matrix: fit on every
    /// other view of the chosen ones (half A: the 1st, 3rd, …) and report each view's ΔE2000
    /// under the fit of the half it is not in, beside the fit on all of them. With
    /// --choose-lanes each half chooses its own wavelengths too.
    #[arg(long, conflicts_with = "out")]
    pub hold_out: bool,
    /// With --hold-out: the rows as JSON.
    #[arg(long, requires = "hold_out")]
    pub json: bool,
    /// What the fit minimises.
    #[arg(long, value_enum, default_value = "least-squares")]
    pub objective: Objective,
}

/// Where `--choose-lanes` looks for each lane's wavelength, nm (inclusive; a 10 nm grid):
/// around the peaks of the colour-matching functions, each range wide enough to move a lane
/// well off García Liñán's choice, and no two lanes the same.
const LANE_RANGES_NM: [(f64, f64); 4] = [
    (570.0, 680.0),
    (510.0, 600.0),
    (450.0, 530.0),
    (400.0, 470.0),
];
const LANE_GRID_STEP_NM: f64 = 10.0;

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

/// The bounds the issue set on each view's ΔE2000 against the spectral set: mean and p95.
const MEAN_BOUND: f64 = 0.5;
const P95_BOUND: f64 = 1.5;

type Sample = ([f64; 4], [f64; 3]);
type Matrix = [[f64; 4]; 3];
/// Four lanes, as indices into the wavelengths rendered, longest first.
type LaneIndices = [usize; 4];

/// One view's radiances at every wavelength rendered and its SpectralN colours, direction by
/// direction, and how it is displayed.
struct ViewData {
    name: String,
    setup: DisplaySetup,
    /// Per covered direction: spectral radiance at each wavelength rendered, W·m⁻²·sr⁻¹·nm⁻¹.
    radiance: Vec<Vec<f64>>,
    /// Per covered direction: the spectral set's linear sRGB.
    target: Vec<[f64; 3]>,
}

impl ViewData {
    fn samples(&self, lanes: LaneIndices) -> Vec<Sample> {
        self.radiance
            .iter()
            .zip(&self.target)
            .map(|(l, c)| (lanes.map(|k| l[k]), *c))
            .collect()
    }
}

/// Wavelengths and matrix: what a fit produces.
#[derive(Debug, Clone, Copy)]
struct Fit {
    lanes: LaneIndices,
    matrix: Matrix,
}

/// The matrix of `objective` over `views` at `lanes`.
fn fit(views: &[&ViewData], lanes: LaneIndices, objective: Objective) -> Option<Matrix> {
    let per_view: Vec<Vec<Sample>> = views.iter().map(|v| v.samples(lanes)).collect();
    let m = fit_matrix(&per_view.concat())?;
    if objective == Objective::LeastSquares {
        return Some(m);
    }
    let unflatten =
        |x: &[f64]| -> Matrix { std::array::from_fn(|r| std::array::from_fn(|k| x[4 * r + k])) };
    let cost = |x: &[f64]| -> f64 {
        let m = unflatten(x);
        views
            .par_iter()
            .zip(&per_view)
            .map(|(v, s)| {
                let [mean, p95] = delta_e(&m, s, v.setup);
                mean / MEAN_BOUND + p95 / P95_BOUND
            })
            .sum()
    };
    let start: Vec<f64> = m.iter().flatten().copied().collect();
    let step: Vec<f64> = start.iter().map(|v| 0.05 * v.abs() + 1e-4).collect();
    let (x, _) = nelder_mead(cost, &start, &step, 1e-9, 6000);
    Some(unflatten(&x))
}

/// How near its bounds the worst of `views` is at `lanes` under their least-squares matrix:
/// the largest over the views of max(mean / 0.5, p95 / 1.5); below 1 every view is within.
fn worst_against_bounds(views: &[&ViewData], lanes: LaneIndices) -> Option<f64> {
    let per_view: Vec<Vec<Sample>> = views.iter().map(|v| v.samples(lanes)).collect();
    let m = fit_matrix(&per_view.concat())?;
    Some(
        views
            .iter()
            .zip(&per_view)
            .map(|(v, s)| {
                let [mean, p95] = delta_e(&m, s, v.setup);
                (mean / MEAN_BOUND).max(p95 / P95_BOUND)
            })
            .fold(0.0, f64::max),
    )
}

/// The candidate whose worst view is furthest within its bounds, by
/// [`worst_against_bounds`] (the first of equals).
fn choose(views: &[&ViewData], candidates: &[LaneIndices]) -> Option<LaneIndices> {
    candidates
        .par_iter()
        .enumerate()
        .filter_map(|(i, &k)| Some((i, k, worst_against_bounds(views, k)?)))
        .min_by(|a, b| a.2.total_cmp(&b.2).then(a.0.cmp(&b.0)))
        .map(|(_, k, _)| k)
}

/// The whole fit on `views`: the lanes (chosen among `candidates`), then the matrix.
fn fit_on(views: &[&ViewData], candidates: &[LaneIndices], objective: Objective) -> Option<Fit> {
    let lanes = match candidates {
        [only] => *only,
        _ => choose(views, candidates)?,
    };
    Some(Fit {
        lanes,
        matrix: fit(views, lanes, objective)?,
    })
}

/// Each direction of a GRID² raster of the view (the sun's disk left out): radiance at
/// `wavelengths_nm` by the Hillaire method, each averaging the sun over 10 nm as Spectral4
/// does, and the colour of `set`.
fn render(
    scene: &Scene,
    projection: atmoscope_model::camera::Projection,
    grid: u32,
    set: WavelengthSet,
    wavelengths_nm: &[f64],
) -> (Vec<Vec<f64>>, Vec<[f64; 3]>) {
    let atm = Atmosphere::for_scene(scene);
    let quality = scene.render.quality;
    let pw = Params::with_batches(
        &atm,
        batches_at(wavelengths_nm, Some(POINT_SET_SOLAR_BAND_NM)),
        quality,
    );
    let pn = Params::new(&atm, set, quality);
    let camera = Camera::new(&scene.camera, atm.bottom_radius_m, projection);
    let vp = hillaire::viewpoint(scene, &camera);
    let (tw, tn) = (Tables::compute(&pw, vp), Tables::compute(&pn, vp));
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
            if in_sun_disk(ray.direction, sun) {
                return None;
            }
            let at = (ray.origin, scene.camera.altitude_m);
            let lw: Vec<f64> = (0..pw.batches.len())
                .flat_map(|b| hillaire::radiance(&pw, &tw, b, at, ray.direction, sun))
                .take(wavelengths_nm.len())
                .collect();
            let ln: Vec<atmoscope_model::lanes::Lanes> = (0..pn.batches.len())
                .map(|b| hillaire::radiance(&pn, &tn, b, at, ray.direction, sun))
                .collect();
            let c = to_linear_srgb(&colours, &ln);
            (linear_srgb_to_xyz(c).y > 0.0).then_some((lw, c))
        })
        .unzip()
}

/// The matrix applied to one direction's four lanes: linear sRGB.
fn apply(m: &Matrix, l: &[f64; 4]) -> [f64; 3] {
    std::array::from_fn(|r| (0..4).map(|k| m[r][k] * l[k]).sum())
}

/// Mean and 95th percentile of ΔE2000 between the matrix's colours and SpectralN's over the
/// samples, display-referred as the view shows them.
fn delta_e(m: &Matrix, samples: &[Sample], setup: DisplaySetup) -> [f64; 2] {
    let test: Vec<[f64; 3]> = samples.iter().map(|(l, _)| apply(m, l)).collect();
    let reference: Vec<[f64; 3]> = samples.iter().map(|&(_, c)| c).collect();
    let de = delta_e2000_map(&test, &reference, setup);
    [
        de.iter().sum::<f64>() / de.len().max(1) as f64,
        percentile(&de, 0.95),
    ]
}

#[derive(Serialize)]
struct HoldOutRow {
    view: String,
    /// "A" or "B": the half the view belongs to; its ΔE is under the other half's fit.
    half: &'static str,
    /// The wavelengths of the other half's fit, nm.
    held_out_lanes_nm: [f64; 4],
    /// [mean, p95] ΔE2000 under the fit on the other half.
    held_out: [f64; 2],
    /// [mean, p95] ΔE2000 under the fit on every chosen view.
    fitted_on_all: [f64; 2],
}

/// Fits on each half of `views`, reports each view under the other half's fit.
fn hold_out(
    views: &[ViewData],
    wavelengths_nm: &[f64],
    all: &Fit,
    fit_half: impl Fn(&[&ViewData]) -> Option<Fit>,
    json: bool,
) -> anyhow::Result<ExitCode> {
    if views.len() < 2 {
        bail!("--hold-out needs at least two views (one per half)");
    }
    let half = |h: usize| -> anyhow::Result<Fit> {
        let chosen: Vec<&ViewData> = views.iter().skip(h).step_by(2).collect();
        fit_half(&chosen)
            .with_context(|| format!("half {} alone does not determine a matrix", ["A", "B"][h]))
    };
    let fits = [half(0)?, half(1)?];
    let nm = |f: &Fit| f.lanes.map(|k| wavelengths_nm[k]);
    let rows: Vec<HoldOutRow> = views
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let other = &fits[1 - i % 2];
            HoldOutRow {
                view: v.name.clone(),
                half: ["A", "B"][i % 2],
                held_out_lanes_nm: nm(other),
                held_out: delta_e(&other.matrix, &v.samples(other.lanes), v.setup),
                fitted_on_all: delta_e(&all.matrix, &v.samples(all.lanes), v.setup),
            }
        })
        .collect();
    if json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "ΔE2000 mean / p95 of Spectral4 against the spectral set, display-referred at each view's exposure:\n\
         under the fit on the other half of the views (held out), and on all of them\n\
         wavelengths: half A {}, half B {}, all {} nm",
        joined(nm(&fits[0]), "/"),
        joined(nm(&fits[1]), "/"),
        joined(nm(all), "/")
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

/// Four wavelengths as "630/560/490/430" (separator "/") or "630,560,490,430" (",").
fn joined(nm: [f64; 4], separator: &str) -> String {
    nm.map(|w| format!("{w}")).join(separator)
}

/// Mean relative error of luminance-weighted colour: |M·l − c| / Y(c).
fn mean_error(m: &Matrix, samples: &[Sample]) -> f64 {
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

/// Every four wavelengths `--choose-lanes` may pick, nm: one from each lane's range on the
/// grid, longest first.
fn lane_candidates() -> Vec<[f64; 4]> {
    let within: [Vec<f64>; 4] = LANE_RANGES_NM.map(|(lo, hi)| {
        let steps = ((hi - lo) / LANE_GRID_STEP_NM).round() as usize;
        (0..=steps)
            .map(|i| lo + LANE_GRID_STEP_NM * i as f64)
            .collect()
    });
    let mut candidates = Vec::new();
    for &r in &within[0] {
        for &g in within[1].iter().filter(|&&g| g < r) {
            for &c in within[2].iter().filter(|&&c| c < g) {
                for &b in within[3].iter().filter(|&&b| b < c) {
                    candidates.push([r, g, c, b]);
                }
            }
        }
    }
    candidates
}

/// `--lanes-nm` checked: four visible wavelengths, longest first.
fn given_lanes(nm: &[f64]) -> anyhow::Result<[f64; 4]> {
    let lanes: [f64; 4] = nm
        .try_into()
        .map_err(|_| anyhow::anyhow!("--lanes-nm takes four wavelengths, not {}", nm.len()))?;
    if !lanes
        .iter()
        .all(|l| (VISIBLE_MIN_NM..=VISIBLE_MAX_NM).contains(l))
    {
        bail!(
            "--lanes-nm: each wavelength must lie in {VISIBLE_MIN_NM}–{VISIBLE_MAX_NM} nm, not {lanes:?}"
        );
    }
    if !lanes.windows(2).all(|p| p[0] > p[1]) {
        bail!(
            "--lanes-nm: the wavelengths go longest first and differ (red, green, blue-green, blue), not {lanes:?}"
        );
    }
    Ok(lanes)
}

pub fn run(args: &FitArgs) -> anyhow::Result<ExitCode> {
    if !matches!(args.spectral, WavelengthSet::SpectralN(_)) {
        bail!("--spectral must be a spectralN set, e.g. spectral32");
    }
    for name in &args.views {
        views::find(name).with_context(|| format!("--views: no view {name}"))?;
    }
    if args.hold_out && args.views.len() == 1 {
        bail!("--hold-out needs at least two views (one per half)");
    }
    let (published_nm, published) = garcia_linan_spectral4();
    // Every wavelength a fit may use, and García Liñán's for comparison, rendered once.
    let candidates_nm: Vec<[f64; 4]> = if args.choose_lanes {
        lane_candidates()
    } else {
        vec![match &args.lanes_nm {
            Some(nm) => given_lanes(nm)?,
            None => spectral4_fitted().0,
        }]
    };
    let mut wavelengths_nm: Vec<f64> = candidates_nm.iter().flatten().copied().collect();
    wavelengths_nm.extend(published_nm);
    wavelengths_nm.sort_by(f64::total_cmp);
    wavelengths_nm.dedup();
    let index = |nm: [f64; 4]| -> LaneIndices {
        nm.map(|w| {
            wavelengths_nm
                .iter()
                .position(|&x| x == w)
                .expect("every lane's wavelength is rendered")
        })
    };
    let candidates: Vec<LaneIndices> = candidates_nm.into_iter().map(index).collect();
    let published_lanes = index(published_nm);

    let chosen = views::suite()
        .iter()
        .filter(|v| args.views.is_empty() || args.views.contains(&v.name));
    let mut per_view = Vec::new();
    for v in chosen {
        let scene = v.apply(&Scene::default());
        let (radiance, target) = render(
            &scene,
            v.projection,
            args.grid.max(2),
            args.spectral,
            &wavelengths_nm,
        );
        eprintln!("{}: {} samples", v.name, target.len());
        per_view.push(ViewData {
            name: v.name.clone(),
            setup: DisplaySetup {
                exposure_ev: scene.display.exposure_ev,
                tone_map: scene.display.tone_map,
                ..DisplaySetup::default()
            },
            radiance,
            target,
        });
    }
    let objective = args.objective;
    let fit_half = |views: &[&ViewData]| fit_on(views, &candidates, objective);
    let everything: Vec<&ViewData> = per_view.iter().collect();
    let all = fit_half(&everything).context("the samples do not determine a matrix")?;
    let lanes_nm = all.lanes.map(|k| wavelengths_nm[k]);
    if args.hold_out {
        return hold_out(&per_view, &wavelengths_nm, &all, fit_half, args.json);
    }
    if args.choose_lanes {
        let worst = |lanes| worst_against_bounds(&everything, lanes).unwrap_or(f64::INFINITY);
        println!(
            "chose {} nm: the worst view at {:.3} of its bounds (mean ΔE2000 {MEAN_BOUND}, p95 {P95_BOUND}) under its least-squares matrix; García Liñán's {} nm at {:.3}",
            joined(lanes_nm, "/"),
            worst(all.lanes),
            joined(published_nm, "/"),
            worst(published_lanes)
        );
    }
    let samples_at = |lanes: LaneIndices| -> Vec<Sample> {
        per_view.iter().flat_map(|v| v.samples(lanes)).collect()
    };
    let fitted_samples = samples_at(all.lanes);
    println!(
        "{} samples; mean relative colour error against {:?}: published matrix {:.4} (at {} nm), fitted {:.4} (at {} nm)",
        fitted_samples.len(),
        args.spectral,
        mean_error(&published, &samples_at(published_lanes)),
        joined(published_nm, "/"),
        mean_error(&all.matrix, &fitted_samples),
        joined(lanes_nm, "/"),
    );
    let mut csv = String::from(
        "# Spectral4: four wavelengths (nm, lanes 0-3, longest first) and the matrix from spectral radiance at them to linear sRGB (rows R, G, B).\n",
    );
    let (flag, how) = match args.objective {
        Objective::LeastSquares => ("", "weighted least squares (weights 1/Y²)"),
        Objective::De2000 => (
            " --objective de2000",
            "ΔE2000 as each view is displayed (Nelder–Mead from weighted least squares)",
        ),
    };
    let lanes_flag = if args.choose_lanes {
        " --choose-lanes".to_string()
    } else {
        format!(" --lanes-nm {}", joined(lanes_nm, ","))
    };
    writeln!(
        csv,
        "# Fitted by Atmoscope (`atmoscope fit-wavelengths --spectral spectral{} --grid {}{lanes_flag}{flag}`): {how}\n\
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
    if args.choose_lanes {
        writeln!(
            csv,
            "# Wavelengths chosen on a {LANE_GRID_STEP_NM} nm grid, one in each of {}: the four under whose least-squares matrix the worst view's larger of mean ΔE2000 / {MEAN_BOUND} and p95 / {P95_BOUND} is smallest.",
            LANE_RANGES_NM
                .map(|(lo, hi)| format!("{lo}-{hi} nm"))
                .join(", ")
        )?;
    }
    csv.push_str("quantity,lane,value\n");
    for (k, w) in lanes_nm.iter().enumerate() {
        writeln!(csv, "wavelength_nm,{k},{w}")?;
    }
    for (r, row) in all.matrix.iter().enumerate() {
        for (k, v) in row.iter().enumerate() {
            writeln!(csv, "{},{k},{v:.9}", ["R", "G", "B"][r])?;
        }
    }
    match &args.out {
        Some(path) => {
            crate::files::write_atomic(path, csv.as_bytes())?;
            eprintln!("wrote {}", path.display());
        }
        None => print!("{csv}"),
    }
    Ok(ExitCode::SUCCESS)
}
