//! The sky pass of Elek (2009): a pixel's radiance from the two azimuth-free tables at the
//! camera's altitude and angles, Rayleigh times the modified Rayleigh phase and Mie times the
//! aerosol phase of the view–sun angle, plus the sun's disk through the transmittance table or
//! the ground lit by the sun alone. A camera above the atmosphere looks up from where its ray
//! enters it. Twin of `shaders/elek/sky.wgsl`.

use super::{Lanes, Tables, look_up, modified_rayleigh_phase};
use crate::geometry::{distance_to_ground, hits_ground};
use crate::methods::shared::aerosol_phase;
use crate::methods::shared::transmittance::{sunlit_ground, transmittance, transmittance_between};
use crate::methods::shared::{entry_into_atmosphere, sun_disk};
use glam::DVec3;

/// The radiance of one batch seen from `position` (m from the planet's centre, altitude `h`)
/// along the unit direction `dir`, with the sun in direction `sun`.
pub fn radiance(
    tables: &Tables,
    layer: usize,
    (position, h): (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
) -> Lanes {
    let p = &tables.params;
    let big_r = p.bottom_radius_m;
    let e = p.batches[layer].solar_irradiance;
    let up = position.normalize();
    let (mu, mu_s, nu) = (dir.dot(up), sun.dot(up), dir.dot(sun).clamp(-1.0, 1.0));
    let disk = sun_disk(dir, sun);
    let (h, mu, mu_s) = if h > p.thickness_m() {
        match entry_into_atmosphere(p, h, mu, mu_s, nu) {
            Some((mu_e, mu_s_e)) => (p.thickness_m(), mu_e, mu_s_e),
            None => return e.map(|e| e * disk),
        }
    } else {
        (h, mu, mu_s)
    };
    let rayleigh = look_up(p, &tables.rayleigh, layer, h, mu, mu_s);
    let mie = look_up(p, &tables.mie, layer, h, mu, mu_s);
    let (pr, pm) = (modified_rayleigh_phase(nu), aerosol_phase(p, layer, nu));
    let t = &tables.transmittance;
    let (tr, behind) = if hits_ground(h, mu, big_r) {
        let d = distance_to_ground(h, mu, big_r);
        let mu_s_g = (((big_r + h) * mu_s + d * nu) / big_r).clamp(-1.0, 1.0);
        (
            transmittance_between(p, t, layer, (h, mu), d),
            sunlit_ground(p, t, layer, mu_s_g),
        )
    } else {
        (transmittance(p, t, layer, h, mu), e.map(|e| e * disk))
    };
    std::array::from_fn(|i| rayleigh[i] * pr + mie[i] * pm[i] + tr[i] * behind[i])
}
