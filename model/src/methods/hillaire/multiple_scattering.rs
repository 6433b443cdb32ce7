//! Hillaire (2020) §5.5: the multiple-scattering table Ψ_ms(h, mu_s), second order with an
//! isotropic phase summed as the geometric series 1/(1 − f_ms), ground bounce included. Twin of
//! `shaders/hillaire/multiple_scattering.wgsl`.

use super::{
    Lanes, Lut, Params, Spacing, TableSpec, mu_s_axis_coordinate, mu_s_axis_mu_s, sun_transmittance,
};
use crate::geometry::{altitude_along, distance_to_ground, distance_to_top, hits_ground};
use crate::methods::Inputs;
use crate::methods::shared::{local_sun, segment_weight};
use crate::wavelengths::LANES;
use glam::DVec3;
use std::f64::consts::PI;

/// Multiple-scattering table size (mu_s, h): 64 × 32, twice the paper's 32 texels of mu_s, most
/// of them in twilight (see [`super::MU_S_AXIS_U`]).
pub const MULTIPLE_SCATTERING_SIZE: [u32; 2] = [64, 32];
/// Directions of the multiple-scattering integral: an 8 × 8 stratified sphere (paper: 64), of
/// which the half on one side of the sun's vertical plane is marched (even, so the azimuths pair).
pub const MULTIPLE_SCATTERING_DIRECTIONS_SQRT: u32 = 8;
const _: () = assert!(MULTIPLE_SCATTERING_DIRECTIONS_SQRT % 2 == 0);

pub const TABLE: TableSpec = TableSpec {
    id: "multiple-scattering",
    label: "multiple scattering",
    size: [MULTIPLE_SCATTERING_SIZE[0], MULTIPLE_SCATTERING_SIZE[1], 1],
    axes: [
        "x: sun zenith cosine μ_s, −1 (left) to 1 (right), dense from −0.3 to 0.1",
        "y: altitude h, ground (top row) to the top (bottom row)",
        "",
    ],
    // Ψ_ms includes the light the ground reflects.
    invalidated_by: Inputs::ATMOSPHERE.union(Inputs::GROUND_ALBEDO),
    transmittance: false,
    describe_texel: |p, _, [x, y, _]| {
        let (h, mu_s) = multiple_scattering_h_mu_s_from_texel(p, x, y);
        format!("h = {:.2} km, μ_s = {mu_s:.4}", h / 1000.0)
    },
};

/// Fractional texel coordinates of (h, mu_s) in the multiple-scattering table.
pub fn multiple_scattering_texel_from_h_mu_s(p: &Params, h: f64, mu_s: f64) -> (f64, f64) {
    let [w, hh] = MULTIPLE_SCATTERING_SIZE;
    (
        mu_s_axis_coordinate(mu_s) * (w - 1) as f64,
        (h / p.thickness_m()) * (hh - 1) as f64,
    )
}

/// (h, mu_s) of the multiple-scattering texel at fractional coordinates (fx, fy).
pub fn multiple_scattering_h_mu_s_from_texel(p: &Params, fx: f64, fy: f64) -> (f64, f64) {
    let [w, hh] = MULTIPLE_SCATTERING_SIZE;
    (
        fy / (hh - 1) as f64 * p.thickness_m(),
        mu_s_axis_mu_s(fx / (w - 1) as f64),
    )
}

/// Direction `i` of an n × n stratified grid over the sphere (uniform in mu and azimuth).
fn sphere_direction(i: u32, n: u32) -> DVec3 {
    let mu = 1.0 - 2.0 * ((i / n) as f64 + 0.5) / n as f64;
    let phi = 2.0 * PI * ((i % n) as f64 + 0.5) / n as f64;
    let s = (1.0 - mu * mu).max(0.0).sqrt();
    DVec3::new(s * phi.cos(), s * phi.sin(), mu)
}

/// Ψ_ms per unit solar irradiance (sr⁻¹): L_2nd/(1 − f_ms), paper eq. 5–10.
pub fn compute_multiple_scattering_lut(p: &Params, t: &Lut) -> Lut {
    Lut::from_spec(&TABLE, p.batches.len(), |layer, _, y, x| {
        let (h, mu_s) = multiple_scattering_h_mu_s_from_texel(p, x as f64, y as f64);
        compute_multiple_scattering(p, t, layer, h, mu_s)
    })
}

fn compute_multiple_scattering(p: &Params, t: &Lut, layer: usize, h: f64, mu_s: f64) -> Lanes {
    let n_dir = MULTIPLE_SCATTERING_DIRECTIONS_SQRT;
    let sun = local_sun(mu_s);
    let mut l_2nd = Lanes::ZERO;
    let mut f_ms = Lanes::ZERO;
    // The directions on one side of the sun's vertical plane: each one's mirror image has the
    // same mu and nu, so the same integrand, and needs no march of its own.
    let half = n_dir / 2;
    for d in 0..n_dir * half {
        let omega = sphere_direction((d / half) * n_dir + d % half, n_dir);
        let (l, f) = direction_terms(p, t, layer, h, mu_s, omega.z, omega.dot(sun));
        l_2nd = l_2nd + l;
        f_ms = f_ms + f;
    }
    let count = (n_dir * half) as f64;
    (l_2nd / count) / (1.0 - f_ms / count)
}

/// The second-order radiance (isotropic phase, sunlit ground) and the transfer f_ms that one
/// direction (mu, nu) brings to Ψ_ms at (h, mu_s), before the average over directions.
fn direction_terms(
    p: &Params,
    t: &Lut,
    layer: usize,
    h: f64,
    mu_s: f64,
    mu: f64,
    nu: f64,
) -> (Lanes, Lanes) {
    let big_r = p.bottom_radius_m;
    let r = big_r + h;
    let isotropic = 1.0 / (4.0 * PI);
    let albedo = p.batches[layer].ground_albedo;
    let mut l_2nd = Lanes::ZERO;
    let mut f_ms = Lanes::ZERO;
    let ground = hits_ground(h, mu, big_r);
    let t_max = if ground {
        distance_to_ground(h, mu, big_r)
    } else {
        distance_to_top(h, mu, big_r, p.top_radius_m)
    };
    let n = p.steps.multiple_scattering;
    let mut throughput = Lanes::ONE;
    for s in 0..n {
        let (t0, t1) = Spacing::Quadratic.segment(0.0, t_max, s, n);
        let (ts, dt) = (0.5 * (t0 + t1), t1 - t0);
        let (h_t, r_t) = altitude_along(h, mu, ts, big_r);
        let mu_s_t = (r * mu_s + ts * nu) / r_t;
        let m = p.medium(layer, h_t);
        let weight = throughput * segment_weight(m.extinction, dt);
        let sca = m.rayleigh_scattering + m.aerosol_scattering;
        let sun_t = sun_transmittance(p, t, layer, h_t, mu_s_t);
        for i in 0..LANES {
            l_2nd[i] += weight[i] * sca[i] * isotropic * sun_t[i];
            f_ms[i] += weight[i] * sca[i];
            throughput[i] *= (-m.extinction[i] * dt).exp();
        }
    }
    if ground {
        let mu_s_g = (r * mu_s + t_max * nu) / big_r;
        let sun_t = sun_transmittance(p, t, layer, 0.0, mu_s_g);
        for i in 0..LANES {
            l_2nd[i] += throughput[i] * sun_t[i] * mu_s_g.max(0.0) * albedo[i] / PI;
        }
    }
    (l_2nd, f_ms)
}

/// Looks up Ψ_ms at (h, mu_s).
pub fn multiple_scattering(p: &Params, ms: &Lut, layer: usize, h: f64, mu_s: f64) -> Lanes {
    let (fx, fy) = multiple_scattering_texel_from_h_mu_s(p, h, mu_s);
    ms.bilinear(layer, fx, fy, 0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::hillaire::ground_irradiance::*;
    use crate::methods::shared::optics::tests::params;

    #[test]
    fn multiple_scattering_and_ground_mappings_round_trip() {
        let p = params();
        for &(h, mu_s) in &[
            (0.0, -1.0),
            (10.0, -0.5),
            (500.0, -0.12),
            (1234.0, 0.2),
            (100_000.0, 1.0),
        ] {
            let (fx, fy) = multiple_scattering_texel_from_h_mu_s(&p, h, mu_s);
            let (h2, mu_s2) = multiple_scattering_h_mu_s_from_texel(&p, fx, fy);
            assert!((h2 - h).abs() < 1e-6 && (mu_s2 - mu_s).abs() < 1e-12);
            let mu_s3 = ground_irradiance_mu_s_from_texel(ground_irradiance_texel_from_mu_s(mu_s));
            assert!((mu_s3 - mu_s).abs() < 1e-12);
        }
        // The axis's knots sit on texel centres of both tables, so each texel interval lies
        // within one linear piece.
        for size in [MULTIPLE_SCATTERING_SIZE[0], GROUND_IRRADIANCE_SIZE] {
            for u in crate::methods::hillaire::MU_S_AXIS_U {
                let texel = u * (size - 1) as f64;
                assert!((texel - texel.round()).abs() < 1e-9, "{u} on {size} texels");
            }
        }
    }

    /// Marching one side of the sun's vertical plane gives Ψ_ms of the whole sphere of
    /// directions, at the ground (where half the sphere hits it) and above, sun up and down.
    #[test]
    fn the_mirror_half_of_the_directions_gives_the_whole_sphere() {
        let p = params();
        let t = crate::methods::hillaire::compute_transmittance_lut(&p);
        let n = MULTIPLE_SCATTERING_DIRECTIONS_SQRT;
        for (h, mu_s) in [(0.0, 0.8), (0.0, -0.1), (3000.0, 0.05), (30_000.0, -0.08)] {
            let sun = local_sun(mu_s);
            let (mut l, mut f) = (Lanes::ZERO, Lanes::ZERO);
            for d in 0..n * n {
                let omega = sphere_direction(d, n);
                let (dl, df) = direction_terms(&p, &t, 0, h, mu_s, omega.z, omega.dot(sun));
                (l, f) = (l + dl, f + df);
            }
            let count = (n * n) as f64;
            let whole: Lanes = (l / count) / (1.0 - f / count);
            let half = compute_multiple_scattering(&p, &t, 0, h, mu_s);
            for i in 0..LANES {
                assert!(whole[i] > 0.0, "h {h}, mu_s {mu_s}, lane {i}");
                let rel = (half[i] / whole[i] - 1.0).abs();
                assert!(rel < 1e-12, "h {h}, mu_s {mu_s}, lane {i}: {rel:e}");
            }
        }
    }
}

#[cfg(test)]
mod twilight {
    use super::*;
    use crate::methods::hillaire::compute_transmittance_lut;
    use crate::methods::hillaire::ground_irradiance::*;
    use crate::methods::shared::optics::tests::params;

    /// Ψ_ms and the ground irradiance fall by orders of magnitude between sunset and −12°; looked
    /// up between texels they stay within 30 % of the value computed at that very μ_s (the
    /// paper's uniform 32-texel axis gave 12–22 times too much at −12°).
    #[test]
    fn twilight_lookups_follow_the_exact_fall_of_multiple_scattering() {
        let p = params();
        let t = compute_transmittance_lut(&p);
        let ms = compute_multiple_scattering_lut(&p, &t);
        let gi = compute_ground_irradiance_lut(&p, &t, &ms);
        let within = |what: &str, table: Lanes, exact: Lanes| {
            for i in 0..LANES {
                let ratio = table[i] / exact[i];
                assert!(
                    (0.8..1.3).contains(&ratio),
                    "{what}, lane {i}: table/exact = {ratio:.3} ({:.3e} / {:.3e})",
                    table[i],
                    exact[i]
                );
            }
        };
        for deg in [30.0f64, 10.0, 2.0, -3.0, -6.0, -7.4, -9.0, -12.0] {
            let mu_s = deg.to_radians().sin();
            for h in [0.0, 5000.0, 20_000.0] {
                within(
                    &format!("Ψ_ms at {h} m, sun {deg}°"),
                    multiple_scattering(&p, &ms, 0, h, mu_s),
                    compute_multiple_scattering(&p, &t, 0, h, mu_s),
                );
            }
            within(
                &format!("ground irradiance, sun {deg}°"),
                ground_irradiance(&gi, 0, mu_s),
                compute_ground_irradiance(&p, &t, &ms, 0, mu_s),
            );
        }
    }
}
