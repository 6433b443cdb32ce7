//! The sky pass of Nishita (1993): per pixel, single scattering marched along the view ray with
//! a nested march towards the sun at every sample, and the sunlit ground behind it; from above
//! the atmosphere the march starts where the ray enters it. Twin of `shaders/nishita/sky.wgsl`.

use super::{steps, sun_transmittance};
use crate::geometry::{altitude_along, distance_to_boundary, hits_ground};
use crate::methods::shared::{
    Lanes, Params, aerosol_phase, entry_into_atmosphere, rayleigh_phase, segment_weight,
};
use glam::DVec3;
use std::f64::consts::PI;

/// The radiance of one batch seen from `position` (m from the planet's centre, altitude `h`)
/// along the unit direction `dir`, with the sun in direction `sun` (the sun's disk not
/// included: `SkyModel::sun`).
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
    let (h0, mu0, mu_s0) = if h <= p.thickness_m() {
        (h, mu, mu_s)
    } else {
        match entry_into_atmosphere(p, h, mu, mu_s, nu) {
            Some((mu_e, mu_s_e)) => (p.thickness_m(), mu_e, mu_s_e),
            None => return [0.0; 4],
        }
    };
    let (view_steps, sun_steps) = steps(p);
    let b = &p.batches[layer];
    let (phase_r, phase_a) = (rayleigh_phase(p, layer, nu), aerosol_phase(p, layer, nu));
    let r0 = big_r + h0;
    let t_max = distance_to_boundary(h0, mu0, big_r, p.top_radius_m);
    let dt = t_max / f64::from(view_steps);
    let mut inscattered = [0.0; 4];
    let mut throughput = [1.0; 4];
    for s in 0..view_steps {
        let t = (f64::from(s) + 0.5) * dt;
        let (h_t, r_t) = altitude_along(h0, mu0, t, big_r);
        let mu_s_t = ((r0 * mu_s0 + t * nu) / r_t).clamp(-1.0, 1.0);
        let m = p.medium(layer, h_t);
        let sun_t = sun_transmittance(p, layer, h_t, mu_s_t, sun_steps);
        let weight = segment_weight(m.extinction, dt);
        for i in 0..4 {
            let source = (m.rayleigh_scattering[i] * phase_r[i]
                + m.aerosol_scattering[i] * phase_a[i])
                * sun_t[i];
            inscattered[i] += throughput[i] * weight[i] * source;
            throughput[i] *= (-m.extinction[i] * dt).exp();
        }
    }
    let mut l: Lanes = std::array::from_fn(|i| inscattered[i] * b.solar_irradiance[i]);
    if hits_ground(h0, mu0, big_r) {
        let mu_s_g = ((r0 * mu_s0 + t_max * nu) / big_r).clamp(-1.0, 1.0);
        let sun_g = sun_transmittance(p, layer, 0.0, mu_s_g, sun_steps);
        for i in 0..4 {
            let ground =
                b.ground_albedo[i] / PI * b.solar_irradiance[i] * sun_g[i] * mu_s_g.max(0.0);
            l[i] += throughput[i] * ground;
        }
    }
    l
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::Atmosphere;
    use crate::geometry::{Ray, direction_from_angles};
    use crate::methods::single_scattering;
    use crate::scene::{Quality, Scene, WavelengthSet};

    /// With fine steps the nested march is the exact single scattering it approximates.
    #[test]
    fn the_nested_march_converges_to_exact_single_scattering() {
        let scene = Scene::default();
        let atm = Atmosphere::for_scene(&scene);
        let mut p = Params::new(&atm, WavelengthSet::SpectralN(4), Quality::High);
        p.steps.sky_view = 256;
        let position = DVec3::new(0.0, 0.0, p.bottom_radius_m + 100.0);
        let sun = direction_from_angles(30.0, 0.0);
        for (elevation, azimuth) in [(60.0, 0.0), (10.0, 90.0), (2.0, 180.0), (-10.0, 30.0)] {
            let dir = direction_from_angles(elevation, azimuth);
            let marched = radiance(&p, 0, (position, 100.0), dir, sun);
            let ray = Ray::new(position, dir);
            for (i, &w) in p.batches[0].colour.wavelengths_nm.iter().enumerate() {
                // Per unit sunlight: the set's sunlight is a band's, the exact one a point's.
                let exact = single_scattering::radiance(&atm, &ray, sun, w)
                    / atm.solar_irradiance(w, None)
                    * p.batches[0].solar_irradiance[i];
                assert!(
                    (marched[i] / exact - 1.0).abs() < 0.02,
                    "{elevation}° {azimuth}° {w} nm: {} vs {exact}",
                    marched[i]
                );
            }
        }
    }
}
