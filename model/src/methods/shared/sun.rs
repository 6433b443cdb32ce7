//! The sun's disk: angular size and limb darkening from `crate::constants`.

use crate::constants::{SUN_ANGULAR_RADIUS_RAD, SUN_LIMB_DARKENING_U};
use glam::DVec3;
use std::f64::consts::PI;

/// Radiance of the sun's disk in direction `dir` (0 outside it), per unit solar irradiance:
/// limb darkened with the linear law I(μ′) ∝ 1 − u(1 − μ′), normalised to the disk's mean.
pub fn sun_disk(dir: DVec3, sun: DVec3) -> f64 {
    if dir.dot(sun) <= 0.0 {
        return 0.0;
    }
    let gamma = dir.cross(sun).length().min(1.0).asin();
    if gamma >= SUN_ANGULAR_RADIUS_RAD {
        return 0.0;
    }
    let x = gamma / SUN_ANGULAR_RADIUS_RAD;
    let mu_prime = (1.0 - x * x).sqrt();
    let limb = (1.0 - SUN_LIMB_DARKENING_U * (1.0 - mu_prime)) / (1.0 - SUN_LIMB_DARKENING_U / 3.0);
    let half = 0.5 * SUN_ANGULAR_RADIUS_RAD;
    let solid_angle = 4.0 * PI * half.sin() * half.sin();
    limb / solid_angle
}

/// Visible fraction of the sun's disk at zenith cosine `mu_s` from altitude `h` above a planet
/// of radius `big_r`: Earth's shadow with its penumbra, as in Bruneton (2017).
pub fn visible_fraction(h: f64, mu_s: f64, big_r: f64) -> f64 {
    let sin_h = big_r / (big_r + h);
    let cos_h = -(1.0 - sin_h * sin_h).max(0.0).sqrt();
    let edge = sin_h * SUN_ANGULAR_RADIUS_RAD;
    smoothstep(-edge, edge, mu_s - cos_h)
}

fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sun_disk_integrates_to_one() {
        let sun = DVec3::Z;
        let n = 400;
        let a = SUN_ANGULAR_RADIUS_RAD;
        let mut sum = 0.0;
        // Rings of the disk: ∫ L dΩ = Σ L(γ)·2π sin γ dγ.
        for i in 0..n {
            let gamma = (i as f64 + 0.5) / n as f64 * a;
            let dir = DVec3::new(gamma.sin(), 0.0, gamma.cos());
            sum += sun_disk(dir, sun) * 2.0 * PI * gamma.sin() * a / n as f64;
        }
        assert!((sum - 1.0).abs() < 1e-3, "{sum}");
        assert_eq!(sun_disk(DVec3::X, sun), 0.0);
    }
}
