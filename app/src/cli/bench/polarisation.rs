//! `atmoscope bench polarisation`: the real-time models' degree of polarisation against the
//! path tracer's vector mode, view by view of the suite (the mean and 95th percentile of the
//! absolute difference over the view's pixels, the sun's disk left out), and what the vector
//! mode costs against the scalar one for the same paths.

use crate::cli::common::{gpu, outside_sun_disk};
use anyhow::Context;
use atmoscope_model::methods::{self, path_tracer::PathTracerSettings};
use atmoscope_model::reference::ReferenceRender;
use atmoscope_model::scene::Method;
use atmoscope_model::views;
use atmoscope_render::{DisplayMode, Engine, View};
use clap::Args;
use serde::Serialize;
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

#[derive(Args, Debug)]
pub struct PolarisationBench {
    /// Views of the suite, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "fisheye-sun90,fisheye-sun30,fisheye-sun5,ground-sunrise,ground-noon"
    )]
    pub views: Vec<String>,
    /// Image size, pixels on the longer side (the view's aspect kept).
    #[arg(long, default_value_t = 32, value_parser = clap::value_parser!(u32).range(8..=512))]
    pub size: u32,
    /// Paths per pixel of the vector references.
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(2..))]
    pub spp: u32,
    /// The scene the views' sun and camera are put on (by default the built-in default).
    #[command(flatten)]
    pub scene: crate::scene_args::SceneArgs,
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize, Debug)]
struct Cost {
    view: String,
    paths: u64,
    scalar_seconds: f64,
    vector_seconds: f64,
}

#[derive(Serialize, Debug)]
struct Row {
    view: String,
    model: String,
    pixels: usize,
    /// Mean and 95th percentile of |DoP_model − DoP_vector tracer|, 0–1.
    mean_abs_error: f64,
    p95_abs_error: f64,
    /// The vector tracer's own mean degree over the pixels compared.
    reference_mean_degree: f64,
}

fn degree(s: [f64; 3]) -> Option<f64> {
    (s[0] > 0.0).then(|| (s[1].hypot(s[2]) / s[0]).min(1.0))
}

pub fn run(args: &PolarisationBench) -> anyhow::Result<ExitCode> {
    let base = args.scene.scene()?;
    let gpu = gpu()?;
    let (mut rows, mut costs) = (Vec::new(), Vec::new());
    let never = AtomicBool::new(false);
    for name in &args.views {
        let view = views::find(name).with_context(|| format!("--views: no view {name}"))?;
        let scene = view.apply(&base);
        let (vw, vh) = view.size;
        let (w, h) = if vw >= vh {
            (args.size, (args.size * vh / vw).max(1))
        } else {
            ((args.size * vw / vh).max(1), args.size)
        };
        // The same paths, scalar then vector: their time, and the vector references.
        let settings = PathTracerSettings::default();
        let mut scalar = ReferenceRender::new(&scene, view.projection, w, h, 1, settings);
        let start = Instant::now();
        scalar.run_pass(args.spp, &never);
        let scalar_seconds = start.elapsed().as_secs_f64();
        let mut vector =
            ReferenceRender::new(&scene, view.projection, w, h, 1, settings).with_stokes();
        let start = Instant::now();
        vector.run_pass(args.spp, &never);
        let vector_seconds = start.elapsed().as_secs_f64();
        let paths = vector.pixels().iter().filter(|p| p.covered).count() as u64 * args.spp as u64;
        eprintln!(
            "{name}: {paths} paths, scalar {scalar_seconds:.1} s, vector {vector_seconds:.1} s"
        );
        costs.push(Cost {
            view: name.clone(),
            paths,
            scalar_seconds,
            vector_seconds,
        });
        let reference: Vec<[f64; 3]> = vector
            .stokes_y()
            .unwrap_or_default()
            .iter()
            .map(|s| [s[0], s[1], s[2]])
            .collect();
        let off_sun = outside_sun_disk(&scene, view.projection, w, h);
        // The empty sky has no light to polarise.
        for model in methods::realtime().filter(|m| m.method != Method::Empty) {
            let mut s = scene.clone();
            s.render.method = model.method;
            if model.cannot_draw(&s).is_some() {
                continue;
            }
            let mut engine = Engine::new(&gpu.device, &gpu.queue);
            let shown = View {
                mode: DisplayMode::Polarisation,
                ..View::new(view.projection, w, h)
            };
            engine.render_still(&s, &shown)?;
            let image = engine.read_radiance()?;
            let mut errors: Vec<f64> = Vec::new();
            let mut reference_degrees = 0.0;
            for (k, p) in image.iter().enumerate() {
                let realtime = [p[0], p[1], p[2]].map(f64::from);
                if let (true, Some(d), Some(r)) =
                    (off_sun[k], degree(realtime), degree(reference[k]))
                {
                    errors.push((d - r).abs());
                    reference_degrees += r;
                }
            }
            if errors.is_empty() {
                continue;
            }
            let n = errors.len();
            errors.sort_by(f64::total_cmp);
            rows.push(Row {
                view: name.clone(),
                model: model.id.to_string(),
                pixels: n,
                mean_abs_error: errors.iter().sum::<f64>() / n as f64,
                p95_abs_error: errors[((n - 1) as f64 * 0.95).round() as usize],
                reference_mean_degree: reference_degrees / n as f64,
            });
        }
    }
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&serde_json::json!({ "rows": rows, "cost": costs }))?
        );
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "degree of polarisation against the vector path tracer ({} paths per pixel)",
        args.spp
    );
    println!(
        "view                 model                 pixels  mean |ΔP|  p95 |ΔP|  tracer's mean P"
    );
    for r in &rows {
        println!(
            "{:20} {:20} {:7}  {:9.3}  {:8.3}  {:15.3}",
            r.view, r.model, r.pixels, r.mean_abs_error, r.p95_abs_error, r.reference_mean_degree
        );
    }
    println!();
    println!("view                  paths   scalar s  vector s  vector/scalar");
    for c in &costs {
        println!(
            "{:20} {:7} {:9.2} {:9.2} {:14.2}",
            c.view,
            c.paths,
            c.scalar_seconds,
            c.vector_seconds,
            c.vector_seconds / c.scalar_seconds
        );
    }
    Ok(ExitCode::SUCCESS)
}
