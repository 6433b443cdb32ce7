//! `atmoscope info`: the scene summary of `crate::summary` as a table or JSON.

use crate::scene_args::SceneArgs;
use crate::summary::{Info, compute};
use clap::Args;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct InfoArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Wavelengths, nm (comma-separated, 360 to 830).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "400,450,500,550,600,650,700",
        value_name = "LIST"
    )]
    pub wavelengths_nm: Vec<f64>,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &InfoArgs) -> anyhow::Result<ExitCode> {
    crate::args::check_wavelengths(&args.wavelengths_nm)?;
    let scene = args.scene.scene()?;
    let info = compute(&scene, &args.wavelengths_nm);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&info)?);
    } else {
        print!("{}", table(&info));
    }
    Ok(ExitCode::SUCCESS)
}

fn table(i: &Info) -> String {
    let mut s = format!(
        "scene: {}\ncamera altitude: {} m   sun: elevation {:.2}°, azimuth {:.2}°\n\
         aerosol: {} (AOD 550 nm {:.3})   ozone: {:.1} DU ({})   air: {}\n\n",
        i.scene,
        i.camera_altitude_m,
        i.sun_elevation_deg,
        i.sun_azimuth_deg,
        i.aerosol_type,
        i.aod550,
        i.ozone_column_du,
        i.ozone_profile,
        i.air_profile
    );
    s.push_str(
        "  λ (nm)   τ Rayleigh    τ ozone   τ aerosol    τ total   aer. SSA   aer. g   T sun   T horiz.\n",
    );
    for r in &i.wavelengths {
        let d = &r.optical_depth;
        s.push_str(&format!(
            "  {:6.1}   {:10.5}  {:9.5}   {:9.5}  {:9.5}   {:8.4}  {:7.4}  {:6.4}  {:9.4}\n",
            r.wavelength_nm,
            d.rayleigh,
            d.ozone,
            d.aerosol,
            d.total,
            r.aerosol_ssa,
            r.aerosol_g,
            r.direct_transmittance,
            r.horizontal_transmittance
        ));
    }
    s.push_str("τ: vertical optical depth from the camera to space; T sun: direct transmittance, top of atmosphere → camera; T horiz.: along the horizontal, camera → space.\n");
    s
}
