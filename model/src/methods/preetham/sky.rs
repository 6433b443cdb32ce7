//! Preetham's sky pass: the Perez distribution in xyY for the sky, the direct sun on the
//! Lambertian ground. Twin of `shaders/preetham/sky.wgsl`.

use super::{
    BASIS_CENTRE_NM, BASIS_SCALE_NM, Constants, MIN_COS_THETA, kcd_per_m2_in_luminance_unit,
    spectral_basis, sun_transmittance,
};
use crate::geometry::{distance_to_ground, hits_ground};
use crate::methods::shared::sun_disk::visible_fraction;
use crate::methods::shared::{Lanes, Params};
use glam::DVec3;
use std::f64::consts::PI;

/// Perez et al.'s distribution F(θ, γ) = (1 + A·e^(B / cos θ))·(1 + C·e^(Dγ) + E·cos²γ) for
/// (Y, x, y), with A–E as `perez` holds them (rows A–E).
fn perez(perez: &[[f64; 3]; 5], cos_theta: f64, gamma: f64) -> [f64; 3] {
    let cos_theta = cos_theta.max(MIN_COS_THETA);
    std::array::from_fn(|q| {
        let [a, b, c, d, e] = [0, 1, 2, 3, 4].map(|k| perez[k][q]);
        (1.0 + a * (b / cos_theta).exp()) * (1.0 + c * (d * gamma).exp() + e * gamma.cos().powi(2))
    })
}

/// Zenith luminance (kcd/m²) and chromaticity x, y at turbidity `t` with the sun at zenith
/// angle `theta_s` (rad, 0–π/2).
pub fn zenith(t: f64, theta_s: f64) -> [f64; 3] {
    let c = Constants::published();
    let chi = (c.chi[0] - t / c.chi[1]) * (PI - 2.0 * theta_s);
    let [a, b, cc, d] = c.zenith_luminance;
    let y = (a * t + b) * chi.tan() + cc * t + d;
    let powers_t = [t * t, t, 1.0];
    let powers_theta = [theta_s.powi(3), theta_s.powi(2), theta_s, 1.0];
    let chromaticity = |m: &[[f64; 4]; 3]| -> f64 {
        (0..3)
            .map(|r| powers_t[r] * (0..4).map(|k| m[r][k] * powers_theta[k]).sum::<f64>())
            .sum()
    };
    [y, chromaticity(&c.zenith_x), chromaticity(&c.zenith_y)]
}

/// The sky's colour in XYZ (the renderer's unit: Y = ∫ȳL dλ, W·m⁻²·sr⁻¹) along a direction of
/// zenith cosine `mu` at cosine `nu` from the sun, the sun at zenith cosine `mu_s`, turbidity `t`.
pub fn xyz(t: f64, mu: f64, mu_s: f64, nu: f64) -> [f64; 3] {
    let c = Constants::published().perez(t);
    let theta_s = mu_s.clamp(0.0, 1.0).acos();
    let gamma = nu.clamp(-1.0, 1.0).acos();
    let here = perez(&c, mu, gamma);
    let at_zenith = perez(&c, 1.0, theta_s);
    let [y_z, x_z, yc_z] = zenith(t, theta_s);
    let luminance = (y_z * here[0] / at_zenith[0]).max(0.0) * kcd_per_m2_in_luminance_unit();
    let x = x_z * here[1] / at_zenith[1];
    let y = yc_z * here[2] / at_zenith[2];
    if y <= 0.0 {
        return [0.0; 3];
    }
    [x / y * luminance, luminance, (1.0 - x - y) / y * luminance]
}

/// The lanes of the spectrum E_sun(λ)·(c₀ + c₁u + c₂u²) whose colour is `xyz`.
pub fn spread(p: &Params, layer: usize, xyz: [f64; 3]) -> Lanes {
    let k = spectral_basis();
    let c: [f64; 3] = std::array::from_fn(|r| (0..3).map(|j| k[r][j] * xyz[j]).sum());
    let b = &p.batches[layer];
    Lanes::from_fn(|i| {
        let u = (b.colour.wavelengths_nm[i] - BASIS_CENTRE_NM) / BASIS_SCALE_NM;
        b.solar_irradiance[i] * (c[0] + c[1] * u + c[2] * u * u)
    })
}

/// The radiance of one batch seen from `position` (m from the planet's centre, altitude `h`)
/// along the unit direction `dir`, with the sun in direction `sun`, at turbidity `t`.
pub fn radiance(
    p: &Params,
    t: f64,
    layer: usize,
    (position, h): (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
) -> Lanes {
    let big_r = p.bottom_radius_m;
    let up = position.normalize();
    let (mu, mu_s, nu) = (dir.dot(up), sun.dot(up), dir.dot(sun));
    if !hits_ground(h, mu, big_r) {
        return spread(p, layer, xyz(t, mu, mu_s, nu));
    }
    let d = distance_to_ground(h, mu, big_r);
    let mu_s_g = (((big_r + h) * mu_s + d * nu) / big_r).clamp(-1.0, 1.0);
    let b = &p.batches[layer];
    let beam = sun_transmittance(b.colour.wavelengths_nm, t, mu_s_g);
    let lit = visible_fraction(0.0, mu_s_g, big_r) * mu_s_g.max(0.0) / PI;
    b.ground_albedo * b.solar_irradiance * beam * lit
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::colour::{Xyz, spectrum_to_xyz};
    use crate::spectrum::Spectrum;

    /// Preetham et al.'s own checks: at the zenith F(θ, γ)/F(0, θ_s) is 1, so the sky there is
    /// the zenith formula's luminance; the sky is brightest near the sun and darkest about 90°
    /// from it; more turbidity whitens the zenith (x and y rise).
    #[test]
    fn the_zenith_is_the_zenith_formula_and_the_sky_is_brightest_near_the_sun() {
        let t = 3.0;
        let (theta_s, mu_s) = (60f64.to_radians(), 60f64.to_radians().cos());
        let [y_z, x_z, yc_z] = zenith(t, theta_s);
        let at_zenith = xyz(t, 1.0, mu_s, mu_s);
        let unit = kcd_per_m2_in_luminance_unit();
        assert!((at_zenith[1] / (y_z * unit) - 1.0).abs() < 1e-12);
        let sum = at_zenith.iter().sum::<f64>();
        assert!((at_zenith[0] / sum - x_z).abs() < 1e-12);
        assert!((at_zenith[1] / sum - yc_z).abs() < 1e-12);
        // Published zenith luminance at T = 3, θ_s = 60°, worked by hand: χ = (4/9 − 3/120)·π/3,
        // (4.0453·3 − 4.9710)·tan χ − 0.2155·3 + 2.4192 = 5.14 kcd/m².
        assert!((y_z - 5.14).abs() < 0.01, "{y_z}");
        // Clear-sky zenith chromaticities lie near (0.25–0.30, 0.26–0.32).
        assert!((0.24..0.31).contains(&x_z) && (0.25..0.33).contains(&yc_z));
        let sun_dir = (theta_s.sin(), theta_s.cos());
        let along = |elevation_deg: f64, azimuth_deg: f64| {
            let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
            let mu = e.sin();
            let nu = e.cos() * a.cos() * sun_dir.0 + mu * sun_dir.1;
            xyz(t, mu, mu_s, nu)[1]
        };
        let near_sun = along(35.0, 0.0);
        let ninety = along(30.0, 90.0);
        assert!(near_sun > 3.0 * ninety, "{near_sun} vs {ninety}");
        let hazy = zenith(8.0, theta_s);
        assert!(hazy[1] > x_z && hazy[2] > yc_z);
    }

    /// The spread spectrum integrates back to the colour it was given, over a fine spectral set.
    #[test]
    fn the_spread_spectrum_has_the_colour_it_was_given() {
        let target = [0.9, 1.0, 1.4];
        let atm = crate::atmosphere::Atmosphere::for_scene(&crate::Scene::default());
        let set = crate::wavelengths::batches(crate::scene::WavelengthSet::SpectralN(96));
        let fine = Params::with_batches(&atm, set, crate::scene::Quality::Low);
        let mut w = Vec::new();
        let mut v = Vec::new();
        for layer in 0..fine.batches.len() {
            let l = spread(&fine, layer, target);
            for i in 0..4 {
                w.push(fine.batches[layer].colour.wavelengths_nm[i]);
                v.push(l[i]);
            }
        }
        let s = Spectrum::new(w, v).expect("increasing wavelengths");
        let Xyz { x, y, z } = spectrum_to_xyz(&s);
        for (got, want) in [x, y, z].into_iter().zip(target) {
            assert!((got / want - 1.0).abs() < 0.02, "{got} vs {want}");
        }
    }
}
