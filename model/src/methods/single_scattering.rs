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
use crate::polarisation::mueller::ReducedMatrix;
use crate::polarisation::{self, Stokes};
use crate::quadrature::integrate_adaptive;
use glam::DVec3;
use std::f64::consts::PI;

/// Relative tolerance of the outer integral.
pub const REL_TOL: f64 = 1e-6;

/// Single-scattered radiance by what scattered it, W·m⁻²·sr⁻¹·nm⁻¹.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Parts {
    /// Sunlight scattered once by air molecules.
    pub rayleigh: f64,
    /// Sunlight scattered once by aerosols.
    pub aerosol: f64,
    /// Sunlight reflected once by the ground (seen where the ray ends on it).
    pub ground: f64,
}

impl Parts {
    pub fn total(&self) -> f64 {
        self.rayleigh + self.aerosol + self.ground
    }
}

/// Single-scattered radiance reaching `ray.origin` from `-ray.direction` at `wavelength_nm`,
/// W·m⁻²·sr⁻¹·nm⁻¹, with the sun in unit direction `sun`.
pub fn radiance(atm: &Atmosphere, ray: &Ray, sun: DVec3, wavelength_nm: f64) -> f64 {
    radiance_parts(atm, ray, sun, wavelength_nm).total()
}

/// [`radiance`] split into its Rayleigh, aerosol and ground parts.
pub fn radiance_parts(atm: &Atmosphere, ray: &Ray, sun: DVec3, wavelength_nm: f64) -> Parts {
    let optics = atm.optics(wavelength_nm);
    let e_sun = atm.solar_irradiance(wavelength_nm, None);
    let (r, mu) = ray.r_mu();
    let Some((t0, t1)) = segment(atm, r, mu) else {
        return Parts::default();
    };
    let nu = ray.direction.dot(sun);
    let p_r = phase::rayleigh(nu, optics.rayleigh_depolarisation);
    let p_a = atm.aerosol_phase(&optics, nu);
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
    // One integrand per constituent: the Rayleigh and aerosol parts each converge on their own.
    let integrand = |rayleigh: bool| {
        move |t: f64| {
            let x = ray.origin + ray.direction * t;
            let c = atm.coefficients(&optics, x.length() - atm.bottom_radius_m);
            let source = if rayleigh {
                c.rayleigh_scattering * p_r
            } else {
                c.aerosol_scattering * p_a
            };
            if source <= 0.0 {
                return 0.0;
            }
            source * e_sun * atm.transmittance_to_sun(&optics, x, sun) * view_transmittance(t)
        }
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
    let along = |rayleigh: bool| -> f64 {
        cuts.windows(2)
            .map(|w| integrate_adaptive(integrand(rayleigh), w[0], w[1], REL_TOL, 0.0).value)
            .sum()
    };
    let mut parts = Parts {
        rayleigh: along(true),
        aerosol: along(false),
        ground: 0.0,
    };
    if geometry::hits_ground(r - atm.bottom_radius_m, mu, atm.bottom_radius_m) {
        let x = ray.origin + ray.direction * t1;
        let n = x.normalize();
        let cos_s = n.dot(sun);
        if cos_s > 0.0 {
            let x = n * atm.bottom_radius_m;
            parts.ground = view_transmittance(t1) * atm.ground_albedo_at(wavelength_nm, None) / PI
                * cos_s
                * e_sun
                * atm.transmittance_to_sun(&optics, x, sun);
        }
    }
    parts
}

/// The atmosphere segment of the ray, ending on the ground when it meets it.
fn segment(atm: &Atmosphere, r: f64, mu: f64) -> Option<(f64, f64)> {
    let (t0, t1) = geometry::sphere_distances(r, mu, atm.top_radius_m)?;
    if t1 <= 0.0 {
        return None;
    }
    let start = t0.max(0.0);
    let end = match geometry::sphere_distances(r, mu, atm.bottom_radius_m) {
        Some((g, _)) if mu < 0.0 && g >= start => g.min(t1),
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

/// The Stokes vector of single-scattered light seen from `ray.origin` looking along
/// `ray.direction` (the light travels along −`ray.direction`), at `wavelength_nm` with the sun
/// in direction `sun` (the exact integrator of [`radiance_parts`];
/// W·m⁻²·sr⁻¹·nm⁻¹).
pub fn stokes(atm: &Atmosphere, ray: &Ray, sun: DVec3, wavelength_nm: f64) -> Stokes {
    let parts = radiance_parts(atm, ray, sun, wavelength_nm);
    let i = parts.total();
    if i <= 0.0 {
        return Stokes::default();
    }
    let optics = atm.optics(wavelength_nm);
    let nu = ray.direction.dot(sun);
    // Q referred to the scattering plane, over I: −b₁ of each constituent is the degree it
    // polarises across the plane.
    let across = -(ReducedMatrix::rayleigh(nu, optics.rayleigh_depolarisation).b1 * parts.rayleigh
        + atm.aerosol_matrix(&optics, nu).b1 * parts.aerosol);
    let chi = polarisation::perpendicular_angle(ray.direction, sun, ray.origin.normalize());
    Stokes::polarised(i, across / i, chi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aerosol::AerosolType;
    use crate::geometry::direction_from_angles;
    use crate::scene::{AtmosphereSettings, Scene};

    fn ray_from_ground(elevation_deg: f64, atm: &Atmosphere) -> Ray {
        Ray::new(
            DVec3::new(0.0, 0.0, atm.bottom_radius_m + 2.0),
            direction_from_angles(elevation_deg, 0.0),
        )
    }

    #[test]
    fn parts_follow_what_the_ray_meets() {
        let sun = direction_from_angles(30.0, 180.0);
        let mut settings = AtmosphereSettings::default();
        settings.ground_albedo = 0.3;
        let atm = Atmosphere::new(&settings);
        let up = radiance_parts(&atm, &ray_from_ground(45.0, &atm), sun, 550.0);
        assert!(up.rayleigh > 0.0 && up.aerosol > 0.0, "{up:?}");
        assert_eq!(up.ground, 0.0, "an upward ray never sees the ground");
        assert_eq!(
            radiance(&atm, &ray_from_ground(45.0, &atm), sun, 550.0),
            up.total()
        );
        let down = radiance_parts(&atm, &ray_from_ground(-30.0, &atm), sun, 550.0);
        assert!(down.ground > 0.0, "{down:?}");

        settings.aerosol.aod550 = 0.0;
        settings.ground_albedo = 0.0;
        let clean = Atmosphere::new(&settings);
        let down = radiance_parts(&clean, &ray_from_ground(-30.0, &clean), sun, 550.0);
        assert_eq!((down.aerosol, down.ground), (0.0, 0.0), "{down:?}");
        assert!(down.rayleigh > 0.0);
    }

    /// A pure-air sky over a black ground: the degree is Rayleigh's at the view's scattering
    /// angle; the electric vector lies across the scattering plane (horizontal where the sun
    /// is in the view's vertical plane); mirror views about the sun's vertical have mirrored
    /// Stokes vectors (U changes sign).
    #[test]
    fn single_scattering_polarises_across_the_scattering_plane_symmetrically() {
        let mut s = Scene::default();
        s.atmosphere.aerosol.kind = AerosolType::None;
        s.atmosphere.aerosol.aod550 = 0.0;
        s.atmosphere.ground_albedo = 0.0;
        s.sun = crate::scene::SunSettings::Angles {
            elevation_deg: 20.0,
            azimuth_deg: 90.0,
        };
        let atm = Atmosphere::for_scene(&s);
        let sun = direction_from_angles(20.0, 90.0);
        let origin = DVec3::new(0.0, 0.0, atm.bottom_radius_m + 1.0);
        let look = |elevation: f64, azimuth: f64| {
            let ray = Ray::new(origin, direction_from_angles(elevation, azimuth));
            stokes(&atm, &ray, sun, 550.0)
        };
        // In the sun's vertical (towards it and away): horizontal, Q < 0, U = 0, χ = 90°.
        for azimuth in [90.0, 270.0] {
            let st = look(45.0, azimuth);
            assert!(st.q < 0.0 && st.u == 0.0, "{azimuth}: {st:?}");
            assert_eq!(st.angle_of_polarization_deg(), 90.0);
        }
        // 90° from the sun (opposite azimuth, 70° up against 20° up): the air's maximum,
        // (1−ρ)/(1+ρ); and Rayleigh's degree at another angle.
        let rho = atm.optics(550.0).rayleigh_depolarisation;
        assert!(direction_from_angles(70.0, 270.0).dot(sun).abs() < 1e-12);
        let peak = look(70.0, 270.0).degree_of_polarization();
        assert!((peak - (1.0 - rho) / (1.0 + rho)).abs() < 1e-9, "{peak}");
        let nu = direction_from_angles(70.0, 180.0).dot(sun);
        let st = look(70.0, 180.0);
        assert!(
            (st.degree_of_polarization() - polarisation::rayleigh_degree(nu, rho)).abs() < 1e-9
        );
        // Mirror views about the sun's vertical plane.
        for (elevation, offset) in [(10.0, 40.0), (50.0, 100.0), (80.0, 150.0)] {
            let (a, b) = (
                look(elevation, 90.0 + offset),
                look(elevation, 90.0 - offset),
            );
            assert!((a.i - b.i).abs() < 1e-9 * a.i, "{a:?} {b:?}");
            assert!((a.q - b.q).abs() < 1e-9 * a.i, "{a:?} {b:?}");
            assert!((a.u + b.u).abs() < 1e-9 * a.i, "{a:?} {b:?}");
        }
    }

    /// Aerosol and ground add unpolarised light: the polarised radiance stays the air's,
    /// and the degree falls by the air's share of the light.
    #[test]
    fn aerosol_and_ground_add_only_unpolarised_light() {
        let s = Scene::default();
        let atm = Atmosphere::for_scene(&s);
        let sun = direction_from_angles(30.0, 180.0);
        let origin = DVec3::new(0.0, 0.0, atm.bottom_radius_m + 1.0);
        let ray = Ray::new(origin, direction_from_angles(40.0, 90.0));
        let st = stokes(&atm, &ray, sun, 450.0);
        let parts = radiance_parts(&atm, &ray, sun, 450.0);
        let rho = atm.optics(450.0).rayleigh_depolarisation;
        let air_only = polarisation::rayleigh_degree(ray.direction.dot(sun), rho);
        let expected = air_only * parts.rayleigh / parts.total();
        assert!((st.degree_of_polarization() - expected).abs() < 1e-12);
        assert!(st.degree_of_polarization() < air_only && parts.aerosol > 0.0);
        assert_eq!(st.i, parts.total());
    }
}
