//! `atmoscope probe`: sky radiance seen from the scene's camera in given directions (zenith
//! angle from straight up, azimuth from the sun's), by the path tracer, the exact
//! single-scattering integrator or the f64 CPU twin of any real-time model of the registry,
//! plus the direct transmittance to the sun.
use super::sky_probe::{ProbeMethod, ProbeRequest, probe};
use crate::scene_args::SceneArgs;
use anyhow::bail;
use atmoscope_model::methods::{self};
use clap::Args;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct ProbeArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub request: ProbeRequest,
    #[arg(long)]
    pub json: bool,
}

pub fn run(probe_args: &ProbeArgs) -> anyhow::Result<ExitCode> {
    let args = &probe_args.request;
    crate::args::check_wavelengths(&args.wavelengths_nm)?;
    if let Some(z) = args
        .view_zenith_deg
        .iter()
        .find(|z| !(**z >= 0.0 && **z <= 180.0))
    {
        bail!("--view-zenith-deg: {z}° is outside 0 to 180°");
    }
    if args.spp < 2 {
        bail!("--spp: at least 2 paths are needed for a standard error");
    }
    if args.stokes && matches!(args.method, ProbeMethod::Model(_)) {
        bail!(
            "--stokes: the Stokes vector comes from the vector path tracer or the exact single-scattering integrator; add --method path-tracer or --method single-scattering"
        );
    }
    let scene = probe_args.scene.scene()?;
    if let ProbeMethod::Model(m) = args.method {
        let mut drawn = scene.clone();
        drawn.render.method = m;
        if let Some(why) = methods::info(m).cannot_draw(&drawn) {
            bail!("{why}");
        }
    }
    let p = probe(&scene, args);
    if probe_args.json {
        println!("{}", serde_json::to_string_pretty(&p)?);
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "scene: {}   method: {}{}",
        scene.name,
        p.method,
        if p.spp > 0 {
            format!(" ({} paths each)", p.spp)
        } else {
            String::new()
        }
    );
    if let Some(t) = p.turbidity {
        println!("turbidity: {t:.3}");
    }
    let polarised = match (args.stokes, p.spp > 0) {
        (true, true) => "   DoP ± s.e.        AoP° ± s.e.",
        (true, false) => "   DoP    AoP°",
        _ => "",
    };
    println!(
        " zenith°  azimuth°   λ (nm)   radiance (W/m²/sr/nm)   L/E (1/sr)    std. error{polarised}"
    );
    for s in &p.samples {
        let polarised = match (s.degree_of_polarization, s.angle_of_polarization_deg) {
            (Some(d), Some(a)) => match (
                s.degree_of_polarization_std_error,
                s.angle_of_polarization_std_error_deg,
            ) {
                (Some(sd), Some(sa)) => format!("  {d:5.3} ± {sd:5.3}  {a:6.1} ± {sa:4.1}"),
                _ => format!("  {d:5.3}  {a:6.1}"),
            },
            _ => String::new(),
        };
        println!(
            "{:8.2}  {:8.2}  {:7.1}   {:>20.6e}   {:>10.6}    {:>10.2e}{polarised}",
            s.view_zenith_deg,
            s.view_azimuth_deg,
            s.wavelength_nm,
            s.radiance,
            s.radiance_per_irradiance,
            s.std_error
        );
    }
    println!("direct transmittance to the sun:");
    for t in &p.direct_transmittance {
        println!("  {:7.1} nm  {:.6}", t.wavelength_nm, t.value);
    }
    Ok(ExitCode::SUCCESS)
}
