//! A ray of a table texel through the atmosphere, as the models that tabulate in-scattering per
//! (h, mu, mu_s, nu) integrate it (Bruneton 2017, Elek 2009): its length, the placement and
//! weights of its samples, the local angles at a sample, and single scattering along it without
//! phase functions. Twin of `shaders/common/ray.wgsl`.

use super::transmittance::{sun_transmittance, transmittance_between};
use super::{Lanes, Lut, Params, entry_into_atmosphere};
use crate::geometry::{altitude_along, distance_to_ground, distance_to_top, hits_ground};
use crate::wavelengths::LANES;
use glam::DVec3;

/// A point of a scattering table's domain: altitude (m), view and sun zenith cosines,
/// view–sun cosine, and whether the view ray ends on the ground.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coords {
    pub h: f64,
    pub mu: f64,
    pub mu_s: f64,
    pub nu: f64,
    pub ground: bool,
}

/// The camera's ray along the unit direction `dir` (camera at `position`, m from the planet's
/// centre, altitude `h`; sun in the unit direction `sun`) as the models that look a whole ray
/// up in their tables see it: at the camera, or where the ray enters the atmosphere when the
/// camera is above it; None when it misses the atmosphere.
pub fn camera_coords(
    p: &Params,
    (position, h): (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
) -> Option<Coords> {
    let up = position.normalize();
    let (mu, mu_s, nu) = (dir.dot(up), sun.dot(up), dir.dot(sun).clamp(-1.0, 1.0));
    let (h, mu, mu_s) = if h > p.thickness_m() {
        let (mu_e, mu_s_e) = entry_into_atmosphere(p, h, mu, mu_s, nu)?;
        (p.thickness_m(), mu_e, mu_s_e)
    } else {
        (h, mu, mu_s)
    };
    Some(Coords {
        h,
        mu,
        mu_s,
        nu,
        ground: hits_ground(h, mu, p.bottom_radius_m),
    })
}

/// What a looked-up ray `c` ends on, seen through the air: the ground, whose radiance
/// `ground(mu_s_g)` gives for the sun's zenith cosine where the ray meets it, or nothing (the
/// sun's disk is the view's to add, `SkyModel::sun`).
pub fn behind(
    p: &Params,
    t: &Lut,
    layer: usize,
    c: &Coords,
    ground: impl Fn(f64) -> Lanes,
) -> Lanes {
    let big_r = p.bottom_radius_m;
    if !c.ground {
        return Lanes::ZERO;
    }
    let d = distance_to_ground(c.h, c.mu, big_r);
    let mu_s_g = (((big_r + c.h) * c.mu_s + d * c.nu) / big_r).clamp(-1.0, 1.0);
    let tr = transmittance_between(p, t, layer, (c.h, c.mu), d);
    let g = ground(mu_s_g);
    tr * g
}

/// Length of the view ray of `c` to where it leaves the atmosphere (its ground flag decides).
pub fn ray_length(p: &Params, c: &Coords) -> f64 {
    if c.ground {
        distance_to_ground(c.h, c.mu, p.bottom_radius_m)
    } else {
        distance_to_top(c.h, c.mu, p.bottom_radius_m, p.top_radius_m)
    }
}

/// Sample `k` of the 2(n + 1) along the ray of `c`: distance and weight. The ray is cut at its
/// lowest point and each piece integrated by the trapezoid rule over n intervals in a variable
/// whose samples crowd quadratically towards that point, where the air and aerosols are dense:
/// uniform intervals put one sample in a 1.2 km aerosol layer along a zenith ray and
/// overestimate its scattering by half.
pub fn ray_sample(p: &Params, c: &Coords, k: u32, n: u32) -> (f64, f64) {
    let length = ray_length(p, c);
    let lowest = if c.ground {
        length
    } else if c.mu >= 0.0 {
        0.0
    } else {
        (-(p.bottom_radius_m + c.h) * c.mu).min(length)
    };
    let i = k % (n + 1);
    let s = f64::from(i) / f64::from(n);
    let trapezoid = if i == 0 || i == n { 0.5 } else { 1.0 } / f64::from(n);
    if k <= n {
        let a = lowest;
        (
            a * (1.0 - (1.0 - s) * (1.0 - s)),
            trapezoid * 2.0 * a * (1.0 - s),
        )
    } else {
        let b = length - lowest;
        (lowest + b * s * s, trapezoid * 2.0 * b * s)
    }
}

/// (altitude, view zenith cosine, sun zenith cosine) at distance `d` along the ray of `c`.
pub fn along(p: &Params, c: &Coords, d: f64) -> (f64, f64, f64) {
    let r = p.bottom_radius_m + c.h;
    let (h_d, r_d) = altitude_along(c.h, c.mu, d, p.bottom_radius_m);
    (
        h_d.max(0.0),
        ((r * c.mu + d) / r_d).clamp(-1.0, 1.0),
        ((r * c.mu_s + d * c.nu) / r_d).clamp(-1.0, 1.0),
    )
}

/// (Rayleigh, Mie) single scattering along the ray of `c` without phase functions,
/// W·m⁻²·nm⁻¹ (radiance times sr): the sun's irradiance through the transmittance to each
/// sample and from it to the start of the ray, times the local scattering coefficient.
pub fn single_scattering(p: &Params, t: &Lut, layer: usize, c: Coords) -> (Lanes, Lanes) {
    let n = p.steps.scattering;
    let (mut rayleigh, mut mie) = (Lanes::ZERO, Lanes::ZERO);
    for k in 0..2 * (n + 1) {
        let (d, w) = ray_sample(p, &c, k, n);
        let (h_d, _, mu_s_d) = along(p, &c, d);
        let to_camera = transmittance_between(p, t, layer, (c.h, c.mu), d);
        let to_sun = sun_transmittance(p, t, layer, h_d, mu_s_d);
        let m = p.medium(layer, h_d);
        for l in 0..LANES {
            let tr = w * to_camera[l] * to_sun[l];
            rayleigh[l] += tr * m.rayleigh_scattering[l];
            mie[l] += tr * m.aerosol_scattering[l];
        }
    }
    let e = p.batches[layer].solar_irradiance;
    (rayleigh * e, mie * e)
}
