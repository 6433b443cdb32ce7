//! `atmoscope aerosols`: the aerosol types with the optics our Mie computation gives them.

use atmoscope_model::aerosol::{self, AerosolType};
use clap::Args;
use serde::Serialize;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct AerosolsArgs {
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Row {
    name: &'static str,
    label: &'static str,
    ssa_550: f64,
    g_550: f64,
    angstrom_440_870: f64,
    default_aod550: f64,
    scale_height_km: f64,
    mixture: &'static str,
}

pub fn run(args: &AerosolsArgs) -> anyhow::Result<ExitCode> {
    let rows: Vec<Row> = AerosolType::MIXTURES
        .iter()
        .filter_map(|&t| {
            let (info, optics) = (t.info()?, aerosol::type_optics(t)?);
            let h = t.mixing_layer_scale_height_m().unwrap_or(0.0);
            Some(Row {
                name: t.cli_name(),
                label: info.label,
                ssa_550: optics.ssa_at(550.0),
                g_550: optics.g_at(550.0),
                angstrom_440_870: optics.angstrom_exponent(),
                default_aod550: info.default_aod550,
                scale_height_km: h / 1000.0,
                mixture: info.note,
            })
        })
        .collect();
    if args.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
        return Ok(ExitCode::SUCCESS);
    }
    println!("type                 SSA(550)  g(550)  Ångström  AOD550  H (km)    mixture");
    for r in rows {
        let h = if r.scale_height_km > 0.0 {
            format!("{:8.2}", r.scale_height_km)
        } else {
            "upper only".into()
        };
        println!(
            "{:20} {:8.4}  {:6.4}  {:8.3}  {:6.3}  {h}  {}",
            r.name, r.ssa_550, r.g_550, r.angstrom_440_870, r.default_aod550, r.mixture
        );
    }
    println!(
        "SSA: single-scattering albedo; g: asymmetry; Ångström exponent between 440 and 870 nm; AOD550: the type's typical optical depth."
    );
    Ok(ExitCode::SUCCESS)
}
