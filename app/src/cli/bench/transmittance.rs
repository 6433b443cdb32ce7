//! `atmoscope bench transmittance`: the optical depth from a point to the top of the
//! atmosphere by each way the models compute it — the midpoint rule (`nishita`), the trapezoid
//! rule (`trapezoid`), each at several step counts, Schuler's Chapman function (`schuler`),
//! Gałaj et al.'s Taylor integral (`galaj-taylor`) and Hermite spline over a 50 × 20 mesh
//! (`galaj-spline`), and Leenman's homogeneous-shell chord (`flat`, `raymarched`) on the fitted
//! exponential medium, and a
//! look-up of the transmittance table the table-based models share — against an adaptive f64
//! quadrature of the scene's medium, over heights and zenith angles, with the CPU time of one
//! evaluation: the comparison of Gałaj et al. (2021) for the methods Atmoscope has. It also
//! repeats their grid search for the Taylor parameters (a, b) on this atmosphere's fitted
//! scale heights.

use crate::scene_args::SceneArgs;
use atmoscope_model::atmosphere::Atmosphere;
use atmoscope_model::geometry::{altitude_along, distance_to_top, hits_ground};
use atmoscope_model::methods::shared::exponential::{
    ExponentialMedium, GALAJ_TAYLOR_A, GALAJ_TAYLOR_B, column_by_quadrature, galaj_grid_search,
    galaj_taylor_mean_error,
};
use atmoscope_model::methods::shared::single_scattering_sky::{Rule, SunRoute, Way, optical_depth};
use atmoscope_model::methods::shared::transmittance::{compute_transmittance_lut, transmittance};
use atmoscope_model::methods::shared::{Lanes, Params};
use atmoscope_model::quadrature::integrate_adaptive;
use atmoscope_model::scene::WavelengthSet;
use clap::Args;
use serde::Serialize;
use std::hint::black_box;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Args, Debug)]
pub struct TransmittanceBench {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Step counts of the midpoint and trapezoid rules, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "4,8,16,32,64,128", value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub steps: Vec<u32>,
    #[arg(long)]
    pub json: bool,
}

/// Heights (m) and zenith angles (degrees) of the rays, from the ground to 50 km and from the
/// zenith to the horizon (rays that end on the ground are left out: no sun ray does).
const HEIGHTS_M: [f64; 6] = [0.0, 1_000.0, 5_000.0, 15_000.0, 30_000.0, 50_000.0];
const ZENITH_DEG: [f64; 8] = [0.0, 30.0, 60.0, 75.0, 85.0, 88.0, 89.5, 90.0];

#[derive(Serialize, Debug)]
struct Row {
    method: String,
    steps: Option<u32>,
    /// Mean and largest |τ − τ_ref| / τ_ref over the rays and the four wavelengths.
    mean_relative_error: f64,
    max_relative_error: f64,
    /// Where the largest error is: height (m), zenith angle (degrees).
    worst_at: (f64, f64),
    /// CPU time of one evaluation (four wavelengths at once), ns.
    ns_per_evaluation: f64,
}

/// Optical depth of the medium from (h, mu) to the top, per lane, by adaptive Gauss–Kronrod
/// quadrature (relative tolerance 1e-10): the reference.
fn reference_depth(p: &Params, h: f64, mu: f64) -> Lanes {
    let d = distance_to_top(h, mu, p.bottom_radius_m, p.top_radius_m);
    Lanes::from_fn(|lane| {
        integrate_adaptive(
            |t| {
                let (h_t, _) = altitude_along(h, mu, t, p.bottom_radius_m);
                p.medium(0, h_t).extinction[lane]
            },
            0.0,
            d,
            1e-10,
            1e-14,
        )
        .value
    })
}

/// Nanoseconds per call of `f` over `rays`, repeated until a quarter of a second has passed.
fn time_per_call(rays: &[(f64, f64)], f: impl Fn(f64, f64) -> Lanes) -> f64 {
    let start = Instant::now();
    let mut calls = 0u64;
    while start.elapsed().as_secs_f64() < 0.25 {
        for &(h, mu) in rays {
            black_box(f(black_box(h), black_box(mu)));
        }
        calls += rays.len() as u64;
    }
    start.elapsed().as_secs_f64() * 1e9 / calls as f64
}

pub fn run(args: &TransmittanceBench) -> anyhow::Result<ExitCode> {
    let scene = args.scene.scene()?;
    let atm = Atmosphere::for_scene(&scene);
    let p = Params::new(&atm, WavelengthSet::Spectral4, scene.render.quality);
    let rays: Vec<(f64, f64)> = HEIGHTS_M
        .iter()
        .flat_map(|&h| ZENITH_DEG.map(|z| (h, z.to_radians().cos())))
        .filter(|&(h, mu)| !hits_ground(h, mu, p.bottom_radius_m))
        .collect();
    let reference: Vec<Lanes> = rays
        .iter()
        .map(|&(h, mu)| reference_depth(&p, h, mu))
        .collect();
    let measure = |method: &str, steps: Option<u32>, f: &dyn Fn(f64, f64) -> Lanes| {
        let (mut sum, mut n, mut worst, mut worst_at) = (0.0, 0.0, 0.0, (0.0, 0.0));
        for (&(h, mu), r) in rays.iter().zip(&reference) {
            let depth = f(h, mu);
            for (d, r) in depth.iter().zip(r) {
                let e = (d - r).abs() / r;
                sum += e;
                n += 1.0;
                if e > worst {
                    worst = e;
                    worst_at = (h, mu.clamp(-1.0, 1.0).acos().to_degrees());
                }
            }
        }
        Row {
            method: method.into(),
            steps,
            mean_relative_error: sum / n,
            max_relative_error: worst,
            worst_at,
            ns_per_evaluation: time_per_call(&rays, f),
        }
    };
    let mut rows = Vec::new();
    for &n in &args.steps {
        rows.push(measure("midpoint (nishita)", Some(n), &|h, mu| {
            optical_depth(&p, 0, h, mu, n, Rule::Midpoint)
        }));
        rows.push(measure("trapezoid", Some(n), &|h, mu| {
            optical_depth(&p, 0, h, mu, n, Rule::Trapezoid)
        }));
    }
    for (name, way) in [
        ("schuler (Chapman)", Way::SchulerChapman),
        ("galaj-taylor", Way::GalajTaylor),
        ("galaj-spline", Way::GalajSpline),
        ("homogeneous shell", Way::HomogeneousShell),
    ] {
        let route = SunRoute::new(&p, way);
        rows.push(measure(name, None, &|h, mu| {
            route.optical_depth(&p, 0, h, mu)
        }));
    }
    let table = compute_transmittance_lut(&p);
    rows.push(measure("transmittance table", None, &|h, mu| {
        transmittance(&p, &table, 0, h, mu).map(|t| -t.max(1e-300).ln())
    }));
    let search = grid_search(&p, &rays);
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&serde_json::json!({
                "rows": rows,
                "galaj_grid_search": search,
            }))?
        );
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "optical depth to the top at {} nm, {} rays (heights 0–50 km, zenith 0–90°), against adaptive quadrature",
        p.batches[0]
            .colour
            .wavelengths_nm
            .map(|w| format!("{w:.0}"))
            .join("/"),
        rays.len()
    );
    println!(
        "{:22} {:>6} {:>12} {:>12} {:>18} {:>10}",
        "method", "steps", "mean |err|", "max |err|", "worst at (h, z°)", "ns / eval"
    );
    for r in &rows {
        println!(
            "{:22} {:>6} {:>11.4}% {:>11.4}% {:>10.0} m {:>5.1}° {:>10.0}",
            r.method,
            r.steps.map_or("-".to_string(), |s| s.to_string()),
            r.mean_relative_error * 100.0,
            r.max_relative_error * 100.0,
            r.worst_at.0,
            r.worst_at.1,
            r.ns_per_evaluation
        );
    }
    println!(
        "\nGałaj's grid search (a, b in 0–1, step 0.01) on this atmosphere's fitted scale heights \
         (air {:.0} m, aerosol {:.0} m), rays up to {}° from the zenith: best a = {:.2}, b = {:.2} \
         (mean error {:.3} %); the paper's a = b = {:.2}: {:.3} %",
        search.air_scale_height_m,
        search.aerosol_scale_height_m,
        SEARCH_MAX_ZENITH_DEG,
        search.best.0,
        search.best.1,
        search.best_mean_relative_error * 100.0,
        GALAJ_TAYLOR_A,
        search.paper_mean_relative_error * 100.0
    );
    Ok(ExitCode::SUCCESS)
}

/// The grid search's rays stop short of the horizon, where no pair fits aerosol's short scale
/// height (the Taylor integral overshoots without bound there).
const SEARCH_MAX_ZENITH_DEG: f64 = 75.0;

#[derive(Serialize, Debug)]
struct GridSearch {
    air_scale_height_m: f64,
    aerosol_scale_height_m: f64,
    best: (f64, f64),
    best_mean_relative_error: f64,
    paper_mean_relative_error: f64,
}

/// Gałaj's grid search over the bench's rays up to [`SEARCH_MAX_ZENITH_DEG`], for the integral
/// of exp(−h/H) at both fitted scale heights, against adaptive quadrature.
fn grid_search(p: &Params, rays: &[(f64, f64)]) -> GridSearch {
    let fit = ExponentialMedium::fit(p);
    let (big_r, top) = (p.bottom_radius_m, p.top_radius_m);
    let min_mu = SEARCH_MAX_ZENITH_DEG.to_radians().cos() - 1e-12;
    let search_rays: Vec<(f64, f64, f64)> = [fit.air, fit.aerosol]
        .iter()
        .filter(|e| e.at_ground > 0.0)
        .flat_map(|e| {
            rays.iter()
                .filter(|&&(_, mu)| mu >= min_mu)
                .map(move |&(h, mu)| (h, mu, e.scale_height_m))
        })
        .collect();
    let exact: Vec<f64> = search_rays
        .iter()
        .map(|&(h, mu, hh)| column_by_quadrature(h, mu, hh, big_r, top))
        .collect();
    let (best, best_mean_relative_error) = galaj_grid_search(&search_rays, &exact, big_r, top);
    let paper_mean_relative_error = galaj_taylor_mean_error(
        &search_rays,
        &exact,
        big_r,
        top,
        (GALAJ_TAYLOR_A, GALAJ_TAYLOR_B),
    );
    GridSearch {
        air_scale_height_m: fit.air.scale_height_m,
        aerosol_scale_height_m: fit.aerosol.scale_height_m,
        best,
        best_mean_relative_error,
        paper_mean_relative_error,
    }
}
