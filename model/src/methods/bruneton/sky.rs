//! The sky pass of Bruneton (2017): a pixel's radiance from the scattering tables (Rayleigh and
//! higher orders times the Rayleigh phase, single Mie times the aerosol phase), plus the sun's
//! disk through the transmittance table or the ground lit by the sun and the sky-irradiance
//! table. A camera above the atmosphere looks up from where its ray enters it. Twin of
//! `shaders/bruneton/sky.wgsl`.

use super::{
    Coords, Lanes, Params, ScatteringTaps, Tables, aerosol_phase, irradiance, rayleigh_phase,
};
use crate::geometry::{distance_to_ground, hits_ground};
use crate::methods::shared::transmittance::{
    sun_transmittance, transmittance, transmittance_between,
};
use crate::methods::shared::{entry_into_atmosphere, sun_disk};
use glam::DVec3;
use std::f64::consts::PI;

/// The radiance of one batch seen from `position` (m from the planet's centre, altitude `h`)
/// along the unit direction `dir`, with the sun in direction `sun`.
pub fn radiance(
    tables: &Tables,
    layer: usize,
    (position, h): (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
) -> Lanes {
    let p: &Params = &tables.params;
    let big_r = p.bottom_radius_m;
    let e = p.batches[layer].solar_irradiance;
    let up = position.normalize();
    let (mu, mu_s, nu) = (dir.dot(up), sun.dot(up), dir.dot(sun).clamp(-1.0, 1.0));
    let disk = sun_disk(dir, sun);
    let (h, mu, mu_s) = if h > p.thickness_m() {
        match entry_into_atmosphere(p, h, mu, mu_s, nu) {
            Some((mu_e, mu_s_e)) => (p.thickness_m(), mu_e, mu_s_e),
            None => return e.map(|e| e * disk),
        }
    } else {
        (h, mu, mu_s)
    };
    let ground = hits_ground(h, mu, big_r);
    let taps = ScatteringTaps::new(
        p,
        layer,
        Coords {
            h,
            mu,
            mu_s,
            nu,
            ground,
        },
    );
    let (s, s_mie) = (taps.read(&tables.scattering), taps.read(&tables.single_mie));
    let (pr, pm) = (rayleigh_phase(p, layer, nu), aerosol_phase(p, layer, nu));
    let inscattered: Lanes = std::array::from_fn(|i| s[i] * pr[i] + s_mie[i] * pm[i]);
    let t = &tables.transmittance;
    let (tr, behind) = if ground {
        let d = distance_to_ground(h, mu, big_r);
        let mu_s_g = (((big_r + h) * mu_s + d * nu) / big_r).clamp(-1.0, 1.0);
        (
            transmittance_between(p, t, layer, (h, mu), d),
            ground_radiance(tables, layer, mu_s_g),
        )
    } else {
        (transmittance(p, t, layer, h, mu), e.map(|e| e * disk))
    };
    std::array::from_fn(|i| inscattered[i] + tr[i] * behind[i])
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
