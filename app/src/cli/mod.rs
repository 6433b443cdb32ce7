//! Command-line subcommands. Each loads a scene the same way (`SceneArgs`), works headless and
//! reports bad input as an error naming the file, field and allowed range.

mod aerosols;
pub mod bench;
pub mod common;
mod compare;
mod export_engine;
mod fit;
mod info;
mod learn;
mod presets;
mod probe;
pub mod progress;
mod reference;
mod render;
pub mod sky_probe;
mod stress;
mod timelapse;

pub use crate::scene_args::SceneArgs;

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
    FitWavelengths(fit::wavelengths::FitArgs),
    /// Refit García Liñán's multiple-scattering constants against path-traced references of
    /// the view suite; reports the error before and after.
    FitGarciaLinan(fit::garcia_linan::FitGarciaLinanArgs),
    /// The scene's atmosphere for bevy, Unreal or Blender: the snippet to paste, and the
    /// ΔE2000 over the view suite of what the engine's parameters keep of the scene.
    ExportEngine(export_engine::ExportEngineArgs),
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
        #[arg(long, value_name = "WxH", value_parser = crate::args::parse_size, default_value = "480x270")]
        size: (u32, u32),
    },
}

pub fn run(command: Command) -> anyhow::Result<ExitCode> {
    match command {
        Command::Presets {
            action: PresetsAction::Validate { files },
        } => presets::validate(&files),
        Command::Presets {
            action: PresetsAction::List,
        } => presets::list(),
        Command::Presets {
            action: PresetsAction::Gallery { out, size },
        } => presets::gallery(&out, size),
        Command::Info(args) => info::run(&args),
        Command::Learn(args) => learn::run(&args),
        Command::Aerosols(args) => aerosols::run(&args),
        Command::Probe(args) => probe::run(&args),
        Command::Reference(args) => reference::run(&args),
        Command::Render(args) => render::run(&args),
        Command::Timelapse(args) => timelapse::run(&args),
        Command::Compare(args) => compare::run(&args),
        Command::FitWavelengths(args) => fit::wavelengths::run(&args),
        Command::FitGarciaLinan(args) => fit::garcia_linan::run(&args),
        Command::ExportEngine(args) => export_engine::run(&args),
        Command::Stress(args) => stress::run(&args),
        Command::Bench { bench } => bench::run(&bench),
    }
}
