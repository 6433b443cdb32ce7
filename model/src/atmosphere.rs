//! The composed atmosphere: optical properties of air, ozone and aerosol at any wavelength and
//! altitude, optical depth along any ray, and the direct transmittance to the sun.
//!
//! Coefficients are per metre. Optical depth integrates each constituent's density along the ray
//! with adaptive Gauss–Kronrod quadrature to a relative error of 1e-7 (below the 1e-6 asked of
//! it), splitting the ray where it crosses a profile's table level, where the interpolated
//! density has a kink, and at the ray's lowest point.

use crate::aerosol::{
    self, AerosolType, FREE_TROPOSPHERE_TOP_M, MIXING_LAYER_TOP_M, MiePhase, STRATOSPHERE_TOP_M,
    SharedLayers, TypeOptics, shared_layers,
};
use crate::constants::AOD_REFERENCE_NM;
use crate::geometry::{self, Ray};
use crate::ground::GroundType;
use crate::ozone::OzoneCrossSection;
use crate::phase;
use crate::polarisation::mueller::ReducedMatrix;
use crate::profiles::{AirProfile, ScaledOzone};
use crate::quadrature::integrate_adaptive;
use crate::rayleigh;
use crate::scene::{AerosolPhase, AtmosphereSettings};
use crate::solar_spectrum::SolarSpectrum;
use glam::DVec3;

/// Relative tolerance of optical-depth integrals.
pub const OPTICAL_DEPTH_REL_TOL: f64 = 1e-7;

/// Aerosol extinction at 550 nm per unit of its optical depth, by altitude (integrates to 1
/// from the ground to the top): the type's own mixing layer plus the layers every type shares.
#[derive(Debug, Clone)]
struct AerosolProfile {
    /// Scale height of the type's own aerosol, m, and the top of its layer, m.
    mixing: Option<(f64, f64)>,
    /// Extinction of the type's own aerosol at the ground per unit AOD, m⁻¹.
    mixing_per_m: f64,
    /// The shared layers' part, scaled per unit AOD (`None`: no shared layers).
    shared: Option<(&'static SharedLayers, f64)>,
}

impl AerosolProfile {
    /// An exponential with `scale_height_m` from the ground to the top and nothing else (the
    /// custom aerosol).
    fn exponential(scale_height_m: f64, top_m: f64) -> AerosolProfile {
        let column = scale_height_m * (1.0 - (-top_m / scale_height_m).exp());
        AerosolProfile {
            mixing: Some((scale_height_m, f64::INFINITY)),
            mixing_per_m: 1.0 / column,
            shared: None,
        }
    }

    /// OPAC's structure for `aod550`: the shared layers keep their own optical depth and the
    /// mixing layer (scale height `mixing_scale_height_m`, up to [`MIXING_LAYER_TOP_M`]) takes
    /// the rest; an AOD below the shared layers' thins them, and a type without a mixing layer
    /// (`None`) is the shared layers alone.
    fn opac(mixing_scale_height_m: Option<f64>, aod550: f64, top_m: f64) -> AerosolProfile {
        let layers = shared_layers();
        let shared_tau = layers.optical_depth_to(top_m);
        let Some(h) = mixing_scale_height_m else {
            return AerosolProfile {
                mixing: None,
                mixing_per_m: 0.0,
                shared: Some((layers, 1.0 / shared_tau)),
            };
        };
        let top = MIXING_LAYER_TOP_M.min(top_m);
        let column = h * (1.0 - (-top / h).exp());
        let (mixing_per_m, shared) = if aod550 > shared_tau {
            ((aod550 - shared_tau) / aod550 / column, 1.0 / aod550)
        } else {
            (0.0, 1.0 / shared_tau)
        };
        AerosolProfile {
            mixing: Some((h, top)),
            mixing_per_m,
            shared: Some((layers, shared)),
        }
    }

    /// Extinction at 550 nm at altitude `h_m` per unit AOD, m⁻¹.
    fn density_per_m(&self, h_m: f64) -> f64 {
        let h = h_m.max(0.0);
        let mixing = match self.mixing {
            Some((scale, top)) if h < top => self.mixing_per_m * (-h / scale).exp(),
            _ => 0.0,
        };
        let shared = self.shared.map_or(0.0, |(layers, per_tau)| {
            layers.extinction_per_m(h) * per_tau
        });
        mixing + shared
    }
}

/// Spectral behaviour of the aerosol.
#[derive(Debug, Clone)]
enum AerosolSpectral {
    None,
    Mie(&'static TypeOptics),
    Custom { ssa: f64, g: f64, angstrom: f64 },
}

/// Optical properties at one wavelength that do not depend on altitude.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Optics {
    pub wavelength_nm: f64,
    /// Rayleigh cross-section per molecule, m².
    pub rayleigh_cross_section_m2: f64,
    /// Depolarisation ratio used in the Rayleigh phase function (0 when disabled).
    pub rayleigh_depolarisation: f64,
    /// Ozone absorption cross-section per molecule, m².
    pub ozone_cross_section_m2: f64,
    /// Aerosol vertical extinction optical depth at this wavelength (ground to top).
    pub aerosol_optical_depth: f64,
    pub aerosol_ssa: f64,
    pub aerosol_g: f64,
}

impl Optics {
    /// Coefficients for the given densities.
    pub fn coefficients(&self, d: &Densities) -> Coefficients {
        let aerosol_ext = self.aerosol_optical_depth * d.aerosol_per_m;
        Coefficients {
            rayleigh_scattering: self.rayleigh_cross_section_m2 * d.air_m3,
            ozone_absorption: self.ozone_cross_section_m2 * d.ozone_m3,
            aerosol_scattering: aerosol_ext * self.aerosol_ssa,
            aerosol_absorption: aerosol_ext * (1.0 - self.aerosol_ssa),
        }
    }
}

/// Number densities at one altitude.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Densities {
    pub air_m3: f64,
    pub ozone_m3: f64,
    /// Aerosol profile per metre of unit-optical-depth column, m⁻¹.
    pub aerosol_per_m: f64,
}

/// Local scattering and absorption coefficients, m⁻¹.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Coefficients {
    pub rayleigh_scattering: f64,
    pub ozone_absorption: f64,
    pub aerosol_scattering: f64,
    pub aerosol_absorption: f64,
}

impl Coefficients {
    pub fn extinction(&self) -> f64 {
        self.rayleigh_scattering
            + self.ozone_absorption
            + self.aerosol_scattering
            + self.aerosol_absorption
    }

    pub fn scattering(&self) -> f64 {
        self.rayleigh_scattering + self.aerosol_scattering
    }
}

/// Optical depth split by constituent (dimensionless).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OpticalDepth {
    pub rayleigh: f64,
    pub ozone: f64,
    /// Aerosol extinction (scattering + absorption).
    pub aerosol: f64,
}

impl OpticalDepth {
    pub fn total(&self) -> f64 {
        self.rayleigh + self.ozone + self.aerosol
    }

    /// The turbidity the analytic daylight fits take (Preetham, Hosek–Wilkie): the ratio of
    /// the optical depth of air with aerosol to that of clean air, (τ_R + τ_a) / τ_R, held to
    /// a fit's `range` (lowest, highest; 1 or more). Ozone, which absorbs and does not
    /// scatter, is left out, as in Preetham et al. (1999). The highest value with no air.
    pub fn turbidity(&self, range: [f64; 2]) -> f64 {
        let [lo, hi] = range;
        let t = if self.rayleigh > 0.0 {
            1.0 + self.aerosol / self.rayleigh
        } else {
            hi
        };
        t.clamp(lo, hi)
    }
}

/// The physical atmosphere built from a scene's settings.
#[derive(Debug, Clone)]
pub struct Atmosphere {
    /// Planet radius, m.
    pub bottom_radius_m: f64,
    /// Radius of the top of the atmosphere, m.
    pub top_radius_m: f64,
    /// The grey ground's albedo (0–1), used where `ground` is grey.
    pub ground_albedo: f64,
    pub ground: GroundType,
    pub solar_spectrum: SolarSpectrum,
    /// The Earth–Sun distance, AU (0.98–1.02; 1 unless built by [`Atmosphere::for_scene`]
    /// from a sun placed by date): sunlight scales as its inverse square.
    pub sun_distance_au: f64,
    pub aerosol_type: AerosolType,
    pub aerosol_phase: AerosolPhase,
    /// The type's tabulated Mie phase function, where `aerosol_phase` is `Mie`.
    pub mie_phase: Option<&'static MiePhase>,
    /// Total ozone column actually used, DU.
    pub ozone_column_du: f64,
    air: AirProfile,
    /// Factor on the air profile's density.
    air_density_scale: f64,
    depolarisation: bool,
    ozone: ScaledOzone,
    ozone_cross_section: OzoneCrossSection,
    ozone_temperature_k: f64,
    aod550: f64,
    aerosol_profile: AerosolProfile,
    aerosol_spectral: AerosolSpectral,
    breakpoints_m: Vec<f64>,
}

impl Atmosphere {
    /// Builds the atmosphere; the settings are assumed validated (see `Scene::validate`).
    pub fn new(s: &AtmosphereSettings) -> Atmosphere {
        let bottom = s.planet_radius_km * 1000.0;
        let top_m = s.top_km * 1000.0;
        let ozone_column_du = s.ozone.column_du(top_m);
        let ozone = s.ozone.profile.scaled(ozone_column_du, top_m);
        let kind = s.aerosol.kind;
        let (aerosol_spectral, aerosol_profile) = match kind {
            AerosolType::None => (
                AerosolSpectral::None,
                AerosolProfile::exponential(1000.0, top_m),
            ),
            AerosolType::Custom => {
                let c = &s.aerosol.custom;
                (
                    AerosolSpectral::Custom {
                        ssa: c.single_scattering_albedo,
                        g: c.asymmetry_g,
                        angstrom: c.angstrom_exponent,
                    },
                    AerosolProfile::exponential(c.scale_height_km * 1000.0, top_m),
                )
            }
            t => {
                let optics =
                    aerosol::type_optics(t).map_or(AerosolSpectral::None, AerosolSpectral::Mie);
                let profile =
                    AerosolProfile::opac(t.mixing_layer_scale_height_m(), s.aerosol.aod550, top_m);
                (optics, profile)
            }
        };
        let aod550 = if matches!(aerosol_spectral, AerosolSpectral::None) {
            0.0
        } else {
            s.aerosol.aod550
        };
        let mut breakpoints_m: Vec<f64> = s.air_profile.breakpoints_m().to_vec();
        breakpoints_m.extend_from_slice(ozone.breakpoints_m());
        breakpoints_m.extend_from_slice(&[
            MIXING_LAYER_TOP_M,
            FREE_TROPOSPHERE_TOP_M,
            STRATOSPHERE_TOP_M,
        ]);
        breakpoints_m.retain(|&z| z > 0.0 && z < top_m);
        breakpoints_m.sort_by(f64::total_cmp);
        breakpoints_m.dedup();
        Atmosphere {
            bottom_radius_m: bottom,
            top_radius_m: bottom + top_m,
            ground_albedo: s.ground_albedo,
            ground: s.ground,
            solar_spectrum: s.solar_spectrum,
            sun_distance_au: 1.0,
            aerosol_type: kind,
            aerosol_phase: s.aerosol.phase,
            mie_phase: match s.aerosol.phase {
                AerosolPhase::Mie => aerosol::type_phase(kind),
                _ => None,
            },
            ozone_column_du,
            air: s.air_profile,
            air_density_scale: s.air_density_scale,
            depolarisation: s.rayleigh_depolarisation,
            ozone,
            ozone_cross_section: s.ozone.cross_section,
            ozone_temperature_k: s.ozone.temperature_k,
            aod550,
            aerosol_profile,
            aerosol_spectral,
            breakpoints_m,
        }
    }

    /// The atmosphere of a scene, lit by a sun at the scene's Earth–Sun distance.
    pub fn for_scene(scene: &crate::Scene) -> Atmosphere {
        Atmosphere {
            sun_distance_au: scene.sun.distance_au(),
            ..Atmosphere::new(&scene.atmosphere)
        }
    }

    /// Extraterrestrial solar irradiance at the sun's distance, W·m⁻²·nm⁻¹: the spectrum's
    /// mean over `band_nm` around `wavelength_nm` (nm, 360–830), or its value there when
    /// `None`, times 1/d² for the distance d in AU.
    pub fn solar_irradiance(&self, wavelength_nm: f64, band_nm: Option<f64>) -> f64 {
        let at_1_au = match band_nm {
            Some(width) => self.solar_spectrum.irradiance(wavelength_nm, width),
            None => self.solar_spectrum.spectrum().sample(wavelength_nm),
        };
        at_1_au * self.sun_distance_au.powi(-2)
    }

    /// The ground's albedo (0–1) at `wavelength_nm`, averaged over a band `band_nm` wide
    /// where given.
    pub fn ground_albedo_at(&self, wavelength_nm: f64, band_nm: Option<f64>) -> f64 {
        self.ground
            .albedo(self.ground_albedo, wavelength_nm, band_nm)
    }

    /// Height of the atmosphere above the ground, m.
    pub fn thickness_m(&self) -> f64 {
        self.top_radius_m - self.bottom_radius_m
    }

    /// Altitude-independent optics at `wavelength_nm` (360–830 nm is the supported range).
    pub fn optics(&self, wavelength_nm: f64) -> Optics {
        let (ratio, ssa, g) = match &self.aerosol_spectral {
            AerosolSpectral::None => (0.0, 1.0, 0.0),
            AerosolSpectral::Mie(o) => (
                o.extinction_ratio_at(wavelength_nm),
                o.ssa_at(wavelength_nm),
                o.g_at(wavelength_nm),
            ),
            AerosolSpectral::Custom { ssa, g, angstrom } => {
                ((wavelength_nm / AOD_REFERENCE_NM).powf(-angstrom), *ssa, *g)
            }
        };
        Optics {
            wavelength_nm,
            rayleigh_cross_section_m2: rayleigh::cross_section_m2(wavelength_nm),
            rayleigh_depolarisation: if self.depolarisation {
                rayleigh::depolarisation_ratio(wavelength_nm)
            } else {
                0.0
            },
            ozone_cross_section_m2: self
                .ozone_cross_section
                .cross_section_m2(wavelength_nm, self.ozone_temperature_k),
            aerosol_optical_depth: self.aod550 * ratio,
            aerosol_ssa: ssa,
            aerosol_g: g,
        }
    }

    /// Air number density at altitude `h_m`, m⁻³ (zero above the top).
    pub fn air_density_m3(&self, h_m: f64) -> f64 {
        if h_m > self.thickness_m() {
            0.0
        } else {
            self.air_density_scale * self.air.number_density_m3(h_m)
        }
    }

    /// Ozone number density at altitude `h_m`, m⁻³ (zero above the top).
    pub fn ozone_density_m3(&self, h_m: f64) -> f64 {
        if h_m > self.thickness_m() {
            0.0
        } else {
            self.ozone.number_density_m3(h_m)
        }
    }

    /// Aerosol profile per metre of column at `h_m` (integrates to 1 over the atmosphere).
    pub fn aerosol_density_per_m(&self, h_m: f64) -> f64 {
        if h_m > self.thickness_m() {
            0.0
        } else {
            self.aerosol_profile.density_per_m(h_m)
        }
    }

    /// Air (m⁻³), ozone (m⁻³) and aerosol-profile (m⁻¹ per unit optical depth) densities at
    /// `h_m`, evaluated once for any number of wavelengths.
    pub fn densities(&self, h_m: f64) -> Densities {
        Densities {
            air_m3: self.air_density_m3(h_m),
            ozone_m3: self.ozone_density_m3(h_m),
            aerosol_per_m: self.aerosol_density_per_m(h_m),
        }
    }

    /// Coefficients at altitude `h_m` for the given optics.
    pub fn coefficients(&self, optics: &Optics, h_m: f64) -> Coefficients {
        optics.coefficients(&self.densities(h_m))
    }

    /// Aerosol phase function value for scattering-angle cosine `nu`.
    pub fn aerosol_phase(&self, optics: &Optics, nu: f64) -> f64 {
        self.aerosol_phase
            .value(self.mie_phase, optics.wavelength_nm, optics.aerosol_g, nu)
    }

    /// The aerosol's scattering matrix over its phase function at scattering cosine `nu`: the
    /// type's Mie matrix where the phase is Mie, else one that makes no polarisation
    /// ([`ReducedMatrix::unpolarising`]).
    pub fn aerosol_matrix(&self, optics: &Optics, nu: f64) -> ReducedMatrix {
        match (self.aerosol_phase, self.mie_phase) {
            (AerosolPhase::Mie, Some(m)) => m.matrix(optics.wavelength_nm, nu),
            _ => ReducedMatrix::unpolarising(nu),
        }
    }

    /// Rayleigh phase function value for scattering-angle cosine `nu`.
    pub fn rayleigh_phase(&self, optics: &Optics, nu: f64) -> f64 {
        phase::rayleigh(nu, optics.rayleigh_depolarisation)
    }

    /// Column integrals of air (m⁻²), ozone (m⁻²) and the aerosol shape (dimensionless) along
    /// `ray` between distances `t0` and `t1`.
    fn columns(&self, ray: &Ray, t0: f64, t1: f64) -> [f64; 3] {
        let (r, mu) = ray.r_mu();
        // Split at the lowest point and where the ray crosses a table level.
        let mut cuts = vec![t0, t1];
        let t_low = -r * mu;
        if t_low > t0 && t_low < t1 {
            cuts.push(t_low);
        }
        for &z in &self.breakpoints_m {
            if let Some((a, b)) = geometry::sphere_distances(r, mu, self.bottom_radius_m + z) {
                cuts.extend([a, b].into_iter().filter(|&t| t > t0 && t < t1));
            }
        }
        cuts.sort_by(f64::total_cmp);
        let altitude = |t: f64| geometry::radius_at(r, mu, t) - self.bottom_radius_m;
        let mut out = [0.0; 3];
        for w in cuts.windows(2) {
            if w[1] - w[0] <= 0.0 {
                continue;
            }
            out[0] += integrate_adaptive(
                |t| self.air_density_m3(altitude(t)),
                w[0],
                w[1],
                OPTICAL_DEPTH_REL_TOL,
                0.0,
            )
            .value;
            out[1] += integrate_adaptive(
                |t| self.ozone_density_m3(altitude(t)),
                w[0],
                w[1],
                OPTICAL_DEPTH_REL_TOL,
                0.0,
            )
            .value;
            out[2] += integrate_adaptive(
                |t| self.aerosol_density_per_m(altitude(t)),
                w[0],
                w[1],
                OPTICAL_DEPTH_REL_TOL,
                0.0,
            )
            .value;
        }
        out
    }

    /// Optical depth along `ray` through the atmosphere, up to where it leaves the atmosphere or
    /// meets the ground.
    pub fn optical_depth(&self, optics: &Optics, ray: &Ray) -> OpticalDepth {
        match ray.atmosphere_segment(self.bottom_radius_m, self.top_radius_m) {
            None => OpticalDepth::default(),
            Some((t0, t1)) => self.optical_depth_between(optics, ray, t0, t1),
        }
    }

    /// Optical depth along `ray` between distances `t0` and `t1` (both inside the atmosphere).
    pub fn optical_depth_between(
        &self,
        optics: &Optics,
        ray: &Ray,
        t0: f64,
        t1: f64,
    ) -> OpticalDepth {
        if t1 <= t0 {
            return OpticalDepth::default();
        }
        let [air, ozone, aerosol] = self.columns(ray, t0, t1);
        OpticalDepth {
            rayleigh: optics.rayleigh_cross_section_m2 * air,
            ozone: optics.ozone_cross_section_m2 * ozone,
            aerosol: optics.aerosol_optical_depth * aerosol,
        }
    }

    /// Vertical optical depth from altitude `altitude_m` straight up to space.
    pub fn vertical_optical_depth(&self, optics: &Optics, altitude_m: f64) -> OpticalDepth {
        let ray = Ray::new(
            DVec3::new(0.0, 0.0, self.bottom_radius_m + altitude_m),
            DVec3::Z,
        );
        self.optical_depth(optics, &ray)
    }

    /// Direct transmittance of sunlight from the top of the atmosphere to `point`
    /// (planet-centred, m), for a point sun in unit direction `sun`; zero in the planet's shadow.
    pub fn transmittance_to_sun(&self, optics: &Optics, point: DVec3, sun: DVec3) -> f64 {
        if geometry::in_planet_shadow(point, sun, self.bottom_radius_m) {
            return 0.0;
        }
        (-self.optical_depth(optics, &Ray::new(point, sun)).total()).exp()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::DOBSON_UNIT_PER_M2;
    use crate::lanes::Lanes;
    use crate::scene::{OzoneColumn, Scene};

    #[test]
    fn sunlight_follows_the_earth_sun_distance_of_the_date_into_every_model() {
        use crate::methods::path_tracer::LaneOptics;
        use crate::methods::shared::optics::Params;
        use crate::scene::{Quality, SunSettings, WavelengthSet};
        use crate::sun_position::DateTime;
        let on = |month| {
            let mut s = Scene::default();
            s.sun = SunSettings::Date {
                time: DateTime {
                    year: 2026,
                    month,
                    day: 4,
                    hour: 12.0,
                    utc_offset_h: 0.0,
                },
                latitude_deg: 45.0,
                longitude_deg: 0.0,
            };
            Atmosphere::for_scene(&s)
        };
        let (january, july) = (on(1), on(7));
        // (1.0167 / 0.9833)² = 1.069: January's sun is 6.9 % stronger than July's.
        let ratio = |f: &dyn Fn(&Atmosphere) -> f64| f(&january) / f(&july);
        let tables = |a: &Atmosphere| {
            Params::new(a, WavelengthSet::Spectral4, Quality::Low).batches[0].solar_irradiance[1]
        };
        let traced = |a: &Atmosphere| LaneOptics::new(a, Lanes::splat(550.0)).solar_irradiance[0];
        for r in [ratio(&tables), ratio(&traced)] {
            assert!((r - 1.069).abs() < 0.002, "{r}");
        }
        // A sun placed by angles stands at the mean distance of the tabulated spectra.
        let by_angles = Atmosphere::for_scene(&Scene::default());
        assert_eq!(
            by_angles.solar_irradiance(550.0, None),
            Atmosphere::new(&Scene::default().atmosphere).solar_irradiance(550.0, None)
        );
    }

    fn clear_air() -> AtmosphereSettings {
        let mut s = Scene::default().atmosphere;
        s.aerosol.kind = AerosolType::None;
        s
    }

    /// Every type's aerosol stays where such aerosol lives: nothing at 50 km (Guimera's
    /// constant Background made it 20 times Rayleigh there), the stratosphere well below
    /// Rayleigh, above 12 km only the stratospheric layer and at most a tenth of the optical depth
    /// (a fifth for Background, which is OPAC's free troposphere and stratosphere alone; the
    /// polar types' 30 km scale height put two thirds there), and the column still the AOD.
    #[test]
    fn aerosol_stays_in_the_troposphere_and_a_thin_stratospheric_layer() {
        for kind in AerosolType::MIXTURES {
            for aod in [0.005, 0.02, kind.default_aod550(), 1.0] {
                let mut s = Scene::default().atmosphere;
                s.aerosol.kind = kind;
                s.aerosol.aod550 = aod;
                let atm = Atmosphere::new(&s);
                let optics = atm.optics(550.0);
                let aerosol = |h: f64| aod * atm.aerosol_density_per_m(h);
                let rayleigh = |h: f64| optics.rayleigh_cross_section_m2 * atm.air_density_m3(h);
                let what = format!("{kind:?} at AOD {aod}");
                assert_eq!(aerosol(50_000.0), 0.0, "{what}");
                // Background is the upper layers alone: at an AOD of 1 it is a volcanic
                // stratosphere by construction.
                if kind != AerosolType::Background || aod <= 0.05 {
                    assert!(aerosol(20_000.0) < 0.5 * rayleigh(20_000.0), "{what}");
                }
                let column = atm.vertical_optical_depth(&optics, 0.0).aerosol;
                assert!((column / aod - 1.0).abs() < 1e-6, "{what}: column {column}");
                let above = atm
                    .vertical_optical_depth(&optics, FREE_TROPOSPHERE_TOP_M)
                    .aerosol;
                let layers = shared_layers();
                let stratosphere = layers.optical_depth_to(STRATOSPHERE_TOP_M)
                    - layers.optical_depth_to(FREE_TROPOSPHERE_TOP_M);
                let share = if kind == AerosolType::Background {
                    0.2
                } else {
                    0.1
                };
                assert!(
                    above < share * aod + stratosphere,
                    "{what}: {above} above 12 km"
                );
            }
        }
    }

    #[test]
    fn rayleigh_vertical_optical_depth_at_550_nm_matches_bucholtz() {
        let atm = Atmosphere::new(&clear_air());
        let tau = atm.vertical_optical_depth(&atm.optics(550.0), 0.0).rayleigh;
        // Bucholtz (1995), Table: 0.0973 at 550 nm for the US standard atmosphere.
        assert!((tau / 0.0973 - 1.0).abs() < 0.01, "τ_R(550) = {tau}");
    }

    #[test]
    fn ozone_vertical_optical_depth_is_column_times_cross_section() {
        let mut s = clear_air();
        s.ozone.column = OzoneColumn::Du(300.0);
        let atm = Atmosphere::new(&s);
        let optics = atm.optics(600.0);
        let tau = atm.vertical_optical_depth(&optics, 0.0).ozone;
        let expected = 300.0 * DOBSON_UNIT_PER_M2 * optics.ozone_cross_section_m2;
        assert!((tau / expected - 1.0).abs() < 1e-4, "{tau} vs {expected}");
    }

    #[test]
    fn aerosol_vertical_optical_depth_is_the_requested_aod() {
        for kind in AerosolType::ALL {
            let mut s = Scene::default().atmosphere;
            s.aerosol.kind = kind;
            s.aerosol.aod550 = 0.25;
            let atm = Atmosphere::new(&s);
            let tau = atm.vertical_optical_depth(&atm.optics(550.0), 0.0).aerosol;
            let expected = if kind == AerosolType::None { 0.0 } else { 0.25 };
            assert!((tau - expected).abs() < 1e-6, "{kind:?}: {tau}");
        }
    }

    /// Composite Simpson with many panels per split interval, as an independent check.
    fn simpson_column(atm: &Atmosphere, ray: &Ray) -> f64 {
        let (t0, t1) = ray
            .atmosphere_segment(atm.bottom_radius_m, atm.top_radius_m)
            .unwrap();
        let (r, mu) = ray.r_mu();
        let mut cuts = vec![t0, t1];
        for &z in atm.breakpoints_m.iter().chain([0.0, 86_000.0].iter()) {
            if let Some((a, b)) = geometry::sphere_distances(r, mu, atm.bottom_radius_m + z) {
                cuts.extend([a, b].into_iter().filter(|&t| t > t0 && t < t1));
            }
        }
        if -r * mu > t0 && -r * mu < t1 {
            cuts.push(-r * mu);
        }
        cuts.sort_by(f64::total_cmp);
        let f = |t: f64| atm.air_density_m3(geometry::radius_at(r, mu, t) - atm.bottom_radius_m);
        cuts.windows(2)
            .map(|w| {
                let n = 2000;
                let h = (w[1] - w[0]) / n as f64;
                let mut s = f(w[0]) + f(w[1]);
                for i in 1..n {
                    s += f(w[0] + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
                }
                s * h / 3.0
            })
            .sum()
    }

    #[test]
    fn slant_optical_depths_meet_the_relative_error_bound() {
        let atm = Atmosphere::new(&clear_air());
        let optics = atm.optics(550.0);
        let r0 = atm.bottom_radius_m;
        let rays = [
            Ray::new(DVec3::new(0.0, 0.0, r0 + 1.0), DVec3::new(1.0, 0.0, 0.0)),
            Ray::new(DVec3::new(0.0, 0.0, r0 + 10.0), DVec3::new(1.0, 0.0, 0.2)),
            Ray::new(
                DVec3::new(0.0, 0.0, r0 + 10_000.0),
                DVec3::new(1.0, 0.0, -0.05),
            ),
            Ray::new(
                DVec3::new(-2_000_000.0, 0.0, r0 + 20_000.0),
                DVec3::new(1.0, 0.0, 0.0),
            ),
        ];
        for ray in rays {
            let tau = atm.optical_depth(&optics, &ray).rayleigh;
            let reference = simpson_column(&atm, &ray) * optics.rayleigh_cross_section_m2;
            assert!(
                ((tau - reference) / reference).abs() < 1e-6,
                "{ray:?}: {tau} vs {reference}"
            );
        }
    }

    #[test]
    fn transmittance_to_the_sun_is_zero_in_the_planet_shadow_and_one_in_space() {
        let atm = Atmosphere::new(&Scene::default().atmosphere);
        let optics = atm.optics(550.0);
        let ground = DVec3::new(0.0, 0.0, atm.bottom_radius_m + 1.0);
        assert_eq!(
            atm.transmittance_to_sun(&optics, ground, DVec3::new(0.0, 1.0, -0.1).normalize()),
            0.0
        );
        let space = DVec3::new(0.0, 0.0, atm.top_radius_m + 1000.0);
        assert_eq!(atm.transmittance_to_sun(&optics, space, DVec3::Z), 1.0);
        let t = atm.transmittance_to_sun(&optics, ground, DVec3::Z);
        assert!(t > 0.5 && t < 1.0, "{t}");
    }

    /// The air density factor scales the air's density, and with it the Rayleigh optical
    /// depth, at every height; nothing else changes.
    #[test]
    fn the_air_density_scale_scales_the_rayleigh_optical_depth() {
        let base = crate::Scene::default().atmosphere;
        let thin = AtmosphereSettings {
            air_density_scale: 0.25,
            ..base.clone()
        };
        let (a, b) = (Atmosphere::new(&base), Atmosphere::new(&thin));
        let optics = a.optics(550.0);
        let (ta, tb) = (
            a.vertical_optical_depth(&optics, 0.0),
            b.vertical_optical_depth(&optics, 0.0),
        );
        assert!(
            (tb.rayleigh / ta.rayleigh - 0.25).abs() < 1e-9,
            "{ta:?} {tb:?}"
        );
        assert_eq!(ta.aerosol, tb.aerosol);
        assert_eq!(ta.ozone, tb.ozone);
        assert!((b.air_density_m3(5_000.0) / a.air_density_m3(5_000.0) - 0.25).abs() < 1e-12);
    }
}
