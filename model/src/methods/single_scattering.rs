//! Exact single scattering by deterministic adaptive quadrature, in f64: the independent check of
//! the path tracer (which must agree with it at maximum order 1).
//!
//! L(λ) = ∫ T(0,t) [σ_R(t) P_R(ν) + σ_A(t) P_A(ν)] E_sun T_sun(x(t)) dt, plus, when the view ray
//! ends on the ground, T(0,t_g)·(a/π)·cos θ_s·E_sun·T_sun(x_g). T are computed by the
//! atmosphere's adaptive optical-depth integrals; the sun is a point at the disk's centre (the
//! disk's 0.27° matters only at the shadow's edge).

use crate::atmosphere::{Atmosphere, Optics};
use crate::geometry::{self, Ray};
use crate::phase;
use crate::quadrature::integrate_adaptive;
use crate::scene::AerosolPhase;
use glam::DVec3;
use std::f64::consts::PI;

/// Relative tolerance of the outer integral.
pub const REL_TOL: f64 = 1e-6;

/// Single-scattered radiance reaching `ray.origin` from `-ray.direction` at `wavelength_nm`,
/// W·m⁻²·sr⁻¹·nm⁻¹, with the sun in unit direction `sun`.
pub fn radiance(atm: &Atmosphere, ray: &Ray, sun: DVec3, wavelength_nm: f64) -> f64 {
    let optics = atm.optics(wavelength_nm);
    let e_sun = atm.solar_spectrum.spectrum().sample(wavelength_nm);
    let (r, mu) = ray.r_mu();
    let Some((t0, t1)) = segment(atm, r, mu) else {
        return 0.0;
    };
    let nu = ray.direction.dot(sun);
    let p_r = phase::rayleigh(nu, optics.rayleigh_depolarisation);
    let p_a = match atm.aerosol_phase {
        AerosolPhase::HenyeyGreenstein => phase::henyey_greenstein(nu, optics.aerosol_g),
        AerosolPhase::CornetteShanks => phase::cornette_shanks(nu, optics.aerosol_g),
    };
    let view_transmittance = |t: f64| {
        if t <= t0 {
            return 1.0;
        }
        let partial = Ray {
            origin: ray.origin + ray.direction * t0,
            direction: ray.direction,
        };
        (-optical_depth_to(atm, &optics, &partial, t - t0)).exp()
    };
    let integrand = |t: f64| {
        let x = ray.origin + ray.direction * t;
        let c = atm.coefficients(&optics, x.length() - atm.bottom_radius_m);
        let source = c.rayleigh_scattering * p_r + c.aerosol_scattering * p_a;
        if source <= 0.0 {
            return 0.0;
        }
        source * e_sun * atm.transmittance_to_sun(&optics, x, sun) * view_transmittance(t)
    };
    // Split where the sun sets for points along the ray (the shadow's edge) and at the ray's
    // lowest point, where the density peaks.
    let mut cuts = vec![t0, t1];
    let t_low = -r * mu;
    if t_low > t0 && t_low < t1 {
        cuts.push(t_low);
    }
    cuts.extend(
        shadow_crossings(atm, ray, sun)
            .into_iter()
            .filter(|&t| t > t0 && t < t1),
    );
    cuts.sort_by(f64::total_cmp);
    let mut l: f64 = cuts
        .windows(2)
        .map(|w| integrate_adaptive(integrand, w[0], w[1], REL_TOL, 0.0).value)
        .sum();
    if geometry::ray_intersects_ground(r, mu, atm.bottom_radius_m) {
        let x = ray.origin + ray.direction * t1;
        let n = x.normalize();
        let cos_s = n.dot(sun);
        if cos_s > 0.0 {
            let x = n * atm.bottom_radius_m;
            l += view_transmittance(t1) * atm.ground_albedo / PI
                * cos_s
                * e_sun
                * atm.transmittance_to_sun(&optics, x, sun);
        }
    }
    l
}

/// The atmosphere segment of the ray, ending on the ground when it meets it.
fn segment(atm: &Atmosphere, r: f64, mu: f64) -> Option<(f64, f64)> {
    let (t0, t1) = geometry::sphere_distances(r, mu, atm.top_radius_m)?;
    if t1 <= 0.0 {
        return None;
    }
    let start = t0.max(0.0);
    let end = match geometry::distance_to_ground(r, mu, atm.bottom_radius_m) {
        Some(g) if g >= start => g,
        _ => t1,
    };
    (end > start).then_some((start, end))
}

/// Optical depth from the ray's origin over a distance `length`.
fn optical_depth_to(atm: &Atmosphere, optics: &Optics, ray: &Ray, length: f64) -> f64 {
    atm.optical_depth_between(optics, ray, 0.0, length).total()
}

/// Distances along the ray where points cross the boundary of the planet's shadow cylinder.
fn shadow_crossings(atm: &Atmosphere, ray: &Ray, sun: DVec3) -> Vec<f64> {
    // Points whose distance from the sun axis equals the planet radius: a quadratic in t.
    let o = ray.origin - sun * ray.origin.dot(sun);
    let d = ray.direction - sun * ray.direction.dot(sun);
    let (a, b, c) = (
        d.dot(d),
        2.0 * o.dot(d),
        o.dot(o) - atm.bottom_radius_m * atm.bottom_radius_m,
    );
    if a <= 0.0 {
        return vec![];
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return vec![];
    }
    let s = disc.sqrt();
    vec![(-b - s) / (2.0 * a), (-b + s) / (2.0 * a)]
}
