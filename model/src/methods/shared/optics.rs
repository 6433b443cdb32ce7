//! The optics of a scene for one wavelength set, as every table-based model reads them: per batch
//! of four wavelengths the scattering and absorption coefficients per unit of a density profile,
//! and the profile itself sampled once. The f64 original of the GPU's uniforms and storage
//! buffers (`render::uniforms`).

use super::Lanes;
use crate::aerosol::MiePhase;
use crate::atmosphere::{Atmosphere, OpticalDepth};
use crate::camera::Camera;
use crate::geometry::direction_from_angles;
use crate::scene::{AerosolPhase, FittedConstants, Quality, RenderSettings, Scene, WavelengthSet};
use crate::wavelengths::{LANES, WavelengthBatch, batches, batches_at};

/// Samples of the density profile table, spaced as h = H·x² (dense near the ground).
pub const PROFILE_SAMPLES: u32 = 256;

/// Ray-marching sample counts, set by the scene's quality.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Steps {
    pub transmittance: u32,
    pub multiple_scattering: u32,
    pub ground_irradiance: u32,
    pub sky_view: u32,
    pub aerial_perspective_per_slice: u32,
    /// Per-pixel march when the camera is above the atmosphere.
    pub ray_march: u32,
    /// Intervals of each of the two pieces (before and after the lowest point) of Bruneton's
    /// single- and multiple-scattering integrals along a ray (2017: 50 uniform ones over the ray).
    pub scattering: u32,
    /// Zenith-angle samples of Bruneton's scattering-density sphere (twice as many azimuths) and
    /// of the indirect-irradiance hemisphere (four times as many azimuths) (2017: 16).
    pub sphere_directions: u32,
}

impl Steps {
    pub fn for_quality(q: Quality) -> Steps {
        let k = match q {
            Quality::Low => 1,
            Quality::Medium => 2,
            Quality::High => 4,
        };
        Steps {
            transmittance: 32 * k,
            multiple_scattering: 10 * k,
            ground_irradiance: 12 * k,
            sky_view: 16 * k,
            aerial_perspective_per_slice: k,
            ray_march: 48 * k,
            scattering: 8 * k,
            // Even, so that no zenith sample lies on the horizontal, where f32 and f64 disagree
            // about whether a ray from the ground meets it.
            sphere_directions: match q {
                Quality::Low => 6,
                Quality::Medium => 10,
                Quality::High => 16,
            },
        }
    }
}

/// The optics of one batch of four wavelengths; coefficients are per unit of the profile.
#[derive(Debug, Clone, PartialEq)]
pub struct BatchOptics {
    pub colour: WavelengthBatch,
    /// Rayleigh scattering at the reference air density, m⁻¹.
    pub rayleigh_scattering: Lanes,
    pub rayleigh_depolarisation: Lanes,
    /// Ozone absorption at the reference ozone density, m⁻¹.
    pub ozone_absorption: Lanes,
    /// Aerosol scattering per unit of the aerosol profile (m⁻¹ per m⁻¹), i.e. AOD·SSA.
    pub aerosol_scattering: Lanes,
    /// Aerosol absorption per unit of the aerosol profile, AOD·(1 − SSA).
    pub aerosol_absorption: Lanes,
    pub aerosol_g: Lanes,
    /// Extraterrestrial solar irradiance, W·m⁻²·nm⁻¹.
    pub solar_irradiance: Lanes,
    pub ground_albedo: Lanes,
}

/// Rows of four lanes that a model may compute for each batch on the CPU and its passes read
/// as `batches[layer].model` (Hosek–Wilkie's coefficients for the sun of the frame): a fit's
/// per-wavelength numbers, too many for `globals.model`.
pub const BATCH_MODEL_ROWS: usize = 22;

/// A batch's [`BATCH_MODEL_ROWS`] rows.
pub type BatchRows = [Lanes; BATCH_MODEL_ROWS];

/// Everything the passes read that depends only on the atmosphere and the wavelength set: the
/// f64 original of the GPU's uniforms and storage buffers.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    pub bottom_radius_m: f64,
    pub top_radius_m: f64,
    pub aerosol_phase: AerosolPhase,
    /// The type's tabulated Mie phase function, where `aerosol_phase` is `Mie`.
    pub mie_phase: Option<&'static MiePhase>,
    /// Relative air, relative ozone and aerosol (m⁻¹) densities at h = H·(i/(n−1))², and 0.
    pub profile: Vec<[f64; 4]>,
    pub batches: Vec<BatchOptics>,
    pub steps: Steps,
    /// Scattering orders the models that gather them one by one compute (Bruneton, Elek, Haber).
    pub scattering_orders: u32,
    /// The fitted constants the models that have them use (García Liñán).
    pub fitted_constants: FittedConstants,
    /// The CIE standard general sky's type the `cie-standard-sky` row draws, 1–15.
    pub cie_sky_type: u8,
    /// Vertical optical depth of the whole atmosphere at 550 nm, by constituent: what the
    /// analytic models that take a turbidity read (Preetham, Hosek–Wilkie).
    pub optical_depth_550: OpticalDepth,
}

impl Params {
    /// Whether the atmosphere holds any aerosol (an amount of zero costs the GPU no work: its
    /// passes skip the aerosol terms).
    pub fn has_aerosol(&self) -> bool {
        self.batches.iter().any(|b| {
            b.aerosol_scattering
                .iter()
                .chain(&b.aerosol_absorption)
                .any(|&v| v != 0.0)
        })
    }

    pub fn new(atm: &Atmosphere, set: WavelengthSet, quality: Quality) -> Params {
        Params::with_batches(atm, batches(set), quality)
    }

    /// The optics at any wavelengths (nm, 360–830), four per batch (the last batch padded by
    /// repeating its last wavelength), as point samples with no colour matrix: for probing a
    /// model at given wavelengths.
    pub fn at_wavelengths(atm: &Atmosphere, wavelengths_nm: &[f64], quality: Quality) -> Params {
        Params::with_batches(atm, batches_at(wavelengths_nm, None), quality)
    }

    /// The optics of `colours` (batches of four wavelengths).
    pub fn with_batches(
        atm: &Atmosphere,
        colours: Vec<WavelengthBatch>,
        quality: Quality,
    ) -> Params {
        let thickness = atm.thickness_m();
        let air_ref = atm.air_density_m3(0.0).max(f64::MIN_POSITIVE);
        let n = PROFILE_SAMPLES as usize;
        let heights: Vec<f64> = (0..n)
            .map(|i| thickness * (i as f64 / (n - 1) as f64).powi(2))
            .collect();
        let ozone_ref = heights
            .iter()
            .map(|&h| atm.ozone_density_m3(h))
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        let profile = heights
            .iter()
            .map(|&h| {
                let d = atm.densities(h);
                [
                    d.air_m3 / air_ref,
                    d.ozone_m3 / ozone_ref,
                    d.aerosol_per_m,
                    0.0,
                ]
            })
            .collect();
        let batches = colours
            .into_iter()
            .map(|colour| {
                let optics = colour.wavelengths_nm.map(|w| atm.optics(w));
                let lanes = |f: &dyn Fn(usize) -> f64| -> Lanes { Lanes::from_fn(f) };
                let solar_irradiance =
                    lanes(&|i| atm.solar_irradiance(colour.wavelengths_nm[i], colour.bandwidth_nm));
                BatchOptics {
                    rayleigh_scattering: lanes(&|i| optics[i].rayleigh_cross_section_m2 * air_ref),
                    rayleigh_depolarisation: lanes(&|i| optics[i].rayleigh_depolarisation),
                    ozone_absorption: lanes(&|i| optics[i].ozone_cross_section_m2 * ozone_ref),
                    aerosol_scattering: lanes(&|i| {
                        optics[i].aerosol_optical_depth * optics[i].aerosol_ssa
                    }),
                    aerosol_absorption: lanes(&|i| {
                        optics[i].aerosol_optical_depth * (1.0 - optics[i].aerosol_ssa)
                    }),
                    aerosol_g: lanes(&|i| optics[i].aerosol_g),
                    solar_irradiance,
                    ground_albedo: lanes(&|i| {
                        atm.ground_albedo_at(colour.wavelengths_nm[i], colour.bandwidth_nm)
                    }),
                    colour,
                }
            })
            .collect();
        Params {
            bottom_radius_m: atm.bottom_radius_m,
            top_radius_m: atm.top_radius_m,
            aerosol_phase: atm.aerosol_phase,
            mie_phase: atm.mie_phase,
            profile,
            batches,
            steps: Steps::for_quality(quality),
            scattering_orders: crate::scene::DEFAULT_SCATTERING_ORDERS,
            fitted_constants: FittedConstants::default(),
            cie_sky_type: crate::scene::DEFAULT_CIE_SKY_TYPE,
            optical_depth_550: atm.vertical_optical_depth(&atm.optics(550.0), 0.0),
        }
    }

    /// The same optics with the model settings of `render`: scattering orders and fitted
    /// constants.
    pub fn with_render(self, render: &RenderSettings) -> Params {
        Params {
            fitted_constants: render.fitted_constants,
            cie_sky_type: render.cie_sky_type,
            ..self.with_scattering_orders(render.scattering_orders)
        }
    }

    /// The same optics for models that gather `orders` scattering orders (clamped to 1–10).
    pub fn with_scattering_orders(mut self, orders: u32) -> Params {
        self.scattering_orders = orders.clamp(1, 10);
        self
    }

    pub fn thickness_m(&self) -> f64 {
        self.top_radius_m - self.bottom_radius_m
    }

    /// Profile values at altitude `h` (linear in the table's x = √(h/H)); zero above the top.
    pub fn densities(&self, h: f64) -> [f64; 3] {
        let thickness = self.thickness_m();
        if h > thickness {
            return [0.0; 3];
        }
        let n = self.profile.len();
        let x = (h.max(0.0) / thickness).sqrt() * (n - 1) as f64;
        let i = (x.floor() as usize).min(n - 2);
        let f = x - i as f64;
        let (a, b) = (self.profile[i], self.profile[i + 1]);
        std::array::from_fn(|k| a[k] + (b[k] - a[k]) * f)
    }

    /// Scattering (Rayleigh, aerosol) and extinction coefficients at altitude `h`, m⁻¹.
    pub fn medium(&self, batch: usize, h: f64) -> Medium {
        let [air, ozone, aerosol] = self.densities(h);
        let b = &self.batches[batch];
        let mut m = Medium::default();
        for i in 0..LANES {
            m.rayleigh_scattering[i] = b.rayleigh_scattering[i] * air;
            m.aerosol_scattering[i] = b.aerosol_scattering[i] * aerosol;
            m.extinction[i] = m.rayleigh_scattering[i]
                + m.aerosol_scattering[i]
                + b.ozone_absorption[i] * ozone
                + b.aerosol_absorption[i] * aerosol;
        }
        m
    }

    /// The aerosol phase function of the scene at scattering cosine `nu` for each lane of
    /// batch `layer`.
    pub fn aerosol_phase(&self, layer: usize, nu: f64) -> Lanes {
        let b = &self.batches[layer];
        Lanes::from_fn(|i| {
            self.aerosol_phase.value(
                self.mie_phase,
                b.colour.wavelengths_nm[i],
                b.aerosol_g[i],
                nu,
            )
        })
    }
}

/// Local coefficients of one batch, m⁻¹.
#[derive(Debug, Clone, Copy, Default)]
pub struct Medium {
    pub rayleigh_scattering: Lanes,
    pub aerosol_scattering: Lanes,
    pub extinction: Lanes,
}

/// Where the camera is, for the tables that depend on it: altitude (m) and the sun's zenith
/// cosine there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Viewpoint {
    pub h: f64,
    pub mu_s: f64,
}

/// The scene's viewpoint for the sky-view and aerial-perspective tables.
pub fn viewpoint(scene: &Scene, camera: &Camera) -> Viewpoint {
    let a = scene.sun.angles();
    let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
    Viewpoint {
        h: scene.camera.altitude_m,
        mu_s: sun.dot(camera.position.normalize()),
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Viewpoints inside the atmosphere, between the texels of the tables' altitude and sun
    /// axes (the ground, a hill at dusk, the stratosphere at sunrise).
    pub(crate) const VIEWPOINTS_INSIDE: [Viewpoint; 3] = [
        Viewpoint { h: 0.0, mu_s: 0.7 },
        Viewpoint {
            h: 1234.0,
            mu_s: -0.15,
        },
        Viewpoint {
            h: 35_000.0,
            mu_s: 0.05,
        },
    ];

    #[test]
    fn aerosol_of_zero_amount_or_type_none_is_no_aerosol() {
        let of = |kind: crate::aerosol::AerosolType, aod550: f64| {
            let mut s = Scene::default().atmosphere;
            s.aerosol.kind = kind;
            s.aerosol.aod550 = aod550;
            Params::new(&Atmosphere::new(&s), WavelengthSet::Rgb3, Quality::Low).has_aerosol()
        };
        use crate::aerosol::AerosolType::{None, Rural};
        assert!(of(Rural, 0.1));
        assert!(!of(Rural, 0.0));
        assert!(!of(None, 0.1));
    }

    #[test]
    fn the_narrow_sets_see_the_band_mean_of_the_sun_not_a_fraunhofer_line() {
        let atm = Atmosphere::new(&Scene::default().atmosphere);
        let solar = atm.solar_spectrum;
        for set in [WavelengthSet::Spectral4, WavelengthSet::Rgb3] {
            let batch = &Params::new(&atm, set, Quality::Low).batches[0];
            for (i, &w) in batch.colour.wavelengths_nm.iter().enumerate() {
                let band = solar.irradiance(w, crate::wavelengths::POINT_SET_SOLAR_BAND_NM);
                let e = batch.solar_irradiance[i];
                assert!(
                    (e / band - 1.0).abs() < 1e-9,
                    "{set:?} {w} nm: {e} vs band {band}"
                );
            }
        }
        // Spectral4's blue lane: the point value sits on the Fraunhofer G band, far below the
        // mean the lane stands for.
        let point = solar.spectrum().sample(430.0);
        assert!(point < 0.85 * solar.irradiance(430.0, 10.0), "{point}");
    }

    /// The default scene's optics at Spectral4, medium quality.
    pub(crate) fn params() -> Params {
        let scene = Scene::default();
        Params::new(
            &Atmosphere::for_scene(&scene),
            WavelengthSet::Spectral4,
            Quality::Medium,
        )
    }
}
