//! The sky pass: the radiance of a pixel from the tables — sky view and transmittance for the
//! sky, aerial perspective (or sky view and transmittance beyond it) for the ground, a march
//! from the top of the atmosphere for a camera in space (Hillaire 2020 §6). Twin of
//! `shaders/hillaire/sky.wgsl`.

use super::{
    AERIAL_PERSPECTIVE_MAX_DISTANCE_M, Lanes, Params, Spacing, Tables, aerial_perspective,
    ground_irradiance, integrate_inscattering, sky_view, sun_transmittance, transmittance,
};
use crate::geometry::{distance_to_ground, distance_to_top, hits_ground};
use crate::methods::shared::{entry_into_atmosphere, sun_relative_angles};
use glam::DVec3;
use std::f64::consts::PI;

/// Radiance of the sunlit, skylit Lambertian ground at a point where the sun's zenith cosine
/// is `mu_s_g`, per lane (W·m⁻²·sr⁻¹·nm⁻¹).
fn ground_radiance(p: &Params, tables: &Tables, layer: usize, mu_s_g: f64) -> Lanes {
    let b = &p.batches[layer];
    let sun_t = sun_transmittance(p, &tables.transmittance, layer, 0.0, mu_s_g);
    let sky = ground_irradiance(&tables.ground_irradiance, layer, mu_s_g);
    Lanes::from_fn(|i| {
        b.ground_albedo[i] / PI * b.solar_irradiance[i] * (sun_t[i] * mu_s_g.max(0.0) + sky[i])
    })
}

/// The camera altitude (m) from which the transmittance to the ground comes from the
/// transmittance table's ratio instead of the aerial-perspective volume: from higher up the
/// volume's rows and slices fall 10–23 % short towards distant ground at grazing angles (from
/// 3, 5 and 10 km) where the ratio stays within 1 %; lower down, the ratio of two near-horizontal
/// table values near the ground is the one that errs (5–19 % high from 30 m) and the volume
/// stays within 2 %. At 300 m both are within 2 %.
pub const GROUND_TRANSMITTANCE_FROM_TABLE_ABOVE_M: f64 = 300.0;

/// In-scattered radiance (per unit solar irradiance × irradiance, as the sky view gives it) and
/// transmittance from the camera at altitude `h` along zenith cosine `mu`, sun-relative angles
/// `(phi, theta)`, to the ground `d` metres away: the aerial-perspective volume within its
/// range, else the sky view's ground half; the transmittance from the table's ratio above
/// [`GROUND_TRANSMITTANCE_FROM_TABLE_ABOVE_M`] or beyond the volume.
pub fn ground_path(
    p: &Params,
    tables: &Tables,
    layer: usize,
    (h, mu): (f64, f64),
    (phi, theta): (f64, f64),
    d: f64,
) -> (Lanes, Lanes) {
    let big_r = p.bottom_radius_m;
    let ratio = || {
        let mu_g = (((big_r + h) * mu + d) / big_r).clamp(-1.0, 1.0);
        let t_g = transmittance(p, &tables.transmittance, layer, 0.0, -mu_g);
        let t_c = transmittance(p, &tables.transmittance, layer, h, -mu);
        t_g.zip_map(t_c, |g, c| (g / c.max(1e-30)).min(1.0))
    };
    if d < AERIAL_PERSPECTIVE_MAX_DISTANCE_M {
        let (s, tr) = aerial_perspective(
            p,
            &tables.aerial_perspective_inscattering,
            &tables.aerial_perspective_transmittance,
            layer,
            h,
            phi,
            theta,
            d,
        );
        if h < GROUND_TRANSMITTANCE_FROM_TABLE_ABOVE_M {
            (s, tr)
        } else {
            (s, ratio())
        }
    } else {
        (
            sky_view(p, &tables.sky_view, layer, h, phi, theta, true),
            ratio(),
        )
    }
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
            let (s, tr) = ground_path(p, tables, layer, (h, mu), (phi, theta), d);
            s + (tr * lg)
        } else {
            sky_view(p, &tables.sky_view, layer, h, phi, theta, false)
        }
    } else {
        // Above the atmosphere: march from where the ray enters it.
        let Some((mu_e, mu_s_e)) = entry_into_atmosphere(p, h, mu, mu_s, nu) else {
            return Lanes::ZERO;
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
            Lanes::ZERO
        };
        s * e + tr * behind
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{altitude_along, distance_to_boundary};
    use crate::methods::hillaire::aerial_perspective::aerial_perspective_angles_from_texel;
    use crate::methods::shared::Viewpoint;
    use crate::methods::shared::direction_from_phi_theta;
    use crate::methods::shared::optics::tests::params;

    /// The transmittance to the ground a ground pixel gets follows a fine march to that
    /// ground on and between the aerial-perspective volume's rows near the horizon: within 4 %
    /// from 30 m (the volume; 1 km of ground or more) and within 2.5 % from 300 m to 10 km (the
    /// table's ratio, where the volume fell 10–23 % short at 3–10 km).
    #[test]
    fn the_transmittance_to_the_ground_follows_the_exact_from_every_height() {
        let p = params();
        for h in [30.0, 300.0, 1000.0, 5000.0, 10_000.0] {
            let tables = Tables::compute(&p, Viewpoint { h, mu_s: 0.5 });
            for fy in [0.0f64, 0.5, 1.5, 2.5, 4.5, 8.5, 12.5] {
                let (phi, theta) = aerial_perspective_angles_from_texel(&p, h, 3.0, fy);
                let mu = direction_from_phi_theta(phi, theta).z;
                let d = distance_to_boundary(h, mu, p.bottom_radius_m, p.top_radius_m);
                if d < 1_000.0 {
                    continue;
                }
                let (_, got) = ground_path(&p, &tables, 0, (h, mu), (phi, theta), d);
                let n = 4000;
                let mut exact = [0.0; 4];
                for s in 0..n {
                    let x = (f64::from(s) + 0.5) * d / f64::from(n);
                    let e = p
                        .medium(0, altitude_along(h, mu, x, p.bottom_radius_m).0)
                        .extinction;
                    for l in 0..4 {
                        exact[l] += e[l] * d / f64::from(n);
                    }
                }
                let bound = if h < GROUND_TRANSMITTANCE_FROM_TABLE_ABOVE_M {
                    0.04
                } else {
                    0.025
                };
                for l in 0..4 {
                    let ratio = -got[l].ln() / exact[l];
                    assert!(
                        (ratio - 1.0).abs() < bound,
                        "h {h} m, row {fy}, ground {:.1} km: depth ratio {ratio}",
                        d / 1000.0
                    );
                }
            }
        }
    }
}
