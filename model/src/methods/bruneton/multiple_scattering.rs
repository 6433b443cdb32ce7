//! Bruneton (2017) pass "multiple scattering": the radiance of order n at every texel, J of
//! order n integrated along the view ray through the transmittance, stored over
//! the Rayleigh phase so that the sum with single Rayleigh takes one phase at look-up; it
//! becomes the delta the next order reads, and is added to the scattering sum. Twin of
//! `shaders/bruneton/multiple_scattering.wgsl`.

use super::{Coords, Lanes, Lut, Params, rayleigh_phase, scattering};
use crate::methods::shared::ray::{along, ray_sample};
use crate::methods::shared::transmittance::transmittance_between;
use crate::wavelengths::LANES;

/// Radiance of the order whose scattering density is `density`, over the Rayleigh phase at
/// the texel's nu (W·m⁻²·nm⁻¹).
pub fn multiple_scattering(p: &Params, t: &Lut, density: &Lut, layer: usize, c: Coords) -> Lanes {
    let n = p.steps.scattering;
    let mut s = Lanes::ZERO;
    for k in 0..2 * (n + 1) {
        let (d, w) = ray_sample(p, &c, k, n);
        let (h_d, mu_d, mu_s_d) = along(p, &c, d);
        let at = Coords {
            h: h_d,
            mu: mu_d,
            mu_s: mu_s_d,
            nu: c.nu,
            ground: c.ground,
        };
        let j = scattering(p, density, layer, at);
        let tr = transmittance_between(p, t, layer, (c.h, c.mu), d);
        for l in 0..LANES {
            s[l] += w * j[l] * tr[l];
        }
    }
    let pr = rayleigh_phase(p, layer, c.nu);
    s / pr
}
