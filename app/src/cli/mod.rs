//! Command-line subcommands. Each loads a scene the same way (`SceneArgs`), works headless and
//! reports bad input as an error naming the file, field and allowed range.

mod aerosols;
mod bench;
mod bench_aod;
mod bench_gpu;
mod bench_leenman;
mod bench_methods;
mod bench_transmittance;
mod compare;
mod fit;
mod fit_garcia_linan;
mod info;
mod learn;
mod presets_cmd;
mod probe;
mod progress;
mod reference;
mod render;
mod scene_args;
mod stress;
mod timelapse;

pub use bench_methods::parse_quality;
pub use render::parse_wavelengths;
pub use scene_args::SceneArgs;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser, Debug)]
#[command(
    name = "atmoscope",
    version,
    about = "An explorer of Earth's atmosphere: physically based sky rendering"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Scene the explorer opens with (without a subcommand).
    #[command(flatten)]
    pub scene: SceneArgs,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Work with scene presets.
    Presets {
        #[command(subcommand)]
        action: PresetsAction,
    },
    /// Optical depths, aerosol optics and sun transmittance of a scene, per wavelength.
    Info(info::InfoArgs),
    /// The Learn menu's guided scenes: the list, or one lesson's text with its numbers.
    Learn(learn::LearnArgs),
    /// The aerosol types: single-scattering albedo, asymmetry and Ångström exponent from Mie theory.
    Aerosols(aerosols::AerosolsArgs),
    /// Diffuse sky radiance in given directions, by the path tracer or exact single scattering.
    Probe(probe::ProbeArgs),
    /// Path-traced reference images (EXR + PNG preview) of a scene, a view or the whole view suite.
    Reference(reference::ReferenceArgs),
    /// Render one view with the real-time GPU engine to PNG (as displayed) or EXR (linear).
    Render(render::RenderArgs),
    /// A sweep of the sun (its elevation, or the hours of a day) as a PNG sequence and an
    /// animated PNG.
    Timelapse(timelapse::TimelapseArgs),
    /// Error metrics of an image against a reference (RMSE, ΔE2000, FLIP), with error maps.
    Compare(compare::CompareArgs),
    /// Fit Spectral4 against SpectralN renders over the view suite: its matrix, and with
    /// --choose-lanes its four wavelengths.
    FitWavelengths(fit::FitArgs),
    /// Refit García Liñán's multiple-scattering constants against path-traced references of
    /// the view suite; reports the error before and after.
    FitGarciaLinan(fit_garcia_linan::FitGarciaLinanArgs),
    /// Numerical stress: scenes over the whole parameter space, every model on the GPU against
    /// its f64 CPU twin; a report, and a preset per failing case.
    Stress(stress::StressArgs),
    /// Benchmarks: run time and convergence (not part of the tests).
    Bench {
        #[command(subcommand)]
        bench: bench::Bench,
    },
}

#[derive(Subcommand, Debug)]
pub enum PresetsAction {
    /// Check preset files (default: every shipped preset); exits non-zero on any failure.
    Validate {
        /// Preset files (.ron) to check.
        files: Vec<std::path::PathBuf>,
    },
    /// List the shipped presets.
    List,
    /// Render every shipped preset with its own settings into DIR (one PNG each) and write
    /// DIR/README.md, the gallery the project's README shows.
    Gallery {
        /// Output folder.
        #[arg(long, value_name = "DIR", default_value = "docs/gallery")]
        out: std::path::PathBuf,
        /// Image size WxH.
        #[arg(long, value_name = "WxH", value_parser = reference::parse_size, default_value = "480x270")]
        size: (u32, u32),
    },
}

pub fn run(command: Command) -> anyhow::Result<ExitCode> {
    match command {
        Command::Presets {
            action: PresetsAction::Validate { files },
        } => presets_cmd::validate(&files),
        Command::Presets {
            action: PresetsAction::List,
        } => presets_cmd::list(),
        Command::Presets {
            action: PresetsAction::Gallery { out, size },
        } => presets_cmd::gallery(&out, size),
        Command::Info(args) => info::run(&args),
        Command::Learn(args) => learn::run(&args),
        Command::Aerosols(args) => aerosols::run(&args),
        Command::Probe(args) => probe::run(&args),
        Command::Reference(args) => reference::run(&args),
        Command::Render(args) => render::run(&args),
        Command::Timelapse(args) => timelapse::run(&args),
        Command::Compare(args) => compare::run(&args),
        Command::FitWavelengths(args) => fit::run(&args),
        Command::FitGarciaLinan(args) => fit_garcia_linan::run(&args),
        Command::Stress(args) => stress::run(&args),
        Command::Bench { bench } => bench::run(&bench),
    }
}

/// Refuses wavelengths outside the visible range the model's tables cover.
pub fn check_wavelengths(wavelengths_nm: &[f64]) -> anyhow::Result<()> {
    use atmoscope_model::constants::{VISIBLE_MAX_NM, VISIBLE_MIN_NM};
    match wavelengths_nm
        .iter()
        .find(|w| !(**w >= VISIBLE_MIN_NM && **w <= VISIBLE_MAX_NM))
    {
        Some(w) => anyhow::bail!(
            "--wavelengths-nm: {w} nm is outside {VISIBLE_MIN_NM} to {VISIBLE_MAX_NM} nm"
        ),
        None => Ok(()),
    }
}

/// A finite number (NaN and infinities are refused: they would pass every later comparison).
pub fn parse_finite(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(v) => Err(format!("{v} is not a finite number")),
        Err(e) => Err(format!("`{s}` is not a number: {e}")),
    }
}

/// A finite number above zero.
pub fn parse_positive(s: &str) -> Result<f64, String> {
    match parse_finite(s)? {
        v if v > 0.0 => Ok(v),
        v => Err(format!("{v} must be above 0")),
    }
}

/// A real-time model by its registry id (`--method`).
pub fn parse_method(id: &str) -> Result<atmoscope_model::scene::Method, String> {
    use atmoscope_model::methods;
    match methods::by_id(id) {
        Some(m) if m.is_realtime() => Ok(m.method),
        Some(m) => Err(format!(
            "{} is the offline ground truth: use `atmoscope reference` for it (real-time models: {})",
            m.id,
            methods::realtime_ids()
        )),
        None => Err(format!(
            "no model `{id}` (real-time models: {})",
            methods::realtime_ids()
        )),
    }
}

/// Real-time models named on the command line (`--methods`).
#[derive(Debug, Clone, PartialEq)]
pub struct MethodList(pub Vec<atmoscope_model::scene::Method>);

/// A comma-separated list of real-time models, or `all` (`--methods`).
pub fn parse_methods(list: &str) -> Result<MethodList, String> {
    if list == "all" {
        return Ok(MethodList(
            atmoscope_model::methods::realtime()
                .map(|m| m.method)
                .collect(),
        ));
    }
    list.split(',')
        .map(|id| parse_method(id.trim()))
        .collect::<Result<_, _>>()
        .map(MethodList)
}

/// The registry id of a method, for tables and file names.
pub fn method_id(method: atmoscope_model::scene::Method) -> &'static str {
    atmoscope_model::methods::info(method).id
}

/// Refuses an output path whose directory does not exist, before any work starts.
pub fn check_writable(path: &std::path::Path) -> anyhow::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => std::path::Path::new("."),
    };
    if !dir.is_dir() {
        anyhow::bail!(
            "{}: the directory {} does not exist",
            path.display(),
            dir.display()
        );
    }
    Ok(())
}

/// Writes `bytes` to `path` atomically (`atmoscope_model::files::write_atomic`).
pub fn write_atomic(path: &std::path::Path, bytes: &[u8]) -> anyhow::Result<()> {
    use anyhow::Context;
    atmoscope_model::files::write_atomic(path, bytes)
        .with_context(|| format!("cannot write {}", path.display()))
}
