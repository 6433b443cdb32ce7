//! The sky pass without an atmosphere: black sky, and the Lambertian ground lit by the sun
//! straight from space. Twin of `shaders/empty/sky.wgsl`.

use crate::geometry::{distance_to_ground, hits_ground};
use crate::methods::shared::sun_disk::visible_fraction;
use crate::methods::shared::{Lanes, Params};
use glam::DVec3;
use std::f64::consts::PI;

/// The radiance of one batch seen from `position` (m from the planet's centre, altitude `h`)
/// along the unit direction `dir`, with the sun in direction `sun`.
pub fn radiance(
    p: &Params,
    layer: usize,
    (position, h): (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
) -> Lanes {
    let big_r = p.bottom_radius_m;
    let up = position.normalize();
    let (mu, mu_s, nu) = (dir.dot(up), sun.dot(up), dir.dot(sun));
    if !hits_ground(h, mu, big_r) {
        return Lanes::ZERO;
    }
    let d = distance_to_ground(h, mu, big_r);
    let mu_s_g = (((big_r + h) * mu_s + d * nu) / big_r).clamp(-1.0, 1.0);
    let lit = visible_fraction(0.0, mu_s_g, big_r) * mu_s_g.max(0.0) / PI;
    let b = &p.batches[layer];
    b.ground_albedo * b.solar_irradiance * lit
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::Atmosphere;
    use crate::geometry::direction_from_angles;
    use crate::scene::{Quality, Scene, WavelengthSet};

    #[test]
    fn the_sky_is_black_and_the_ground_lambertian() {
        let atm = Atmosphere::for_scene(&Scene::default());
        let p = Params::new(&atm, WavelengthSet::Spectral4, Quality::Medium);
        let position = DVec3::new(0.0, 0.0, p.bottom_radius_m + 10.0);
        let sun = direction_from_angles(30.0, 0.0);
        assert_eq!(
            radiance(
                &p,
                0,
                (position, 10.0),
                direction_from_angles(20.0, 0.0),
                sun
            ),
            Lanes::ZERO
        );
        let ground = radiance(&p, 0, (position, 10.0), -DVec3::Z, sun);
        let b = &p.batches[0];
        // The sun at 30°: cos θ_s = 0.5 on the Lambertian ground below.
        for ((g, a), e) in ground.iter().zip(b.ground_albedo).zip(b.solar_irradiance) {
            let expected = a * e * 0.5 / PI;
            assert!((g / expected - 1.0).abs() < 1e-6, "{g} vs {expected}");
        }
    }
}
