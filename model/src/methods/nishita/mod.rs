//! Nishita et al. (1993), "Display of the Earth Taking into Account Atmospheric Scattering"
//! (SIGGRAPH), in the per-pixel form O'Neil (2005, GPU Gems 2, ch. 16) brought to the GPU:
//! single scattering by nested quadrature, with no tables at all. Each pixel marches its view
//! ray; at every sample a second march along the ray towards the sun gives the optical depth to
//! the sun. A frame costs view steps × sun steps medium evaluations per pixel and batch, and no
//! scene change costs more than a frame. There are no higher orders: the sky lacks what
//! multiple scattering adds, and the ground is lit by the sun alone.
//!
//! The medium (profiles, cross-sections, phase functions, sun) is the scene's, shared with
//! every other model, so that comparisons measure the method. One file per pass: [`sky`], twin
//! of `shaders/nishita/sky.wgsl`.

pub mod sky;

use super::shared::sun::visible_fraction;
use super::shared::{Lanes, Lut, Params, TableSpec, Viewpoint, entry_into_atmosphere};
use super::{Domain, SkyModel};
use crate::geometry::{altitude_along, distance_to_top};
use glam::DVec3;

/// The method has no tables.
pub const TABLES: [TableSpec; 0] = [];

/// Where the model is meant to work: anywhere with the sun up. Below the horizon the sky is
/// lit by light scattered more than once, which the model leaves out; above it the sky lacks
/// the higher orders too (35 % of the path tracer's radiance with the sun at 30° and almost
/// no aerosol, `atmoscope bench aod`), so no aerosol amount is inside its AOD range.
pub const DOMAIN: Domain = Domain {
    max_altitude_m: f64::INFINITY,
    min_sun_elevation_deg: 0.0,
    note: "ground, plane and space views in daylight; single scattering only, so the sky lacks what higher orders add and twilight, lit by them, is outside",
    max_aod550: 0.0,
};

/// Samples of the view march and of each march towards the sun: (view, sun). Twice and once
/// the sky-view march's count (32 and 16 at Medium), O'Neil's budget scaled with the quality.
pub fn steps(p: &Params) -> (u32, u32) {
    (2 * p.steps.sky_view, p.steps.sky_view)
}

/// The four values the GPU reads from `globals.model`: the two step counts.
pub fn constants(p: &Params) -> [f64; 4] {
    let (view, sun) = steps(p);
    [f64::from(view), f64::from(sun), 0.0, 0.0]
}

/// Transmittance per lane from altitude `h` (m) towards the sun at zenith cosine `mu_s`, by a
/// march of `steps` midpoint samples to the top of the atmosphere, times the visible fraction
/// of the sun's disk above the horizon (0, and no march, where the planet hides it).
pub fn sun_transmittance(p: &Params, layer: usize, h: f64, mu_s: f64, steps: u32) -> Lanes {
    let visible = visible_fraction(h, mu_s, p.bottom_radius_m);
    if visible <= 0.0 {
        return [0.0; 4];
    }
    let d = distance_to_top(h, mu_s, p.bottom_radius_m, p.top_radius_m);
    let dt = d / f64::from(steps);
    let mut depth = [0.0; 4];
    for s in 0..steps {
        let (h_t, _) = altitude_along(h, mu_s, (f64::from(s) + 0.5) * dt, p.bottom_radius_m);
        let m = p.medium(layer, h_t);
        for (d, e) in depth.iter_mut().zip(m.extinction) {
            *d += e * dt;
        }
    }
    depth.map(|d| (-d).exp() * visible)
}

/// [`sun_transmittance`] seen from any altitude: from where the sun's ray enters the
/// atmosphere when the point is above it (1 where the ray misses the atmosphere).
pub fn sun_seen_from(p: &Params, layer: usize, h: f64, mu_s: f64, steps: u32) -> Lanes {
    if h <= p.thickness_m() {
        return sun_transmittance(p, layer, h, mu_s, steps);
    }
    match entry_into_atmosphere(p, h, mu_s, mu_s, 1.0) {
        Some((mu_entry, _)) => sun_transmittance(p, layer, p.thickness_m(), mu_entry, steps),
        None => [1.0; 4],
    }
}

/// The model for one atmosphere: the optics alone.
#[derive(Debug, Clone)]
pub struct Nishita {
    pub params: Params,
}

impl SkyModel for Nishita {
    fn params(&self) -> &Params {
        &self.params
    }

    fn radiance(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
        sky::radiance(&self.params, layer, at, dir, sun)
    }

    fn table(&self, _: &str) -> Option<&Lut> {
        None
    }

    fn sun(&self, layer: usize, h: f64, mu_s: f64, disk: f64) -> Lanes {
        if disk <= 0.0 {
            return [0.0; 4];
        }
        let p = &self.params;
        let tr = sun_seen_from(p, layer, h, mu_s, steps(p).1);
        std::array::from_fn(|i| p.batches[layer].solar_irradiance[i] * tr[i] * disk)
    }
}

/// The registry's constructor (no table depends on the viewpoint: there are none).
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    Box::new(Nishita {
        params: params.clone(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::shared::optics::tests::params;
    use crate::methods::shared::transmittance::{compute_transmittance_lut, transmittance};

    #[test]
    fn the_nested_march_agrees_with_the_transmittance_table() {
        let p = params();
        let table = compute_transmittance_lut(&p);
        for (h, mu_s) in [(0.0, 1.0), (0.0, 0.3), (5_000.0, 0.1), (30_000.0, 0.6)] {
            let marched = sun_transmittance(&p, 0, h, mu_s, 4096);
            let looked_up = transmittance(&p, &table, 0, h, mu_s);
            for (m, t) in marched.iter().zip(looked_up) {
                assert!((m / t - 1.0).abs() < 0.01, "h {h} mu_s {mu_s}: {m} vs {t}");
            }
        }
        // Behind the planet the sun is gone, and above the atmosphere nothing dims it.
        assert_eq!(sun_transmittance(&p, 0, 0.0, -0.2, 16), [0.0; 4]);
        let top = p.thickness_m() + 1_000.0;
        assert_eq!(sun_seen_from(&p, 0, top, 0.5, 16), [1.0; 4]);
    }
}
