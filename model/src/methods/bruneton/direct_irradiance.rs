//! Bruneton (2017) pass "direct irradiance": sunlight on a horizontal surface through the
//! transmittance table, the sun's disk partly below the surface's plane near mu_s = 0. It
//! seeds the delta-irradiance table the first scattering density reads (the ground bounce of
//! order 2) and clears the sky-irradiance sum. Twin of `shaders/bruneton/direct_irradiance.wgsl`.

use super::{Lanes, Lut, Params};
use crate::constants::SUN_ANGULAR_RADIUS_RAD;
use crate::methods::shared::transmittance::transmittance;

/// The visible part of mu_s for a horizontal surface: mu_s above the disk's size, a quadratic
/// ramp across it, 0 below.
pub fn cosine_factor(mu_s: f64) -> f64 {
    let a = SUN_ANGULAR_RADIUS_RAD;
    if mu_s < -a {
        0.0
    } else if mu_s > a {
        mu_s
    } else {
        (mu_s + a) * (mu_s + a) / (4.0 * a)
    }
}

/// Direct solar irradiance on a horizontal surface at altitude `h`, W·m⁻²·nm⁻¹.
pub fn direct_irradiance(p: &Params, t: &Lut, layer: usize, h: f64, mu_s: f64) -> Lanes {
    let e = p.batches[layer].solar_irradiance;
    let tr = transmittance(p, t, layer, h, mu_s);
    let c = cosine_factor(mu_s);
    e * tr * c
}
