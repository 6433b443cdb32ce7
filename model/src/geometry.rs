//! Ray geometry around a spherical planet, in f64 and metres.
//!
//! Distances to spheres use the cancellation-free form of the quadratic's roots (one root from
//! the sum of like-signed terms, the other from the product c/q), so a ray grazing the top of the
//! atmosphere from 40 000 km away keeps its precision. Names follow Bruneton (2017): r is the
//! distance to the planet's centre, mu the cosine of the view zenith angle.

use glam::DVec3;

/// The two distances (t₀ ≤ t₁) along a ray from a point at radius `r` with zenith cosine `mu`
/// to the sphere of radius `radius`, or None when the line misses it. Distances may be negative
/// (behind the origin).
pub fn sphere_distances(r: f64, mu: f64, radius: f64) -> Option<(f64, f64)> {
    let b = r * mu;
    // r²(mu²−1) + R², written to keep its precision when r ≈ R.
    let discriminant = (radius - r) * (radius + r) + b * b;
    if discriminant < 0.0 {
        return None;
    }
    let q = -(b + b.signum() * discriminant.sqrt());
    let c = (r - radius) * (r + radius);
    if q == 0.0 {
        return Some((0.0, 0.0));
    }
    let (t0, t1) = (q, c / q);
    Some(if t0 <= t1 { (t0, t1) } else { (t1, t0) })
}

/// Whether a ray from radius `r` with zenith cosine `mu` hits the ground of radius `bottom`
/// in front of it.
pub fn ray_intersects_ground(r: f64, mu: f64, bottom: f64) -> bool {
    mu < 0.0 && (bottom - r) * (bottom + r) + r * r * mu * mu >= 0.0
}

/// Distance from radius `r` along zenith cosine `mu` to where the ray leaves the sphere of
/// radius `top` (the far intersection), or None if it never reaches it.
pub fn distance_to_top(r: f64, mu: f64, top: f64) -> Option<f64> {
    sphere_distances(r, mu, top)
        .map(|(_, t1)| t1)
        .filter(|&t| t >= 0.0)
}

/// Distance to the ground along the ray, if it hits the ground in front.
pub fn distance_to_ground(r: f64, mu: f64, bottom: f64) -> Option<f64> {
    if !ray_intersects_ground(r, mu, bottom) {
        return None;
    }
    sphere_distances(r, mu, bottom)
        .map(|(t0, _)| t0)
        .filter(|&t| t >= 0.0)
}

/// Radius reached after travelling `t` from radius `r` along zenith cosine `mu`.
pub fn radius_at(r: f64, mu: f64, t: f64) -> f64 {
    (t * t + 2.0 * r * mu * t + r * r).max(0.0).sqrt()
}

/// A ray in planet-centred coordinates (m); `direction` is unit length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub direction: DVec3,
}

impl Ray {
    pub fn new(origin: DVec3, direction: DVec3) -> Ray {
        Ray {
            origin,
            direction: direction.normalize(),
        }
    }

    /// (r, mu) of the ray's origin.
    pub fn r_mu(&self) -> (f64, f64) {
        let r = self.origin.length();
        let mu = if r > 0.0 {
            self.origin.dot(self.direction) / r
        } else {
            1.0
        };
        (r, mu.clamp(-1.0, 1.0))
    }

    /// The part [t_start, t_end] of the ray inside the shell between `bottom` and `top`,
    /// stopping at the ground; None if the ray never enters the atmosphere.
    pub fn atmosphere_segment(&self, bottom: f64, top: f64) -> Option<(f64, f64)> {
        let (r, mu) = self.r_mu();
        let (t0, t1) = sphere_distances(r, mu, top)?;
        if t1 < 0.0 {
            return None;
        }
        let start = t0.max(0.0);
        let end = match sphere_distances(r, mu, bottom) {
            Some((g0, _)) if g0 >= start && mu < 0.0 => g0.min(t1),
            _ => t1,
        };
        (end > start).then_some((start, end))
    }
}

/// Whether `point` (planet-centred, m) lies in the planet's shadow for a point sun in the unit
/// direction `sun`.
pub fn in_planet_shadow(point: DVec3, sun: DVec3, planet_radius: f64) -> bool {
    let r = point.length();
    let mu = point.dot(sun) / r;
    ray_intersects_ground(r, mu, planet_radius)
}

/// Unit vector for an elevation above the horizon and an azimuth clockwise from north, in a
/// local frame where +z is up, +y north and +x east.
pub fn direction_from_angles(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    DVec3::new(e.cos() * a.sin(), e.cos() * a.cos(), e.sin())
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: f64 = 6_360_000.0;
    const TOP: f64 = 6_460_000.0;

    #[test]
    fn vertical_distances_are_exact() {
        assert_eq!(distance_to_top(R, 1.0, TOP), Some(100_000.0));
        assert_eq!(distance_to_ground(R + 1000.0, -1.0, R), Some(1000.0));
        assert!(distance_to_ground(R + 1000.0, 1.0, R).is_none());
    }

    #[test]
    fn horizontal_ray_from_the_ground_reaches_the_top_at_the_pythagorean_distance() {
        let d = distance_to_top(R, 0.0, TOP).unwrap();
        let exact = (TOP * TOP - R * R).sqrt();
        assert!((d - exact).abs() < 1e-6);
        assert!(!ray_intersects_ground(R, 0.0, R) || distance_to_ground(R, 0.0, R) == Some(0.0));
    }

    #[test]
    fn grazing_ray_from_far_away_keeps_precision() {
        // From 40 000 km, aim a ray tangent to a sphere 1 m above the top of the atmosphere.
        let r = R + 40_000_000.0;
        let tangent = TOP + 1.0;
        let mu = -(1.0 - (tangent / r).powi(2)).sqrt();
        assert!(sphere_distances(r, mu, TOP).is_none(), "passes 1 m above");
        let mu_in = -(1.0 - ((TOP - 1.0) / r).powi(2)).sqrt();
        let (t0, t1) = sphere_distances(r, mu_in, TOP).unwrap();
        // The chord through a sphere 1 m below its top is 2·sqrt(2·R·1) long.
        let chord = 2.0 * (2.0 * TOP).sqrt();
        assert!(
            ((t1 - t0) / chord - 1.0).abs() < 1e-3,
            "{} vs {chord}",
            t1 - t0
        );
    }

    #[test]
    fn radius_along_the_ray_matches_the_intersection() {
        for mu in [-0.9, -0.1, 0.0, 0.3, 1.0] {
            let r = R + 5000.0;
            let t = distance_to_top(r, mu, TOP).unwrap();
            assert!((radius_at(r, mu, t) - TOP).abs() < 1e-6);
        }
    }

    #[test]
    fn atmosphere_segment_from_space_and_shadow() {
        let ray = Ray::new(
            DVec3::new(0.0, 0.0, R + 400_000.0),
            DVec3::new(0.0, 0.0, -1.0),
        );
        let (a, b) = ray.atmosphere_segment(R, TOP).unwrap();
        assert!((a - 300_000.0).abs() < 1e-6 && (b - 400_000.0).abs() < 1e-6);
        let up = Ray::new(DVec3::new(0.0, 0.0, R + 400_000.0), DVec3::Z);
        assert!(up.atmosphere_segment(R, TOP).is_none());
        let night = DVec3::new(0.0, 0.0, -(R + 10.0));
        assert!(in_planet_shadow(night, DVec3::Z, R));
        assert!(!in_planet_shadow(-night, DVec3::Z, R));
    }
}
