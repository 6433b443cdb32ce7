//! Phase functions, normalised to 1 over the sphere (sr⁻¹), as functions of nu = cos θ, the
//! cosine of the angle between the incoming and scattered directions.
//!
//! Rayleigh with depolarisation follows Chandrasekhar (1960); Henyey–Greenstein (1941);
//! Cornette–Shanks (1992), the Mie approximation used by Bruneton & Neyret (2008).

use std::f64::consts::PI;

/// Elek's (2009) modified Rayleigh phase, in units of 1/(4π): a + b·nu with [a, b] = 0.8·[1.4,
/// 0.5], as Bodare & Sandberg (2014) and the Atmosphere Plus notes give it. Its odd term darkens
/// the sky opposite the sun, standing in for the azimuth his tables leave out.
pub const ELEK_MODIFIED_RAYLEIGH: [f64; 2] = [0.8 * 1.4, 0.8 * 0.5];

/// Rayleigh phase function for depolarisation ratio `rho` (0 = ideal dipole, air ≈ 0.03):
/// 3/(16π)·[(1+3γ) + (1−γ)ν²]/(1+2γ), γ = ρ/(2−ρ).
pub fn rayleigh(nu: f64, rho: f64) -> f64 {
    let gamma = rho / (2.0 - rho);
    3.0 / (16.0 * PI) * ((1.0 + 3.0 * gamma) + (1.0 - gamma) * nu * nu) / (1.0 + 2.0 * gamma)
}

/// Henyey–Greenstein phase function with asymmetry `g` ∈ (−1, 1).
pub fn henyey_greenstein(nu: f64, g: f64) -> f64 {
    let denom = 1.0 + g * g - 2.0 * g * nu;
    (1.0 - g * g) / (4.0 * PI * denom * denom.sqrt())
}

/// Cornette–Shanks phase function with parameter `g` ∈ (−1, 1); like Henyey–Greenstein but
/// with Rayleigh's (1 + ν²) factor, which brightens the backward lobe.
pub fn cornette_shanks(nu: f64, g: f64) -> f64 {
    let denom = 1.0 + g * g - 2.0 * g * nu;
    3.0 / (8.0 * PI) * (1.0 - g * g) * (1.0 + nu * nu) / ((2.0 + g * g) * denom * denom.sqrt())
}

/// A phase function tabulated as ln p (sr⁻¹) at θ_i = π·(i/(n−1))², i = 0 … n−1, one row of n
/// per node (`ln_rows`), at scattering cosine `nu`: ln p linear in u = √(θ/π) within a row, and
/// p linear between rows ⌊node⌋ and ⌊node⌋ + 1 (`node` a fractional row index, clamped).
/// Twin of `tabulated_phase` in `shaders/common/phase.wgsl`.
pub fn tabulated(ln_rows: &[f64], n: usize, node: f64, nu: f64) -> f64 {
    let rows = ln_rows.len() / n;
    let u = (nu.clamp(-1.0, 1.0).acos() / PI).sqrt();
    let x = u * (n - 1) as f64;
    let i = (x as usize).min(n - 2);
    let t = x - i as f64;
    let row = |r: usize| {
        let l = &ln_rows[r * n..(r + 1) * n];
        (l[i] + t * (l[i + 1] - l[i])).exp()
    };
    let node = node.clamp(0.0, (rows - 1) as f64);
    let r0 = (node as usize).min(rows - 1);
    let r1 = (r0 + 1).min(rows - 1);
    let s = node - r0 as f64;
    row(r0) + s * (row(r1) - row(r0))
}

/// ∫ p dΩ of one row of [`tabulated`] (n values of ln p), as it interpolates them: the
/// midpoint rule on 32 points per interval of u, dΩ = 2π sin θ dθ with θ = π u².
pub fn tabulated_integral(ln_row: &[f64], n: usize) -> f64 {
    let steps = 32 * (n - 1);
    let du = 1.0 / steps as f64;
    (0..steps)
        .map(|k| {
            let u = (k as f64 + 0.5) * du;
            let theta = PI * u * u;
            tabulated(ln_row, n, 0.0, theta.cos()) * 2.0 * PI * theta.sin() * 2.0 * PI * u * du
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quadrature::integrate_adaptive;

    fn sphere_integral(p: impl Fn(f64) -> f64) -> f64 {
        2.0 * PI * integrate_adaptive(p, -1.0, 1.0, 1e-12, 0.0).value
    }

    fn mean_cosine(p: impl Fn(f64) -> f64) -> f64 {
        2.0 * PI * integrate_adaptive(|nu| nu * p(nu), -1.0, 1.0, 1e-12, 0.0).value
    }

    #[test]
    fn every_phase_function_is_normalised() {
        for rho in [0.0, 0.0279, 0.1] {
            assert!((sphere_integral(|nu| rayleigh(nu, rho)) - 1.0).abs() < 1e-10);
        }
        for g in [-0.5, 0.0, 0.3, 0.76, 0.9] {
            assert!(
                (sphere_integral(|nu| henyey_greenstein(nu, g)) - 1.0).abs() < 1e-8,
                "HG {g}"
            );
            assert!(
                (sphere_integral(|nu| cornette_shanks(nu, g)) - 1.0).abs() < 1e-8,
                "CS {g}"
            );
        }
    }

    #[test]
    fn henyey_greenstein_mean_cosine_is_g() {
        for g in [-0.3, 0.0, 0.5, 0.8] {
            assert!((mean_cosine(|nu| henyey_greenstein(nu, g)) - g).abs() < 1e-8);
        }
        assert!((henyey_greenstein(0.3, 0.0) - 1.0 / (4.0 * PI)).abs() < 1e-15);
    }

    #[test]
    fn rayleigh_is_symmetric_and_peaks_forward_and_back() {
        let rho = 0.0279;
        assert!((rayleigh(0.7, rho) - rayleigh(-0.7, rho)).abs() < 1e-15);
        assert!(rayleigh(1.0, rho) > rayleigh(0.0, rho));
        assert!((rayleigh(1.0, 0.0) / rayleigh(0.0, 0.0) - 2.0).abs() < 1e-12);
    }
}
