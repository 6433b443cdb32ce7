//! Elek (2009) pass "gather": the last order's Rayleigh and Mie tables gathered over the sphere
//! around a point, each with its own phase function between the gathered direction and the
//! view (Rayleigh feeds Rayleigh, Mie feeds Mie). The table looked up is azimuth-free, so every
//! direction of a zenith ring reads the same texel: one look-up per ring, weighted by the
//! phase function summed over the ring. Midpoint rule in zenith and azimuth; by symmetry about
//! the view's plane, half the azimuths counted twice. Twin of `shaders/elek/gather.wgsl`.

use super::{Lanes, Lut, Params, texel_from_h_mu_mu_s};
use crate::methods::shared::{aerosol_phase, rayleigh_phase};
use crate::wavelengths::LANES;
use std::f64::consts::PI;

/// (Rayleigh, Mie) radiance of the last order arriving at altitude `h` from every direction,
/// weighted by the phase function towards the view direction of zenith cosine `mu`, with the
/// sun at zenith cosine `mu_s`, W·m⁻²·nm⁻¹ (per unit phase, as the tables store it).
pub fn gather(
    p: &Params,
    delta: (&Lut, &Lut),
    layer: usize,
    h: f64,
    mu: f64,
    mu_s: f64,
) -> (Lanes, Lanes) {
    let n = p.steps.sphere_directions;
    let step = PI / f64::from(n);
    let sin_v = (1.0 - mu * mu).max(0.0).sqrt();
    let (mut rayleigh, mut mie) = ([0.0; LANES], [0.0; LANES]);
    for l in 0..n {
        let theta = (f64::from(l) + 0.5) * step;
        let (sin_t, cos_t) = theta.sin_cos();
        let [fx, fy, fz] = texel_from_h_mu_mu_s(p, h, cos_t, mu_s);
        let (r, m) = (
            delta.0.trilinear(layer, fx, fy, fz),
            delta.1.trilinear(layer, fx, fy, fz),
        );
        let (mut w_r, mut w_m) = ([0.0; LANES], [0.0; LANES]);
        for k in 0..n {
            let phi = (f64::from(k) + 0.5) * step;
            let nu = (sin_t * phi.cos() * sin_v + cos_t * mu).clamp(-1.0, 1.0);
            let (pr, pm) = (rayleigh_phase(p, layer, nu), aerosol_phase(p, layer, nu));
            for i in 0..LANES {
                w_r[i] += pr[i];
                w_m[i] += pm[i];
            }
        }
        let d_omega = 2.0 * step * step * sin_t;
        for i in 0..LANES {
            rayleigh[i] += r[i] * w_r[i] * d_omega;
            mie[i] += m[i] * w_m[i] * d_omega;
        }
    }
    (Lanes(rayleigh), Lanes(mie))
}
