//! `atmoscope bench`: run-time and accuracy benchmarks (never timed tests), one module each.

mod accuracy;
mod aod;
mod clear_sky;
mod clear_sky_charts;
mod gpu;
mod leenman;
mod measured;
mod measured_charts;
mod methods;
mod path_tracer;
mod polarisation;
mod transmittance;

use clap::Subcommand;
use std::process::ExitCode;

#[derive(Subcommand, Debug)]
pub enum Bench {
    /// Path tracer speed and time to a noise level on views of the suite.
    PathTracer(path_tracer::PathTracerBench),
    /// GPU time of each pass of the real-time engine and of whole frames, per wavelength set.
    Gpu(gpu::GpuBench),
    /// ΔE2000 of the real-time engine against path-traced references of the view suite.
    Accuracy(accuracy::AccuracyBench),
    /// Each model's sky radiance against the path tracer as the aerosol optical depth grows:
    /// the measurement behind each model's stated AOD range.
    Aod(aod::AodBench),
    /// Bruneton's (2016) evaluation of clear-sky models replayed on the path tracer: over the
    /// suite's sky domes (sun 90° to −12°), each model's zenith luminance, horizontal sky
    /// illuminance, zenith spectrum and dome error map; CSV, charts and a summary of which
    /// model is closest where.
    ClearSky(clear_sky::ClearSkyBench),
    /// Every model × wavelength set × quality over views of the suite: precompute and frame
    /// time, table memory and error against path-traced references; results.csv, a summary
    /// and the Pareto chart of time against error.
    Methods(methods::MethodsBench),
    /// The real-time models' degree of polarisation against the path tracer's vector mode,
    /// per view of the suite (mean and 95th percentile of the absolute difference), and the
    /// vector mode's cost against the scalar one.
    Polarisation(polarisation::PolarisationBench),
    /// Optical depth to the top of the atmosphere by the midpoint rule, the trapezoid rule and
    /// the transmittance table against adaptive quadrature, with the CPU time per evaluation.
    Transmittance(transmittance::TransmittanceBench),
    /// Leenman's (2025) comparison replayed: his Earth, views and metrics (his appendices
    /// A–D), every model he compares and ours; leenman.csv and leenman.md with his value
    /// beside ours.
    Leenman(leenman::LeenmanBench),
    /// Every model and the path tracer against measured spectral sky radiance (Kider et al.
    /// 2014 or any folder in its format): the sun placed from time and place, the aerosol from
    /// AERONET, the pyranometer or a cross-validated fit; per model the median and 95th
    /// percentile of the radiance error over 360–720 nm, luminance, chromaticity, zenith
    /// luminance and global irradiance; measured.md, measured.json, a CSV per scan, charts.
    Measured(measured::MeasuredBench),
    /// A scripted session of the explorer in its window: a fresh start with each model, every
    /// tab, the preset list and a preset loaded; the longest and 99th-percentile UI frame
    /// interval per step (gui.csv, gui.md). Needs a display (Xvfb where there is none).
    Gui(crate::gui_bench::GuiBenchArgs),
}

pub fn run(bench: &Bench) -> anyhow::Result<ExitCode> {
    match bench {
        Bench::PathTracer(args) => path_tracer::run(args),
        Bench::Gpu(args) => gpu::run(args),
        Bench::Accuracy(args) => accuracy::run(args),
        Bench::Aod(args) => aod::run(args),
        Bench::Methods(args) => methods::run(args),
        Bench::ClearSky(args) => clear_sky::run(args),
        Bench::Leenman(args) => leenman::run(args),
        Bench::Transmittance(args) => transmittance::run(args),
        Bench::Polarisation(args) => polarisation::run(args),
        Bench::Measured(args) => measured::run(args),
        // The session plays in the explorer's window, which `atmoscope::run` opens for it.
        Bench::Gui(_) => anyhow::bail!("`bench gui` runs from the atmoscope command"),
    }
}
