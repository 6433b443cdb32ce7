//! The sky pass of Bruneton (2017): a pixel's radiance from the scattering tables (Rayleigh and
//! higher orders times the Rayleigh phase, single Mie times the aerosol phase), plus the ground
//! lit by the sun and the sky-irradiance table. A camera above the atmosphere looks up from where its ray enters it. Twin of
//! `shaders/bruneton/sky.wgsl`.

use super::{Lanes, Params, ScatteringTaps, Tables, aerosol_phase, irradiance, rayleigh_phase};
use crate::methods::shared::ray::{behind, camera_coords};
use crate::methods::shared::transmittance::sun_transmittance;
use glam::DVec3;
use std::f64::consts::PI;

/// The radiance of one batch seen from `at` (position from the planet's centre and altitude,
/// m) along the unit direction `dir`, with the sun in direction `sun` (the sun's disk
/// not included: `SkyModel::sun`).
pub fn radiance(tables: &Tables, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
    let p: &Params = &tables.params;
    let Some(c) = camera_coords(p, at, dir, sun) else {
        return [0.0; 4];
    };
    let taps = ScatteringTaps::new(p, layer, c);
    let (s, s_mie) = (taps.read(&tables.scattering), taps.read(&tables.single_mie));
    let (pr, pm) = (
        rayleigh_phase(p, layer, c.nu),
        aerosol_phase(p, layer, c.nu),
    );
    let behind = behind(p, &tables.transmittance, layer, &c, |mu_s_g| {
        ground_radiance(tables, layer, mu_s_g)
    });
    std::array::from_fn(|i| s[i] * pr[i] + s_mie[i] * pm[i] + behind[i])
}

/// The Lambertian ground where the sun's zenith cosine is `mu_s_g`: albedo/π times the direct
/// sunlight (through Earth's shadow) and the sky-irradiance table.
pub fn ground_radiance(tables: &Tables, layer: usize, mu_s_g: f64) -> Lanes {
    let p = &tables.params;
    let b = &p.batches[layer];
    let sun_t = sun_transmittance(p, &tables.transmittance, layer, 0.0, mu_s_g);
    let sky = irradiance(p, &tables.irradiance, layer, 0.0, mu_s_g);
    std::array::from_fn(|i| {
        b.ground_albedo[i] / PI * (b.solar_irradiance[i] * sun_t[i] * mu_s_g.max(0.0) + sky[i])
    })
}
