//! The sky-radiance probe `atmoscope probe` and `atmoscope bench aod` share: diffuse sky
//! radiance seen from the scene's camera in given directions, by the path tracer, the exact
//! single-scattering integrator or a real-time model's f64 CPU twin, with the direct
//! transmittance to the sun.

use atmoscope_model::camera::{Camera, Projection};
use atmoscope_model::geometry::{Ray, direction_from_angles};
use atmoscope_model::lanes::Lanes;
use atmoscope_model::methods::path_tracer::{LANES, LaneOptics, PathTracer, PathTracerSettings};
use atmoscope_model::methods::rng::Rng;
use atmoscope_model::methods::shared::{Params, sun_disk, viewpoint};
use atmoscope_model::methods::{self, single_scattering};
use atmoscope_model::polarisation::estimate::{StokesEstimate, StokesMean};
use atmoscope_model::polarisation::{self, Stokes};
use atmoscope_model::scene::Method;
use atmoscope_model::{Atmosphere, Scene};
use clap::Args;
use rayon::prelude::*;
use serde::Serialize;

/// What computes the radiance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProbeMethod {
    PathTracer,
    SingleScattering,
    /// The CPU twin of a real-time model.
    Model(Method),
}

impl ProbeMethod {
    fn id(self) -> &'static str {
        match self {
            ProbeMethod::PathTracer => "path-tracer",
            ProbeMethod::SingleScattering => "single-scattering",
            ProbeMethod::Model(m) => crate::args::method_id(m),
        }
    }
}

fn parse_probe_method(s: &str) -> Result<ProbeMethod, String> {
    match s {
        "path-tracer" => Ok(ProbeMethod::PathTracer),
        "single-scattering" => Ok(ProbeMethod::SingleScattering),
        id => crate::args::parse_method(id)
            .map(ProbeMethod::Model)
            .map_err(|_| {
                format!(
                    "no method `{id}` (path-tracer, single-scattering, {})",
                    methods::realtime_ids()
                )
            }),
    }
}

/// What to probe: directions, wavelengths and method.
#[derive(Args, Debug, Clone)]
pub struct ProbeRequest {
    /// View zenith angles, degrees (0 = straight up, 180 = straight down).
    #[arg(
        long,
        value_delimiter = ',',
        required = true,
        value_name = "LIST",
        value_parser = crate::args::parse_finite,
        allow_hyphen_values = true
    )]
    pub view_zenith_deg: Vec<f64>,
    /// View azimuths measured from the sun's azimuth, degrees (0 = towards the sun).
    #[arg(
        long,
        value_delimiter = ',',
        required = true,
        value_name = "LIST",
        value_parser = crate::args::parse_finite,
        allow_hyphen_values = true
    )]
    pub view_azimuth_deg: Vec<f64>,
    /// Wavelengths, nm (360 to 830).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "440,550,680",
        value_name = "LIST"
    )]
    pub wavelengths_nm: Vec<f64>,
    /// path-tracer, single-scattering, or a real-time model's registry id (its f64 CPU twin;
    /// an unknown id is answered with the list).
    #[arg(long, value_parser = parse_probe_method, default_value = "path-tracer")]
    pub method: ProbeMethod,
    /// Highest scattering order (path tracer; 1 = single scattering). Default: all orders.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub max_order: Option<u32>,
    /// Paths per direction and wavelength batch (path tracer).
    #[arg(long, default_value_t = 4096, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub spp: u64,
    /// Random seed (path tracer).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Give each sample's Stokes vector (I, Q, U, V) in the meridian frame, its degree and
    /// angle of polarisation: with --method single-scattering, the exact polarisation of
    /// sunlight scattered once; with --method path-tracer, the vector path tracer's, with
    /// standard errors (air and Mie aerosols polarise; Henyey–Greenstein and Cornette–Shanks
    /// aerosols make no polarisation; the ground depolarises).
    #[arg(long)]
    pub stokes: bool,
}

#[derive(Serialize, Debug)]
pub struct Sample {
    pub view_zenith_deg: f64,
    pub view_azimuth_deg: f64,
    pub wavelength_nm: f64,
    /// W·m⁻²·sr⁻¹·nm⁻¹ for the scene's solar spectrum.
    pub radiance: f64,
    /// Radiance over the extraterrestrial solar irradiance at that wavelength, sr⁻¹.
    pub radiance_per_irradiance: f64,
    /// Monte Carlo standard error of `radiance_per_irradiance` (0 for deterministic methods).
    pub std_error: f64,
    /// With `--stokes`: (I, Q, U, V) in the unit of `radiance`, Q and U in the meridian frame
    /// (`model::polarisation`): Q > 0 vibrating vertically, the angle from up towards right.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stokes: Option<[f64; 4]>,
    /// With `--stokes`: √(Q² + U² + V²)/I, 0–1.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub degree_of_polarization: Option<f64>,
    /// With `--stokes`: ½·atan2(U, Q), degrees, −90–90.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angle_of_polarization_deg: Option<f64>,
    /// With `--stokes` and the path tracer: standard errors of `stokes`, of the degree (0–1)
    /// and of the angle (degrees).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stokes_std_error: Option<[f64; 4]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub degree_of_polarization_std_error: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angle_of_polarization_std_error_deg: Option<f64>,
}

#[derive(Serialize, Debug)]
pub struct Transmittance {
    pub wavelength_nm: f64,
    pub value: f64,
}

#[derive(Serialize, Debug)]
pub struct Probe {
    pub samples: Vec<Sample>,
    pub direct_transmittance: Vec<Transmittance>,
    pub method: String,
    pub spp: u64,
    /// The turbidity a fit took from the scene (Preetham, Hosek–Wilkie, the CIE sky's zenith
    /// luminance), 1–10; absent for the other methods.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turbidity: Option<f64>,
}

/// Runs the probe.
pub fn probe(scene: &Scene, args: &ProbeRequest) -> Probe {
    let atm = Atmosphere::for_scene(&scene);
    let sun_angles = scene.sun.angles();
    let sun = direction_from_angles(sun_angles.elevation_deg, sun_angles.azimuth_deg);
    let camera = Camera::new(&scene.camera, atm.bottom_radius_m, Projection::Perspective);
    let directions: Vec<(f64, f64)> = args
        .view_zenith_deg
        .iter()
        .flat_map(|&z| args.view_azimuth_deg.iter().map(move |&a| (z, a)))
        .collect();
    let settings = PathTracerSettings {
        max_order: args.max_order,
        ..PathTracerSettings::default()
    };
    let tracer = PathTracer::new(&atm, sun, settings);
    let model = match args.method {
        ProbeMethod::Model(m) => methods::info(m).build.map(|build| {
            let p = Params::at_wavelengths(&atm, &args.wavelengths_nm, scene.render.quality)
                .with_render(&scene.render);
            build(&p, viewpoint(scene, &camera))
        }),
        _ => None,
    };
    let batches: Vec<Vec<f64>> = args
        .wavelengths_nm
        .chunks(LANES)
        .map(<[f64]>::to_vec)
        .collect();
    let jobs: Vec<(usize, usize)> = (0..directions.len())
        .flat_map(|d| (0..batches.len()).map(move |b| (d, b)))
        .collect();
    let results: Vec<Vec<Sample>> = jobs
        .par_iter()
        .map(|&(d, b)| {
            let (zenith, azimuth) = directions[d];
            let dir = camera.local_to_world(direction_from_angles(
                90.0 - zenith,
                sun_angles.azimuth_deg + azimuth,
            ));
            let ray = Ray::new(camera.position, dir);
            let batch = &batches[b];
            let lanes_nm = Lanes::from_fn(|i| batch[i.min(batch.len() - 1)]);
            let mut traced_stokes = None;
            let (mean, se) = match args.method {
                ProbeMethod::Model(_) => (
                    model.as_ref().map_or([f64::NAN; LANES], |m| {
                        let h = scene.camera.altitude_m;
                        let sky = m.radiance(b, (camera.position, h), dir, sun);
                        let mu_s = sun.dot(camera.position.normalize());
                        let disk = m.sun(b, h, mu_s, sun_disk(dir, sun, &lanes_nm));
                        (sky + disk).0
                    }),
                    [0.0; LANES],
                ),
                ProbeMethod::SingleScattering => (
                    lanes_nm
                        .0
                        .map(|w| single_scattering::radiance(&atm, &ray, sun, w)),
                    [0.0; LANES],
                ),
                ProbeMethod::PathTracer if args.stokes => {
                    let lanes = LaneOptics::new(&atm, lanes_nm);
                    let mut sums = [StokesMean::default(); LANES];
                    let (up, _) = polarisation::meridian_frame(dir, camera.position.normalize());
                    for k in 0..args.spp {
                        let mut rng = Rng::new(args.seed, (d * 1000 + b) as u64, k);
                        let s = tracer.radiance_stokes(&ray, up, &lanes, &mut rng);
                        sums.iter_mut().zip(s).for_each(|(m, s)| m.add(s));
                    }
                    let estimates = sums.map(|m| m.estimate());
                    traced_stokes = Some(estimates);
                    (
                        estimates.map(|e| e.mean.i),
                        estimates.map(|e| e.std_error[0]),
                    )
                }
                ProbeMethod::PathTracer => {
                    let lanes = LaneOptics::new(&atm, lanes_nm);
                    let (mut sum, mut sum2) = ([0.0; LANES], [0.0; LANES]);
                    for k in 0..args.spp {
                        let mut rng = Rng::new(args.seed, (d * 1000 + b) as u64, k);
                        let l = tracer.radiance(&ray, &lanes, &mut rng);
                        for i in 0..LANES {
                            sum[i] += l[i];
                            sum2[i] += l[i] * l[i];
                        }
                    }
                    let n = args.spp.max(2) as f64;
                    let mean = sum.map(|s| s / n);
                    let se = std::array::from_fn(|i| {
                        ((sum2[i] / n - mean[i] * mean[i]).max(0.0) / (n - 1.0)).sqrt()
                    });
                    (mean, se)
                }
            };
            batch
                .iter()
                .enumerate()
                .map(|(i, &w)| {
                    let e = atm.solar_irradiance(w, None);
                    let traced = traced_stokes.map(|e: [StokesEstimate; LANES]| e[i]);
                    let stokes = traced.map(|e| e.mean).or_else(|| {
                        (args.stokes && args.method == ProbeMethod::SingleScattering)
                            .then(|| single_scattering::stokes(&atm, &ray, sun, w))
                    });
                    Sample {
                        view_zenith_deg: zenith,
                        view_azimuth_deg: azimuth,
                        wavelength_nm: w,
                        radiance: mean[i],
                        radiance_per_irradiance: mean[i] / e,
                        std_error: se[i] / e,
                        stokes: stokes.map(Stokes::to_array),
                        degree_of_polarization: stokes.map(|s| s.degree_of_polarization()),
                        angle_of_polarization_deg: stokes.map(|s| s.angle_of_polarization_deg()),
                        stokes_std_error: traced.map(|e| e.std_error),
                        degree_of_polarization_std_error: traced.map(|e| e.degree_std_error),
                        angle_of_polarization_std_error_deg: traced.map(|e| e.angle_std_error_deg),
                    }
                })
                .collect()
        })
        .collect();
    let direct_transmittance = args
        .wavelengths_nm
        .iter()
        .map(|&w| Transmittance {
            wavelength_nm: w,
            value: atm.transmittance_to_sun(&atm.optics(w), camera.position, sun),
        })
        .collect();
    Probe {
        samples: results.into_iter().flatten().collect(),
        direct_transmittance,
        method: args.method.id().into(),
        turbidity: model.as_ref().and_then(|m| m.turbidity()),
        spp: if args.method == ProbeMethod::PathTracer {
            args.spp
        } else {
            0
        },
    }
}
