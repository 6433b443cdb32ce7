//! Ray geometry around a spherical planet, in f64 and metres: the one geometry vocabulary of
//! the model crate, the path tracer and every sky model alike (WGSL twins of the altitude form
//! in `shaders/common/geometry.wgsl`).
//!
//! Distances to spheres use the cancellation-free form of the quadratic's roots (one root from
//! the sum of like-signed terms, the other from the product c/q), so a ray grazing the top of the
//! atmosphere from 40 000 km away keeps its precision. Names follow Bruneton (2017): r is the
//! distance to the planet's centre, mu the cosine of the view zenith angle, h = r − R the
//! altitude. Points inside the atmosphere are given by altitude h, with r² − R² formed as
//! h(2R + h), which stays accurate in f32 at 1 m above the ground; points anywhere (the path
//! tracer's, a camera in space) by radius r through [`sphere_distances`].

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

/// r² − R² for altitude `h` (m) above a planet of radius `big_r` (m), cancellation-free.
pub fn rho_squared(h: f64, big_r: f64) -> f64 {
    h * (2.0 * big_r + h)
}

/// Whether the ray from altitude `h` (m, ≥ 0) with zenith cosine `mu` hits the ground.
pub fn hits_ground(h: f64, mu: f64, big_r: f64) -> bool {
    let r = big_r + h;
    mu < 0.0 && r * r * mu * mu - rho_squared(h, big_r) >= 0.0
}

/// Distance (m) to the top of the atmosphere (radius `top`) from altitude `h` inside it. Each
/// root is formed without cancellation (the product of the roots is −(top² − r²)), which f32
/// needs.
pub fn distance_to_top(h: f64, mu: f64, big_r: f64, top: f64) -> f64 {
    let r = big_r + h;
    let rm = r * mu;
    let c = (top - big_r - h) * (top + r);
    let q = (rm * rm + c).max(0.0).sqrt();
    if rm > 0.0 {
        (c / (rm + q)).max(0.0)
    } else {
        -rm + q
    }
}

/// Distance (m) to the ground along a ray that hits it, as (r² − R²)/(−r·mu + √disc) so that
/// short distances near the ground keep their precision in f32.
pub fn distance_to_ground(h: f64, mu: f64, big_r: f64) -> f64 {
    let rm = (big_r + h) * mu;
    let disc = (rm * rm - rho_squared(h, big_r)).max(0.0);
    let denom = -rm + disc.sqrt();
    if denom > 0.0 {
        rho_squared(h, big_r) / denom
    } else {
        0.0
    }
}

/// Distance (m) to where the ray leaves the atmosphere: the ground if it hits it, else the top.
pub fn distance_to_boundary(h: f64, mu: f64, big_r: f64, top: f64) -> f64 {
    if hits_ground(h, mu, big_r) {
        distance_to_ground(h, mu, big_r)
    } else {
        distance_to_top(h, mu, big_r, top)
    }
}

/// Bruneton's (2017, §4.1) unit coordinates (x_mu, x_r) of a ray from altitude `h` (m,
/// 0 to top − R) with zenith cosine `mu` that reaches the top of the atmosphere (radius `top`)
/// without meeting the ground: x_r = ρ/H, x_mu the distance to the top between its least and
/// greatest over rays from that height.
pub fn transmittance_x_mu_x_r(h: f64, mu: f64, big_r: f64, top: f64) -> (f64, f64) {
    let thickness = top - big_r;
    let big_h = rho_squared(thickness, big_r).sqrt();
    let rho = rho_squared(h.max(0.0), big_r).sqrt();
    let d = distance_to_top(h, mu, big_r, top);
    let d_min = thickness - h;
    let d_max = rho + big_h;
    ((d - d_min) / (d_max - d_min).max(1e-9), rho / big_h)
}

/// The (h, mu) of Bruneton's unit coordinates (x_mu, x_r): the inverse of
/// [`transmittance_x_mu_x_r`].
pub fn transmittance_h_mu(x_mu: f64, x_r: f64, big_r: f64, top: f64) -> (f64, f64) {
    let thickness = top - big_r;
    let big_h = rho_squared(thickness, big_r).sqrt();
    let rho = big_h * x_r;
    let h = rho * rho / ((rho * rho + big_r * big_r).sqrt() + big_r);
    let r = big_r + h;
    let d_min = thickness - h;
    let d_max = rho + big_h;
    let d = d_min + x_mu * (d_max - d_min);
    let mu = if d <= 0.0 {
        1.0
    } else {
        ((big_h * big_h - rho * rho - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0)
    };
    (h, mu)
}

/// Altitude and radius (m) at distance `t` along the ray (h, mu).
pub fn altitude_along(h: f64, mu: f64, t: f64, big_r: f64) -> (f64, f64) {
    let r = big_r + h;
    let r_t = (r * r + t * t + 2.0 * r * mu * t).max(0.0).sqrt();
    let h_t = (rho_squared(h, big_r) + t * (t + 2.0 * r * mu)) / (r_t + big_r);
    (h_t, r_t)
}

/// Angle (rad) between the nadir and the horizon seen from altitude `h` (β in Hillaire 2020).
pub fn horizon_beta(h: f64, big_r: f64) -> f64 {
    big_r.atan2(rho_squared(h.max(0.0), big_r).sqrt())
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
    hits_ground(r - planet_radius, mu, planet_radius)
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
        assert_eq!(distance_to_top(0.0, 1.0, R, TOP), 100_000.0);
        assert!(hits_ground(1000.0, -1.0, R));
        assert!((distance_to_ground(1000.0, -1.0, R) - 1000.0).abs() < 1e-9);
        assert!(!hits_ground(1000.0, 1.0, R));
        assert!((distance_to_boundary(1000.0, 1.0, R, TOP) - 99_000.0).abs() < 1e-9);
    }

    #[test]
    fn horizontal_ray_from_the_ground_reaches_the_top_at_the_pythagorean_distance() {
        let d = distance_to_top(0.0, 0.0, R, TOP);
        let exact = (TOP * TOP - R * R).sqrt();
        assert!((d - exact).abs() < 1e-6);
        assert!(!hits_ground(0.0, 0.0, R) || distance_to_ground(0.0, 0.0, R) == 0.0);
    }

    #[test]
    fn altitude_along_the_ray_agrees_with_the_radius() {
        for mu in [-0.9, -0.1, 0.0, 0.3, 1.0] {
            let h = 5000.0;
            let t = distance_to_boundary(h, mu, R, TOP);
            let (h_t, r_t) = altitude_along(h, mu, t, R);
            assert!((r_t - radius_at(R + h, mu, t)).abs() < 1e-6);
            assert!((h_t - (r_t - R)).abs() < 1e-6);
        }
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
            let (_, t) = sphere_distances(r, mu, TOP).unwrap();
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
