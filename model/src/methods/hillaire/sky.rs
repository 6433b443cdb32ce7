//! The sky pass: the radiance of a pixel from the tables — sky view and transmittance for the
//! sky, aerial perspective (or sky view and transmittance beyond it) for the ground, a march
//! from the top of the atmosphere for a camera in space (Hillaire 2020 §6). Twin of
//! `shaders/hillaire/sky.wgsl`.

use super::{
    AERIAL_PERSPECTIVE_MAX_DISTANCE_M, Lanes, Params, Spacing, Tables, aerial_perspective,
    ground_irradiance, integrate_inscattering, sky_view, sun_transmittance, transmittance,
};
use crate::geometry::{distance_to_ground, distance_to_top, hits_ground};
use crate::methods::shared::{add, entry_into_atmosphere, mul, sun_relative_angles};
use glam::DVec3;
use std::f64::consts::PI;

/// Radiance of the sunlit, skylit Lambertian ground at a point where the sun's zenith cosine
/// is `mu_s_g`, per lane (W·m⁻²·sr⁻¹·nm⁻¹).
fn ground_radiance(p: &Params, tables: &Tables, layer: usize, mu_s_g: f64) -> Lanes {
    let b = &p.batches[layer];
    let sun_t = sun_transmittance(p, &tables.transmittance, layer, 0.0, mu_s_g);
    let sky = ground_irradiance(&tables.ground_irradiance, layer, mu_s_g);
    std::array::from_fn(|i| {
        b.ground_albedo[i] / PI * b.solar_irradiance[i] * (sun_t[i] * mu_s_g.max(0.0) + sky[i])
    })
}

/// The radiance of one batch seen from `position` (m from the planet's centre, altitude `h`)
/// along the unit direction `dir`, with the sun in direction `sun` (the sun's disk not included:
/// `SkyModel::sun`).
pub fn radiance(
    p: &Params,
    tables: &Tables,
    layer: usize,
    (position, h): (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
) -> Lanes {
    let big_r = p.bottom_radius_m;
    let top = p.top_radius_m;
    let thickness = p.thickness_m();
    let e = p.batches[layer].solar_irradiance;
    let r = big_r + h;
    let up = position.normalize();
    let (mu, mu_s, nu) = (dir.dot(up), sun.dot(up), dir.dot(sun));
    if h <= thickness {
        let (phi, theta) = sun_relative_angles(up, dir, sun);
        if hits_ground(h, mu, big_r) {
            let d = distance_to_ground(h, mu, big_r);
            let mu_s_g = ((r * mu_s + d * nu) / big_r).clamp(-1.0, 1.0);
            let lg = ground_radiance(p, tables, layer, mu_s_g);
            let (s, tr) = if d < AERIAL_PERSPECTIVE_MAX_DISTANCE_M {
                aerial_perspective(
                    p,
                    &tables.aerial_perspective_inscattering,
                    &tables.aerial_perspective_transmittance,
                    layer,
                    h,
                    phi,
                    theta,
                    d,
                )
            } else {
                let mu_g = ((r * mu + d) / big_r).clamp(-1.0, 1.0);
                let t_g = transmittance(p, &tables.transmittance, layer, 0.0, -mu_g);
                let t_c = transmittance(p, &tables.transmittance, layer, h, -mu);
                let tr = std::array::from_fn(|i| (t_g[i] / t_c[i].max(1e-30)).min(1.0));
                (
                    sky_view(p, &tables.sky_view, layer, h, phi, theta, true),
                    tr,
                )
            };
            add(s, mul(tr, lg))
        } else {
            sky_view(p, &tables.sky_view, layer, h, phi, theta, false)
        }
    } else {
        // Above the atmosphere: march from where the ray enters it.
        let Some((mu_e, mu_s_e)) = entry_into_atmosphere(p, h, mu, mu_s, nu) else {
            return [0.0; 4];
        };
        let ground = hits_ground(thickness, mu_e, big_r);
        let t_max = if ground {
            distance_to_ground(thickness, mu_e, big_r)
        } else {
            distance_to_top(thickness, mu_e, big_r, top)
        };
        let (s, tr) = integrate_inscattering(
            p,
            &tables.transmittance,
            &tables.multiple_scattering,
            layer,
            (thickness, mu_e, mu_s_e, nu),
            (0.0, t_max),
            p.steps.ray_march,
            if ground {
                Spacing::QuadraticToEnd
            } else {
                Spacing::Uniform
            },
        );
        let behind = if ground {
            let mu_s_g = ((top * mu_s_e + t_max * nu) / big_r).clamp(-1.0, 1.0);
            ground_radiance(p, tables, layer, mu_s_g)
        } else {
            [0.0; 4]
        };
        std::array::from_fn(|i| s[i] * e[i] + tr[i] * behind[i])
    }
}
