//! `atmoscope bench accuracy`: ΔE2000 (mean and 95th percentile, at each view's exposure) of
//! real-time models and wavelength sets against path-traced references of the view suite, and
//! of the other sets against the first.

use crate::args::parse_wavelengths;
use crate::args::set_name;
use crate::cli::common::{gpu, suite_reference};

use atmoscope_eval::metrics::{DisplaySetup, compare};
use atmoscope_model::Scene;
use atmoscope_model::scene::Method;
use atmoscope_model::scene::WavelengthSet;
use atmoscope_model::views;
use atmoscope_render::{Engine, View};
use clap::Args;
use serde::Serialize;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct AccuracyBench {
    /// Directory of path-traced references named `<view>.exr`
    /// (from `atmoscope reference --suite --out-dir DIR`); default: the repository's
    /// tests/data/references, under the working directory or above the program.
    #[arg(long, value_name = "DIR")]
    pub refs: Option<PathBuf>,
    /// Views of the suite, comma-separated (default: every view with a reference in --refs).
    #[arg(long, value_delimiter = ',')]
    pub views: Vec<String>,
    /// The spectral set the others are compared with.
    #[arg(long, value_parser = parse_wavelengths, default_value = "spectral32")]
    pub spectral: WavelengthSet,
    /// Wavelength sets to measure, comma-separated, the first being the one the others are
    /// compared with (default: the --spectral set, spectral4, rgb3).
    #[arg(long, value_delimiter = ',', value_parser = parse_wavelengths)]
    pub sets: Vec<WavelengthSet>,
    /// Sky models, comma-separated registry ids, or `all`.
    #[arg(long, value_name = "IDS", value_parser = crate::args::parse_methods, default_value = "hillaire")]
    pub methods: crate::args::MethodList,
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize, Debug)]
struct AccuracyRow {
    view: String,
    sun_elevation_deg: f64,
    exposure_ev: f64,
    /// (model/set, mean, p95) ΔE2000 against the path-traced reference, per model and set.
    vs_reference: Vec<(String, f64, f64)>,
    /// (model/set, mean, p95) ΔE2000 of Spectral4 and RGB3 against the model's spectral set.
    vs_spectral: Vec<(String, f64, f64)>,
}

pub fn run(args: &AccuracyBench) -> anyhow::Result<ExitCode> {
    let refs = crate::shipped::references(args.refs.as_deref())?;
    let context = gpu()?;
    let sets = if args.sets.is_empty() {
        vec![args.spectral, WavelengthSet::Spectral4, WavelengthSet::Rgb3]
    } else {
        args.sets.clone()
    };
    let runs: Vec<(Method, WavelengthSet)> = args
        .methods
        .0
        .iter()
        .flat_map(|&m| sets.iter().map(move |&s| (m, s)))
        .collect();
    let name =
        |(m, s): (Method, WavelengthSet)| format!("{}/{}", crate::args::method_id(m), set_name(s));
    let mut rows = Vec::new();
    // One engine per run, kept across views: a table whose inputs a view leaves unchanged is
    // not rebuilt (Bruneton's 4D tables, which depend on the atmosphere alone, are built once).
    let mut engines: Vec<Engine> = runs
        .iter()
        .map(|_| Engine::new(&context.device, &context.queue))
        .collect();
    for v in views::suite() {
        if !args.views.is_empty() && !args.views.iter().any(|n| n == v.name.as_str()) {
            continue;
        }
        let Some((reference, w, h)) = suite_reference(&refs, &v.name, !args.views.is_empty())?
        else {
            continue;
        };
        let scene: Scene = v.apply(&Scene::default());
        let setup = DisplaySetup {
            exposure_ev: scene.display.exposure_ev,
            tone_map: scene.display.tone_map,
            ..DisplaySetup::default()
        };
        // None where the model refuses the view (its figures are then NaN, null in JSON).
        let images: Vec<Option<Vec<[f64; 3]>>> = runs
            .iter()
            .zip(engines.iter_mut())
            .map(|(&(method, set), engine)| {
                let mut s = scene.clone();
                s.render.method = method;
                s.render.wavelengths = set;
                if atmoscope_model::methods::info(method)
                    .cannot_draw(&s)
                    .is_some()
                {
                    return Ok(None);
                }
                engine.try_render(&s, &View::new(v.projection, w, h))?;
                Ok(Some(
                    engine
                        .read_radiance()?
                        .iter()
                        .map(|p| [p[0], p[1], p[2]].map(f64::from))
                        .collect(),
                ))
            })
            .collect::<anyhow::Result<_>>()?;
        let de = |a: &Option<Vec<[f64; 3]>>, b: &[[f64; 3]]| match a {
            Some(a) => {
                let (c, _) = compare(a, b, w, h, setup);
                (c.delta_e2000_mean, c.delta_e2000_p95)
            }
            None => (f64::NAN, f64::NAN),
        };
        let vs_reference = runs
            .iter()
            .zip(&images)
            .map(|(&run, img)| {
                let (m, p) = de(img, &reference);
                (name(run), m, p)
            })
            .collect();
        // Each model's other sets against its first (by default Spectral4 and RGB3 against
        // the spectral set).
        let vs_spectral = runs
            .iter()
            .enumerate()
            .filter(|(i, _)| i % sets.len() != 0)
            .map(|(i, &run)| {
                let (m, p) = match &images[i - i % sets.len()] {
                    Some(first) => de(&images[i], first),
                    None => (f64::NAN, f64::NAN),
                };
                (name(run), m, p)
            })
            .collect();
        rows.push(AccuracyRow {
            view: v.name.clone(),
            sun_elevation_deg: scene.sun.angles().elevation_deg,
            exposure_ev: scene.display.exposure_ev,
            vs_reference,
            vs_spectral,
        });
        eprintln!("{} done", v.name);
    }
    if rows.is_empty() {
        anyhow::bail!("no references found in {}", refs.display());
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
        return Ok(ExitCode::SUCCESS);
    }
    let s = set_name(sets[0]);
    println!("ΔE2000 mean / p95, display-referred at each view's exposure");
    print!("{:20} {:>6} ", "view", "sun°");
    let first = &rows[0];
    for (n, _, _) in &first.vs_reference {
        print!(" {:>17}", format!("{n} vs ref"));
    }
    for (n, _, _) in &first.vs_spectral {
        print!(" {:>17}", format!("{n} vs {s}"));
    }
    println!();
    for r in &rows {
        print!("{:20} {:>6.1} ", r.view, r.sun_elevation_deg);
        for (_, m, p) in r.vs_reference.iter().chain(&r.vs_spectral) {
            if m.is_nan() {
                print!(" {:>17}", "refused");
            } else {
                print!(" {:>9.2} / {:>5.2}", m, p);
            }
        }
        println!();
    }
    for (label, daylight) in [
        ("daylight (sun ≥ 0°)", true),
        ("twilight (sun < 0°)", false),
    ] {
        let group: Vec<&AccuracyRow> = rows
            .iter()
            .filter(|r| (r.sun_elevation_deg >= 0.0) == daylight)
            .collect();
        if group.is_empty() {
            continue;
        }
        // Over the views each run draws (a refusing model's are fewer).
        let mean = |f: &dyn Fn(&AccuracyRow) -> f64| {
            let drawn: Vec<f64> = group.iter().map(|r| f(r)).filter(|v| !v.is_nan()).collect();
            drawn.iter().sum::<f64>() / drawn.len() as f64
        };
        println!("{label}, {} views, mean ΔE2000 (mean / p95):", group.len());
        for (i, (n, _, _)) in first.vs_reference.iter().enumerate() {
            let drawn = group
                .iter()
                .filter(|r| !r.vs_reference[i].1.is_nan())
                .count();
            if drawn == 0 {
                println!("  {n} vs ref: refuses these views");
                continue;
            }
            println!(
                "  {n} vs ref {:.2} / {:.2}{}",
                mean(&|r| r.vs_reference[i].1),
                mean(&|r| r.vs_reference[i].2),
                if drawn < group.len() {
                    format!(" (over the {drawn} views it draws)")
                } else {
                    String::new()
                }
            );
        }
        for (i, (n, _, _)) in first.vs_spectral.iter().enumerate() {
            let m = mean(&|r| r.vs_spectral[i].1);
            if m.is_nan() {
                println!("  {n} vs {s}: refuses these views");
            } else {
                println!("  {n} vs {s} {m:.2}");
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}
