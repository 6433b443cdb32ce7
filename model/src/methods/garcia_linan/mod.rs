//! García Liñán (2023), "A real-time spectral atmosphere model" (master's thesis), as the thesis
//! describes it: the transmittance table, single scattering ray-marched into a sky texture at
//! the camera, and two closed-form stand-ins for the higher orders added to every sample's
//! source — the ground bounce L_g (the sunlit ground below the sample seen as one Lambertian
//! disk of solid angle Ω) and the logistic multiple-scattering fit L_ms(μ_s) with its
//! published constants (`data/garcia_linan_2023_constants.csv`). No aerial-perspective volume:
//! ground seen from the camera takes the sky texture's in-scattering plus the sunlit ground
//! through the transmittance table. A camera above the atmosphere marches each pixel with the
//! same integrand.
//!
//! Where the thesis text is incomplete, the form used by the author's published shaders is
//! followed (recorded in docs/models/garcia_linan.md): the single-scattering term carries the
//! sun's transmittance, and L_g and L_ms are multiplied by the local scattering coefficient (of
//! air and aerosol), by the solar irradiance and by the view transmittance like the rest.
//!
//! The medium (profiles, cross-sections, phase functions, sun) is the scene's, shared with
//! every other model, so that comparisons measure the method and not the inputs. One file per
//! pass: [`sky_texture`] and [`sky`], twins of `shaders/garcia_linan/*.wgsl`.

pub mod sky;
pub mod sky_texture;

use super::shared::march::march_inscattering;
use super::shared::transmittance::{self, compute_transmittance_lut, sun_transmittance};
use super::shared::{Lanes, Lut, Params, Spacing, TableSpec, Viewpoint};
use super::{Domain, SkyModel};
use crate::csv_table::tables;
use crate::geometry::rho_squared;
use crate::scene::FittedConstants;
use glam::DVec3;
use std::f64::consts::PI;

/// Every table of the method, in pass order.
pub const TABLES: [TableSpec; 2] = [transmittance::TABLE, sky_texture::TABLE];

/// Where the model is meant to work: below 100 km (the thesis shows views up to 80 km, inside
/// its 100 km atmosphere) with the sun up; the multiple-scattering fit was made at 10 km in
/// daylight.
pub const DOMAIN: Domain = Domain {
    max_altitude_m: 100_000.0,
    min_sun_elevation_deg: 0.0,
    note: "views from below 100 km in daylight; L_ms was fitted at 10 km altitude with the sun above the horizon",
    max_aod550: 0.1,
    refuses: false,
};

/// The fitted constants of L_ms = scale·(λ_ref/λ)⁴ / (1 + a·exp(−b·μ_s)) (thesis eq. 5.7, the
/// λ⁻⁴ factor normalised to λ_ref).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Constants {
    /// Amplitude at λ_ref, sr⁻¹ per unit solar irradiance (published: 0.02).
    pub ms_scale: f64,
    /// Logistic offset a (published: 5).
    pub ms_a: f64,
    /// Logistic slope b (published: 17.92).
    pub ms_b: f64,
    /// Wavelength where the λ⁻⁴ tint is 1, nm (published: 430).
    pub reference_wavelength_nm: f64,
}

impl Constants {
    /// The published constants, read from the embedded table: the reference wavelength is the
    /// one whose tint is 1.
    pub fn published() -> Constants {
        static PUBLISHED: std::sync::OnceLock<Constants> = std::sync::OnceLock::new();
        *PUBLISHED.get_or_init(Constants::read_published)
    }

    /// The project's refit against the path tracer (`atmoscope fit-garcia-linan`), read from
    /// the embedded `data/garcia_linan_refit.csv`.
    pub fn refit() -> Constants {
        static REFIT: std::sync::OnceLock<Constants> = std::sync::OnceLock::new();
        *REFIT.get_or_init(|| {
            let t = tables::garcia_linan_refit();
            let (names, values) = (t.text("name"), t.numbers("value"));
            let value = |name: &str| {
                (0..t.len())
                    .find(|&i| names[i] == name)
                    .map_or(f64::NAN, |i| values[i])
            };
            Constants {
                ms_scale: value("ms_scale"),
                ms_a: value("ms_a"),
                ms_b: value("ms_b"),
                reference_wavelength_nm: value("reference_wavelength_nm"),
            }
        })
    }

    /// The constants a scene chooses (`render.fitted_constants`).
    pub fn chosen(choice: FittedConstants) -> Constants {
        match choice {
            FittedConstants::Published => Constants::published(),
            FittedConstants::Refit => Constants::refit(),
        }
    }

    fn read_published() -> Constants {
        let t = tables::garcia_linan_constants();
        let value = |name: &str, index: &str| -> f64 {
            let names = t.text("name");
            let indices = t.text("index");
            let values = t.numbers("value");
            (0..t.len())
                .find(|&i| names[i] == name && indices[i] == index)
                .map_or(f64::NAN, |i| values[i])
        };
        let reference = (0..4)
            .find(|i| value("ms_tint", &i.to_string()) == 1.0)
            .map_or(f64::NAN, |i| value("wavelength", &i.to_string()));
        Constants {
            ms_scale: value("ms_scale", ""),
            ms_a: value("ms_a", ""),
            ms_b: value("ms_b", ""),
            reference_wavelength_nm: reference,
        }
    }

    /// The four values the GPU reads from `globals.model`.
    pub fn uniform(&self) -> [f64; 4] {
        [
            self.ms_scale,
            self.ms_a,
            self.ms_b,
            self.reference_wavelength_nm,
        ]
    }
}

/// L_ms per lane at sun zenith cosine `mu_s` (sr⁻¹ per unit solar irradiance).
pub fn multiple_scattering_fit(c: &Constants, wavelengths_nm: &Lanes, mu_s: f64) -> Lanes {
    let logistic = c.ms_scale / (1.0 + c.ms_a * (-c.ms_b * mu_s).exp());
    wavelengths_nm.map(|w| logistic * (c.reference_wavelength_nm / w).powi(4))
}

/// Solid angle (sr) of the ground seen from altitude `h` (m): 2π(1 − √(r² − R²)/r).
pub fn ground_solid_angle(h: f64, big_r: f64) -> f64 {
    let r = big_r + h;
    (2.0 * PI * (1.0 - rho_squared(h.max(0.0), big_r).sqrt() / r)).max(0.0)
}

/// L_g per lane at altitude `h` with the sun at zenith cosine `mu_s` (sr⁻¹ per unit solar
/// irradiance): the ground straight below, lit by the sun through T(ground → sun), seen
/// through the vertical transmittance T(ground → h), as a Lambertian disk of solid angle Ω
/// scattered isotropically (thesis eq. 5.2–5.6).
pub fn ground_bounce(p: &Params, t: &Lut, layer: usize, h: f64, mu_s: f64) -> Lanes {
    let albedo = p.batches[layer].ground_albedo;
    let t_ground_sun = sun_transmittance(p, t, layer, 0.0, mu_s);
    let t_up_ground = transmittance::ground_to_top(t, layer);
    let t_up_here = transmittance::transmittance(p, t, layer, h, 1.0);
    let k = ground_solid_angle(h, p.bottom_radius_m) / (4.0 * PI) * mu_s.max(0.0) / PI;
    Lanes::from_fn(|i| {
        let t_vertical = (t_up_ground[i] / t_up_here[i].max(1e-30)).min(1.0);
        k * albedo[i] * t_ground_sun[i] * t_vertical
    })
}

/// In-scattered radiance per unit solar irradiance and transmittance along (h, mu) over
/// [t_start, t_end]: `steps` uniform segments with midpoint samples, the higher orders being
/// (L_g + L_ms) times the scattering coefficient (Hillaire's energy-conserving segment weight,
/// as the thesis uses).
pub fn integrate(
    p: &Params,
    t: &Lut,
    c: &Constants,
    layer: usize,
    ray: (f64, f64, f64, f64),
    segment: (f64, f64),
    steps: u32,
) -> (Lanes, Lanes) {
    let wavelengths_nm = &Lanes(p.batches[layer].colour.wavelengths_nm);
    let psi = |h_t, mu_s_t| {
        ground_bounce(p, t, layer, h_t, mu_s_t) + multiple_scattering_fit(c, wavelengths_nm, mu_s_t)
    };
    march_inscattering(p, t, layer, ray, segment, steps, Spacing::Uniform, psi)
}

/// Every table of the method for one atmosphere and viewpoint, with the constants used.
#[derive(Debug, Clone)]
pub struct Tables {
    pub params: Params,
    pub constants: Constants,
    pub transmittance: Lut,
    pub sky_texture: Lut,
    pub viewpoint: Viewpoint,
}

impl Tables {
    pub fn compute(p: &Params, c: Constants, vp: Viewpoint) -> Tables {
        let transmittance = compute_transmittance_lut(p);
        let sky_texture = sky_texture::compute_sky_texture(p, &transmittance, &c, vp);
        Tables {
            params: p.clone(),
            constants: c,
            transmittance,
            sky_texture,
            viewpoint: vp,
        }
    }
}

impl SkyModel for Tables {
    fn params(&self) -> &Params {
        &self.params
    }

    fn radiance(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
        sky::radiance(self, layer, at, dir, sun)
    }

    fn table(&self, id: &str) -> Option<&Lut> {
        match id {
            "transmittance" => Some(&self.transmittance),
            "sky-texture" => Some(&self.sky_texture),
            _ => None,
        }
    }
}

/// Builds the method's CPU twin with the constants `params` chooses (the registry's
/// constructor).
pub fn build(params: &Params, vp: Viewpoint) -> Box<dyn SkyModel> {
    let c = Constants::chosen(params.fitted_constants);
    Box::new(Tables::compute(params, c, vp))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_published_constants_are_read_from_the_table() {
        let c = Constants::published();
        assert_eq!(c.ms_scale, 0.02);
        assert_eq!(c.ms_a, 5.0);
        assert_eq!(c.ms_b, 17.92);
        assert_eq!(c.reference_wavelength_nm, 430.0);
        // The tabulated tints are (430/λ)⁴ to within their rounding (0.594 for 0.5931).
        let tints = multiple_scattering_fit(&c, &Lanes([630.0, 560.0, 490.0, 430.0]), 1.0)
            .map(|v| v / multiple_scattering_fit(&c, &Lanes::splat(430.0), 1.0)[0]);
        for (t, published) in tints.iter().zip([0.217, 0.347, 0.594, 1.0]) {
            assert!((t - published).abs() < 1.5e-3, "{t} vs {published}");
        }
    }

    #[test]
    fn the_refit_is_read_from_its_table_and_chosen_by_the_scene() {
        let (published, refit) = (Constants::published(), Constants::refit());
        for v in refit.uniform() {
            assert!(v.is_finite() && v > 0.0, "{refit:?}");
        }
        assert_eq!(
            refit.reference_wavelength_nm,
            published.reference_wavelength_nm
        );
        assert_ne!(refit.ms_scale, published.ms_scale);
        assert_eq!(Constants::chosen(FittedConstants::Refit), refit);
        assert_eq!(Constants::chosen(FittedConstants::Published), published);
        // The registry's constructor follows the choice carried by the optics.
        let p = crate::methods::shared::optics::tests::params();
        let vp = Viewpoint { h: 10.0, mu_s: 0.5 };
        let texture = |choice| {
            let p = Params {
                fitted_constants: choice,
                ..p.clone()
            };
            build(&p, vp)
                .table("sky-texture")
                .cloned()
                .expect("sky texture")
        };
        assert_ne!(
            texture(FittedConstants::Published),
            texture(FittedConstants::Refit)
        );
    }

    #[test]
    fn the_logistic_fit_and_the_ground_solid_angle_match_hand_values() {
        let c = Constants::published();
        let at = |mu_s: f64| multiple_scattering_fit(&c, &Lanes::splat(430.0), mu_s)[0];
        assert!((at(0.0) - 0.02 / 6.0).abs() < 1e-12);
        assert!((at(0.1) - 0.02 / (1.0 + 5.0 * (-1.792_f64).exp())).abs() < 1e-12);
        assert!(at(-0.1) < at(0.0) && at(0.0) < at(0.3) && at(1.0) < 0.02);
        let big_r = 6_371_000.0;
        assert!((ground_solid_angle(0.0, big_r) - 2.0 * PI).abs() < 1e-12);
        assert!((ground_solid_angle(10_000.0, big_r) - 5.93156).abs() < 1e-4);
        assert!((ground_solid_angle(100_000.0, big_r) - 5.18285).abs() < 1e-4);
    }
}
