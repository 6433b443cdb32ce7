//! Preetham, Shirley & Smits (1999), "A Practical Analytic Model for Daylight" (SIGGRAPH): the
//! sky seen from the ground as Perez et al.'s (1993) five-parameter luminance distribution in
//! CIE xyY, each parameter linear in the turbidity T, scaled by a fitted zenith luminance and
//! zenith chromaticity. No tables, no march: a frame costs one closed form per pixel. Leenman
//! (2025) compares it as the classic analytic model.
//!
//! What the fit does not cover, it refuses: views from above the ground layer (2 km) and a sun
//! below the horizon get a message instead of an image (`Domain::refuses`). The turbidity comes
//! from the scene's vertical optical depths at 550 nm, T = (τ_Rayleigh + τ_aerosol) / τ_Rayleigh,
//! held to the fit's range 2–10; the month (ozone) and the aerosol type change nothing else.
//! Preetham's xyY is spread over the renderer's wavelengths as the solar spectrum times a
//! quadratic in wavelength chosen so that the spectrum's XYZ is the model's ([`spectral_basis`]),
//! so every wavelength set shows the same colour. The ground gets the sun's direct beam through
//! Preetham's Rayleigh and Ångström haze transmittances, and no sky light (the model has none).
//! One file per pass: [`sky`], twin of `shaders/preetham/sky.wgsl`.

pub mod sky;

use super::shared::sun_disk::visible_fraction;
use super::shared::{Lanes, Lut, Params, TableSpec, Viewpoint};
use super::{Domain, GROUND_VIEW_MAX_ALTITUDE_M, SkyModel};
use crate::colour::cie1931;
use crate::constants::{VISIBLE_MAX_NM, VISIBLE_MIN_NM};
use crate::csv_table::tables;
use crate::solar_spectrum::SolarSpectrum;
use glam::DVec3;
use std::sync::OnceLock;

/// The method has no tables.
pub const TABLES: [TableSpec; 0] = [];

/// The fit's domain, refused outside: a viewer on the ground under a sun above the horizon.
pub const DOMAIN: Domain = Domain {
    max_altitude_m: GROUND_VIEW_MAX_ALTITUDE_M,
    min_sun_elevation_deg: 0.0,
    note: "Preetham's fit describes the daytime sky seen from the ground (turbidity 2–10)",
    // A fit to another atmosphere, not the scene's: far too bright against the path tracer
    // already at AOD 0.15, more in cleaner air, where the turbidity stops at 2 (`bench aod`).
    max_aod550: 0.0,
    refuses: true,
};

/// Wavelength about which the spectral basis's quadratic is written, and its unit, nm: the
/// quadratic is in u = (λ − centre) / scale.
pub const BASIS_CENTRE_NM: f64 = 550.0;
pub const BASIS_SCALE_NM: f64 = 100.0;

/// Smallest view-zenith cosine the Perez gradation term takes: the horizon's value serves the
/// directions below it (the term is exp(B / cos θ), B < 0).
pub const MIN_COS_THETA: f64 = 1e-3;

/// kcd/m² in the renderer's luminance unit (Y = ∫ȳL dλ, W·m⁻²·sr⁻¹).
pub fn kcd_per_m2_in_luminance_unit() -> f64 {
    1000.0 / crate::constants::MAX_LUMINOUS_EFFICACY_LM_PER_W
}

/// The published constants (Preetham et al. 1999, Appendix A; `data/preetham1999_constants.csv`).
#[derive(Debug, Clone, PartialEq)]
pub struct Constants {
    /// Perez A–E for (Y, x, y): the change per unit turbidity.
    pub perez_slope: [[f64; 3]; 5],
    /// Perez A–E for (Y, x, y) at zero turbidity.
    pub perez_intercept: [[f64; 3]; 5],
    /// Zenith luminance (a·T + b)·tan χ + c·T + d, kcd/m²: [a, b, c, d].
    pub zenith_luminance: [f64; 4],
    /// χ = (chi[0] − T / chi[1])·(π − 2θ_s).
    pub chi: [f64; 2],
    /// Zenith chromaticity x: rows T², T, 1; columns θ_s³, θ_s², θ_s, 1 (θ_s in rad).
    pub zenith_x: [[f64; 4]; 3],
    /// Zenith chromaticity y, as `zenith_x`.
    pub zenith_y: [[f64; 4]; 3],
    /// Rayleigh optical depth of the vertical column per air mass at 1 µm and its wavelength
    /// exponent: τ = c·λ_µm^−e.
    pub sun_rayleigh: [f64; 2],
    /// Ångström haze: [α, β per unit turbidity, β at zero turbidity].
    pub haze: [f64; 3],
    /// Kasten's (1966) air mass 1 / (cos θ_s + a·(b − θ_s°)^−c): [a, b, c].
    pub air_mass: [f64; 3],
    /// Turbidity range of the fit.
    pub turbidity_range: [f64; 2],
}

impl Constants {
    /// The constants of the embedded table.
    pub fn published() -> &'static Constants {
        static C: OnceLock<Constants> = OnceLock::new();
        C.get_or_init(|| {
            let t = tables::preetham_constants();
            let (group, name, index, value) = (
                t.text("group"),
                t.text("name"),
                t.text("index"),
                t.numbers("value"),
            );
            let v = |g: &str, n: &str, i: &str| -> f64 {
                (0..t.len())
                    .find(|&r| group[r] == g && name[r] == n && index[r] == i)
                    .map(|r| value[r])
                    .unwrap_or_else(|| panic!("preetham1999_constants.csv lacks {g}/{n}/{i}"))
            };
            let perez = |suffix: &str| -> [[f64; 3]; 5] {
                std::array::from_fn(|k| {
                    let letter = ["A", "B", "C", "D", "E"][k];
                    ["Y", "x", "y"].map(|q| v("perez", q, &format!("{letter}_{suffix}")))
                })
            };
            let zenith = |q: &str| -> [[f64; 4]; 3] {
                std::array::from_fn(|row| {
                    std::array::from_fn(|col| {
                        v(
                            "zenith_chromaticity",
                            q,
                            &format!("T{}_theta{}", 2 - row, 3 - col),
                        )
                    })
                })
            };
            Constants {
                perez_slope: perez("slope"),
                perez_intercept: perez("intercept"),
                zenith_luminance: [
                    v("zenith_luminance", "Y_z", "tan_chi_slope"),
                    v("zenith_luminance", "Y_z", "tan_chi_intercept"),
                    v("zenith_luminance", "Y_z", "slope"),
                    v("zenith_luminance", "Y_z", "intercept"),
                ],
                chi: [
                    v("zenith_luminance", "chi", "constant"),
                    v("zenith_luminance", "chi", "divisor"),
                ],
                zenith_x: zenith("x_z"),
                zenith_y: zenith("y_z"),
                sun_rayleigh: [
                    v("sun", "rayleigh", "coefficient"),
                    v("sun", "rayleigh", "exponent"),
                ],
                haze: [
                    v("sun", "haze", "alpha"),
                    v("sun", "haze", "beta_slope"),
                    v("sun", "haze", "beta_intercept"),
                ],
                air_mass: [
                    v("sun", "air_mass", "a"),
                    v("sun", "air_mass", "b"),
                    v("sun", "air_mass", "c"),
                ],
                turbidity_range: [
                    v("range", "turbidity", "min"),
                    v("range", "turbidity", "max"),
                ],
            }
        })
    }

    /// Perez A–E for (Y, x, y) at turbidity `t`.
    pub fn perez(&self, t: f64) -> [[f64; 3]; 5] {
        std::array::from_fn(|k| {
            std::array::from_fn(|q| self.perez_slope[k][q] * t + self.perez_intercept[k][q])
        })
    }
}

/// The scene's turbidity: (τ_R + τ_a) / τ_R at 550 nm over the vertical
/// (`OpticalDepth::turbidity`, as Hosek–Wilkie's), held to the fit's range.
pub fn turbidity(p: &Params) -> f64 {
    p.optical_depth_550
        .turbidity(Constants::published().turbidity_range)
}

/// The matrix that turns a colour (XYZ, in the renderer's unit) into the coefficients c of the
/// spectrum E_sun(λ)·(c₀ + c₁u + c₂u²), u = (λ − [`BASIS_CENTRE_NM`]) / [`BASIS_SCALE_NM`],
/// whose XYZ it is: the inverse of ∫[x̄ ȳ z̄](λ)·E_sun(λ)·uᵏ dλ over the visible range, with the
/// default solar spectrum at 1 AU. Rows c₀, c₁, c₂; columns X, Y, Z.
pub fn spectral_basis() -> [[f64; 3]; 3] {
    static K: OnceLock<[[f64; 3]; 3]> = OnceLock::new();
    *K.get_or_init(|| {
        let cmf = cie1931();
        let sun = SolarSpectrum::default();
        let step = 1.0;
        let mut m = [[0.0; 3]; 3];
        let mut l = VISIBLE_MIN_NM + 0.5 * step;
        while l < VISIBLE_MAX_NM {
            let e = sun.irradiance(l, step) * step;
            let u = (l - BASIS_CENTRE_NM) / BASIS_SCALE_NM;
            for (row, bar) in [&cmf.x, &cmf.y, &cmf.z].into_iter().enumerate() {
                let w = bar.sample(l) * e;
                for (k, m) in m[row].iter_mut().enumerate() {
                    *m += w * u.powi(k as i32);
                }
            }
            l += step;
        }
        // Columns of Mᵀ are the rows of M, so the columns of (Mᵀ)⁻¹ are the rows of M⁻¹.
        glam::DMat3::from_cols_array_2d(&m)
            .inverse()
            .to_cols_array_2d()
    })
}

/// The model constants the GPU reads (`globals.model`): the turbidity (the published
/// constants and the spectral basis reach the shader through the prelude).
pub fn constants(p: &Params) -> [f64; 12] {
    let mut c = [0.0; 12];
    c[0] = turbidity(p);
    c
}

/// Transmittance of the sun's direct beam at the ground with the sun at zenith cosine `mu_s`,
/// for the four lanes of `wavelengths_nm` at turbidity `t`: Preetham's Rayleigh and Ångström
/// haze terms over Kasten's air mass; 0 with the sun below the horizon.
pub fn sun_transmittance(wavelengths_nm: [f64; 4], t: f64, mu_s: f64) -> Lanes {
    if mu_s <= 0.0 {
        return Lanes::ZERO;
    }
    let c = Constants::published();
    let theta_deg = mu_s.min(1.0).acos().to_degrees();
    let [a, b, e] = c.air_mass;
    let m = 1.0 / (mu_s + a * (b - theta_deg).powf(-e));
    let [alpha, beta_slope, beta_intercept] = c.haze;
    let beta = beta_slope * t + beta_intercept;
    let [rc, re] = c.sun_rayleigh;
    Lanes(wavelengths_nm.map(|l| {
        let um = l * 1e-3;
        (-(rc * um.powf(-re) + beta * um.powf(-alpha)) * m).exp()
    }))
}

/// Preetham's sky for one atmosphere.
#[derive(Debug, Clone)]
pub struct Preetham {
    pub params: Params,
    /// [`turbidity`] of the atmosphere.
    pub turbidity: f64,
}

impl SkyModel for Preetham {
    fn params(&self) -> &Params {
        &self.params
    }

    fn radiance(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
        sky::radiance(&self.params, self.turbidity, layer, at, dir, sun)
    }

    fn turbidity(&self) -> Option<f64> {
        Some(self.turbidity)
    }

    fn table(&self, _: &str) -> Option<&Lut> {
        None
    }

    /// The sun's disk through Preetham's direct-beam transmittance at the ground.
    fn sun(&self, layer: usize, h: f64, mu_s: f64, disk: Lanes) -> Lanes {
        let p = &self.params;
        let b = &p.batches[layer];
        let visible = visible_fraction(h, mu_s, p.bottom_radius_m);
        let t = sun_transmittance(b.colour.wavelengths_nm, self.turbidity, mu_s);
        Lanes::from_fn(|i| b.solar_irradiance[i] * t[i] * visible * disk[i].max(0.0))
    }
}

/// The registry's constructor.
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    Box::new(Preetham {
        turbidity: turbidity(params),
        params: params.clone(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// The turbidity follows the aerosol: T = 1 + τ_a/τ_R at 550 nm, inside the fit's 2–10.
    #[test]
    fn turbidity_is_the_ratio_of_optical_depths_held_to_the_fit() {
        let params = |aod550: f64| {
            let mut s = Scene::default();
            s.atmosphere.aerosol.aod550 = aod550;
            let atm = crate::atmosphere::Atmosphere::for_scene(&s);
            Params::new(
                &atm,
                crate::scene::WavelengthSet::Rgb3,
                crate::scene::Quality::Low,
            )
        };
        let p = params(0.3);
        let tau = p.optical_depth_550;
        assert!((0.09..0.11).contains(&tau.rayleigh), "{tau:?}");
        assert!((tau.aerosol - 0.3).abs() < 0.01, "{tau:?}");
        assert!((turbidity(&p) - (1.0 + tau.aerosol / tau.rayleigh)).abs() < 1e-12);
        assert_eq!(turbidity(&params(0.01)), 2.0);
        assert_eq!(turbidity(&params(3.0)), 10.0);
    }
}
