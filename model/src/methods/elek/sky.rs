//! The sky pass of Elek (2009): a pixel's radiance from the two azimuth-free tables at the
//! camera's altitude and angles, Rayleigh times the modified Rayleigh phase and Mie times the
//! aerosol phase of the view–sun angle, plus the ground lit by the sun alone. A camera above the atmosphere looks up from where its ray
//! enters it. Twin of `shaders/elek/sky.wgsl`.

use super::{Lanes, Tables, look_up, modified_rayleigh_phase};
use crate::methods::shared::aerosol_phase;
use crate::methods::shared::ray::{behind, camera_coords};
use crate::methods::shared::transmittance::sunlit_ground;
use glam::DVec3;

/// The radiance of one batch seen from `at` (position from the planet's centre and altitude,
/// m) along the unit direction `dir`, with the sun in direction `sun` (the sun's disk
/// not included: `SkyModel::sun`).
pub fn radiance(tables: &Tables, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
    let p = &tables.params;
    let t = &tables.transmittance;
    let Some(c) = camera_coords(p, at, dir, sun) else {
        return Lanes::ZERO;
    };
    let rayleigh = look_up(p, &tables.rayleigh, layer, c.h, c.mu, c.mu_s);
    let mie = look_up(p, &tables.mie, layer, c.h, c.mu, c.mu_s);
    let (pr, pm) = (modified_rayleigh_phase(c.nu), aerosol_phase(p, layer, c.nu));
    let behind = behind(p, t, layer, &c, |mu_s_g| sunlit_ground(p, t, layer, mu_s_g));
    rayleigh * pr + mie * pm + behind
}
