//! The Inspector: what one pixel is made of, and plots of the atmosphere itself.
//!
//! A click on a view traces the pixel's ray off the UI thread: its spectral radiance by the path
//! tracer's vector mode (all orders, with the standard error) and the polarisation of its light
//! (the Stokes vector weighted by ȳ like the luminance, its degree and angle, in the ray's
//! meridian frame), the exact single-scattering integral split into Rayleigh, aerosol and
//! ground (Bruneton's and Hillaire's decomposition of the sky, computed here by quadrature) with
//! its own degree of polarisation, multiple scattering as the rest, and the transmittance to
//! the sun. The pixel's XYZ, sRGB and luminance are those of the real-time render on screen.

use super::jobs::{Job, Progress};
use atmoscope_model::atmosphere::Atmosphere;
use atmoscope_model::colour::{cie1931, linear_srgb_to_xyz};
use atmoscope_model::constants::MAX_LUMINOUS_EFFICACY_LM_PER_W;
use atmoscope_model::display::{display_balanced, to_u8};
use atmoscope_model::geometry::{Ray, direction_from_angles};
use atmoscope_model::lanes::Lanes;
use atmoscope_model::methods::path_tracer::{LANES, LaneOptics, PathTracer, PathTracerSettings};
use atmoscope_model::methods::rng::Rng;
use atmoscope_model::methods::single_scattering::{self, Parts};
use atmoscope_model::polarisation::estimate::{StokesEstimate, StokesMean};
use atmoscope_model::polarisation::{Stokes, meridian_frame};
use atmoscope_model::scene::AtmosphereSettings;
use atmoscope_model::{Scene, phase};
use eframe::egui;
use egui_plot::{Legend, Line, Plot, PlotPoints};

/// Wavelengths of the pixel's spectrum, nm.
pub const INSPECT_NM: std::ops::RangeInclusive<u32> = 380..=780;
const INSPECT_STEP_NM: usize = 20;
/// Paths per wavelength batch for the pixel's spectrum.
pub const INSPECT_PATHS: u64 = 2048;

/// A pixel to analyse.
#[derive(Debug, Clone)]
pub struct Probe {
    pub label: String,
    pub scene: Scene,
    pub ray: Ray,
    /// Linear sRGB radiance of the pixel as rendered, W·m⁻²·sr⁻¹ (Y = ∫ȳL dλ).
    pub displayed: Option<[f64; 3]>,
}

/// What a pixel is made of.
#[derive(Debug, Clone)]
pub struct Analysis {
    pub probe: Probe,
    pub wavelengths_nm: Vec<f64>,
    /// Path-traced radiance, all orders (the vector mode's I), W·m⁻²·sr⁻¹·nm⁻¹, and its
    /// standard error.
    pub radiance: Vec<f64>,
    pub std_error: Vec<f64>,
    /// The path-traced Stokes vector weighted by ȳ like the luminance, W·m⁻²·sr⁻¹, in the
    /// ray's meridian frame, with its standard errors.
    pub stokes: StokesEstimate,
    /// The degree of polarisation of the single-scattered light alone, weighted by ȳ.
    pub single_degree: f64,
    pub single: Vec<Parts>,
    /// Direct transmittance from the camera to the sun.
    pub sun_transmittance: Vec<f64>,
    /// Shares of the luminance: Rayleigh, aerosol and ground single scattering, and multiple
    /// scattering (the path-traced total less the single-scattered part).
    pub shares: [f64; 4],
}

pub const SHARE_NAMES: [&str; 4] = [
    "Rayleigh (single)",
    "aerosol (single)",
    "ground (single)",
    "multiple scattering",
];

/// Traces the probe's ray. Returns None when cancelled.
pub fn analyse(probe: Probe, progress: &Progress) -> Option<Analysis> {
    let atm = Atmosphere::for_scene(&probe.scene);
    let angles = probe.scene.sun.angles();
    let sun = direction_from_angles(angles.elevation_deg, angles.azimuth_deg);
    let wavelengths_nm: Vec<f64> = INSPECT_NM.step_by(INSPECT_STEP_NM).map(f64::from).collect();
    let tracer = PathTracer::new(&atm, sun, PathTracerSettings::default());
    let (mut radiance, mut std_error, mut single) = (Vec::new(), Vec::new(), Vec::new());
    let (up, _) = meridian_frame(probe.ray.direction, probe.ray.origin.normalize());
    let y_bar = &cie1931().y;
    // Per path, the ȳ-weighted sum of its lanes' Stokes vectors (a rectangle rule over the
    // wavelengths, as the luminance below weighs them); the paths of one index across the
    // batches make one sample.
    let mut photometric = vec![Stokes::default(); INSPECT_PATHS as usize];
    let mut single_polarised = Stokes::default();
    let batches: Vec<&[f64]> = wavelengths_nm.chunks(LANES).collect();
    for (b, batch) in batches.iter().enumerate() {
        if progress.cancelled() {
            return None;
        }
        let lanes_nm = Lanes::from_fn(|i| batch[i.min(batch.len() - 1)]);
        let lanes = LaneOptics::new(&atm, lanes_nm);
        let (mut sum, mut sum2) = ([0.0; LANES], [0.0; LANES]);
        for (k, sample) in photometric.iter_mut().enumerate() {
            let mut rng = Rng::new(1, b as u64, k as u64);
            let s = tracer.radiance_stokes(&probe.ray, up, &lanes, &mut rng);
            for i in 0..LANES {
                sum[i] += s[i].i;
                sum2[i] += s[i].i * s[i].i;
            }
            for (i, &w) in batch.iter().enumerate() {
                *sample = sample.plus(s[i].scaled(y_bar.sample(w)));
            }
        }
        let n = INSPECT_PATHS as f64;
        for (i, &w) in batch.iter().enumerate() {
            let mean = sum[i] / n;
            radiance.push(mean);
            std_error.push(((sum2[i] / n - mean * mean).max(0.0) / (n - 1.0)).sqrt());
            single.push(single_scattering::radiance_parts(&atm, &probe.ray, sun, w));
            let s = single_scattering::stokes(&atm, &probe.ray, sun, w);
            single_polarised = single_polarised.plus(s.scaled(y_bar.sample(w)));
        }
        progress.set((b + 1) as f32 / batches.len() as f32);
    }
    let mut stokes = StokesMean::default();
    photometric.into_iter().for_each(|s| stokes.add(s));
    let sun_transmittance = wavelengths_nm
        .iter()
        .map(|&w| atm.transmittance_to_sun(&atm.optics(w), probe.ray.origin, sun))
        .collect();
    let weigh = |f: &dyn Fn(usize) -> f64| -> f64 {
        (0..wavelengths_nm.len())
            .map(|i| y_bar.sample(wavelengths_nm[i]) * f(i))
            .sum()
    };
    let total = weigh(&|i| radiance[i]);
    let parts = [
        weigh(&|i| single[i].rayleigh),
        weigh(&|i| single[i].aerosol),
        weigh(&|i| single[i].ground),
    ];
    let multiple = (total - parts.iter().sum::<f64>()).max(0.0);
    let sum = parts.iter().sum::<f64>() + multiple;
    let shares = if sum > 0.0 {
        [parts[0], parts[1], parts[2], multiple].map(|p| p / sum)
    } else {
        [0.0; 4]
    };
    Some(Analysis {
        probe,
        wavelengths_nm,
        radiance,
        std_error,
        single,
        stokes: stokes.estimate(),
        single_degree: single_polarised.degree_of_polarization(),
        sun_transmittance,
        shares,
    })
}

/// Curves of the atmosphere, recomputed when its settings change.
struct AtmospherePlots {
    settings: AtmosphereSettings,
    /// (scattering angle °, log10 phase) for Rayleigh and aerosol at 550 nm.
    phase: [Vec<[f64; 2]>; 2],
    /// (km, log10 m⁻¹) of Rayleigh, ozone and aerosol extinction at 550 nm.
    extinction: [Vec<[f64; 2]>; 3],
    /// (nm, vertical optical depth from the ground) of Rayleigh, ozone, aerosol.
    optical_depth: [Vec<[f64; 2]>; 3],
}

impl AtmospherePlots {
    fn new(settings: &AtmosphereSettings) -> AtmospherePlots {
        let atm = Atmosphere::new(settings);
        let o = atm.optics(550.0);
        let angles = (0..=180).map(f64::from);
        let phase = [
            angles
                .clone()
                .map(|a| {
                    [
                        a,
                        phase::rayleigh(a.to_radians().cos(), o.rayleigh_depolarisation).log10(),
                    ]
                })
                .collect(),
            angles
                .map(|a| {
                    let nu = a.to_radians().cos();
                    let p = atm.aerosol_phase(&o, nu);
                    [a, p.log10()]
                })
                .collect(),
        ];
        let top_km = settings.top_km;
        let heights: Vec<f64> = (0..=200).map(|i| top_km * f64::from(i) / 200.0).collect();
        let coefficient = |f: &dyn Fn(&atmoscope_model::atmosphere::Coefficients) -> f64| {
            heights
                .iter()
                .filter_map(|&km| {
                    let v = f(&atm.coefficients(&o, km * 1000.0));
                    (v > 0.0).then(|| [km, v.log10()])
                })
                .collect()
        };
        let extinction = [
            coefficient(&|c| c.rayleigh_scattering),
            coefficient(&|c| c.ozone_absorption),
            coefficient(&|c| c.aerosol_scattering + c.aerosol_absorption),
        ];
        let depths: Vec<(f64, _)> = (360..=830)
            .step_by(10)
            .map(|w| {
                let w = f64::from(w);
                (w, atm.vertical_optical_depth(&atm.optics(w), 0.0))
            })
            .collect();
        let optical_depth = [
            depths.iter().map(|(w, d)| [*w, d.rayleigh]).collect(),
            depths.iter().map(|(w, d)| [*w, d.ozone]).collect(),
            depths.iter().map(|(w, d)| [*w, d.aerosol]).collect(),
        ];
        AtmospherePlots {
            settings: settings.clone(),
            phase,
            extinction,
            optical_depth,
        }
    }
}

#[derive(Default)]
pub struct Inspector {
    job: Option<Job<Option<Analysis>>>,
    pub result: Option<Analysis>,
    plots: Option<AtmospherePlots>,
}

impl Inspector {
    /// Starts analysing `probe`, cancelling any analysis still running.
    pub fn inspect(&mut self, ctx: &egui::Context, probe: Probe) {
        if let Some(job) = &self.job {
            job.cancel();
        }
        let label = format!("tracing {}", probe.label);
        self.job = Some(Job::spawn(label, ctx, move |p| analyse(probe, p)));
    }

    /// Cancels any analysis and forgets the last: the scene it was made for is gone.
    pub fn clear(&mut self) {
        if let Some(job) = self.job.take() {
            job.cancel();
        }
        self.result = None;
    }

    pub fn job(&self) -> Option<&Job<Option<Analysis>>> {
        self.job.as_ref().filter(|j| j.is_running())
    }

    /// Collects a finished analysis; an error message if the worker failed.
    pub fn poll(&mut self) -> Option<String> {
        let job = self.job.as_mut()?;
        match job.take()? {
            Ok(Some(a)) => self.result = Some(a),
            Ok(None) => {}
            Err(e) => return Some(e),
        }
        self.job = None;
        None
    }

    pub fn show(&mut self, ui: &mut egui::Ui, scene: &Scene) {
        ui.heading("Inspector");
        egui::CollapsingHeader::new("Pixel")
            .default_open(true)
            .show(ui, |ui| self.pixel(ui));
        egui::CollapsingHeader::new("Atmosphere")
            .default_open(true)
            .show(ui, |ui| self.atmosphere(ui, scene));
    }

    fn pixel(&self, ui: &mut egui::Ui) {
        if let Some(job) = self.job() {
            job.show(ui);
        }
        let Some(a) = &self.result else {
            ui.label(
                "Click a pixel of the Sky, Fisheye, Luminance or Polarisation view to see what it is made of.",
            );
            return;
        };
        ui.label(&a.probe.label);
        if let Some(rgb) = a.probe.displayed {
            let xyz = linear_srgb_to_xyz(rgb);
            let d = &a.probe.scene.display;
            let balance = atmoscope_model::white_balance::matrix(&a.probe.scene);
            let shown = display_balanced(rgb, &balance, d.exposure_ev, d.tone_map).map(to_u8);
            ui.label(format!(
                "as rendered: XYZ ({:.4}, {:.4}, {:.4}) W/(m² sr) · luminance {:.4e} cd/m²",
                xyz.x,
                xyz.y,
                xyz.z,
                MAX_LUMINOUS_EFFICACY_LM_PER_W * xyz.y
            ))
            .on_hover_text("CIE 1931 tristimulus values of the real-time render's pixel; luminance = 683 lm/W · Y.");
            ui.label(format!(
                "linear sRGB ({:.4}, {:.4}, {:.4}) · on screen sRGB ({}, {}, {})",
                rgb[0], rgb[1], rgb[2], shown[0], shown[1], shown[2]
            ))
            .on_hover_text("Linear sRGB radiance, then the 8-bit sRGB value after the scene's exposure and tone map.");
        }
        let n = a.wavelengths_nm.len();
        let series = |f: &dyn Fn(usize) -> f64| -> Vec<[f64; 2]> {
            (0..n).map(|i| [a.wavelengths_nm[i], f(i)]).collect()
        };
        curves(
            ui,
            "pixel spectrum",
            ["wavelength (nm)", "W/(m² sr nm)"],
            &[
                ("all orders (path traced)", series(&|i| a.radiance[i])),
                (
                    "+ 1 standard error",
                    series(&|i| a.radiance[i] + a.std_error[i]),
                ),
                ("single: Rayleigh", series(&|i| a.single[i].rayleigh)),
                ("single: aerosol", series(&|i| a.single[i].aerosol)),
                ("single: ground", series(&|i| a.single[i].ground)),
            ],
            &format!(
                "Spectral radiance of the pixel's ray: {INSPECT_PATHS} paths per batch of four wavelengths, plus the exact single-scattering parts."
            ),
        );
        ui.label("Share of the luminance:")
            .on_hover_text("Each constituent's single scattering, integrated against the eye's response ȳ(λ); multiple scattering is the path-traced total less all single scattering.");
        for (name, share) in SHARE_NAMES.iter().zip(a.shares) {
            ui.add(
                egui::ProgressBar::new(share as f32)
                    .text(format!("{name}: {:.1} %", 100.0 * share)),
            );
        }
        let st = &a.stokes;
        let m = st.mean;
        ui.label(format!(
            "polarisation: degree {:.1} % ± {:.1} (single scattering alone {:.1} %), angle {:.1}° ± {:.1}° from up",
            100.0 * m.degree_of_polarization(),
            100.0 * st.degree_std_error,
            100.0 * a.single_degree,
            m.angle_of_polarization_deg(),
            st.angle_std_error_deg.min(90.0),
        ))
        .on_hover_text("The path tracer's vector mode: the share of the pixel's light (weighted by the eye's response) that is polarised, and the angle of its electric vector from up towards right in the plane through the zenith and the view (90° = horizontal). Multiple scattering lowers the degree below that of single scattering.");
        ui.label(format!(
            "Stokes (I, Q, U, V) = ({:.4e}, {:.4e}, {:.4e}, {:.1e}) W/(m² sr), ȳ-weighted",
            m.i, m.q, m.u, m.v
        ))
        .on_hover_text("Q > 0: vibrating vertically; Q < 0: horizontally; U: at ±45°; V: circular (tiny in the sky).");
        let at = |nm: f64| {
            a.wavelengths_nm
                .iter()
                .position(|&w| w >= nm)
                .map_or(0.0, |i| a.sun_transmittance[i])
        };
        ui.label(format!(
            "transmittance to the sun: {:.3} at 440 nm, {:.3} at 560 nm, {:.3} at 680 nm",
            at(440.0),
            at(560.0),
            at(680.0)
        ))
        .on_hover_text("Fraction of sunlight reaching the camera directly (Beer–Lambert along the sun's ray); 0 when the sun is below the horizon.");
    }

    fn atmosphere(&mut self, ui: &mut egui::Ui, scene: &Scene) {
        if self
            .plots
            .as_ref()
            .is_none_or(|p| p.settings != scene.atmosphere)
        {
            self.plots = Some(AtmospherePlots::new(&scene.atmosphere));
        }
        let Some(plots) = &self.plots else { return };
        let named = |curves: &[Vec<[f64; 2]>],
                     names: &[&'static str]|
         -> Vec<(&'static str, Vec<[f64; 2]>)> {
            names.iter().copied().zip(curves.iter().cloned()).collect()
        };
        let constituents = ["Rayleigh", "ozone", "aerosol"];
        curves(
            ui,
            "phase functions",
            ["scattering angle (°)", "log10 phase (1/sr)"],
            &named(&plots.phase, &["Rayleigh", "aerosol"]),
            "How much light each scatterer sends into each angle at 550 nm: air almost evenly forward and back, aerosols strongly forward (the glow around the sun).",
        );
        curves(
            ui,
            "extinction",
            ["altitude (km)", "log10 extinction (1/m)"],
            &named(&plots.extinction, &constituents),
            "Extinction at 550 nm against altitude: air thins exponentially (≈ 8 km scale height), ozone peaks near 25 km, aerosols stay in the lowest few kilometres.",
        );
        curves(
            ui,
            "optical depth",
            ["wavelength (nm)", "vertical optical depth"],
            &named(&plots.optical_depth, &constituents),
            "Optical depth from the ground to space: Rayleigh falls as λ^-4 (why the sky is blue), ozone absorbs in the Chappuis band around 600 nm (why twilight stays blue).",
        );
    }
}

/// A small plot of named curves with labelled axes (x, y) and a tooltip.
fn curves(
    ui: &mut egui::Ui,
    id: &str,
    axes: [&str; 2],
    lines: &[(&str, Vec<[f64; 2]>)],
    tip: &str,
) {
    Plot::new(id)
        .height(120.0)
        .legend(Legend::default())
        .x_axis_label(axes[0])
        .y_axis_label(axes[1])
        .show(ui, |p| {
            for (name, points) in lines {
                p.line(Line::new(*name, PlotPoints::from(points.clone())));
            }
        })
        .response
        .on_hover_text(tip);
}
