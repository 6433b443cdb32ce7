//! The sky pass of Bruneton (2017): a pixel's radiance from the scattering tables (Rayleigh and
//! higher orders times the Rayleigh phase, single Mie times the aerosol phase), plus the ground
//! lit by the sun and the sky-irradiance table. A camera above the atmosphere looks up from
//! where its ray enters it. Twin of `shaders/bruneton/sky.wgsl`.
//!
//! The tables stop at the sun 102° from the zenith ([`MU_S_MIN`]), where the reference treats
//! the air as dark. A ray that starts beyond that, which a camera in space looking at the night
//! side or at the limb from behind the terminator sees, would read the light of 102° if the
//! look-up clamped; instead it is looked up from the point where the sun's zenith angle along
//! the ray comes back to 102°, through the transmittance to there (the air before that point
//! counted as dark, as the tables count it: the paper's light-shaft construction, Eq. 13, with
//! the dark stretch at the start of the ray instead of its end), and a ray that never gets
//! there fades to dark within 1.2° past the edge. The sky-irradiance table, whose orders were
//! gathered from clamped look-ups, lights the ground there with the skylight of 102° as well;
//! it fades the same way.

use super::{
    Coords, Lanes, MU_S_FADE, MU_S_MIN, Params, ScatteringTaps, Tables, aerosol_phase, irradiance,
    rayleigh_phase,
};
use crate::methods::shared::ray::{along, behind, camera_coords, ray_length};
use crate::methods::shared::transmittance::{sun_transmittance, transmittance_between};
use glam::DVec3;
use std::f64::consts::PI;

/// The distance along the ray of `c`, m, at which the sun's zenith cosine first rises to
/// [`MU_S_MIN`], if it does before the ray ends; for `c.mu_s` < `MU_S_MIN`. Along the ray
/// mu_s(d) = (r·mu_s + d·nu) / r(d); squaring mu_s(d) = m gives a quadratic in d whose smallest
/// positive root is the first crossing (mu_s starts below m and is continuous).
pub fn lit_distance(p: &Params, c: &Coords) -> Option<f64> {
    let r = p.bottom_radius_m + c.h;
    let m2 = MU_S_MIN * MU_S_MIN;
    let a = c.nu * c.nu - m2;
    let half_b = r * (c.mu_s * c.nu - m2 * c.mu);
    let cc = r * r * (c.mu_s * c.mu_s - m2);
    let disc = half_b * half_b - a * cc;
    if disc < 0.0 {
        return None;
    }
    // Roots q/a and cc/q without cancellation.
    let q = -(half_b + half_b.signum() * disc.sqrt());
    let roots = [
        if a != 0.0 { q / a } else { -1.0 },
        if q != 0.0 { cc / q } else { -1.0 },
    ];
    let d = roots
        .into_iter()
        .filter(|&d| d > 0.0)
        .fold(f64::INFINITY, f64::min);
    (d <= ray_length(p, c)).then_some(d)
}

/// 1 with the sun within the tables' range, falling to 0 over [`MU_S_FADE`] below it.
pub fn edge_fade(mu_s: f64) -> f64 {
    ((mu_s - (MU_S_MIN - MU_S_FADE)) / MU_S_FADE).clamp(0.0, 1.0)
}

/// The in-scattered radiance of the tables along the ray of `c` (the scattering sum times the
/// Rayleigh phase plus single Mie times the aerosol phase). Beyond the tables' range it is read
/// where the sun comes back to 102° along the ray, through the transmittance to there — at the
/// edge that point is `c` itself, so nothing jumps — and a ray that never gets there reads the
/// edge, faded to dark over [`MU_S_FADE`]. One look-up either way.
fn inscattered(tables: &Tables, layer: usize, c: Coords) -> Lanes {
    let p: &Params = &tables.params;
    let (at, factor) = if c.mu_s >= MU_S_MIN {
        (c, Lanes::ONE)
    } else if let Some(d) = lit_distance(p, &c) {
        let (h, mu, mu_s) = along(p, &c, d);
        let t = transmittance_between(p, &tables.transmittance, layer, (c.h, c.mu), d);
        (Coords { h, mu, mu_s, ..c }, t)
    } else {
        (c, Lanes::splat(edge_fade(c.mu_s)))
    };
    let taps = ScatteringTaps::new(p, layer, at);
    let (s, s_mie) = (taps.read(&tables.scattering), taps.read(&tables.single_mie));
    let (pr, pm) = (
        rayleigh_phase(p, layer, c.nu),
        aerosol_phase(p, layer, c.nu),
    );
    factor * (s * pr + s_mie * pm)
}

/// The radiance of one batch seen from `at` (position from the planet's centre and altitude,
/// m) along the unit direction `dir`, with the sun in direction `sun` (the sun's disk
/// not included: `SkyModel::sun`).
pub fn radiance(tables: &Tables, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
    let p: &Params = &tables.params;
    let Some(c) = camera_coords(p, at, dir, sun) else {
        return Lanes::ZERO;
    };
    let s = inscattered(tables, layer, c);
    let behind = behind(p, &tables.transmittance, layer, &c, |mu_s_g| {
        ground_radiance(tables, layer, mu_s_g)
    });
    s + behind
}

/// The Lambertian ground where the sun's zenith cosine is `mu_s_g`: albedo/π times the direct
/// sunlight (through Earth's shadow) and the sky-irradiance table (dark beyond its range).
pub fn ground_radiance(tables: &Tables, layer: usize, mu_s_g: f64) -> Lanes {
    let p = &tables.params;
    let b = &p.batches[layer];
    let sun_t = sun_transmittance(p, &tables.transmittance, layer, 0.0, mu_s_g);
    let sky = irradiance(p, &tables.irradiance, layer, 0.0, mu_s_g);
    let fade = edge_fade(mu_s_g);
    Lanes::from_fn(|i| {
        b.ground_albedo[i] / PI
            * (b.solar_irradiance[i] * sun_t[i] * mu_s_g.max(0.0) + fade * sky[i])
    })
}
