//! `atmoscope compare TEST.exr REFERENCE.exr`: every error metric of `atmoscope_eval::metrics`,
//! and the ΔE2000 and FLIP error maps as PNG heat maps.

use crate::images::{read_exr, write_heat_map};
use anyhow::bail;
use atmoscope_eval::metrics::{DisplaySetup, compare};
use atmoscope_model::scene::ToneMap;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct CompareArgs {
    /// The image under test (linear EXR).
    pub test: PathBuf,
    /// The reference (linear EXR, e.g. from `atmoscope reference`).
    pub reference: PathBuf,
    /// Exposure of the display-referred metrics, EV.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = crate::args::parse_finite)]
    pub exposure_ev: f64,
    /// Write `<stem>-delta-e.png` and `<stem>-flip.png` heat maps into this directory.
    #[arg(long, value_name = "DIR")]
    pub maps: Option<PathBuf>,
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &CompareArgs) -> anyhow::Result<ExitCode> {
    let (test, tw, th) = read_exr(&args.test)?;
    let (reference, rw, rh) = read_exr(&args.reference)?;
    if (tw, th) != (rw, rh) {
        bail!(
            "{} is {tw}x{th} but {} is {rw}x{rh}",
            args.test.display(),
            args.reference.display()
        );
    }
    let setup = DisplaySetup {
        exposure_ev: args.exposure_ev,
        tone_map: ToneMap::Exponential,
        ..DisplaySetup::default()
    };
    let (c, maps) = compare(&test, &reference, tw, th, setup);
    if let Some(dir) = &args.maps {
        std::fs::create_dir_all(dir)?;
        let stem = args
            .test
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "test".into());
        write_heat_map(
            &dir.join(format!("{stem}-delta-e.png")),
            &maps.delta_e2000,
            tw,
            th,
            10.0,
        )?;
        write_heat_map(
            &dir.join(format!("{stem}-flip.png")),
            &maps.ldr_flip,
            tw,
            th,
            1.0,
        )?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&c)?);
    } else {
        println!(
            "RMSE {:.4e} W/m²/sr (relative {:.4})",
            c.rmse, c.relative_rmse
        );
        println!(
            "luminance RMSE {:.4e} cd/m² (relative {:.4}); median pixel {:.4}× the reference's luminance",
            c.luminance_rmse_cd_m2, c.luminance_relative_rmse, c.luminance_ratio
        );
        println!(
            "ΔE2000 mean {:.3}, 95th percentile {:.3}  (display: exposure {} EV, exponential tone map, sRGB)",
            c.delta_e2000_mean, c.delta_e2000_p95, c.display.exposure_ev
        );
        println!(
            "LDR-FLIP mean {:.4}, HDR-FLIP mean {:.4}  ({} pixels per degree)",
            c.ldr_flip_mean, c.hdr_flip_mean, c.display.pixels_per_degree
        );
    }
    Ok(ExitCode::SUCCESS)
}
