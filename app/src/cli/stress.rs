//! `atmoscope stress`: the long numerical stress run. Draws scenes over the whole parameter
//! space (`atmoscope_render::stress`), renders each with every real-time model on the GPU and
//! with its f64 CPU twin, and reports NaN, Inf, negative and out-of-bound counts per model, the
//! worst GPU–CPU difference per camera altitude class, and broken monotonicity. Each failing
//! case is written as a preset that `--replay` re-checks; the exit code is non-zero on any
//! failure.

use crate::args::{MethodList, parse_methods, set_name};
use anyhow::Context;
use atmoscope_model::methods::{self, rng::Rng};
use atmoscope_model::scene::Scene;
use atmoscope_render::stress::{
    DIMENSIONS, Findings, GPU_CPU_BOUND, GPU_CPU_DARKEST_CD_M2, GPU_CPU_FLOOR, Stress, VIEW_SIZE,
    scene_at,
};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

#[derive(Args, Debug)]
pub struct StressArgs {
    /// Number of cases: a scene and a model each, the models taken in turn.
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u32).range(1..=10_000_000))]
    pub cases: u32,
    /// Random seed of the draws.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Consecutive cases that share one drawn atmosphere (and so its tables).
    #[arg(long, default_value_t = 100, value_parser = clap::value_parser!(u32).range(1..))]
    pub per_atmosphere: u32,
    /// Models to stress: `all` or a comma-separated list of registry ids.
    #[arg(long, default_value = "all", value_parser = parse_methods)]
    pub methods: MethodList,
    /// Directory for report.md, report.json and a preset per failing case (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Re-run the checks on scenes that failing cases wrote (each preset's own model and
    /// wavelength set), in the order given, on one engine: a case that failed only after
    /// another one is reproduced by replaying both.
    #[arg(long, value_name = "FILE", num_args = 1.., conflicts_with_all = ["cases", "seed", "per_atmosphere", "out"])]
    pub replay: Vec<PathBuf>,
}

/// Camera altitude classes of the report: where f32 geometry breaks first.
fn altitude_class(scene: &Scene) -> &'static str {
    let h = scene.camera.altitude_m;
    let top = scene.atmosphere.top_km * 1000.0;
    match h {
        0.0 => "0 m",
        1.0 => "1 m",
        h if h == top - 1.0 => "top − 1 m",
        h if h == top => "top",
        h if h == top + 1.0 => "top + 1 m",
        h if h == atmoscope_model::scene::MAX_CAMERA_ALTITUDE_M => "1e8 m",
        h if h < top => "inside (other)",
        _ => "above (other)",
    }
}

#[derive(Debug, Default, Serialize)]
struct Tally {
    name: String,
    cases: usize,
    failed_cases: usize,
    nan: usize,
    inf: usize,
    negative: usize,
    out_of_bound: usize,
    monotonicity: usize,
    faults: usize,
    /// Worst GPU–CPU difference on the model's domain, and the case.
    worst_gpu_cpu: f64,
    worst_case: Option<u32>,
    /// Worst GPU–CPU difference outside the model's domain (reported, not bounded).
    worst_outside: f64,
}

impl Tally {
    fn named(name: &str) -> Tally {
        Tally {
            name: name.into(),
            ..Tally::default()
        }
    }

    fn add(&mut self, case: u32, f: &Findings) {
        self.cases += 1;
        self.failed_cases += usize::from(f.failed());
        self.nan += f.nan;
        self.inf += f.inf;
        self.negative += f.negative;
        self.out_of_bound += f.out_of_bound;
        self.monotonicity += f.monotonicity.len();
        self.faults += usize::from(f.fault.is_some());
        if f.refused {
            // Refused, and refused on the GPU too (else a fault): nothing drawn to compare.
            return;
        }
        if !f.in_domain {
            self.worst_outside = self.worst_outside.max(f.worst_gpu_cpu);
        } else if f.worst_gpu_cpu > self.worst_gpu_cpu || self.worst_case.is_none() {
            self.worst_gpu_cpu = f.worst_gpu_cpu;
            self.worst_case = Some(case);
        }
    }

    fn row(&self) -> String {
        format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.2e} | {} | {:.2e} |",
            self.name,
            self.cases,
            self.failed_cases,
            self.nan,
            self.inf,
            self.negative,
            self.out_of_bound,
            self.monotonicity,
            self.faults,
            self.worst_gpu_cpu,
            self.worst_case.map_or("–".into(), |c| c.to_string()),
            self.worst_outside
        )
    }
}

const HEADER: &str = "| | cases | failed | NaN | Inf | negative | out of bound | monotonicity | GPU faults | worst GPU–CPU in domain | its case | worst GPU–CPU outside |\n|---|---|---|---|---|---|---|---|---|---|---|---|";

#[derive(Debug, Serialize)]
struct Report {
    seed: u64,
    cases: u32,
    per_atmosphere: u32,
    seconds: f64,
    adapter: String,
    gpu_cpu_bound: f64,
    by_model: Vec<Tally>,
    by_altitude: Vec<Tally>,
    failures: Vec<Failure>,
}

#[derive(Debug, Serialize)]
struct Failure {
    case: u32,
    model: &'static str,
    wavelengths: String,
    findings: String,
    preset: Option<PathBuf>,
}

impl Report {
    fn markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "# atmoscope stress — {} cases, seed {}, {} per atmosphere\n\n{} in {:.0} s. A case is \
             a {VIEW_SIZE}×{VIEW_SIZE} perspective view rendered on the GPU and by the model's f64 \
             CPU twin; out of bound: on the model's domain, a pixel's luminance off the twin's by \
             more than {:.0} % of the twin's plus {GPU_CPU_FLOOR:e} of the view's brightest pixel (at least \
             {GPU_CPU_DARKEST_CD_M2:e} cd/m², the eye's threshold).\n",
            self.cases,
            self.seed,
            self.per_atmosphere,
            self.adapter,
            self.seconds,
            self.gpu_cpu_bound * 100.0
        );
        let _ = writeln!(s, "## By model\n\n{HEADER}");
        for t in &self.by_model {
            let _ = writeln!(s, "{}", t.row());
        }
        let _ = writeln!(
            s,
            "\n## By camera altitude (f32 at planet scale)\n\n{HEADER}"
        );
        for t in &self.by_altitude {
            let _ = writeln!(s, "{}", t.row());
        }
        let _ = writeln!(s, "\n## Failures ({})\n", self.failures.len());
        for f in &self.failures {
            let _ = writeln!(
                s,
                "- case {} ({}, {}): {}{}",
                f.case,
                f.model,
                f.wavelengths,
                f.findings,
                f.preset.as_ref().map_or(String::new(), |p| format!(
                    " — `atmoscope stress --replay {}`",
                    p.display()
                ))
            );
        }
        s
    }
}

fn describe(f: &Findings) -> String {
    let mut parts = Vec::new();
    for (n, what) in [(f.nan, "NaN"), (f.inf, "Inf"), (f.negative, "negative")] {
        if n > 0 {
            parts.push(format!("{n} {what} pixels"));
        }
    }
    if f.out_of_bound > 0 {
        parts.push(format!(
            "{} pixels beyond the GPU–CPU bound (worst {:.3e})",
            f.out_of_bound, f.worst_gpu_cpu
        ));
    }
    parts.extend(f.monotonicity.iter().cloned());
    parts.extend(f.fault.iter().map(|e| format!("GPU fault: {e}")));
    parts.join("; ")
}

pub fn run(args: &StressArgs) -> anyhow::Result<ExitCode> {
    if let Some(dir) = &args.out {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("--out {}: cannot create the directory", dir.display()))?;
    }
    let gpu = crate::cli::common::gpu()?;
    let mut stress = Stress::new(&gpu.device, &gpu.queue);
    if !args.replay.is_empty() {
        let mut code = ExitCode::SUCCESS;
        for path in &args.replay {
            if replay(&mut stress, path)? != ExitCode::SUCCESS {
                code = ExitCode::FAILURE;
            }
        }
        return Ok(code);
    }
    let models: Vec<_> = args.methods.0.iter().map(|m| methods::info(*m)).collect();
    let mut by_model: Vec<Tally> = models.iter().map(|m| Tally::named(m.id)).collect();
    let mut by_altitude: Vec<Tally> = Vec::new();
    let mut failures = Vec::new();
    let bar = ProgressBar::new(u64::from(args.cases));
    bar.set_style(
        ProgressStyle::with_template("stress [{bar:30}] {pos}/{len} cases  {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let start = Instant::now();
    for case in 0..args.cases {
        let mut u = [0.0; DIMENSIONS];
        // The atmosphere is drawn per group of cases, the viewpoint per case.
        let mut atmosphere = Rng::new(args.seed, u64::from(case / args.per_atmosphere), 0);
        let mut viewpoint = Rng::new(args.seed, u64::from(case), 1);
        for (i, x) in u.iter_mut().enumerate() {
            *x = if i < 5 {
                atmosphere.uniform()
            } else {
                viewpoint.uniform()
            };
        }
        let model = case as usize % models.len();
        let scene = scene_at(&u, models[model].method);
        let findings = stress.check(&scene);
        by_model[model].add(case, &findings);
        let class = altitude_class(&scene);
        let i = match by_altitude.iter().position(|t| t.name == class) {
            Some(i) => i,
            None => {
                by_altitude.push(Tally::named(class));
                by_altitude.len() - 1
            }
        };
        by_altitude[i].add(case, &findings);
        if findings.failed() {
            let preset = match &args.out {
                Some(dir) => {
                    let path = dir.join(format!("case-{case:07}.ron"));
                    crate::files::write_atomic(&path, scene.to_ron().as_bytes())?;
                    Some(path)
                }
                None => None,
            };
            failures.push(Failure {
                case,
                model: models[model].id,
                wavelengths: set_name(scene.render.wavelengths),
                findings: describe(&findings),
                preset,
            });
            bar.set_message(format!("{} failing", failures.len()));
        }
        bar.inc(1);
    }
    bar.finish_and_clear();
    by_altitude.sort_by(|a, b| a.name.cmp(&b.name));
    let report = Report {
        seed: args.seed,
        cases: args.cases,
        per_atmosphere: args.per_atmosphere,
        seconds: start.elapsed().as_secs_f64(),
        adapter: gpu.describe(),
        gpu_cpu_bound: GPU_CPU_BOUND,
        by_model,
        by_altitude,
        failures,
    };
    let markdown = report.markdown();
    print!("{markdown}");
    if let Some(dir) = &args.out {
        crate::files::write_atomic(&dir.join("report.md"), markdown.as_bytes())?;
        crate::files::write_atomic(
            &dir.join("report.json"),
            serde_json::to_string_pretty(&report)?.as_bytes(),
        )?;
        eprintln!("wrote {}", dir.join("report.md").display());
    }
    Ok(if report.failures.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn replay(stress: &mut Stress, path: &Path) -> anyhow::Result<ExitCode> {
    let scene = Scene::load(path)?;
    if let Err(e) = crate::args::parse_method(crate::args::method_id(scene.render.method)) {
        anyhow::bail!("{}: {e}", path.display());
    }
    let f = stress.check(&scene);
    let id = crate::args::method_id(scene.render.method);
    let set = set_name(scene.render.wavelengths);
    if f.failed() {
        println!("{}: {id}, {set}: {}", path.display(), describe(&f));
        Ok(ExitCode::FAILURE)
    } else {
        println!(
            "{}: {id}, {set}: passes (worst GPU–CPU {:.3e})",
            path.display(),
            f.worst_gpu_cpu
        );
        Ok(ExitCode::SUCCESS)
    }
}
