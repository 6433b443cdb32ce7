//! Nishita et al.'s (1996) "intensity volumes": the radiance scattered in the atmosphere,
//! stored at points of the atmosphere for a fixed set of directions, from which the next
//! scattering order is gathered. Nishita et al. sampled the volume in a grid aligned with the
//! sun; in a spherically symmetric atmosphere a point is known by its altitude h and the sun's
//! zenith cosine μ_s there, and the field at it by directions fixed relative to the sun and the
//! zenith there, so one volume is a table over (μ_s, h) per direction.
//!
//! The directions are centred on the sun, whose once-scattered aerosol light (the aureole) is
//! the brightest and narrowest part of the field: [`SUN_ANGLE_BANDS`] bands of angle α from the
//! sun, narrow near it ([`SUN_ANGLE_EDGES_DEG`]), times [`AZIMUTH_BANDS`] equal bands of azimuth
//! β about the sun over [0, π], β = 0 towards the zenith. Each cell stands for itself and its
//! mirror image across the sun's vertical plane, which sees the same radiance, so the table
//! holds half the directions of the quadrature; each weighs its cell's solid angle and is
//! looked up at its centre (the mean of the band's cos α, the middle of its β).
//!
//! Order 1 ([`compute_single`]): the sunlight scattered once along each texel's ray, through the
//! transmittance table, and the sunlit ground behind it. Order n + 1 ([`compute_next`]): the
//! light of order n gathered at every sample of the ray through each constituent's phase
//! function ([`gathered`]), and the ground lit by the order-n sky ([`sky_irradiance`]). The
//! tables hold radiance per unit solar irradiance, sr⁻¹. Twin of
//! `shaders/shared/intensity_volume.wgsl` (the look-ups and the gather) and
//! `shaders/shared/intensity_volume_march.wgsl` (the passes).

use super::mu_s_axis::{mu_s_axis_coordinate, mu_s_axis_mu_s};
use super::transmittance::sun_transmittance;
use super::{Lanes, Lut, Params, Spacing, TableSpec, aerosol_phase, rayleigh_phase};
use crate::geometry::{altitude_along, distance_to_ground, distance_to_top, hits_ground};
use crate::methods::Inputs;
use crate::methods::shared::segment_weight;
use std::f64::consts::PI;

/// Bands of angle from the sun.
pub const SUN_ANGLE_BANDS: u32 = 8;
/// Their edges, degrees from the sun: narrow around it, where the aerosol's aureole is.
pub const SUN_ANGLE_EDGES_DEG: [f64; SUN_ANGLE_BANDS as usize + 1] =
    [0.0, 4.0, 10.0, 20.0, 35.0, 55.0, 80.0, 115.0, 180.0];
/// Bands of azimuth about the sun over [0, π] (each with its mirror image).
pub const AZIMUTH_BANDS: u32 = 4;
/// Directions in the table: half the quadrature's, whose other half are their mirror images.
pub const DIRECTIONS: u32 = SUN_ANGLE_BANDS * AZIMUTH_BANDS;
/// Texels of one direction's table: (μ_s, h); 64 on the μ_s axis, whose knots fall on texel
/// centres of 64.
pub const SIZE: [u32; 2] = [64, 16];

/// What changes a volume: the medium and the ground that reflects into it.
const INVALIDATED_BY: Inputs = Inputs::ATMOSPHERE.union(Inputs::GROUND_ALBEDO);

/// The sum of the orders a model gathers from (`nishita-96`: order 1; `haber`: 1 to N).
pub const TABLE: TableSpec = TableSpec {
    id: "intensity-volume",
    label: "intensity volume (scattered radiance per direction)",
    size: [SIZE[0], SIZE[1], DIRECTIONS],
    axes: [
        "x: sun zenith cosine μ_s, −1 (left) to 1 (right), dense from −0.3 to 0.1",
        "y: altitude h, ground (top row) to the top (bottom row), quadratic",
        "z: direction k: band k / 4 of angle from the sun (0°–4° first), band k % 4 of azimuth about it (towards the zenith first)",
    ],
    invalidated_by: INVALIDATED_BY,
    transmittance: false,
    describe_texel: |p, _, [x, y, z]| {
        let (h, mu_s) = h_mu_s_from_texel(p, x, y);
        let (cos_alpha, beta, _) = cell(z.round() as u32);
        format!(
            "h = {:.2} km, μ_s = {mu_s:.4}, direction {:.1}° from the sun at azimuth {:.1}°",
            h / 1000.0,
            cos_alpha.acos().to_degrees(),
            beta.to_degrees()
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

/// The cosines of the edges of the bands of angle from the sun, from the sun outwards.
pub fn band_edge_cosines() -> [f64; SUN_ANGLE_BANDS as usize + 1] {
    SUN_ANGLE_EDGES_DEG.map(|deg| deg.to_radians().cos())
}

/// Sub-cells per side of the grid over which [`projected_solid_angle`] integrates a cell.
pub const SUBCELLS: u32 = 4;

/// The bounds of the cell of table direction `k`: the cosines of its band's edges (from the
/// sun outwards), its azimuth band's first β (rad) and the bands' width in β.
fn cell_bounds(k: u32) -> (f64, f64, f64, f64) {
    let band = (k / AZIMUTH_BANDS) as usize;
    let edges = band_edge_cosines();
    let width = PI / f64::from(AZIMUTH_BANDS);
    (
        edges[band],
        edges[band + 1],
        width * f64::from(k % AZIMUTH_BANDS),
        width,
    )
}

/// The zenith cosine of the direction at angle α from the sun (cosine `cos_alpha`) and azimuth
/// `beta` about it, where the sun's zenith cosine is `mu_s`.
fn zenith_cosine(cos_alpha: f64, beta: f64, mu_s: f64) -> f64 {
    cos_alpha * mu_s + sine(cos_alpha) * beta.cos() * sine(mu_s)
}

/// ∫ max(μ, 0) dΩ over one of the mirror cells of table direction `k` where the sun's zenith
/// cosine is `mu_s`, sr: its weight in the irradiance of a horizontal surface, by the midpoint
/// rule on a [`SUBCELLS`]² grid of its cos α and β, so that the cells the horizon cuts count
/// for the part above it.
pub fn projected_solid_angle(k: u32, mu_s: f64) -> f64 {
    let (c0, c1, beta0, width) = cell_bounds(k);
    let n = f64::from(SUBCELLS);
    let mut sum = 0.0;
    for i in 0..SUBCELLS {
        let cos_alpha = c0 + (c1 - c0) * (f64::from(i) + 0.5) / n;
        for j in 0..SUBCELLS {
            let beta = beta0 + width * (f64::from(j) + 0.5) / n;
            sum += zenith_cosine(cos_alpha, beta, mu_s).max(0.0);
        }
    }
    sum * (c0 - c1) * width / (n * n)
}

/// Table direction `k` relative to the sun: the cosine of its cell's centre's angle from the sun
/// (the mean of the band's), its azimuth β about the sun (rad, in [0, π], 0 towards the zenith)
/// and the solid angle of one of its two mirror cells, sr.
pub fn cell(k: u32) -> (f64, f64, f64) {
    let (c0, c1, beta0, width) = cell_bounds(k);
    (0.5 * (c0 + c1), beta0 + 0.5 * width, (c0 - c1) * width)
}

/// The zenith cosine μ and the view–sun cosine ν of table direction `k` where the sun's zenith
/// cosine is `mu_s` (both mirror cells have them).
pub fn direction(k: u32, mu_s: f64) -> (f64, f64) {
    let (cos_alpha, beta, _) = cell(k);
    (
        zenith_cosine(cos_alpha, beta, mu_s).clamp(-1.0, 1.0),
        cos_alpha,
    )
}

fn sine(cosine: f64) -> f64 {
    (1.0 - cosine * cosine).max(0.0).sqrt()
}

/// Fractional texel coordinates of (h, mu_s): x on Hillaire's μ_s axis, dense in twilight
/// (`shared::mu_s_axis`: the light falls about exponentially with μ_s once the sun is
/// below the horizon, which linear interpolation between coarse texels overestimates, and the
/// error grows with every order gathered from it); y = √(h / thickness), dense near the ground.
pub fn texel_from_h_mu_s(p: &Params, h: f64, mu_s: f64) -> (f64, f64) {
    let [w, hh] = SIZE;
    let v = (h / p.thickness_m()).clamp(0.0, 1.0).sqrt();
    (
        mu_s_axis_coordinate(mu_s) * f64::from(w - 1),
        v * f64::from(hh - 1),
    )
}

/// (h, mu_s) of the texel at fractional coordinates (fx, fy): the inverse of
/// [`texel_from_h_mu_s`].
pub fn h_mu_s_from_texel(p: &Params, fx: f64, fy: f64) -> (f64, f64) {
    let [w, hh] = SIZE;
    let v = fy / f64::from(hh - 1);
    (
        v * v * p.thickness_m(),
        mu_s_axis_mu_s(fx / f64::from(w - 1)),
    )
}

/// The radiance per unit solar irradiance of direction `k` at (h, mu_s), bilinear in the table.
pub fn lookup(p: &Params, volume: &Lut, layer: usize, h: f64, mu_s: f64, k: u32) -> Lanes {
    let (fx, fy) = texel_from_h_mu_s(p, h, mu_s);
    volume.bilinear(layer, fx, fy, k as usize)
}

/// The light of `volume` gathered at (h, mu_s) towards the direction of zenith cosine `mu` and
/// view–sun cosine `nu`, through the Rayleigh and the aerosol phase functions, each quadrature
/// normalised to the phase's integral ([`normalised`]): the scattering source per unit
/// scattering coefficient of each constituent, (air, aerosol), sr⁻¹ per unit solar
/// irradiance.
pub fn gathered(
    p: &Params,
    volume: &Lut,
    layer: usize,
    (h, mu_s): (f64, f64),
    mu: f64,
    nu: f64,
) -> (Lanes, Lanes) {
    let (s, s_s) = (sine(mu), sine(mu_s));
    // The view's azimuth from the sun's about the zenith; any where the view or the sun is
    // vertical.
    let cos_phi = if s * s_s > 1e-6 {
        ((nu - mu * mu_s) / (s * s_s)).clamp(-1.0, 1.0)
    } else {
        1.0
    };
    // The view against the sun's frame: along the sun (ν), along the great circle through the
    // sun and the zenith (towards the zenith), and across it.
    let towards_zenith = mu * s_s - s * cos_phi * mu_s;
    let across = s * sine(cos_phi);
    let (mut air, mut aerosol) = (Lanes::ZERO, Lanes::ZERO);
    let (mut air_weights, mut aerosol_weights) = (Lanes::ZERO, Lanes::ZERO);
    for k in 0..DIRECTIONS {
        let (cos_alpha, beta, solid_angle) = cell(k);
        let l = lookup(p, volume, layer, h, mu_s, k);
        let sin_alpha = sine(cos_alpha);
        let along = cos_alpha * nu + sin_alpha * beta.cos() * towards_zenith;
        // The cell and its mirror image: ±β.
        for side in [1.0, -1.0] {
            let cos_theta = (along + side * sin_alpha * beta.sin() * across).clamp(-1.0, 1.0);
            let (w_air, w_aerosol) = (
                rayleigh_phase(p, layer, cos_theta) * solid_angle,
                aerosol_phase(p, layer, cos_theta) * solid_angle,
            );
            air += w_air * l;
            aerosol += w_aerosol * l;
            air_weights += w_air;
            aerosol_weights += w_aerosol;
        }
    }
    (
        normalised(air, air_weights),
        normalised(aerosol, aerosol_weights),
    )
}

/// `sum` over the quadrature's `weights`: the gather with each phase function's quadrature
/// scaled to its integral, 1, so that no order gains or loses light where a peaked phase (the
/// aerosol's forward lobe) falls between the directions. Zero where every weight is.
fn normalised(sum: Lanes, weights: Lanes) -> Lanes {
    Lanes::from_fn(|i| {
        if weights[i] > 0.0 {
            sum[i] / weights[i]
        } else {
            0.0
        }
    })
}

/// The irradiance per unit solar irradiance that the sky of `volume` sends onto the ground where
/// the sun's zenith cosine is `mu_s`: each cell's light weighted by its part of the cosine-
/// weighted hemisphere ([`projected_solid_angle`]).
pub fn sky_irradiance(p: &Params, volume: &Lut, layer: usize, mu_s: f64) -> Lanes {
    let mut e = Lanes::ZERO;
    for k in 0..DIRECTIONS {
        let weight = projected_solid_angle(k, mu_s);
        if weight > 0.0 {
            e += lookup(p, volume, layer, 0.0, mu_s, k) * (2.0 * weight);
        }
    }
    e
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
    let (mu, nu) = direction(k, mu_s);
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

/// A volume whose every texel is [`march`]ed with the source `source(layer, h, mu_s, mu, nu)`
/// and the ground's `ground(layer, mu_s_g)`.
fn volume(
    p: &Params,
    source: impl Fn(usize, f64, f64, f64, f64) -> (Lanes, Lanes) + Sync,
    ground: impl Fn(usize, f64) -> Lanes + Sync,
) -> Lut {
    Lut::from_spec(&TABLE, p.batches.len(), |layer, z, y, x| {
        march(
            p,
            layer,
            h_mu_s_from_texel(p, x as f64, y as f64),
            z as u32,
            |h, mu_s, mu, nu| source(layer, h, mu_s, mu, nu),
            |mu_s_g| ground(layer, mu_s_g),
        )
    })
}

/// Order 1: the sunlight scattered once towards each texel's point along its direction, and
/// the sunlit ground, per unit solar irradiance.
pub fn compute_single(p: &Params, transmittance: &Lut) -> Lut {
    volume(
        p,
        |layer, h, mu_s, _, nu| {
            let sun_t = sun_transmittance(p, transmittance, layer, h, mu_s);
            (
                rayleigh_phase(p, layer, nu) * sun_t,
                aerosol_phase(p, layer, nu) * sun_t,
            )
        },
        |layer, mu_s_g| sun_transmittance(p, transmittance, layer, 0.0, mu_s_g) * mu_s_g.max(0.0),
    )
}

/// Order n + 1 from order n (`previous`): its light gathered along each texel's ray, and the
/// ground lit by its sky.
pub fn compute_next(p: &Params, previous: &Lut) -> Lut {
    volume(
        p,
        |layer, h, mu_s, mu, nu| gathered(p, previous, layer, (h, mu_s), mu, nu),
        |layer, mu_s_g| sky_irradiance(p, previous, layer, mu_s_g),
    )
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

    /// The cells tile the sphere (4π); the gather of a field that differs from cell to cell is
    /// the normalised sum over the cells' centres taken as vectors; before the normalisation
    /// the quadrature integrates the Rayleigh phase within 2 %; a uniform sky's irradiance is
    /// π within 1 % wherever the sun is (which turns the cells about the zenith).
    #[test]
    fn the_direction_set_integrates_the_sphere_and_the_phase_functions() {
        use glam::DVec3;
        let p = params();
        let total: f64 = (0..DIRECTIONS).map(|k| 2.0 * cell(k).2).sum();
        assert!((total - 4.0 * PI).abs() < 1e-12, "{total}");
        let field = |k: usize| 1.0 + (k * k) as f64;
        let volume = Lut::from_spec(&TABLE, p.batches.len(), |_, z, _, _| Lanes::splat(field(z)));
        for (mu_s, mu, nu) in [
            (0.5f64, 1.0f64, 0.5),
            (0.2, -0.3, 0.1),
            (-0.1, 0.0, 0.9),
            (0.7, 0.4, -0.2),
        ] {
            // The cells' centres as vectors in the local frame (x towards the sun's azimuth,
            // `up` the sun's frame's axis towards the zenith), against the view's.
            let sun = DVec3::new(sine(mu_s), 0.0, mu_s);
            let up = DVec3::new(-mu_s, 0.0, sine(mu_s));
            let cos_phi = if mu.abs() < 1.0 {
                ((nu - mu * mu_s) / (sine(mu) * sine(mu_s))).clamp(-1.0, 1.0)
            } else {
                1.0
            };
            let view = DVec3::new(sine(mu) * cos_phi, sine(mu) * sine(cos_phi), mu);
            assert!((view.dot(sun) - nu).abs() < 1e-12);
            let (mut sums, mut weights) = ([Lanes::ZERO; 2], [Lanes::ZERO; 2]);
            for k in 0..DIRECTIONS {
                let (cos_alpha, beta, solid_angle) = cell(k);
                for b in [beta, -beta] {
                    let d = sun * cos_alpha + (up * b.cos() + DVec3::Y * b.sin()) * sine(cos_alpha);
                    assert!((d.z - direction(k, mu_s).0).abs() < 1e-12);
                    let cos_theta = view.dot(d).clamp(-1.0, 1.0);
                    let phases = [
                        rayleigh_phase(&p, 0, cos_theta),
                        aerosol_phase(&p, 0, cos_theta),
                    ];
                    for c in 0..2 {
                        sums[c] += phases[c] * solid_angle * field(k as usize);
                        weights[c] += phases[c] * solid_angle;
                    }
                }
            }
            let (air, aerosol) = gathered(&p, &volume, 0, (1_000.0, mu_s), mu, nu);
            for (c, got) in [air, aerosol].iter().enumerate() {
                for i in 0..4 {
                    let want = sums[c][i] / weights[c][i];
                    assert!(
                        (got[i] / want - 1.0).abs() < 1e-9,
                        "{mu_s} {mu} {nu}, {c}: {} vs {want}",
                        got[i]
                    );
                }
            }
            assert!((weights[0][0] - 1.0).abs() < 0.02, "{}", weights[0][0]);
        }
        let uniform = Lut::from_spec(&TABLE, p.batches.len(), |_, _, _, _| Lanes::ONE);
        for mu_s in [1.0, 0.5, 0.0, -0.3] {
            let e = sky_irradiance(&p, &uniform, 0, mu_s);
            assert!((e[0] / PI - 1.0).abs() < 0.01, "{mu_s}: {}", e[0]);
        }
    }

    /// Order 1 is what the transmittance lets through: brighter towards the sun than away
    /// from it in daylight, dark where the planet hides the sun from every ray; at the ground
    /// in daylight the second order is positive in every cell, below the first in the cells
    /// that look steeply up, and so is its skylight.
    #[test]
    fn the_orders_fall_and_the_first_sees_the_sun() {
        let p = params();
        let t = compute_transmittance_lut(&p);
        let first = compute_single(&p, &t);
        let second = compute_next(&p, &first);
        let (x, y) = texel_from_h_mu_s(&p, 0.0, 0.5);
        let texel = |lut: &Lut, k: u32| lut.texel(0, x as usize, y as usize, k as usize);
        // The first band is the aureole round the sun; the last looks away from it.
        let (towards, away) = (texel(&first, 0), texel(&first, DIRECTIONS - 1));
        assert!(towards[0] > away[0], "{towards:?} {away:?}");
        // With the sun 30° below the horizon, the Earth's shadow covers every ray from the
        // ground, and the ground its rays meet; in daylight every ray sees light.
        for k in 0..DIRECTIONS {
            assert_eq!(lookup(&p, &first, 0, 0.0, -0.5, k), Lanes::ZERO, "{k}");
            assert!(lookup(&p, &first, 0, 0.0, 0.5, k).iter().all(|&l| l > 0.0));
        }
        // Along steep rays up the second order is below the first; near the horizon, where
        // a ray crosses optical depths past 1 at blue wavelengths, it need not be.
        for k in 0..DIRECTIONS {
            for i in 0..4 {
                if direction(k, 0.5).0 > 0.5 {
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
