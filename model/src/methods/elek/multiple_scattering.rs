//! Elek (2009) pass "multiple scattering": order k of every texel, the gathered order k − 1
//! times the local Rayleigh or Mie scattering coefficient, integrated along the texel's ray
//! through the transmittance (no sun transmittance: the light was gathered where it scattered).
//! Becomes the last order the next gather reads ([`super::accumulate`] adds it to the sums). Twin of
//! `shaders/elek/multiple_scattering.wgsl`.

use super::{Coords, Lanes, Lut, Params, texel_from_h_mu_mu_s};
use crate::methods::shared::ray::{along, ray_sample};
use crate::methods::shared::transmittance::transmittance_between;
use crate::wavelengths::LANES;

/// (Rayleigh, Mie) in-scattering of the order whose gathered tables are `gathered` along the
/// ray of `c`, W·m⁻²·nm⁻¹ (per unit phase).
pub fn multiple_scattering(
    p: &Params,
    t: &Lut,
    gathered: (&Lut, &Lut),
    layer: usize,
    c: Coords,
) -> (Lanes, Lanes) {
    let n = p.steps.scattering;
    let (mut rayleigh, mut mie) = ([0.0; LANES], [0.0; LANES]);
    for k in 0..2 * (n + 1) {
        let (d, w) = ray_sample(p, &c, k, n);
        let (h_d, mu_d, mu_s_d) = along(p, &c, d);
        let [fx, fy, fz] = texel_from_h_mu_mu_s(p, h_d, mu_d, mu_s_d);
        let (g_r, g_m) = (
            gathered.0.trilinear(layer, fx, fy, fz),
            gathered.1.trilinear(layer, fx, fy, fz),
        );
        let tr = transmittance_between(p, t, layer, (c.h, c.mu), d);
        let m = p.medium(layer, h_d);
        for l in 0..LANES {
            rayleigh[l] += w * tr[l] * m.rayleigh_scattering[l] * g_r[l];
            mie[l] += w * tr[l] * m.aerosol_scattering[l] * g_m[l];
        }
    }
    (Lanes(rayleigh), Lanes(mie))
}
