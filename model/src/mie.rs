//! Lorenz–Mie scattering by homogeneous spheres and its average over log-normal size
//! distributions (the OPAC components of Hess et al. 1998).
//!
//! The series follows Bohren & Huffman (1983, appendix A): the logarithmic derivative D_n(mx) by
//! downward recurrence (stable for absorbing particles), the Riccati–Bessel functions by upward
//! recurrence, n_max = x + 4x^(1/3) + 2 terms (Wiscombe 1980). Refractive index m = n + ik with
//! k ≥ 0 meaning absorption.

use num_complex::Complex64;
use std::f64::consts::PI;

/// Efficiencies of one sphere (cross-section / geometric cross-section πr²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MieEfficiencies {
    pub q_ext: f64,
    pub q_sca: f64,
    /// Asymmetry parameter g = ⟨cos θ⟩.
    pub g: f64,
}

/// Mie efficiencies for size parameter `x` = 2πr/λ > 0 and relative refractive index `m`.
pub fn sphere(x: f64, m: Complex64) -> MieEfficiencies {
    efficiencies(x, &coefficients(x, m))
}

/// The scattering coefficients (a_n, b_n), n = 1 … n_max.
fn coefficients(x: f64, m: Complex64) -> Vec<(Complex64, Complex64)> {
    let n_max = (x + 4.0 * x.cbrt() + 2.0).ceil() as usize;
    let mx = m * x;
    // D_n(mx) by downward recurrence from well above n_max.
    let n_start = n_max.max(mx.norm().ceil() as usize) + 16;
    let mut d = vec![Complex64::new(0.0, 0.0); n_start + 1];
    for n in (1..=n_start).rev() {
        let nf = n as f64;
        d[n - 1] = nf / mx - 1.0 / (d[n] + nf / mx);
    }
    // Riccati–Bessel ψ_n(x) = x j_n(x) and χ_n(x) = −x y_n(x), upward.
    let (mut psi_prev, mut psi) = (x.cos(), x.sin());
    let (mut chi_prev, mut chi) = (-x.sin(), x.cos());
    let mut xi_prev;
    let mut xi = Complex64::new(psi, -chi);
    let mut ab = Vec::with_capacity(n_max);
    for n in 1..=n_max {
        let nf = n as f64;
        let psi_next = (2.0 * nf - 1.0) / x * psi - psi_prev;
        let chi_next = (2.0 * nf - 1.0) / x * chi - chi_prev;
        psi_prev = psi;
        psi = psi_next;
        chi_prev = chi;
        chi = chi_next;
        xi_prev = xi;
        xi = Complex64::new(psi, -chi);
        let da = d[n] / m + nf / x;
        let db = d[n] * m + nf / x;
        let a = (da * psi - psi_prev) / (da * xi - xi_prev);
        let b = (db * psi - psi_prev) / (db * xi - xi_prev);
        ab.push((a, b));
    }
    ab
}

fn efficiencies(x: f64, ab: &[(Complex64, Complex64)]) -> MieEfficiencies {
    let (mut q_ext, mut q_sca, mut g_sum) = (0.0, 0.0, 0.0);
    let (mut a_prev, mut b_prev) = (Complex64::new(0.0, 0.0), Complex64::new(0.0, 0.0));
    for (i, &(a, b)) in ab.iter().enumerate() {
        let nf = (i + 1) as f64;
        q_ext += (2.0 * nf + 1.0) * (a + b).re;
        q_sca += (2.0 * nf + 1.0) * (a.norm_sqr() + b.norm_sqr());
        g_sum += (2.0 * nf + 1.0) / (nf * (nf + 1.0)) * (a * b.conj()).re;
        if i > 0 {
            let np = nf - 1.0;
            g_sum += np * (np + 2.0) / (np + 1.0) * (a_prev * a.conj() + b_prev * b.conj()).re;
        }
        a_prev = a;
        b_prev = b;
    }
    let scale = 2.0 / (x * x);
    let q_sca = scale * q_sca;
    MieEfficiencies {
        q_ext: scale * q_ext,
        q_sca,
        g: if q_sca > 0.0 {
            2.0 * scale * g_sum / q_sca
        } else {
            0.0
        },
    }
}

/// The four independent elements of a sphere's scattering matrix, (S₁₁, S₁₂, S₃₃, S₃₄) in
/// Bohren & Huffman's notation (§4.4): S₁₁ = (|S₂|² + |S₁|²)/2 the intensity of unpolarised
/// light, S₁₂ = (|S₂|² − |S₁|²)/2, S₃₃ = Re(S₂S₁*), S₃₄ = Im(S₂S₁*); with S₂₂ = S₁₁ and
/// S₄₄ = S₃₃. Stokes vectors referred to the scattering plane (Q = I∥ − I⊥).
pub type MatrixElements = [f64; 4];

/// [`sphere`] and the scattering matrix's [`MatrixElements`] at each scattering cosine of `nus`
/// (S₁, S₂ from the angular functions π_n, τ_n by upward recurrence). The differential
/// scattering cross-section of unpolarised light is S₁₁/k², k = 2π/λ, and its integral over the
/// sphere is Q_sca·πr².
pub fn sphere_matrix(x: f64, m: Complex64, nus: &[f64]) -> (MieEfficiencies, Vec<MatrixElements>) {
    let ab = coefficients(x, m);
    let elements = nus
        .iter()
        .map(|&mu| {
            let (mut s1, mut s2) = (Complex64::new(0.0, 0.0), Complex64::new(0.0, 0.0));
            let (mut pi_prev, mut pi) = (0.0, 1.0);
            for (i, &(a, b)) in ab.iter().enumerate() {
                let nf = (i + 1) as f64;
                let tau = nf * mu * pi - (nf + 1.0) * pi_prev;
                let e = (2.0 * nf + 1.0) / (nf * (nf + 1.0));
                s1 += e * (a * pi + b * tau);
                s2 += e * (a * tau + b * pi);
                let pi_next = ((2.0 * nf + 1.0) * mu * pi - (nf + 1.0) * pi_prev) / nf;
                pi_prev = pi;
                pi = pi_next;
            }
            let s2_s1 = s2 * s1.conj();
            [
                0.5 * (s2.norm_sqr() + s1.norm_sqr()),
                0.5 * (s2.norm_sqr() - s1.norm_sqr()),
                s2_s1.re,
                s2_s1.im,
            ]
        })
        .collect();
    (efficiencies(x, &ab), elements)
}

/// A log-normal number size distribution dN/d ln r ∝ exp(−(ln r − ln r_mod)²/(2 ln²σ)),
/// truncated to [r_min, r_max] (OPAC's form). Radii in µm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LogNormal {
    pub r_mod_um: f64,
    pub sigma: f64,
    pub r_min_um: f64,
    pub r_max_um: f64,
}

impl LogNormal {
    /// Mean particle volume of the truncated distribution, µm³ (midpoint rule in ln r, as
    /// [`lognormal`] averages the cross-sections).
    pub fn mean_volume_um3(&self, points: usize) -> f64 {
        let (ln_lo, ln_hi) = (self.r_min_um.ln(), self.r_max_um.ln());
        let ln_s = self.sigma.ln();
        let step = (ln_hi - ln_lo) / points as f64;
        let (mut weight_sum, mut volume) = (0.0, 0.0);
        for i in 0..points {
            let ln_r = ln_lo + (i as f64 + 0.5) * step;
            let w = (-(ln_r - self.r_mod_um.ln()).powi(2) / (2.0 * ln_s * ln_s)).exp();
            weight_sum += w;
            volume += w * 4.0 / 3.0 * PI * (3.0 * ln_r).exp();
        }
        volume / weight_sum
    }
}

/// Mean optical cross-sections per particle of a size distribution at one wavelength.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BulkOptics {
    /// Extinction cross-section per particle, µm².
    pub ext_um2: f64,
    /// Scattering cross-section per particle, µm².
    pub sca_um2: f64,
    /// Asymmetry parameter of the scattered light.
    pub g: f64,
}

impl BulkOptics {
    pub fn single_scattering_albedo(&self) -> f64 {
        if self.ext_um2 > 0.0 {
            self.sca_um2 / self.ext_um2
        } else {
            0.0
        }
    }
}

/// Averages Mie over the distribution at `wavelength_um` with `points` radii evenly spaced in
/// ln r (Gauss–Legendre would gain little: the integrand's ripples are not smooth in r).
pub fn lognormal(dist: &LogNormal, wavelength_um: f64, m: Complex64, points: usize) -> BulkOptics {
    lognormal_scattering(dist, wavelength_um, m, points, &[]).0
}

/// [`lognormal`] and the distribution's mean scattering matrix per particle at each scattering
/// cosine of `nus`: the [`MatrixElements`] over k², µm² sr⁻¹ (the first, the differential
/// scattering cross-section, divided by `sca_um2` is the phase function, normalised to 1 over
/// the sphere).
pub fn lognormal_scattering(
    dist: &LogNormal,
    wavelength_um: f64,
    m: Complex64,
    points: usize,
    nus: &[f64],
) -> (BulkOptics, Vec<MatrixElements>) {
    let (ln_lo, ln_hi) = (dist.r_min_um.ln(), dist.r_max_um.ln());
    let ln_s = dist.sigma.ln();
    let step = (ln_hi - ln_lo) / points as f64;
    let k = 2.0 * PI / wavelength_um;
    let (mut weight_sum, mut ext, mut sca, mut g_sca) = (0.0, 0.0, 0.0, 0.0);
    let mut differential = vec![[0.0; 4]; nus.len()];
    for i in 0..points {
        let ln_r = ln_lo + (i as f64 + 0.5) * step;
        let w = (-(ln_r - dist.r_mod_um.ln()).powi(2) / (2.0 * ln_s * ln_s)).exp();
        if w < 1e-14 {
            continue;
        }
        let r = ln_r.exp();
        let (e, elements) = sphere_matrix(k * r, m, nus);
        let area = PI * r * r;
        weight_sum += w;
        ext += w * e.q_ext * area;
        sca += w * e.q_sca * area;
        g_sca += w * e.q_sca * area * e.g;
        for (d, s) in differential.iter_mut().zip(&elements) {
            for (d, s) in d.iter_mut().zip(s) {
                *d += w * s / (k * k);
            }
        }
    }
    differential
        .iter_mut()
        .for_each(|d| d.iter_mut().for_each(|d| *d /= weight_sum));
    let bulk = BulkOptics {
        ext_um2: ext / weight_sum,
        sca_um2: sca / weight_sum,
        g: if sca > 0.0 { g_sca / sca } else { 0.0 },
    };
    (bulk, differential)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_particles_follow_the_rayleigh_limit() {
        // Q_sca → (8/3) x⁴ |(m²−1)/(m²+2)|², Q_abs → 4x Im((m²−1)/(m²+2)), g → 0.
        let m = Complex64::new(1.5, 0.01);
        let x = 0.01;
        let e = sphere(x, m);
        let k = (m * m - 1.0) / (m * m + 2.0);
        let q_sca = 8.0 / 3.0 * x.powi(4) * k.norm_sqr();
        let q_abs = 4.0 * x * k.im;
        assert!(
            (e.q_sca / q_sca - 1.0).abs() < 1e-3,
            "{} vs {}",
            e.q_sca,
            q_sca
        );
        assert!(((e.q_ext - e.q_sca) / q_abs - 1.0).abs() < 1e-3);
        assert!(e.g.abs() < 1e-3);
    }

    #[test]
    fn large_particles_tend_to_extinction_efficiency_two() {
        for m in [
            Complex64::new(1.33, 0.0),
            Complex64::new(1.53, 0.008),
            Complex64::new(1.75, 0.44),
        ] {
            let e = sphere(2000.0, m);
            assert!((e.q_ext - 2.0).abs() < 0.02, "{m}: Q_ext = {}", e.q_ext);
        }
    }

    #[test]
    fn non_absorbing_spheres_scatter_all_they_extinguish() {
        for x in [0.1, 1.0, 5.0, 30.0, 300.0] {
            let e = sphere(x, Complex64::new(1.45, 0.0));
            assert!((e.q_sca / e.q_ext - 1.0).abs() < 1e-9, "x = {x}");
            assert!(e.g > -1.0 && e.g < 1.0);
        }
    }

    #[test]
    fn matches_bohren_huffman_reference_case() {
        // Bohren & Huffman (1983) appendix A example: water droplet m = 1.55, x = 5.213
        // (r = 0.525 µm at λ = 0.6328 µm): Q_ext = 3.1054, Q_sca = 3.1054, g ≈ 0.6
        // (the book prints Q_sca = 3.10543; our series reproduces it).
        let e = sphere(5.213, Complex64::new(1.55, 0.0));
        assert!((e.q_ext - 3.1054).abs() < 2e-3, "{}", e.q_ext);
    }

    /// The intensity integrates over the sphere to k²·C_sca = x²·π·Q_sca and its mean cosine
    /// is g; a small sphere scatters as a dipole, i(0) = i(π) = 2·i(π/2).
    #[test]
    fn scattered_intensity_integrates_to_the_cross_section_and_its_mean_cosine_is_g() {
        let n = 4000;
        let nus: Vec<f64> = (0..n)
            .map(|i| -1.0 + 2.0 * (i as f64 + 0.5) / n as f64)
            .collect();
        for (x, m) in [
            (0.05, Complex64::new(1.5, 0.0)),
            (3.0, Complex64::new(1.53, 0.008)),
            (25.0, Complex64::new(1.45, 0.0)),
        ] {
            let (e, elements) = sphere_matrix(x, m, &nus);
            let i: Vec<f64> = elements.iter().map(|e| e[0]).collect();
            let d_nu = 2.0 / n as f64;
            let total: f64 = 2.0 * PI * i.iter().sum::<f64>() * d_nu;
            let mean_cos: f64 =
                2.0 * PI * i.iter().zip(&nus).map(|(i, nu)| i * nu).sum::<f64>() * d_nu / total;
            // k²·C_sca = x²·π·Q_sca (k r = x).
            let expected = x * x * PI * e.q_sca;
            assert!(
                (total / expected - 1.0).abs() < 2e-3,
                "x {x}: {total} vs {expected}"
            );
            assert!(
                (mean_cos - e.g).abs() < 2e-3,
                "x {x}: {mean_cos} vs {}",
                e.g
            );
        }
        let (_, e) = sphere_matrix(0.01, Complex64::new(1.5, 0.0), &[1.0, 0.0, -1.0]);
        assert!((e[0][0] / e[2][0] - 1.0).abs() < 1e-3 && (e[0][0] / e[1][0] - 2.0).abs() < 1e-3);
    }

    /// A small sphere scatters as a dipole: Rayleigh's matrix without depolarisation
    /// (S₁₂/S₁₁ = −sin²Θ/(1+cos²Θ), S₃₃/S₁₁ = 2cosΘ/(1+cos²Θ), S₃₄ ≈ 0). Every size keeps
    /// S₁₂² + S₃₃² + S₃₄² = S₁₁² (one sphere scatters fully polarised light, Bohren & Huffman
    /// eq. 4.78), and the polarisation at 90° of a large one is far from full.
    #[test]
    fn the_matrix_of_a_small_sphere_is_the_dipoles_and_every_sphere_is_pure() {
        let nus = [0.9, 0.5, 0.0, -0.4, -0.95];
        let (_, small) = sphere_matrix(0.01, Complex64::new(1.5, 0.0), &nus);
        for (nu, e) in nus.iter().zip(&small) {
            let dipole = crate::polarisation::mueller::ReducedMatrix::rayleigh(*nu, 0.0);
            assert!((e[1] / e[0] - dipole.b1).abs() < 1e-3, "{nu}: {e:?}");
            assert!((e[2] / e[0] - dipole.a3).abs() < 1e-3, "{nu}: {e:?}");
            assert!((e[3] / e[0]).abs() < 1e-3, "{nu}: {e:?}");
        }
        for x in [0.01, 2.0, 15.0] {
            let (_, elements) = sphere_matrix(x, Complex64::new(1.45, 0.01), &nus);
            for e in &elements {
                let pure = e[1] * e[1] + e[2] * e[2] + e[3] * e[3];
                assert!((pure / (e[0] * e[0]) - 1.0).abs() < 1e-9, "x {x}: {e:?}");
            }
        }
        let (_, large) = sphere_matrix(15.0, Complex64::new(1.45, 0.01), &[0.0]);
        assert!((large[0][1] / large[0][0]).abs() < 0.9);
    }

    #[test]
    fn lognormal_average_is_finite_and_consistent() {
        let d = LogNormal {
            r_mod_um: 0.0262,
            sigma: 2.24,
            r_min_um: 0.006,
            r_max_um: 25.0,
        };
        let b = lognormal(&d, 0.55, Complex64::new(1.437, 0.003179), 400);
        assert!(b.ext_um2 > 0.0 && b.sca_um2 > 0.0 && b.sca_um2 <= b.ext_um2);
        assert!(b.g > 0.3 && b.g < 0.9, "g = {}", b.g);
        let finer = lognormal(&d, 0.55, Complex64::new(1.437, 0.003179), 1600);
        assert!((finer.ext_um2 / b.ext_um2 - 1.0).abs() < 1e-3);
    }
}
