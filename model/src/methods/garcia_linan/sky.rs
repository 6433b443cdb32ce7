//! The sky pass of García Liñán (2023): a pixel's radiance from the sky texture, the sun's disk
//! through the transmittance table, and the sunlit ground behind the in-scattering; from above
//! the atmosphere each pixel is marched with the model's integrand from where it enters. Twin
//! of `shaders/garcia_linan/sky.wgsl`.

use super::sky_texture::sky_texture;
use super::{Lanes, Tables, ground_radiance, integrate};
use crate::geometry::{distance_to_boundary, distance_to_ground, hits_ground};
use crate::methods::shared::sun_disk;
use crate::methods::shared::transmittance::{transmittance, transmittance_between};
use glam::DVec3;
use std::f64::consts::FRAC_PI_2;

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
    let t = &tables.transmittance;
    let big_r = p.bottom_radius_m;
    let top = p.top_radius_m;
    let thickness = p.thickness_m();
    let e = p.batches[layer].solar_irradiance;
    let r = big_r + h;
    let up = position.normalize();
    let (mu, mu_s, nu) = (dir.dot(up), sun.dot(up), dir.dot(sun));
    let disk = sun_disk(dir, sun);
    if h <= thickness {
        let dir_t = dir - up * mu;
        let sun_t = sun - up * mu_s;
        let l = dir_t.length() * sun_t.length();
        let cos_phi = if l > 1e-12 { dir_t.dot(sun_t) / l } else { 1.0 };
        let phi = cos_phi.clamp(-1.0, 1.0).acos();
        let elevation = FRAC_PI_2 - mu.clamp(-1.0, 1.0).acos();
        let s = sky_texture(&tables.sky_texture, layer, phi, elevation);
        if hits_ground(h, mu, big_r) {
            let d = distance_to_ground(h, mu, big_r);
            let mu_s_g = ((r * mu_s + d * nu) / big_r).clamp(-1.0, 1.0);
            let lg = ground_radiance(p, t, layer, mu_s_g);
            let tr = transmittance_between(p, t, layer, (h, mu), d, true);
            std::array::from_fn(|i| s[i] + tr[i] * lg[i])
        } else {
            let tr = transmittance(p, t, layer, h, mu);
            std::array::from_fn(|i| s[i] + tr[i] * e[i] * disk)
        }
    } else {
        let disc = r * r * mu * mu - (h - thickness) * (r + top);
        if mu >= 0.0 || disc < 0.0 {
            return e.map(|e| e * disk);
        }
        let t_entry = -r * mu - disc.sqrt();
        let mu_e = ((r * mu + t_entry) / top).clamp(-1.0, 1.0);
        let mu_s_e = ((r * mu_s + t_entry * nu) / top).clamp(-1.0, 1.0);
        let t_max = distance_to_boundary(thickness, mu_e, big_r, top);
        let (s, tr) = integrate(
            p,
            t,
            &tables.constants,
            layer,
            (thickness, mu_e, mu_s_e, nu),
            (0.0, t_max),
            p.steps.ray_march,
        );
        let behind = if hits_ground(thickness, mu_e, big_r) {
            let mu_s_g = ((top * mu_s_e + t_max * nu) / big_r).clamp(-1.0, 1.0);
            ground_radiance(p, t, layer, mu_s_g)
        } else {
            e.map(|e| e * disk)
        };
        std::array::from_fn(|i| s[i] * e[i] + tr[i] * behind[i])
    }
}
