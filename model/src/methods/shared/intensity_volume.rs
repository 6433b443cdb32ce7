//! Nishita et al.'s (1996) "intensity volumes": the radiance scattered in the atmosphere,
//! stored at points of the atmosphere for a fixed set of directions, from which the next
//! scattering order is gathered. Nishita et al. sampled the volume in a grid aligned with the
//! sun; in a spherically symmetric atmosphere a point is known by its altitude h and the sun's
//! zenith cosine μ_s there, and the field at it by directions fixed in its local frame (its
//! zenith, the sun's azimuth), so one volume is a table over (μ_s, h) per direction.
//!
//! The directions: [`MU_NODES`] zenith cosines at the midpoints of equal bands of μ over
//! [−1, 1] times [`AZIMUTH_NODES`] azimuths from the sun at the midpoints of equal bands of
//! [0, π]; each stands for itself and its mirror image across the sun's vertical plane, which
//! sees the same radiance, so the table holds half the directions of the quadrature and every
//! one of them weighs the same solid angle [`SOLID_ANGLE_SR`].
//!
//! Order 1 ([`compute_single`]): the sunlight scattered once along each texel's ray, through the
//! transmittance table, and the sunlit ground behind it. Order n + 1 ([`compute_next`]): the
//! light of order n gathered at every sample of the ray through each constituent's phase
//! function ([`gathered`]), and the ground lit by the order-n sky ([`sky_irradiance`]). The
//! tables hold radiance per unit solar irradiance, sr⁻¹. Twin of
//! `shaders/shared/intensity_volume.wgsl` (the look-ups and the gather) and
//! `shaders/shared/intensity_volume_march.wgsl` (the passes).

use super::transmittance::sun_transmittance;
use super::{Lanes, Lut, Params, Spacing, TableSpec, aerosol_phase, rayleigh_phase};
use crate::geometry::{altitude_along, distance_to_ground, distance_to_top, hits_ground};
use crate::methods::Inputs;
use crate::methods::shared::segment_weight;
use std::f64::consts::PI;

/// Zenith cosines of the direction set (the midpoints of equal bands over [−1, 1]).
pub const MU_NODES: u32 = 8;
// The first half of the directions look up (the ground's skylight sums them).
const _: () = assert!(MU_NODES.is_multiple_of(2));
/// Azimuths from the sun of the direction set over [0, π] (each with its mirror image).
pub const AZIMUTH_NODES: u32 = 4;
/// Directions in the table: half the quadrature's, whose other half are their mirror images.
pub const DIRECTIONS: u32 = MU_NODES * AZIMUTH_NODES;
/// The solid angle each direction of the quadrature stands for, sr: 4π over 2·[`DIRECTIONS`].
pub const SOLID_ANGLE_SR: f64 = 4.0 * PI / (2 * DIRECTIONS) as f64;
/// Texels of one direction's table: (μ_s, h).
pub const SIZE: [u32; 2] = [32, 16];

/// What changes a volume: the medium and the ground that reflects into it.
const INVALIDATED_BY: Inputs = Inputs::ATMOSPHERE.union(Inputs::GROUND_ALBEDO);

/// The sum of the orders a model gathers from (`nishita-96`: order 1; `haber`: 1 to N).
pub const TABLE: TableSpec = TableSpec {
    id: "intensity-volume",
    label: "intensity volume (scattered radiance per direction)",
    size: [SIZE[0], SIZE[1], DIRECTIONS],
    axes: [
        "x: sun zenith cosine μ_s, −1 (left) to 1 (right), √ spacing around the horizon",
        "y: altitude h, ground (top row) to the top (bottom row), quadratic",
        "z: direction k: zenith cosine band k / 4 (from up to down), azimuth band k % 4 from the sun",
    ],
    invalidated_by: INVALIDATED_BY,
    transmittance: false,
    describe_texel: |p, _, [x, y, z]| {
        let (h, mu_s) = h_mu_s_from_texel(p, x, y);
        let (mu, phi) = direction(z.round() as u32);
        format!(
            "h = {:.2} km, μ_s = {mu_s:.4}, direction μ = {mu:.3}, φ = {:.1}°",
            h / 1000.0,
            phi.to_degrees()
        )
    },
};

/// The last order computed, from which the next is gathered (`haber`'s order loop).
pub const DELTA: TableSpec = TableSpec {
    id: "delta-intensity",
    label: "intensity volume of the last order",
    ..TABLE
};

/// The order before the last, which the loop's next order reads while it rewrites [`DELTA`].
pub const PREVIOUS: TableSpec = TableSpec {
    id: "previous-intensity",
    label: "intensity volume of the order gathered from",
    ..TABLE
};

/// Zenith cosine μ and azimuth from the sun φ (rad, in [0, π]) of table direction `k`.
pub fn direction(k: u32) -> (f64, f64) {
    let (i, a) = (k / AZIMUTH_NODES, k % AZIMUTH_NODES);
    (
        1.0 - 2.0 * (f64::from(i) + 0.5) / f64::from(MU_NODES),
        PI * (f64::from(a) + 0.5) / f64::from(AZIMUTH_NODES),
    )
}

/// The view–sun cosine of the direction (μ, φ) where the sun's zenith cosine is `mu_s`.
fn nu_of(mu: f64, phi: f64, mu_s: f64) -> f64 {
    (mu * mu_s + sine(mu) * sine(mu_s) * phi.cos()).clamp(-1.0, 1.0)
}

fn sine(cosine: f64) -> f64 {
    (1.0 - cosine * cosine).max(0.0).sqrt()
}

/// Fractional texel coordinates of (h, mu_s): x = (1 + sign(μ_s)·√|μ_s|)/2, dense where the
/// sun crosses the horizon; y = √(h / thickness), dense near the ground.
pub fn texel_from_h_mu_s(p: &Params, h: f64, mu_s: f64) -> (f64, f64) {
    let [w, hh] = SIZE;
    let u = 0.5 * (1.0 + mu_s.signum() * mu_s.abs().sqrt());
    let v = (h / p.thickness_m()).clamp(0.0, 1.0).sqrt();
    (u * f64::from(w - 1), v * f64::from(hh - 1))
}

/// (h, mu_s) of the texel at fractional coordinates (fx, fy): the inverse of
/// [`texel_from_h_mu_s`].
pub fn h_mu_s_from_texel(p: &Params, fx: f64, fy: f64) -> (f64, f64) {
    let [w, hh] = SIZE;
    let s = 2.0 * fx / f64::from(w - 1) - 1.0;
    let v = fy / f64::from(hh - 1);
    (v * v * p.thickness_m(), s.signum() * s * s)
}

/// The radiance per unit solar irradiance of direction `k` at (h, mu_s), bilinear in the table.
pub fn lookup(p: &Params, volume: &Lut, layer: usize, h: f64, mu_s: f64, k: u32) -> Lanes {
    let (fx, fy) = texel_from_h_mu_s(p, h, mu_s);
    volume.bilinear(layer, fx, fy, k as usize)
}

/// The light of `volume` gathered at (h, mu_s) towards the direction of zenith cosine `mu` and
/// view–sun cosine `nu`, through the Rayleigh and the aerosol phase functions: the scattering
/// source per unit scattering coefficient of each constituent, (air, aerosol), sr⁻¹ per unit
/// solar irradiance.
pub fn gathered(
    p: &Params,
    volume: &Lut,
    layer: usize,
    (h, mu_s): (f64, f64),
    mu: f64,
    nu: f64,
) -> (Lanes, Lanes) {
    let (s, s_s) = (sine(mu), sine(mu_s));
    // The view's azimuth from the sun; any where the view or the sun is vertical.
    let cos_phi = if s * s_s > 1e-6 {
        ((nu - mu * mu_s) / (s * s_s)).clamp(-1.0, 1.0)
    } else {
        1.0
    };
    let sin_phi = sine(cos_phi);
    let (mut air, mut aerosol) = (Lanes::ZERO, Lanes::ZERO);
    for k in 0..DIRECTIONS {
        let (mu_k, phi_k) = direction(k);
        let l = lookup(p, volume, layer, h, mu_s, k);
        let (a, b) = (mu * mu_k, s * sine(mu_k));
        // The direction and its mirror image: cos(φ ∓ φ_k).
        for cos_diff in [
            cos_phi * phi_k.cos() + sin_phi * phi_k.sin(),
            cos_phi * phi_k.cos() - sin_phi * phi_k.sin(),
        ] {
            let cos_theta = (a + b * cos_diff).clamp(-1.0, 1.0);
            air += rayleigh_phase(p, layer, cos_theta) * l;
            aerosol += aerosol_phase(p, layer, cos_theta) * l;
        }
    }
    (air * SOLID_ANGLE_SR, aerosol * SOLID_ANGLE_SR)
}

/// The irradiance per unit solar irradiance that the sky of `volume` sends onto the ground where
/// the sun's zenith cosine is `mu_s`: the light of every direction above the horizon, weighted
/// by its zenith cosine.
pub fn sky_irradiance(p: &Params, volume: &Lut, layer: usize, mu_s: f64) -> Lanes {
    let mut e = Lanes::ZERO;
    for k in 0..DIRECTIONS {
        let (mu_k, _) = direction(k);
        if mu_k > 0.0 {
            e += lookup(p, volume, layer, 0.0, mu_s, k) * mu_k;
        }
    }
    e * (2.0 * SOLID_ANGLE_SR)
}

/// One texel's ray: from (h, mu_s) along table direction `k`, the in-scattered light of
/// `source(h_t, mu_s_t, mu_t, nu)` (per unit scattering coefficient of each constituent) marched
/// in the multiple-scattering count of segments, quadratic towards the start, and the ground's
/// radiance `ground(mu_s_g)` behind it where the ray meets the ground.
fn march(
    p: &Params,
    layer: usize,
    (h, mu_s): (f64, f64),
    k: u32,
    source: impl Fn(f64, f64, f64, f64) -> (Lanes, Lanes),
    ground: impl Fn(f64) -> Lanes,
) -> Lanes {
    let big_r = p.bottom_radius_m;
    let r = big_r + h;
    let (mu, phi) = direction(k);
    let nu = nu_of(mu, phi, mu_s);
    let hit = hits_ground(h, mu, big_r);
    let t_max = if hit {
        distance_to_ground(h, mu, big_r)
    } else {
        distance_to_top(h, mu, big_r, p.top_radius_m)
    };
    let n = p.steps.multiple_scattering;
    let mut l = Lanes::ZERO;
    let mut throughput = Lanes::ONE;
    for s in 0..n {
        let (t0, t1) = Spacing::Quadratic.segment(0.0, t_max, s, n);
        let (t, dt) = (0.5 * (t0 + t1), t1 - t0);
        let (h_t, r_t) = altitude_along(h, mu, t, big_r);
        let mu_t = ((r * mu + t) / r_t).clamp(-1.0, 1.0);
        let mu_s_t = ((r * mu_s + t * nu) / r_t).clamp(-1.0, 1.0);
        let m = p.medium(layer, h_t);
        let (air, aerosol) = source(h_t, mu_s_t, mu_t, nu);
        let j = m.rayleigh_scattering * air + m.aerosol_scattering * aerosol;
        l += throughput * segment_weight(m.extinction, dt) * j;
        throughput *= (m.extinction * -dt).exp();
    }
    if hit {
        let mu_s_g = ((r * mu_s + t_max * nu) / big_r).clamp(-1.0, 1.0);
        l += throughput * p.batches[layer].ground_albedo / PI * ground(mu_s_g);
    }
    l
}

/// Order 1: the sunlight scattered once towards each texel's point along its direction, and
/// the sunlit ground, per unit solar irradiance.
pub fn compute_single(p: &Params, transmittance: &Lut) -> Lut {
    Lut::from_spec(&TABLE, p.batches.len(), |layer, z, y, x| {
        let at = h_mu_s_from_texel(p, x as f64, y as f64);
        march(
            p,
            layer,
            at,
            z as u32,
            |h_t, mu_s_t, _, nu| {
                let sun_t = sun_transmittance(p, transmittance, layer, h_t, mu_s_t);
                (
                    rayleigh_phase(p, layer, nu) * sun_t,
                    aerosol_phase(p, layer, nu) * sun_t,
                )
            },
            |mu_s_g| sun_transmittance(p, transmittance, layer, 0.0, mu_s_g) * mu_s_g.max(0.0),
        )
    })
}

/// Order n + 1 from order n (`previous`): its light gathered along each texel's ray, and the
/// ground lit by its sky.
pub fn compute_next(p: &Params, previous: &Lut) -> Lut {
    Lut::from_spec(&TABLE, p.batches.len(), |layer, z, y, x| {
        let at = h_mu_s_from_texel(p, x as f64, y as f64);
        march(
            p,
            layer,
            at,
            z as u32,
            |h_t, mu_s_t, mu_t, nu| gathered(p, previous, layer, (h_t, mu_s_t), mu_t, nu),
            |mu_s_g| sky_irradiance(p, previous, layer, mu_s_g),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::shared::optics::tests::params;
    use crate::methods::shared::transmittance::compute_transmittance_lut;

    #[test]
    fn the_texel_mapping_inverts_and_spans_the_table() {
        let p = params();
        for (h, mu_s) in [
            (0.0, -1.0),
            (1_000.0, -0.05),
            (20_000.0, 0.3),
            (p.thickness_m(), 1.0),
        ] {
            let (fx, fy) = texel_from_h_mu_s(&p, h, mu_s);
            let (h2, mu_s2) = h_mu_s_from_texel(&p, fx, fy);
            assert!(
                (h2 - h).abs() < 1e-6 && (mu_s2 - mu_s).abs() < 1e-12,
                "{h} {mu_s}"
            );
        }
        assert_eq!(texel_from_h_mu_s(&p, 0.0, -1.0), (0.0, 0.0));
        assert_eq!(
            texel_from_h_mu_s(&p, p.thickness_m(), 1.0),
            (f64::from(SIZE[0] - 1), f64::from(SIZE[1] - 1))
        );
    }

    /// The quadrature of the direction set integrates the sphere and the phase functions
    /// exactly enough: 4π, and each phase function to 1 for any direction it is gathered to.
    #[test]
    fn the_direction_set_integrates_the_sphere_and_the_phase_functions() {
        let p = params();
        let mut volume = Lut::from_spec(&TABLE, p.batches.len(), |_, _, _, _| Lanes::ONE);
        let total = (0..DIRECTIONS).count() as f64 * 2.0 * SOLID_ANGLE_SR;
        assert!((total - 4.0 * PI).abs() < 1e-12);
        // A uniform field of unit radiance gathers to the phase function's integral, 1, for
        // directions up, down, along and across the sun.
        for (mu_s, mu, nu) in [(0.5, 1.0, 0.5), (0.2, -0.3, 0.1), (-0.1, 0.0, 0.9)] {
            let (air, _) = gathered(&p, &volume, 0, (1_000.0, mu_s), mu, nu);
            for a in air {
                assert!((a - 1.0).abs() < 0.01, "{mu_s} {mu} {nu}: {a}");
            }
        }
        // A uniform sky of unit radiance gives π on a horizontal surface (the midpoint bands
        // of μ integrate μ dμ exactly).
        let e = sky_irradiance(&p, &volume, 0, 0.3);
        assert!((e[0] - PI).abs() < 1e-9, "{}", e[0]);
        volume.data.fill(Lanes::ZERO);
        assert_eq!(sky_irradiance(&p, &volume, 0, 0.3), Lanes::ZERO);
    }

    /// Order 1 is what the transmittance lets through: brighter towards the sun than away
    /// from it in daylight, dark where the planet hides the sun from the whole ray; the second
    /// order is everywhere positive and dimmer than the first on the ground and up high.
    #[test]
    fn the_orders_fall_and_the_first_sees_the_sun() {
        let p = params();
        let t = compute_transmittance_lut(&p);
        let first = compute_single(&p, &t);
        let second = compute_next(&p, &first);
        let (x, y) = texel_from_h_mu_s(&p, 0.0, 0.5);
        let texel = |lut: &Lut, k: u32| lut.texel(0, x as usize, y as usize, k as usize);
        // Direction 2 of band 1 looks up towards the sun's side; its mirror band 3 away.
        let (towards, away) = (
            texel(&first, AZIMUTH_NODES),
            texel(&first, 2 * AZIMUTH_NODES - 1),
        );
        assert!(towards[0] > away[0], "{towards:?} {away:?}");
        let night = h_mu_s_from_texel(&p, 0.0, 0.0);
        assert_eq!(night.1, -1.0);
        assert!(first.texel(0, 0, 0, 0)[0] < 1e-12);
        // Along steep rays up the second order is below the first; near the horizon, where
        // a ray crosses optical depths past 1 at blue wavelengths, it need not be.
        for k in 0..DIRECTIONS {
            for i in 0..4 {
                if direction(k).0 > 0.5 {
                    assert!(texel(&second, k)[i] < texel(&first, k)[i], "{k} {i}");
                }
                assert!(texel(&second, k)[i] > 0.0);
            }
        }
        let (e1, e2) = (
            sky_irradiance(&p, &first, 0, 0.5),
            sky_irradiance(&p, &second, 0, 0.5),
        );
        for i in 0..4 {
            assert!(e2[i] < e1[i], "lane {i}: {} vs {}", e2[i], e1[i]);
        }
    }
}
