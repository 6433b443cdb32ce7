//! Bruneton (2017) pass "scattering density": J of order n at every texel, the radiance of
//! order n − 1 arriving from every direction of the sphere (the delta tables, plus the ground
//! lit by the delta irradiance of order n − 2 where a direction meets it) scattered towards the
//! view direction. Midpoint rule over zenith and azimuth. Twin of
//! `shaders/bruneton/scattering_density.wgsl`.

use super::{
    Coords, Deltas, Lanes, Lut, Params, aerosol_phase, irradiance, mu_s_texel, mu_texel, nu_texel,
    previous_order, r_texel, rayleigh_phase,
};
use crate::geometry::{distance_to_ground, hits_ground};
use crate::methods::shared::transmittance::transmittance_between;
use crate::wavelengths::LANES;
use glam::DVec3;
use std::f64::consts::PI;

/// The view and sun directions of `c` in a frame whose z is the local vertical.
pub fn local_frame(c: &Coords) -> (DVec3, DVec3) {
    let view = DVec3::new((1.0 - c.mu * c.mu).max(0.0).sqrt(), 0.0, c.mu);
    let s_x = if view.x == 0.0 {
        0.0
    } else {
        (c.nu - c.mu * c.mu_s) / view.x
    };
    let sun = DVec3::new(
        s_x,
        (1.0 - s_x * s_x - c.mu_s * c.mu_s).max(0.0).sqrt(),
        c.mu_s,
    );
    (view, sun)
}

/// Scattering density J at `c`, W·m⁻³·sr⁻¹·nm⁻¹.
pub fn scattering_density(
    p: &Params,
    t: &Lut,
    delta: Deltas,
    delta_irradiance: &Lut,
    layer: usize,
    c: Coords,
) -> Lanes {
    let big_r = p.bottom_radius_m;
    let r = big_r + c.h;
    let (view, sun) = local_frame(&c);
    let n = p.steps.sphere_directions;
    let step = PI / f64::from(n);
    let m = p.medium(layer, c.h);
    let albedo = p.batches[layer].ground_albedo;
    // mu_s and r are the same for every direction, mu for every azimuth: map them once.
    let (x_mu_s, x_r) = (mu_s_texel(p, c.mu_s), r_texel(p, c.h));
    let mut j = Lanes::ZERO;
    for l in 0..n {
        let theta = (f64::from(l) + 0.5) * step;
        let (sin_t, cos_t) = theta.sin_cos();
        let ground = hits_ground(c.h, cos_t, big_r);
        let (d_g, t_g) = if ground {
            let d = distance_to_ground(c.h, cos_t, big_r);
            (d, transmittance_between(p, t, layer, (c.h, cos_t), d))
        } else {
            (0.0, Lanes::ZERO)
        };
        let x_mu = mu_texel(p, c.h, cos_t, ground);
        let d_omega = step * step * sin_t;
        for k in 0..2 * n {
            let phi = (f64::from(k) + 0.5) * step;
            let (sin_p, cos_p) = phi.sin_cos();
            let w = DVec3::new(cos_p * sin_t, sin_p * sin_t, cos_t);
            let nu = sun.dot(w).clamp(-1.0, 1.0);
            let texel = [x_mu_s, nu_texel(nu), x_mu, x_r];
            let mut radiance = previous_order(p, delta, layer, texel, nu);
            if ground {
                let normal = (DVec3::Z * r + w * d_g).normalize();
                let e = irradiance(p, delta_irradiance, layer, 0.0, normal.dot(sun));
                for i in 0..LANES {
                    radiance[i] += t_g[i] * albedo[i] / PI * e[i];
                }
            }
            let nu_v = view.dot(w).clamp(-1.0, 1.0);
            let (pr, pm) = (
                rayleigh_phase(p, layer, nu_v),
                aerosol_phase(p, layer, nu_v),
            );
            for i in 0..LANES {
                j[i] += radiance[i]
                    * (m.rayleigh_scattering[i] * pr[i] + m.aerosol_scattering[i] * pm[i])
                    * d_omega;
            }
        }
    }
    j
}
