//! `atmoscope bench aod`: how each real-time model's sky radiance departs from the path tracer
//! as the aerosol optical depth grows, which sets the AOD range each model states in its
//! domain (`Domain::max_aod550`).

use crate::cli::sky_probe::{ProbeMethod, ProbeRequest, probe};
use crate::scene_args::SceneArgs;
use anyhow::bail;
use atmoscope_model::Scene;
use atmoscope_model::methods::{self, AOD_RANGE_ERROR};
use atmoscope_model::scene::SunSettings;
use clap::Args;
use serde::Serialize;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct AodBench {
    /// The scene (default: the built-in one, rural aerosol); its AOD and sun are swept.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Aerosol optical depths at 550 nm, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "0.05,0.1,0.15,0.2,0.3,0.5,1,2,5", value_parser = crate::args::parse_positive)]
    pub aods: Vec<f64>,
    /// Sun elevations, degrees, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "30,5", value_parser = crate::args::parse_finite, allow_hyphen_values = true)]
    pub suns: Vec<f64>,
    /// Sky models, comma-separated registry ids, or `all`.
    #[arg(long, value_name = "IDS", value_parser = crate::args::parse_methods, default_value = "all")]
    pub methods: crate::args::MethodList,
    /// Path-tracer paths per direction.
    #[arg(long, default_value_t = 40_000, value_parser = clap::value_parser!(u64).range(2..))]
    pub spp: u64,
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize, Debug)]
struct Row {
    method: String,
    sun_elevation_deg: f64,
    aod550: f64,
    /// Mean |model/path tracer − 1| over the directions and wavelengths.
    mean_abs_error: f64,
    /// Mean (model/path tracer − 1): negative when the model is too dark.
    bias: f64,
    /// The largest error of one direction and wavelength, signed.
    worst: f64,
    /// The model's stated AOD range.
    max_aod550: f64,
}

/// View zenith angles and azimuths from the sun's: the zenith, the sky's middle and the
/// horizon, towards, across and away from the sun.
const ZENITH_DEG: [f64; 4] = [0.0, 45.0, 75.0, 85.0];
const AZIMUTH_DEG: [f64; 3] = [30.0, 90.0, 180.0];
const WAVELENGTHS_NM: [f64; 3] = [450.0, 550.0, 650.0];

pub fn run(args: &AodBench) -> anyhow::Result<ExitCode> {
    if let Some(s) = args.suns.iter().find(|s| !(-90.0..=90.0).contains(*s)) {
        bail!("--suns: {s}° is outside −90 to 90°");
    }
    let base = args.scene.scene()?;
    let request = |method| ProbeRequest {
        view_zenith_deg: ZENITH_DEG.to_vec(),
        view_azimuth_deg: AZIMUTH_DEG.to_vec(),
        wavelengths_nm: WAVELENGTHS_NM.to_vec(),
        method,
        max_order: None,
        spp: args.spp,
        seed: 1,
        stokes: false,
    };
    let mut rows = Vec::new();
    for &sun in &args.suns {
        for &aod in &args.aods {
            let mut scene: Scene = base.clone();
            scene.atmosphere.aerosol.aod550 = aod;
            let azimuth_deg = scene.sun.angles().azimuth_deg;
            scene.sun = SunSettings::Angles {
                elevation_deg: sun,
                azimuth_deg,
            };
            if let Err(e) = scene.validate() {
                bail!("AOD {aod}, sun {sun}°: {}", e[0]);
            }
            let truth = probe(&scene, &request(ProbeMethod::PathTracer));
            for &method in &args.methods.0 {
                let info = methods::info(method);
                let model = probe(&scene, &request(ProbeMethod::Model(method)));
                let errors: Vec<f64> = model
                    .samples
                    .iter()
                    .zip(&truth.samples)
                    .filter(|(_, t)| t.radiance > 0.0)
                    .map(|(m, t)| m.radiance / t.radiance - 1.0)
                    .collect();
                let n = errors.len().max(1) as f64;
                rows.push(Row {
                    method: info.id.into(),
                    sun_elevation_deg: sun,
                    aod550: aod,
                    mean_abs_error: errors.iter().map(|e| e.abs()).sum::<f64>() / n,
                    bias: errors.iter().sum::<f64>() / n,
                    worst: errors
                        .iter()
                        .copied()
                        .fold(0.0, |w, e| if e.abs() > f64::abs(w) { e } else { w }),
                    max_aod550: info.domain.max_aod550,
                });
            }
            eprintln!("sun {sun}°, AOD {aod} done");
        }
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "sky radiance against the path tracer ({} paths per direction), mean |error| / bias / worst, {} directions × {} wavelengths",
        args.spp,
        ZENITH_DEG.len() * AZIMUTH_DEG.len(),
        WAVELENGTHS_NM.len()
    );
    for &method in &args.methods.0 {
        let info = methods::info(method);
        println!(
            "\n{} (stated AOD range: up to {:.2})",
            info.id, info.domain.max_aod550
        );
        println!(
            "{:>6} {:>6} {:>9} {:>8} {:>8}",
            "sun°", "AOD", "mean", "bias", "worst"
        );
        let mine: Vec<&Row> = rows.iter().filter(|r| r.method == info.id).collect();
        for r in &mine {
            println!(
                "{:>6.1} {:>6.2} {:>8.1}% {:>+7.1}% {:>+7.0}%",
                r.sun_elevation_deg,
                r.aod550,
                r.mean_abs_error * 100.0,
                r.bias * 100.0,
                r.worst * 100.0
            );
        }
        // The largest swept AOD below which every sun keeps the mean error in bounds.
        let mut aods = args.aods.clone();
        aods.sort_by(f64::total_cmp);
        let within = aods
            .iter()
            .take_while(|&&aod| {
                mine.iter()
                    .filter(|r| r.aod550 <= aod)
                    .all(|r| r.mean_abs_error <= AOD_RANGE_ERROR)
            })
            .last();
        match within {
            Some(a) => println!(
                "mean error within {:.0} % up to AOD {a}",
                AOD_RANGE_ERROR * 100.0
            ),
            None => println!(
                "mean error above {:.0} % at every AOD swept",
                AOD_RANGE_ERROR * 100.0
            ),
        }
    }
    Ok(ExitCode::SUCCESS)
}
