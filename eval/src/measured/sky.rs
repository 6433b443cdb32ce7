//! The scene of a measured scan and the sky it makes: the site, the sun placed by the project's
//! solar-position code from the scan's time and place, ozone from the month and latitude, the
//! aerosol from one of the retrievals ([`super::retrieve`]), and the spectral radiance of a model's
//! CPU twin or of the path tracer in the scan's directions.

use super::files::{Day, Scan};
use atmoscope_model::aerosol::AerosolType;
use atmoscope_model::camera::{Camera, Projection};
use atmoscope_model::geometry::{Ray, direction_from_angles};
use atmoscope_model::ground::GroundType;
use atmoscope_model::lanes::Lanes;
use atmoscope_model::methods::path_tracer::{LANES, LaneOptics, PathTracer, PathTracerSettings};
use atmoscope_model::methods::rng::Rng;
use atmoscope_model::methods::shared::{Params, viewpoint};
use atmoscope_model::methods::{self, CannotDraw, SkyModel};
use atmoscope_model::scene::{AerosolPhase, CustomAerosol, Method, OzoneColumn, SunSettings};
use atmoscope_model::sun_position::DateTime;
use atmoscope_model::wavelengths::batches_at;
use atmoscope_model::{Atmosphere, Scene};
use rayon::prelude::*;

/// Where the instrument stood.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Site {
    /// Degrees north (−90–90).
    pub latitude_deg: f64,
    /// Degrees east (−180–180).
    pub longitude_deg: f64,
    /// Above sea level, m (0–5000).
    pub altitude_m: f64,
}

impl Site {
    /// Kider et al. (2014): the roof of Rhodes Hall, Cornell University, Ithaca NY.
    pub const CORNELL: Site = Site {
        latitude_deg: 42.443449,
        longitude_deg: -76.481962,
        altitude_m: 250.0,
    };

    /// Air pressure at the site over that at sea level in the US Standard Atmosphere 1976
    /// troposphere, (1 − 2.25577·10⁻⁵ h)^5.25588: the share of the air column above the site.
    pub fn pressure_ratio(&self) -> f64 {
        (1.0 - 2.255_77e-5 * self.altitude_m).powf(5.255_88)
    }
}

/// Single-scattering albedo of the aerosol where no measurement gives one: a continental
/// aerosol of a clean day (AERONET's retrievals of it are trusted only above AOD(440) 0.4, the
/// network's own Level 2 criterion).
pub const DEFAULT_SSA: f64 = 0.95;
/// Ångström exponent where no measurement gives one: continental aerosol.
pub const DEFAULT_ANGSTROM: f64 = 1.3;
/// Scale height of the aerosol's exponential profile, km (a boundary layer of about 1–2 km).
pub const AEROSOL_SCALE_HEIGHT_KM: f64 = 1.2;

/// The aerosol of a scan, however it was found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aerosol {
    /// Vertical optical depth at 550 nm above the site (0–5).
    pub aod550: f64,
    /// Ångström exponent (−1–4).
    pub angstrom: f64,
    /// Henyey–Greenstein asymmetry parameter at 550 nm (−0.95–0.95).
    pub asymmetry_g: f64,
    /// Single-scattering albedo (0–1).
    pub ssa: f64,
}

impl Default for Aerosol {
    fn default() -> Aerosol {
        Aerosol {
            aod550: 0.1,
            angstrom: DEFAULT_ANGSTROM,
            asymmetry_g: CustomAerosol::default().asymmetry_g,
            ssa: DEFAULT_SSA,
        }
    }
}

/// The scene of `scan` at `site` with `aerosol`:
/// - the sun by date, time and place (its zenith angle; the measured directions are turned
///   to the sun's azimuth as the sky's symmetry shows it, [`ScanGeometry`]), at the date's
///   Earth–Sun distance;
/// - the camera on the ground at the site, with the air column above it (the air's density
///   scaled by the pressure ratio), so that the aerosol's optical depth is the column above
///   the instrument, as sun photometers measure it;
/// - ozone: the zonal mean of the site's latitude in the scan's month;
/// - the ground: grass (the site's roof has lawns and trees around), spectral;
/// - the aerosol: the Custom type (optical depth, Ångström exponent, Henyey–Greenstein g, SSA).
pub fn scene(day: &Day, scan: &Scan, site: &Site, aerosol: &Aerosol) -> Scene {
    let mut s = Scene::default();
    s.name = format!("Measured sky {} {}", day.date, scan.time_local);
    s.description = "A measured scan's time, place and aerosol (atmoscope bench measured).".into();
    s.sun = SunSettings::Date {
        time: DateTime {
            year: day.year,
            month: day.month,
            day: day.day,
            hour: scan.time_local.hours(),
            utc_offset_h: scan.utc_offset_h(),
        },
        latitude_deg: site.latitude_deg,
        longitude_deg: site.longitude_deg,
    };
    let a = &mut s.atmosphere;
    a.air_density_scale = site.pressure_ratio();
    a.ozone.column = OzoneColumn::Zonal {
        latitude_deg: site.latitude_deg,
        month: day.month,
    };
    a.ground = GroundType::Grass;
    a.aerosol.kind = AerosolType::Custom;
    a.aerosol.aod550 = aerosol.aod550;
    a.aerosol.phase = AerosolPhase::HenyeyGreenstein;
    a.aerosol.custom = CustomAerosol {
        single_scattering_albedo: aerosol.ssa,
        asymmetry_g: aerosol.asymmetry_g,
        angstrom_exponent: aerosol.angstrom,
        scale_height_km: AEROSOL_SCALE_HEIGHT_KM,
    };
    s.camera.altitude_m = 0.0;
    s
}

/// A view direction: zenith angle (0–90°) and azimuth from the sun's (degrees, 0 = towards it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    pub zenith_deg: f64,
    pub azimuth_from_sun_deg: f64,
}

/// What computes a sky.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Source {
    /// The spectral path tracer, `spp` paths per direction and batch of four wavelengths.
    PathTracer { spp: u64, seed: u64 },
    /// A real-time model's f64 CPU twin.
    Model(Method),
}

/// Width of the band each modelled wavelength averages the solar spectrum over, nm: the
/// measured spectra are 5 nm means.
pub const BAND_NM: f64 = 5.0;

/// A scene's sky by one source at some wavelengths, built once (a model's tables take a
/// while) and then asked for radiance and irradiance.
pub struct Sky {
    scene: Scene,
    atm: Atmosphere,
    source: Source,
    wavelengths_nm: Vec<f64>,
    batches: Vec<atmoscope_model::wavelengths::WavelengthBatch>,
    camera: Camera,
    sun: glam::DVec3,
    sun_azimuth_deg: f64,
    model: Option<Box<dyn SkyModel>>,
}

impl Sky {
    /// The sky of `scene` by `source` at `wavelengths_nm` (360–830): the model's CPU twin
    /// built, or the path tracer's atmosphere prepared. Err when the model refuses the scene.
    pub fn new(scene: &Scene, source: Source, wavelengths_nm: &[f64]) -> Result<Sky, CannotDraw> {
        let atm = Atmosphere::for_scene(scene);
        let a = scene.sun.angles();
        let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
        let camera = Camera::new(&scene.camera, atm.bottom_radius_m, Projection::Perspective);
        let batches = batches_at(wavelengths_nm, Some(BAND_NM));
        let model = match source {
            Source::PathTracer { .. } => None,
            Source::Model(method) => {
                let row = methods::info(method);
                let mut s = scene.clone();
                s.render.method = method;
                if let Some(why) = row.cannot_draw(&s) {
                    return Err(why);
                }
                let build = row
                    .build
                    .ok_or_else(|| CannotDraw::NotRealtime(row.id, methods::realtime_ids()))?;
                let p = Params::with_batches(&atm, batches.clone(), scene.render.quality)
                    .with_render(&scene.render);
                Some(build(&p, viewpoint(scene, &camera)))
            }
        };
        Ok(Sky {
            scene: scene.clone(),
            atm,
            source,
            wavelengths_nm: wavelengths_nm.to_vec(),
            batches,
            camera,
            sun,
            sun_azimuth_deg: a.azimuth_deg,
            model,
        })
    }

    pub fn wavelengths_nm(&self) -> &[f64] {
        &self.wavelengths_nm
    }

    /// The turbidity a fitted model took from the scene by its own conversion (Preetham,
    /// Hosek–Wilkie, the CIE sky), 1–10; None for the others.
    pub fn turbidity(&self) -> Option<f64> {
        self.model.as_ref().and_then(|m| m.turbidity())
    }

    fn world(&self, v: &View) -> glam::DVec3 {
        self.camera.local_to_world(direction_from_angles(
            90.0 - v.zenith_deg,
            self.sun_azimuth_deg + v.azimuth_from_sun_deg,
        ))
    }

    /// Diffuse sky radiance (W·m⁻²·sr⁻¹·nm⁻¹, no sun disk) from the scene's camera in `views`:
    /// one spectrum per view.
    pub fn radiance(&self, views: &[View]) -> Vec<Vec<f64>> {
        let h = self.scene.camera.altitude_m;
        let per_batch: Vec<Vec<Lanes>> = match (&self.model, self.source) {
            (Some(model), _) => (0..self.batches.len())
                .map(|b| {
                    views
                        .par_iter()
                        .map(|v| {
                            model.radiance(b, (self.camera.position, h), self.world(v), self.sun)
                        })
                        .collect()
                })
                .collect(),
            (None, Source::PathTracer { spp, seed }) => {
                let tracer = PathTracer::new(&self.atm, self.sun, PathTracerSettings::default());
                self.batches
                    .iter()
                    .enumerate()
                    .map(|(b, batch)| {
                        let w = Lanes(batch.wavelengths_nm);
                        let lanes = LaneOptics::from_optics(
                            w.0.map(|w| self.atm.optics(w)),
                            w.map(|w| self.atm.solar_irradiance(w, Some(BAND_NM))),
                        );
                        views
                            .par_iter()
                            .enumerate()
                            .map(|(d, v)| {
                                let ray = Ray::new(self.camera.position, self.world(v));
                                let mut sum = [0.0; LANES];
                                for k in 0..spp {
                                    let mut rng = Rng::new(seed, (d * 1000 + b) as u64, k);
                                    let l = tracer.radiance(&ray, &lanes, &mut rng);
                                    sum.iter_mut().zip(l.0).for_each(|(s, l)| *s += l);
                                }
                                Lanes(sum.map(|s| s / spp.max(1) as f64))
                            })
                            .collect()
                    })
                    .collect()
            }
            (None, Source::Model(_)) => unreachable!("a model's sky holds its built model"),
        };
        (0..views.len())
            .map(|d| {
                (0..self.wavelengths_nm.len())
                    .map(|i| per_batch[i / LANES][d].0[i % LANES])
                    .collect()
            })
            .collect()
    }

    /// Direct and diffuse irradiance on a horizontal surface at the camera over the sky's
    /// wavelengths (the trapezoid rule; W·m⁻²): the direct beam through the scene's atmosphere
    /// (Beer–Lambert, the same for every source) and the diffuse sky over a cosine-weighted
    /// stratified set of `strata`² directions.
    pub fn horizontal_irradiance(&self, strata: u32) -> Irradiance {
        let mu_s = self.sun.dot(self.camera.position.normalize()).max(0.0);
        let views = cosine_weighted_views(strata);
        let sky = self.radiance(&views);
        let weights = trapezoid_weights(&self.wavelengths_nm);
        let (mut direct, mut diffuse) = (0.0, 0.0);
        for (i, &w) in self.wavelengths_nm.iter().enumerate() {
            let t =
                self.atm
                    .transmittance_to_sun(&self.atm.optics(w), self.camera.position, self.sun);
            direct += weights[i] * self.atm.solar_irradiance(w, Some(BAND_NM)) * t * mu_s;
            let mean = sky.iter().map(|l| l[i]).sum::<f64>() / views.len() as f64;
            diffuse += weights[i] * std::f64::consts::PI * mean;
        }
        Irradiance { direct, diffuse }
    }
}

/// Diffuse sky radiance of `scene` by `source` in `views` at `wavelengths_nm`: [`Sky`] built
/// for one question.
pub fn radiance(
    scene: &Scene,
    source: Source,
    views: &[View],
    wavelengths_nm: &[f64],
) -> Result<Vec<Vec<f64>>, CannotDraw> {
    Ok(Sky::new(scene, source, wavelengths_nm)?.radiance(views))
}

/// Irradiance on a horizontal surface over a band, W·m⁻².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Irradiance {
    pub direct: f64,
    pub diffuse: f64,
}

impl Irradiance {
    pub fn global(&self) -> f64 {
        self.direct + self.diffuse
    }
}

/// `n`² directions over the upper hemisphere, one per stratum of equal projected solid angle
/// (cos θ dω): the mean radiance over them times π is the irradiance.
pub fn cosine_weighted_views(n: u32) -> Vec<View> {
    let n = n.max(1);
    (0..n * n)
        .map(|i| {
            let (u, v) = (
                (f64::from(i % n) + 0.5) / f64::from(n),
                (f64::from(i / n) + 0.5) / f64::from(n),
            );
            View {
                zenith_deg: u.sqrt().asin().to_degrees(),
                azimuth_from_sun_deg: 360.0 * v,
            }
        })
        .collect()
}

/// Trapezoid weights (nm) of a grid of increasing wavelengths.
pub fn trapezoid_weights(wavelengths_nm: &[f64]) -> Vec<f64> {
    let n = wavelengths_nm.len();
    (0..n)
        .map(|i| {
            let lo = if i > 0 {
                wavelengths_nm[i] - wavelengths_nm[i - 1]
            } else {
                0.0
            };
            let hi = if i + 1 < n {
                wavelengths_nm[i + 1] - wavelengths_nm[i]
            } else {
                0.0
            };
            0.5 * (lo + hi)
        })
        .collect()
}
