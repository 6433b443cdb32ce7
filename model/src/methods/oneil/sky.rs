//! O'Neil's sky pass: the view ray in [`super::SAMPLES`] samples, every optical depth from the
//! fitted scale function; the chapter's ground formulation for rays that meet the ground. Twin
//! of `shaders/oneil/sky.wgsl`.

use super::ScaleFit;
use crate::geometry::{altitude_along, distance_to_ground, distance_to_top};
use crate::methods::shared::ray::camera_coords;
use crate::methods::shared::{Lanes, Params};
use glam::DVec3;
use std::f64::consts::PI;

/// Extinction per lane of batch `layer` per unit of the fit's column (m⁻¹ at the ground
/// densities): air's scattering and the aerosol's extinction; no ozone.
pub fn extinction(p: &Params, fit: &ScaleFit, layer: usize) -> Lanes {
    let b = &p.batches[layer];
    b.rayleigh_scattering * fit.air_at_ground
        + (b.aerosol_scattering + b.aerosol_absorption) * fit.aerosol_at_ground
}

/// The chapter's phase functions at view–sun cosine `nu`, sr⁻¹: Rayleigh 3/4·(1 + ν²) and the
/// aerosol's 3(1 − g²)/(2(2 + g²))·(1 + ν²)/(1 + g² − 2gν)^(3/2), each over 4π.
pub fn phases(p: &Params, layer: usize, nu: f64) -> (f64, Lanes) {
    let rayleigh = 0.75 * (1.0 + nu * nu) / (4.0 * PI);
    let aerosol = p.batches[layer].aerosol_g.map(|g| {
        1.5 * (1.0 - g * g) / (2.0 + g * g) * (1.0 + nu * nu)
            / (1.0 + g * g - 2.0 * g * nu).powf(1.5)
            / (4.0 * PI)
    });
    (rayleigh, aerosol)
}

/// The radiance of one batch seen from `position` (m from the planet's centre, altitude `h`)
/// along the unit direction `dir`, with the sun in direction `sun` (the disk not included).
pub fn radiance(
    p: &Params,
    fit: &ScaleFit,
    layer: usize,
    at: (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
) -> Lanes {
    let Some(c) = camera_coords(p, at, dir, sun) else {
        return Lanes::ZERO;
    };
    let (big_r, top) = (p.bottom_radius_m, p.top_radius_m);
    let b = &p.batches[layer];
    let depth_per_column = extinction(p, fit, layer) * fit.scale_height_m;
    let r0 = big_r + c.h;
    let n = super::SAMPLES;
    let t_max = if c.ground {
        distance_to_ground(c.h, c.mu, big_r)
    } else {
        distance_to_top(c.h, c.mu, big_r, top)
    };
    let dt = t_max / f64::from(n);
    // Angles at distance t along the ray: view and sun zenith cosines, and the altitude.
    let at_t = |t: f64| {
        let (h_t, r_t) = altitude_along(c.h, c.mu, t, big_r);
        (
            h_t,
            ((r0 * c.mu + t) / r_t).clamp(-1.0, 1.0),
            ((r0 * c.mu_s + t * c.nu) / r_t).clamp(-1.0, 1.0),
        )
    };
    let scattering_air = b.rayleigh_scattering * fit.air_at_ground;
    let scattering_aerosol = b.aerosol_scattering * fit.aerosol_at_ground;
    if !c.ground {
        let start = fit.density(c.h) * fit.scale(c.mu);
        let mut front = Lanes::ZERO;
        for k in 0..n {
            let (h_k, mu_k, mu_s_k) = at_t((f64::from(k) + 0.5) * dt);
            let density = fit.density(h_k);
            let scatter = start + density * (fit.scale(mu_s_k) - fit.scale(mu_k));
            front += (depth_per_column * -scatter).exp() * (density * dt);
        }
        let (phase_r, phase_a) = phases(p, layer, c.nu);
        return b.solar_irradiance
            * (scattering_air * phase_r + scattering_aerosol * phase_a)
            * front;
    }
    // The ground: the angles where the ray meets it, looking back up towards the camera.
    let (_, mu_g, mu_s_g) = at_t(t_max);
    let camera_scale = fit.scale(-mu_g);
    let camera_offset = fit.density(c.h) * camera_scale;
    let both = fit.scale(mu_s_g) + camera_scale;
    let mut front = Lanes::ZERO;
    for k in 0..n {
        let (h_k, _, _) = at_t((f64::from(k) + 0.5) * dt);
        let density = fit.density(h_k);
        front += (depth_per_column * -(density * both - camera_offset)).exp() * (density * dt);
    }
    let isotropic = 1.0 / (4.0 * PI);
    let in_scattered =
        b.solar_irradiance * (scattering_air + scattering_aerosol) * isotropic * front;
    let through = (depth_per_column * -(both - camera_offset)).exp();
    let surface = Lanes::from_fn(|i| {
        b.ground_albedo[i] / PI * b.solar_irradiance[i] * mu_s_g.max(0.0) * through[i]
    });
    in_scattered + surface
}
