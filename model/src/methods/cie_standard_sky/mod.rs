//! The CIE standard general sky (CIE S 011/E:2003, ISO 15469:2004): fifteen relative luminance
//! distributions, from the heavily overcast to the cloudless turbid sky, each the product of a
//! gradation function of the zenith angle Z and an indicatrix of the angle χ from the sun,
//!
//! L / L_z = f(χ)·φ(Z) / (f(Z_s)·φ(0)),   φ(Z) = 1 + a·e^(b / cos Z),
//! f(χ) = 1 + c·(e^(dχ) − e^(dπ/2)) + e·cos²χ,
//!
//! with a–e per type (`model/data/cie2003_standard_general_sky.csv`). The daylighting
//! standard (Radiance's `gensky`, ISO 15469) and a luminance model: it has no spectrum.
//!
//! What the standard leaves open is chosen here. The zenith luminance L_z is Preetham et al.'s
//! (1999) published formula at the scene's turbidity (`preetham::sky::zenith`), so the sky's
//! brightness follows the scene's sun and haze; its colour is the sun's: every direction's
//! spectrum is the scene's solar spectrum scaled to the direction's luminance. The clear and
//! turbid types (11–15) show the sun, through Preetham's direct-beam transmittance; the others
//! hide it. The ground is Lambertian under that sun and the type's sky. The type is the
//! scene's `render.cie_sky_type`.
//!
//! Everything the sky pass needs for the sun at the camera is computed on the CPU
//! ([`batch_rows`]) and read on the GPU as `batches[layer].model`; [`sky`] is the twin of
//! `shaders/cie_standard_sky/sky.wgsl`.

pub mod sky;

use super::preetham;
use super::shared::sun_rows::{RowSky, hemisphere_irradiance};
use super::shared::{BatchRows, Lanes, Params, TableSpec, Viewpoint};
use super::{Domain, SkyModel};
use crate::colour::cie1931;
use crate::constants::{VISIBLE_MAX_NM, VISIBLE_MIN_NM};
use crate::csv_table::tables;
use crate::solar_spectrum::SolarSpectrum;
use crate::wavelengths::LANES;
use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::OnceLock;

/// The method has no tables.
pub const TABLES: [TableSpec; 0] = [];

/// The standard's domain, refused outside: the sky seen from the ground with the sun up.
/// It is Preetham's, with its own note: luminance distributions of measured skies, not of the
/// scene's atmosphere, so no AOD range either.
pub const DOMAIN: Domain = Domain {
    note: "the CIE standard general sky describes the daytime sky's luminance seen from the ground",
    ..super::preetham::DOMAIN
};

/// Rows of [`batch_rows`]: the lane's radiance per unit of f(χ)·φ(Z); a, b, c, d; e; the
/// sun's transmittance (0 for a type that hides the sun); the ground's radiance.
pub const ROW_SCALE: usize = 0;
pub const ROW_ABCD: usize = 1;
pub const ROW_E: usize = 2;
pub const ROW_SUN: usize = 3;
pub const ROW_GROUND: usize = 4;

/// Quadrature of the sky's illuminance on the ground: zenith-cosine and azimuth steps.
pub const GROUND_SKY_STEPS: [usize; 2] = [24, 24];

/// One of the fifteen types.
#[derive(Debug, Clone, PartialEq)]
pub struct SkyType {
    /// 1–15.
    pub number: u8,
    /// Gradation group (I–VI) and indicatrix group (1–6).
    pub gradation_group: String,
    pub indicatrix_group: u8,
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
    pub e: f64,
    /// Whether the type's sky shows the sun's disk.
    pub sun: bool,
    /// The standard's words.
    pub description: String,
}

impl SkyType {
    /// The gradation φ(Z) for a zenith cosine `cos_z`: 1 at and below the horizon.
    pub fn gradation(&self, cos_z: f64) -> f64 {
        if cos_z <= 0.0 {
            1.0
        } else {
            1.0 + self.a * (self.b / cos_z).exp()
        }
    }

    /// The indicatrix f(χ) at `chi` (rad) from the sun.
    pub fn indicatrix(&self, chi: f64) -> f64 {
        1.0 + self.c * ((self.d * chi).exp() - (self.d * FRAC_PI_2).exp())
            + self.e * chi.cos().powi(2)
    }

    /// L / L_z along a direction of zenith cosine `cos_z` at `chi` (rad) from the sun, the sun
    /// at zenith angle `sun_zenith` (rad).
    pub fn relative_luminance(&self, cos_z: f64, chi: f64, sun_zenith: f64) -> f64 {
        self.indicatrix(chi) * self.gradation(cos_z)
            / (self.indicatrix(sun_zenith) * self.gradation(1.0))
    }
}

/// The fifteen types of the embedded table, in order.
pub fn types() -> &'static [SkyType] {
    static T: OnceLock<Vec<SkyType>> = OnceLock::new();
    T.get_or_init(|| {
        let t = tables::cie_standard_general_sky();
        let n = |c: &str| t.numbers(c);
        let (number, a, b, c, d, e, sun, indicatrix) = (
            n("type"),
            n("a"),
            n("b"),
            n("c"),
            n("d"),
            n("e"),
            n("sun"),
            n("indicatrix"),
        );
        let (gradation, description) = (t.text("gradation"), t.text("description"));
        let all: Vec<SkyType> = (0..t.len())
            .map(|r| SkyType {
                number: number[r] as u8,
                gradation_group: gradation[r].to_string(),
                indicatrix_group: indicatrix[r] as u8,
                a: a[r],
                b: b[r],
                c: c[r],
                d: d[r],
                e: e[r],
                sun: sun[r] != 0.0,
                description: description[r].to_string(),
            })
            .collect();
        assert!(
            all.iter()
                .enumerate()
                .all(|(i, s)| usize::from(s.number) == i + 1)
                && all.len() == 15,
            "the CIE table lists types 1–15 in order"
        );
        all
    })
}

/// Type `number`, held to 1–15.
pub fn sky_type(number: u8) -> &'static SkyType {
    &types()[usize::from(number.clamp(1, 15)) - 1]
}

/// ∫ȳ(λ)·E_sun(λ) dλ over the visible range for the default solar spectrum at 1 AU, in the
/// renderer's luminance unit (W·m⁻²·nm⁻¹ × nm): the luminance of a spectrum equal to the solar
/// spectrum, to which each lane's solar irradiance is compared.
fn solar_luminance() -> f64 {
    static Y: OnceLock<f64> = OnceLock::new();
    *Y.get_or_init(|| {
        let (cmf, sun) = (cie1931(), SolarSpectrum::default());
        let mut y = 0.0;
        let mut l = VISIBLE_MIN_NM + 0.5;
        while l < VISIBLE_MAX_NM {
            y += cmf.y.sample(l) * sun.irradiance(l, 1.0);
            l += 1.0;
        }
        y
    })
}

/// The zenith luminance in the renderer's unit (Y = ∫ȳL dλ, W·m⁻²·sr⁻¹): Preetham et al.'s
/// (1999) formula at the scene's turbidity with the sun at zenith cosine `mu_s`.
pub fn zenith_luminance(p: &Params, mu_s: f64) -> f64 {
    let theta_s = mu_s.clamp(0.0, 1.0).acos();
    preetham::sky::zenith(preetham::turbidity(p), theta_s)[0].max(0.0)
        * preetham::kcd_per_m2_in_luminance_unit()
}

/// ∫ (L / L_z)·cos Z dω over the upper hemisphere for type `t` with the sun at zenith cosine
/// `mu_s` ([`GROUND_SKY_STEPS`]): the horizontal sky illuminance over the zenith luminance, sr.
pub fn illuminance_over_zenith(t: &SkyType, mu_s: f64) -> f64 {
    let sun_zenith = mu_s.clamp(-1.0, 1.0).acos();
    hemisphere_irradiance(mu_s, GROUND_SKY_STEPS, |mu, chi| {
        t.relative_luminance(mu, chi, sun_zenith)
    })
}

/// What the sky pass reads for batch `layer` of `p` with the sun at zenith cosine `mu_s`
/// ([`ROW_SCALE`] …): per lane the radiance per unit of f(χ)·φ(Z) (the zenith luminance over
/// f(Z_s)·φ(0), spread over the lanes as the solar spectrum), the type's a–e, the sun's
/// transmittance and the ground's radiance.
pub fn batch_rows(p: &Params, layer: usize, mu_s: f64) -> BatchRows {
    let t = sky_type(p.cie_sky_type);
    let b = &p.batches[layer];
    let sun_zenith = mu_s.clamp(-1.0, 1.0).acos();
    let luminance_to_lanes = b.solar_irradiance * (1.0 / solar_luminance());
    let zenith = luminance_to_lanes * zenith_luminance(p, mu_s);
    let mut rows = [Lanes::ZERO; super::shared::BATCH_MODEL_ROWS];
    rows[ROW_SCALE] = zenith * (1.0 / (t.indicatrix(sun_zenith) * t.gradation(1.0)));
    rows[ROW_ABCD] = Lanes([t.a, t.b, t.c, t.d]);
    rows[ROW_E] = Lanes([t.e, 0.0, 0.0, 0.0]);
    rows[ROW_SUN] = if t.sun {
        preetham::sun_transmittance(b.colour.wavelengths_nm, preetham::turbidity(p), mu_s)
    } else {
        Lanes::ZERO
    };
    let direct = b.solar_irradiance * rows[ROW_SUN] * mu_s.max(0.0);
    let sky = zenith * illuminance_over_zenith(t, mu_s);
    rows[ROW_GROUND] = Lanes::from_fn(|i| b.ground_albedo[i] / PI) * (direct + sky);
    debug_assert!(rows.iter().all(|r| r.0.len() == LANES));
    rows
}

/// The registry's constructor: the twin of the sky pass over [`batch_rows`].
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    Box::new(RowSky::new(
        params,
        batch_rows,
        sky::radiance,
        ROW_SUN,
        preetham::turbidity(params),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Scene, WavelengthSet};

    /// The standard's own examples. Type 12 is the CIE standard clear sky of 1973 (CIE
    /// 110-1994), published as L/L_z = (0.91 + 10·e^(−3χ) + 0.45·cos²χ)(1 − e^(−0.32/cos Z))
    /// / ((0.91 + 10·e^(−3Z_s) + 0.45·cos²Z_s)(1 − e^(−0.32))); type 1 stands for the CIE
    /// standard overcast sky of Moon and Spencer (1942), L/L_z = (1 + 2·cos Z)/3, whose
    /// horizon is a third of its zenith; type 5 is uniform.
    #[test]
    fn the_types_give_the_standards_published_skies() {
        let clear = sky_type(12);
        let published = |cos_z: f64, chi: f64, z_s: f64| {
            (0.91 + 10.0 * (-3.0 * chi).exp() + 0.45 * chi.cos().powi(2))
                * (1.0 - (-0.32 / cos_z).exp())
                / ((0.91 + 10.0 * (-3.0 * z_s).exp() + 0.45 * z_s.cos().powi(2))
                    * (1.0 - (-0.32f64).exp()))
        };
        for (z_deg, chi_deg, zs_deg) in [(0.0, 40.0, 40.0), (60.0, 90.0, 30.0), (85.0, 10.0, 80.0)]
        {
            let (z, chi, zs) = (
                f64::to_radians(z_deg),
                f64::to_radians(chi_deg),
                f64::to_radians(zs_deg),
            );
            let got = clear.relative_luminance(z.cos(), chi, zs);
            // The table's 0.91 is 1 − 10·e^(−3π/2) rounded: 0.1 % apart.
            assert!(
                (got / published(z.cos(), chi, zs) - 1.0).abs() < 2e-3,
                "{got}"
            );
        }
        let overcast = sky_type(1);
        for z_deg in [0.0, 30.0, 60.0, 90.0] {
            let z = f64::to_radians(z_deg);
            let got = overcast.relative_luminance(z.cos(), 1.0, 0.5);
            let moon_spencer = (1.0 + 2.0 * z.cos()) / 3.0;
            // The standard's type 1 is an exponential stand-in for Moon and Spencer's cosine:
            // within 0.03 of L_z everywhere, equal at the zenith and the horizon within 0.01.
            assert!(
                (got - moon_spencer).abs() < 0.03,
                "Z {z_deg}°: {got} vs {moon_spencer}"
            );
        }
        let horizon = overcast.relative_luminance(0.0, 1.0, 0.5);
        assert!((horizon - 1.0 / 3.0).abs() < 0.01, "{horizon}");
        let uniform = sky_type(5);
        assert_eq!(uniform.relative_luminance(0.3, 2.0, 0.4), 1.0);
        // The clear sky is darkest about 90° from the sun, brightest around it.
        let zs = 30f64.to_radians();
        assert!(
            clear.relative_luminance(0.5, 0.1, zs) > 5.0 * clear.relative_luminance(0.5, 1.6, zs)
        );
    }

    /// The zenith's luminance is the zenith luminance formula's, and the rows spread it over
    /// the lanes as the solar spectrum: its luminance over Spectral32 is the formula's.
    #[test]
    fn the_zenith_has_the_formulas_luminance() {
        let s = Scene::default();
        let atm = crate::atmosphere::Atmosphere::for_scene(&s);
        let p = Params::new(
            &atm,
            WavelengthSet::SpectralN(32),
            crate::scene::Quality::Low,
        );
        let mu_s = 40f64.to_radians().sin();
        let mut y = 0.0;
        for layer in 0..p.batches.len() {
            let rows = batch_rows(&p, layer, mu_s);
            let l = sky::sky(&rows, 1.0, mu_s);
            let to_xyz = crate::colour::linear_srgb_to_xyz;
            let rgb: [f64; 3] = std::array::from_fn(|r| {
                (0..LANES)
                    .map(|i| p.batches[layer].colour.to_srgb[r][i] * l[i])
                    .sum()
            });
            y += to_xyz(rgb).y;
        }
        let want = zenith_luminance(&p, mu_s);
        assert!((y / want - 1.0).abs() < 0.02, "{y} vs {want}");
        // Preetham's clear-sky zenith at T ≈ 2.5 and sun 40° up: a few kcd/m².
        let kcd = want / preetham::kcd_per_m2_in_luminance_unit();
        assert!((2.0..8.0).contains(&kcd), "{kcd}");
    }

    /// The overcast types hide the sun; the clear ones show it, and their ground is brighter.
    #[test]
    fn the_clear_types_show_the_sun() {
        let mut s = Scene::default();
        let mu_s = 0.5;
        let rows = |n: u8, s: &mut Scene| {
            s.render.cie_sky_type = n;
            let atm = crate::atmosphere::Atmosphere::for_scene(s);
            let p = Params::new(&atm, WavelengthSet::Spectral4, crate::scene::Quality::Low)
                .with_render(&s.render);
            batch_rows(&p, 0, mu_s)
        };
        let (overcast, clear) = (rows(1, &mut s), rows(12, &mut s));
        assert_eq!(overcast[ROW_SUN], Lanes::ZERO);
        assert!(
            clear[ROW_SUN].iter().all(|&t| t > 0.3 && t < 1.0),
            "{:?}",
            clear[ROW_SUN]
        );
        assert!(
            clear[ROW_GROUND]
                .iter()
                .zip(overcast[ROW_GROUND].iter())
                .all(|(c, o)| c > o)
        );
    }

    /// A type outside 1–15 is refused when the scene is checked.
    #[test]
    fn a_cie_type_outside_the_fifteen_is_refused() {
        let mut s = Scene::default();
        s.render.cie_sky_type = 16;
        let e = s.validate().expect_err("type 16 does not exist");
        assert!(e.iter().any(|f| f.path == "render.cie_sky_type"), "{e:?}");
    }
}
