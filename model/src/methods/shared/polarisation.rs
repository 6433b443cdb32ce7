//! The polarisation the real-time models show: sunlight scattered once along the view ray,
//! lit through the model's own transmittance towards the sun, and a correction for the light
//! of the higher orders, whose polarisation the model does not carry. Twin of
//! `shaders/views/polarisation.wgsl`.
//!
//! **Single scattering** is marched like the table-free models' skies ([`VIEW_STEPS`] midpoint
//! samples, crowded near a camera in the lower atmosphere): its radiance I₁ and its Q referred to the scattering plane, from air's matrix
//! (`mueller::ReducedMatrix::rayleigh`). The aerosols polarise nothing here, whatever their
//! phase: the GPU holds no Mie matrix.
//!
//! **The higher orders.** The model's radiance I less I₁ is the light of the higher orders,
//! I_ms. The vector path tracer shows it partly polarised in two ways (measured in
//! `docs/measurements/polarisation-2026-12-06.md`): like the single-scattered light of the same
//! view, scaled down (light scattered twice near the forward and backward directions keeps the
//! primary pattern), and vertically, by light from the bright band near the horizon scattered
//! towards the observer at about 90°, which is why the neutral points of Arago, Babinet and
//! Brewster exist. So in the sky
//!
//! (Q, U) = (Q₁, U₁)·(1 + β·I_ms/I₁) + α·sin²θ_v·I_ms·(cos 2χ_v, sin 2χ_v),
//!
//! with θ_v the view's zenith angle and χ_v the angle of the vertical. β and α are fitted to
//! the vector tracer ([`MS_LIKE_SINGLE`], [`MS_VERTICAL`]); over the ground only single
//! scattering's Q and U count (the ground depolarises). The polarised part never exceeds I.

use super::ray::camera_coords;
use super::{Params, aerosol_phase, rayleigh_phase, segment_weight};
use crate::geometry::{altitude_along, distance_to_ground, distance_to_top};
use crate::lanes::Lanes;
use crate::polarisation::mueller::ReducedMatrix;
use glam::DVec3;

/// β: the share of the higher orders' light polarised like single scattering's.
pub const MS_LIKE_SINGLE: f64 = 0.44;

/// α: the higher orders' vertical polarisation, per unit sin²θ_v. Between the best fits of the
/// degree over clear and hazy skies together and over clear skies alone: the vertical part is
/// what moves the neutral points off the sun, and the smaller fit left Arago's point below
/// the horizon at sunset (the fits are in the measurement log named in the module's docs).
pub const MS_VERTICAL: f64 = 0.15;

/// Midpoint samples of single scattering along a view ray ([`view_step`]).
pub const VIEW_STEPS: u32 = 24;

/// Once-scattered sunlight along a view ray, per lane, W·m⁻²·sr⁻¹·nm⁻¹.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingleScattered {
    pub i: Lanes,
    /// Q referred to the scattering plane (negative: polarised across it).
    pub q_plane: Lanes,
    /// Whether the ray ends on the ground.
    pub ground: bool,
}

/// Single scattering of batch `layer` seen from `at` (position, altitude h) along `dir` with
/// the sun in direction `sun`, lit through `sun_transmittance(h, mu_s)` (per lane); None where
/// the ray misses the atmosphere.
pub fn single_scattered(
    p: &Params,
    layer: usize,
    at: (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
    sun_transmittance: impl Fn(f64, f64) -> Lanes,
) -> Option<SingleScattered> {
    let big_r = p.bottom_radius_m;
    let c = camera_coords(p, at, dir, sun)?;
    let (h0, mu0, mu_s0, nu) = (c.h, c.mu, c.mu_s, c.nu);
    let b = &p.batches[layer];
    let (phase_r, phase_a) = (rayleigh_phase(p, layer, nu), aerosol_phase(p, layer, nu));
    let b1 = b
        .rayleigh_depolarisation
        .map(|rho| ReducedMatrix::rayleigh(nu, rho).b1);
    let r0 = big_r + h0;
    let t_max = if c.ground {
        distance_to_ground(h0, mu0, big_r)
    } else {
        distance_to_top(h0, mu0, big_r, p.top_radius_m)
    };
    let (mut i, mut q) = (Lanes::ZERO, Lanes::ZERO);
    let mut throughput = Lanes::ONE;
    for s in 0..VIEW_STEPS {
        let (t, dt) = view_step(s, t_max, h0);
        let (h_t, r_t) = altitude_along(h0, mu0, t, big_r);
        let mu_s_t = ((r0 * mu_s0 + t * nu) / r_t).clamp(-1.0, 1.0);
        let m = p.medium(layer, h_t);
        let sun_t = sun_transmittance(h_t, mu_s_t);
        let weight = segment_weight(m.extinction, dt);
        for k in 0..4 {
            let w = throughput[k] * weight[k] * sun_t[k] * b.solar_irradiance[k];
            let air = m.rayleigh_scattering[k] * phase_r[k];
            i[k] += w * (air + m.aerosol_scattering[k] * phase_a[k]);
            q[k] += w * air * b1[k];
            throughput[k] *= (-m.extinction[k] * dt).exp();
        }
    }
    Some(SingleScattered {
        i,
        q_plane: q,
        ground: c.ground,
    })
}

/// The middle and length (m) of sample `s` of a view ray `t_max` long from altitude `h0`:
/// spaced as u² (u = s/[`VIEW_STEPS`]) from a camera in the lower atmosphere, where a low-lying
/// haze of scale height 1–2 km would otherwise fall inside the first sample of a long slant
/// ray, and evenly from higher up.
pub fn view_step(s: u32, t_max: f64, h0: f64) -> (f64, f64) {
    let n = f64::from(VIEW_STEPS);
    let (u0, u1) = (f64::from(s) / n, f64::from(s + 1) / n);
    let (a, b) = if h0 < DENSE_NEAR_CAMERA_BELOW_M {
        (u0 * u0, u1 * u1)
    } else {
        (u0, u1)
    };
    (0.5 * (a + b) * t_max, (b - a) * t_max)
}

/// Below this altitude (m) the view samples crowd near the camera ([`view_step`]).
pub const DENSE_NEAR_CAMERA_BELOW_M: f64 = 20_000.0;

/// (cos 2χ, sin 2χ) of the unit vector `e` (perpendicular to the view) in the frame whose e₁
/// is `e_up` and e₂ = `dir` × e₁; zeros for a zero `e`.
fn double_angle(e: DVec3, e_up: DVec3, dir: DVec3) -> (f64, f64) {
    let (c, s) = (e.dot(e_up), e.dot(dir.cross(e_up)));
    (c * c - s * s, 2.0 * c * s)
}

/// The Stokes Q and U per lane of the light a real-time model gives as `i_model` (W·m⁻²·sr⁻¹·
/// nm⁻¹, the sun's disk excluded) along `dir` from `at`, referred to the frame whose e₁ is the
/// unit vector `e_up` (perpendicular to `dir`; e₂ = `dir` × e₁), with the model's
/// `sun_transmittance(h, mu_s)`.
#[allow(clippy::too_many_arguments)]
pub fn sky_stokes(
    p: &Params,
    layer: usize,
    at: (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
    e_up: DVec3,
    i_model: Lanes,
    sun_transmittance: impl Fn(f64, f64) -> Lanes,
) -> [Lanes; 2] {
    let Some(ss) = single_scattered(p, layer, at, dir, sun, sun_transmittance) else {
        return [Lanes::ZERO; 2];
    };
    let across = dir.cross(sun).normalize_or_zero();
    let (cp, sp) = double_angle(across, e_up, dir);
    let zenith = at.0.normalize();
    let vertical = (zenith - dir * dir.dot(zenith)).normalize_or_zero();
    let (cv, sv) = double_angle(vertical, e_up, dir);
    let sin2_view = 1.0 - dir.dot(zenith).powi(2);
    let (mut q, mut u) = (Lanes::ZERO, Lanes::ZERO);
    for k in 0..4 {
        // The degree of single scattering across the scattering plane, times its radiance.
        let mut polarised = -ss.q_plane[k];
        let mut vertical_part = 0.0;
        if !ss.ground && ss.i[k] > 0.0 {
            let multiple = (i_model[k] - ss.i[k]).max(0.0);
            polarised *= 1.0 + MS_LIKE_SINGLE * multiple / ss.i[k];
            vertical_part = MS_VERTICAL * sin2_view * multiple;
        }
        q[k] = polarised * cp + vertical_part * cv;
        u[k] = polarised * sp + vertical_part * sv;
        // No more polarised light than light.
        let length = q[k].hypot(u[k]);
        if length > i_model[k].max(0.0) {
            let scale = if length > 0.0 {
                i_model[k].max(0.0) / length
            } else {
                0.0
            };
            q[k] *= scale;
            u[k] *= scale;
        }
    }
    [q, u]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::Atmosphere;
    use crate::geometry::direction_from_angles;
    use crate::polarisation::{Stokes, meridian_frame, rayleigh_degree};
    use crate::scene::Scene;

    fn clear_air() -> (Params, Atmosphere) {
        let mut s = Scene::default();
        s.atmosphere.aerosol.kind = crate::aerosol::AerosolType::None;
        s.atmosphere.ground_albedo = 0.0;
        let atm = Atmosphere::for_scene(&s);
        let p = Params::at_wavelengths(&atm, &[450.0, 550.0, 650.0, 700.0], s.render.quality);
        (p, atm)
    }

    /// Where the model's radiance is single scattering's own (no higher orders), the view's
    /// Stokes vector is single scattering's: Rayleigh's degree at the view's scattering angle in
    /// a thin-air view, across the scattering plane (horizontal in the sun's vertical); and the
    /// march of 24 samples agrees with the exact integrator's polarised radiance within 2 %.
    #[test]
    fn without_higher_orders_it_is_single_scattering() {
        let (p, atm) = clear_air();
        let position = DVec3::new(0.0, 0.0, p.bottom_radius_m + 1.0);
        let sun = direction_from_angles(30.0, 0.0);
        let exact_t = |h: f64, mu_s: f64| {
            Lanes::from_fn(|k| {
                let o = atm.optics(p.batches[0].colour.wavelengths_nm[k]);
                let x = DVec3::new(0.0, 0.0, p.bottom_radius_m + h);
                let d = DVec3::new((1.0 - mu_s * mu_s).max(0.0).sqrt(), 0.0, mu_s);
                atm.transmittance_to_sun(&o, x, d)
            })
        };
        for (elevation, azimuth) in [(60.0, 180.0), (40.0, 90.0), (20.0, 300.0)] {
            let dir = direction_from_angles(elevation, azimuth);
            let (up, _) = meridian_frame(dir, position.normalize());
            let ss = single_scattered(&p, 0, (position, 1.0), dir, sun, exact_t).unwrap();
            let [q, u] = sky_stokes(&p, 0, (position, 1.0), dir, sun, up, ss.i, exact_t);
            for k in 0..4 {
                let w = p.batches[0].colour.wavelengths_nm[k];
                let exact = crate::methods::single_scattering::stokes(
                    &atm,
                    &crate::geometry::Ray::new(position, dir),
                    sun,
                    w,
                );
                let s = Stokes {
                    i: ss.i[k],
                    q: q[k],
                    u: u[k],
                    v: 0.0,
                };
                let polarised = q[k].hypot(u[k]);
                let exact_polarised = exact.q.hypot(exact.u);
                assert!(
                    (polarised / exact_polarised - 1.0).abs() < 0.02,
                    "{elevation}° {azimuth}° {w} nm: {polarised} vs {exact_polarised}"
                );
                assert!(
                    (s.angle_of_polarization_deg() - exact.angle_of_polarization_deg()).abs()
                        < 1e-6
                        || (s.angle_of_polarization_deg() - exact.angle_of_polarization_deg())
                            .abs()
                            > 180.0 - 1e-6,
                    "{s:?} vs {exact:?}"
                );
                let rho = p.batches[0].rayleigh_depolarisation[k];
                let degree = rayleigh_degree(dir.dot(sun), rho);
                assert!(s.degree_of_polarization() <= degree + 1e-12);
            }
        }
    }

    /// The higher orders: more light than single scattering lowers the degree, but less than
    /// if it were unpolarised; it turns the light vertical where single scattering is weak (above
    /// the sun: Babinet's neutral point lies between); and the degree never exceeds 1, even
    /// for a model darker than single scattering.
    #[test]
    fn the_higher_orders_depolarise_partly_and_polarise_vertically() {
        let (p, atm) = clear_air();
        let position = DVec3::new(0.0, 0.0, p.bottom_radius_m + 1.0);
        let sun = direction_from_angles(20.0, 0.0);
        let t = |h: f64, mu_s: f64| {
            Lanes::from_fn(|k| {
                let o = atm.optics(p.batches[0].colour.wavelengths_nm[k]);
                let x = DVec3::new(0.0, 0.0, p.bottom_radius_m + h);
                let d = DVec3::new((1.0 - mu_s * mu_s).max(0.0).sqrt(), 0.0, mu_s);
                atm.transmittance_to_sun(&o, x, d)
            })
        };
        let at = (position, 1.0);
        let meridian = |dir: DVec3| meridian_frame(dir, position.normalize()).0;
        // 90° from the sun.
        let dir = direction_from_angles(70.0, 180.0);
        let ss = single_scattered(&p, 0, at, dir, sun, t).unwrap();
        let bright = ss.i * 1.5;
        let [q, u] = sky_stokes(&p, 0, at, dir, sun, meridian(dir), bright, t);
        let [q1, u1] = sky_stokes(&p, 0, at, dir, sun, meridian(dir), ss.i, t);
        for k in 0..4 {
            let (d, d1) = (q[k].hypot(u[k]) / bright[k], q1[k].hypot(u1[k]) / ss.i[k]);
            assert!(d < d1 && d > d1 / 1.5, "{d} vs {d1}");
        }
        // Just above the sun single scattering is horizontal and weak; with higher orders the
        // light there vibrates vertically (Q > 0), as above Babinet's point.
        let dir = direction_from_angles(25.0, 0.0);
        let ss = single_scattered(&p, 0, at, dir, sun, t).unwrap();
        let [q1, _] = sky_stokes(&p, 0, at, dir, sun, meridian(dir), ss.i, t);
        let [q, _] = sky_stokes(&p, 0, at, dir, sun, meridian(dir), ss.i * 2.0, t);
        assert!(q1[1] < 0.0 && q[1] > 0.0, "{q1:?} → {q:?}");
        // A model darker than single scattering: at most fully polarised.
        let dir = direction_from_angles(70.0, 180.0);
        let ss = single_scattered(&p, 0, at, dir, sun, t).unwrap();
        let dark = ss.i * 0.5;
        let [q, u] = sky_stokes(&p, 0, at, dir, sun, meridian(dir), dark, t);
        for k in 0..4 {
            assert!(q[k].hypot(u[k]) <= dark[k] * (1.0 + 1e-12));
        }
    }
}
