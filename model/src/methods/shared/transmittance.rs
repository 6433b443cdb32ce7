//! The transmittance table every table-based model shares: exp(−∫ extinction) from (h, mu) to
//! the top of the atmosphere, in Bruneton's (2017) mapping (§4.1 of his notes) at Hillaire's
//! (2020) 256 × 64. The pass is `shaders/shared/transmittance.wgsl`.

use super::{Lanes, Lut, Params, Spacing, TableSpec};
use crate::geometry::{
    altitude_along, distance_to_top, rho_squared, transmittance_h_mu, transmittance_x_mu_x_r,
};
use crate::methods::Inputs;

/// Transmittance table size (mu, h): Hillaire's 256 × 64.
pub const TRANSMITTANCE_SIZE: [u32; 2] = [256, 64];

pub const TABLE: TableSpec = TableSpec {
    id: "transmittance",
    label: "transmittance",
    size: [TRANSMITTANCE_SIZE[0], TRANSMITTANCE_SIZE[1], 1],
    axes: [
        "x: view zenith cosine μ, from the horizon of each altitude (left) to straight up (right), Bruneton's mapping",
        "y: altitude h, ground (top row) to the top of the atmosphere (bottom row), √ spacing",
        "",
    ],
    invalidated_by: Inputs::ATMOSPHERE,
    transmittance: true,
    describe_texel: |p, _, [x, y, _]| {
        let (h, mu) = transmittance_h_mu_from_texel(p, x, y);
        format!("h = {:.2} km, μ = {mu:.4}", h / 1000.0)
    },
};

/// Fractional texel coordinates of (h, mu) in the transmittance table (Bruneton 2017 §4.1).
pub fn transmittance_texel_from_h_mu(p: &Params, h: f64, mu: f64) -> (f64, f64) {
    let (x_mu, x_r) = transmittance_x_mu_x_r(h, mu, p.bottom_radius_m, p.top_radius_m);
    let [w, hh] = TRANSMITTANCE_SIZE;
    (x_mu * (w - 1) as f64, x_r * (hh - 1) as f64)
}

/// (h, mu) of the transmittance texel at fractional coordinates (fx, fy).
pub fn transmittance_h_mu_from_texel(p: &Params, fx: f64, fy: f64) -> (f64, f64) {
    let [w, hh] = TRANSMITTANCE_SIZE;
    transmittance_h_mu(
        fx / (w - 1) as f64,
        fy / (hh - 1) as f64,
        p.bottom_radius_m,
        p.top_radius_m,
    )
}

/// The transmittance table: exp(−∫ extinction) from (h, mu) to the top, midpoint rule on
/// quadratically spaced segments (dense where the air is dense).
pub fn compute_transmittance_lut(p: &Params) -> Lut {
    Lut::from_spec(&TABLE, p.batches.len(), |layer, _, y, x| {
        let (h, mu) = transmittance_h_mu_from_texel(p, x as f64, y as f64);
        compute_transmittance(p, layer, h, mu)
    })
}

fn compute_transmittance(p: &Params, layer: usize, h: f64, mu: f64) -> Lanes {
    let big_r = p.bottom_radius_m;
    let t_max = distance_to_top(h, mu, big_r, p.top_radius_m);
    let n = p.steps.transmittance;
    let mut depth = Lanes::ZERO;
    for i in 0..n {
        let (t0, t1) = Spacing::Quadratic.segment(0.0, t_max, i, n);
        let (h_t, _) = altitude_along(h, mu, 0.5 * (t0 + t1), big_r);
        let m = p.medium(layer, h_t);
        depth = depth + (m.extinction * (t1 - t0));
    }
    depth.map(|d| (-d).exp())
}

/// Looks up the transmittance from (h, mu) to the top.
pub fn transmittance(p: &Params, t: &Lut, layer: usize, h: f64, mu: f64) -> Lanes {
    let (fx, fy) = transmittance_texel_from_h_mu(p, h, mu);
    t.bilinear(layer, fx, fy, 0)
}

/// Transmittance straight up from the ground, T(0, 1): the table's first texel, where its
/// mapping puts h = 0, mu = 1 (one read where a look-up blends four).
pub fn ground_to_top(t: &Lut, layer: usize) -> Lanes {
    t.texel(layer, 0, 0, 0)
}

/// Transmittance to the sun from (h, mu_s), times the visible fraction of the sun's disk above
/// the horizon (Earth's shadow with its penumbra, as in Bruneton 2017).
pub fn sun_transmittance(p: &Params, t: &Lut, layer: usize, h: f64, mu_s: f64) -> Lanes {
    let visible = super::sun_disk::visible_fraction(h, mu_s, p.bottom_radius_m);
    transmittance(p, t, layer, h, mu_s) * visible
}

/// Transmittance to the sun seen from altitude `h` (m, anywhere up to space) with the sun at
/// zenith cosine `mu_s`: along the sun's own ray, from where it enters the atmosphere when the
/// point is above it (1 where the ray misses the atmosphere), behind the planet's limb or not.
pub fn sun_seen_from(p: &Params, t: &Lut, layer: usize, h: f64, mu_s: f64) -> Lanes {
    if h <= p.thickness_m() {
        return sun_transmittance(p, t, layer, h, mu_s);
    }
    match super::entry_into_atmosphere(p, h, mu_s, mu_s, 1.0) {
        Some((mu_entry, _)) => sun_transmittance(p, t, layer, p.thickness_m(), mu_entry),
        None => Lanes::ONE,
    }
}

/// The radiance of the Lambertian ground where the sun's zenith cosine is `mu_s_g`, lit by
/// direct sunlight alone (for models with no skylight term for surfaces), W·m⁻²·sr⁻¹·nm⁻¹.
pub fn sunlit_ground(p: &Params, t: &Lut, layer: usize, mu_s_g: f64) -> Lanes {
    let b = &p.batches[layer];
    let sun_t = sun_transmittance(p, t, layer, 0.0, mu_s_g);
    Lanes::from_fn(|i| {
        b.ground_albedo[i] / std::f64::consts::PI
            * b.solar_irradiance[i]
            * sun_t[i]
            * mu_s_g.max(0.0)
    })
}

/// The transmittance between the point at altitude `h` and the point at distance `d` along the
/// ray (h, mu), as ratios of table values in which every ray rises from where it starts, so
/// that no factor depends on the table's steep column at the horizon: along the reversed ray
/// while the point is still descending (Bruneton 2017's form for rays to the ground), through
/// the ray's lowest point once it has passed it, else directly. Clamped to 1.
pub fn transmittance_between(
    p: &Params,
    t: &Lut,
    layer: usize,
    (h, mu): (f64, f64),
    d: f64,
) -> Lanes {
    let big_r = p.bottom_radius_m;
    let r = big_r + h;
    let (h_d, r_d) = altitude_along(h, mu, d, big_r);
    let mu_d = ((r * mu + d) / r_d).clamp(-1.0, 1.0);
    let table = |h, mu| transmittance(p, t, layer, h, mu);
    let ratio = |a: Lanes, b: Lanes| -> Lanes { Lanes::from_fn(|i| a[i] / b[i].max(1e-30)) };
    let v = if mu_d < 0.0 {
        ratio(table(h_d, -mu_d), table(h, -mu))
    } else if mu < 0.0 {
        let low = table(lowest_altitude(h, mu, big_r), 0.0);
        ratio(ratio(low * low, table(h, -mu)), table(h_d, mu_d))
    } else {
        ratio(table(h, mu), table(h_d, mu_d))
    };
    v.map(|x| x.min(1.0))
}

/// Altitude of the lowest point of the line through altitude `h` with zenith cosine `mu`,
/// r·√(1 − mu²) − R, cancellation-free; 0 for a line that meets the ground.
pub fn lowest_altitude(h: f64, mu: f64, big_r: f64) -> f64 {
    let r = big_r + h;
    let rho2 = rho_squared(h, big_r) - r * r * mu * mu;
    (rho2 / ((rho2 + big_r * big_r).max(0.0).sqrt() + big_r)).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::Atmosphere;
    use crate::scene::{Quality, Scene, WavelengthSet};
    use glam::DVec3;

    fn params() -> Params {
        let scene = Scene::default();
        Params::new(
            &Atmosphere::for_scene(&scene),
            WavelengthSet::Spectral4,
            Quality::Medium,
        )
    }

    #[test]
    fn transmittance_mapping_round_trips() {
        let p = params();
        for &(h, mu) in &[
            (0.0, 1.0),
            (0.0, 0.001),
            (10_000.0, 0.3),
            (50_000.0, -0.05),
            (99_000.0, 0.9),
        ] {
            let (fx, fy) = transmittance_texel_from_h_mu(&p, h, mu);
            let (h2, mu2) = transmittance_h_mu_from_texel(&p, fx, fy);
            assert!((h2 - h).abs() < 1e-6 * (1.0 + h), "h {h} -> {h2}");
            assert!((mu2 - mu).abs() < 1e-9, "mu {mu} -> {mu2} at h {h}");
        }
    }

    /// The first texel is the look-up at h = 0, mu = 1, in every layer (the GPU's
    /// `transmittance_ground_to_top` reads it so).
    #[test]
    fn the_first_texel_is_the_transmittance_straight_up_from_the_ground() {
        let scene = Scene::default();
        let p = Params::new(
            &Atmosphere::for_scene(&scene),
            WavelengthSet::SpectralN(8),
            Quality::Low,
        );
        let t = compute_transmittance_lut(&p);
        assert_eq!(transmittance_texel_from_h_mu(&p, 0.0, 1.0), (0.0, 0.0));
        for layer in 0..p.batches.len() {
            let (corner, lookup) = (
                ground_to_top(&t, layer),
                transmittance(&p, &t, layer, 0.0, 1.0),
            );
            assert_eq!(corner, lookup, "layer {layer}");
            assert!(corner.iter().all(|&v| v > 0.0 && v < 1.0), "{corner:?}");
        }
        assert_ne!(ground_to_top(&t, 0), ground_to_top(&t, 1));
    }

    #[test]
    fn zenith_transmittance_matches_the_exact_optical_depth() {
        let scene = Scene::default();
        let atm = Atmosphere::for_scene(&scene);
        let p = Params::new(&atm, WavelengthSet::Spectral4, Quality::High);
        let t = compute_transmittance_lut(&p);
        for (lane, &w) in p.batches[0].colour.wavelengths_nm.iter().enumerate() {
            for &(h, mu) in &[(0.0, 1.0), (0.0, 0.2), (5000.0, 0.5)] {
                let ray = crate::geometry::Ray::new(
                    DVec3::new(0.0, 0.0, atm.bottom_radius_m + h),
                    DVec3::new((1.0_f64 - mu * mu).sqrt(), 0.0, mu),
                );
                let exact = (-atm.optical_depth(&atm.optics(w), &ray).total()).exp();
                let lut = transmittance(&p, &t, 0, h, mu)[lane];
                assert!(
                    (lut - exact).abs() < 2e-3,
                    "{w} nm, h {h}, mu {mu}: LUT {lut} vs exact {exact}"
                );
            }
        }
    }
}
