//! The sky pass of García Liñán (2023): a pixel's radiance from the sky texture and the
//! sunlit ground behind the in-scattering through the transmittance table; from above
//! the atmosphere each pixel is marched with the model's integrand from where it enters. Twin
//! of `shaders/garcia_linan/sky.wgsl`.

use super::sky_texture::sky_texture;
use super::{Constants, Lanes, Lut, Params, Tables, integrate};
use crate::geometry::{distance_to_boundary, distance_to_ground, hits_ground};
use crate::methods::shared::transmittance::{sunlit_ground, transmittance_between};
use crate::methods::shared::{entry_into_atmosphere, sun_relative_angles};
use glam::DVec3;
use std::f64::consts::FRAC_PI_2;

/// The radiance of one batch seen from `position` (m from the planet's centre, altitude `h`)
/// along the unit direction `dir`, with the sun in direction `sun` (the sun's disk not included:
/// `SkyModel::sun`).
pub fn radiance(tables: &Tables, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
    let texture = |phi: f64, elevation: f64, _: (f64, f64, f64, f64)| {
        sky_texture(&tables.sky_texture, layer, phi, elevation)
    };
    radiance_with(
        &tables.params,
        &tables.transmittance,
        &tables.constants,
        layer,
        at,
        dir,
        sun,
        texture,
    )
}

/// The radiance with the sky texture's in-scattering integrated along the ray itself instead of
/// looked up: the exact value the texture samples, for fitting the model's constants.
pub fn radiance_marched(
    p: &Params,
    t: &Lut,
    c: &Constants,
    layer: usize,
    at: (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
) -> Lanes {
    let march = |_: f64, _: f64, (h, mu, mu_s, nu): (f64, f64, f64, f64)| {
        let h = h.min(p.thickness_m());
        let t_max = distance_to_boundary(h, mu, p.bottom_radius_m, p.top_radius_m);
        let (l, _) = integrate(
            p,
            t,
            c,
            layer,
            (h, mu, mu_s, nu),
            (0.0, t_max),
            p.steps.sky_view,
        );
        l * p.batches[layer].solar_irradiance
    };
    radiance_with(p, t, c, layer, at, dir, sun, march)
}

/// The sky pass with the in-scattering of a direction inside the atmosphere given by
/// `inscattering(φ, elevation, (h, mu, mu_s, nu))`.
#[allow(clippy::too_many_arguments)]
fn radiance_with(
    p: &Params,
    t: &Lut,
    c: &Constants,
    layer: usize,
    (position, h): (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
    inscattering: impl Fn(f64, f64, (f64, f64, f64, f64)) -> Lanes,
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
        let elevation = FRAC_PI_2 - theta;
        let s = inscattering(phi, elevation, (h, mu, mu_s, nu));
        if hits_ground(h, mu, big_r) {
            let d = distance_to_ground(h, mu, big_r);
            let mu_s_g = ((r * mu_s + d * nu) / big_r).clamp(-1.0, 1.0);
            let lg = sunlit_ground(p, t, layer, mu_s_g);
            let tr = transmittance_between(p, t, layer, (h, mu), d);
            s + tr * lg
        } else {
            s
        }
    } else {
        let Some((mu_e, mu_s_e)) = entry_into_atmosphere(p, h, mu, mu_s, nu) else {
            return Lanes::ZERO;
        };
        let t_max = distance_to_boundary(thickness, mu_e, big_r, top);
        let (s, tr) = integrate(
            p,
            t,
            c,
            layer,
            (thickness, mu_e, mu_s_e, nu),
            (0.0, t_max),
            p.steps.ray_march,
        );
        let behind = if hits_ground(thickness, mu_e, big_r) {
            let mu_s_g = ((top * mu_s_e + t_max * nu) / big_r).clamp(-1.0, 1.0);
            sunlit_ground(p, t, layer, mu_s_g)
        } else {
            Lanes::ZERO
        };
        s * e + tr * behind
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::Atmosphere;
    use crate::camera::{Camera, Projection};
    use crate::geometry::direction_from_angles;
    use crate::methods::shared::viewpoint;
    use crate::scene::{Quality, Scene, WavelengthSet};

    #[test]
    fn the_sky_texture_agrees_with_the_march_it_samples() {
        let scene = Scene::default();
        let atm = Atmosphere::for_scene(&scene);
        let p = Params::new(&atm, WavelengthSet::Spectral4, Quality::Low);
        let camera = Camera::new(&scene.camera, atm.bottom_radius_m, Projection::Perspective);
        let tables = Tables::compute(&p, Constants::published(), viewpoint(&scene, &camera));
        let a = scene.sun.angles();
        let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
        let at = (camera.position, scene.camera.altitude_m);
        for (elevation, azimuth) in [(80.0, 0.0), (30.0, 90.0), (5.0, 200.0), (-20.0, 45.0)] {
            let dir = camera.local_to_world(direction_from_angles(elevation, azimuth));
            let looked_up = radiance(&tables, 0, at, dir, sun);
            let marched = radiance_marched(
                &p,
                &tables.transmittance,
                &tables.constants,
                0,
                at,
                dir,
                sun,
            );
            for (l, m) in looked_up.iter().zip(&marched) {
                assert!(
                    (l / m - 1.0).abs() < 0.02,
                    "{elevation}° {azimuth}°: {l} vs {m}"
                );
            }
        }
    }
}
