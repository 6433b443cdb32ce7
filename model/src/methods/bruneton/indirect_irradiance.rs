//! Bruneton (2017) pass "indirect irradiance": the sky irradiance of order n − 1 on a
//! horizontal surface, the delta tables integrated over the upper hemisphere (midpoint rule),
//! added to the sky-irradiance sum. Twin of `shaders/bruneton/indirect_irradiance.wgsl`.

use super::{Deltas, Lanes, Params, mu_s_texel, mu_texel, nu_texel, previous_order, r_texel};
use crate::wavelengths::LANES;
use glam::DVec3;
use std::f64::consts::FRAC_PI_2;

/// Sky irradiance of the order held by the delta tables, W·m⁻²·nm⁻¹.
pub fn indirect_irradiance(p: &Params, delta: Deltas, layer: usize, h: f64, mu_s: f64) -> Lanes {
    let n = p.steps.sphere_directions;
    let step = FRAC_PI_2 / f64::from(n);
    let sun = DVec3::new((1.0 - mu_s * mu_s).max(0.0).sqrt(), 0.0, mu_s);
    let (x_mu_s, x_r) = (mu_s_texel(p, mu_s), r_texel(p, h));
    let mut e = Lanes::ZERO;
    for l in 0..n {
        let theta = (f64::from(l) + 0.5) * step;
        let (sin_t, cos_t) = theta.sin_cos();
        let x_mu = mu_texel(p, h, cos_t, false);
        for k in 0..4 * n {
            let phi = (f64::from(k) + 0.5) * step;
            let (sin_p, cos_p) = phi.sin_cos();
            let w = DVec3::new(cos_p * sin_t, sin_p * sin_t, cos_t);
            let nu = w.dot(sun).clamp(-1.0, 1.0);
            let l_in = previous_order(p, delta, layer, [x_mu_s, nu_texel(nu), x_mu, x_r], nu);
            for i in 0..LANES {
                e[i] += l_in[i] * cos_t * sin_t * step * step;
            }
        }
    }
    e
}
