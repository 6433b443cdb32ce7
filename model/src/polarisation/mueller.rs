//! Mueller calculus for the vector path tracer: scattering matrices divided by their phase
//! function, and the rotations between Stokes frames (Hansen & Travis 1974, §2.2 and §2.4;
//! Chandrasekhar 1950, §I.15).
//!
//! A Stokes vector is referred to a frame (e₁, e₂) perpendicular to the light's travel, with
//! e₁ × e₂ pointing against the travel (towards where the light comes from, as in the
//! meridian frame of [`super::meridian_frame`]): Q = ⟨E₁²⟩ − ⟨E₂²⟩, U = ⟨2E₁E₂⟩. A scattering
//! matrix acts on Stokes vectors referred to the scattering plane: e₁ in it ("parallel"),
//! e₂ = its normal ("perpendicular").

/// A Mueller matrix, row by row.
pub type Mueller = [[f64; 4]; 4];

pub const IDENTITY: Mueller = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// A scattering matrix of the form of spheres and of air, divided by its (1,1) element a₁
/// (the phase function):
///
/// ```text
/// | 1   b₁  0   0  |
/// | b₁  a₂  0   0  |
/// | 0   0   a₃  b₂ |
/// | 0   0  −b₂  a₄ |
/// ```
///
/// −b₁ is the degree of polarisation of unpolarised light scattered once (b₁ < 0: across the
/// scattering plane).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReducedMatrix {
    pub b1: f64,
    pub a2: f64,
    pub a3: f64,
    pub a4: f64,
    pub b2: f64,
}

impl ReducedMatrix {
    /// What the Henyey–Greenstein and Cornette–Shanks aerosols scatter with at scattering
    /// cosine `nu`: no polarisation made from unpolarised light (b₁ = 0), and what arrives
    /// polarised keeps its polarisation near the forward peak, where most of an aerosol's light
    /// goes, as real particles do (a₂ = 1, a₃ = a₄ → 1); a₃ and a₄ follow a small sphere's
    /// 2ν/(1+ν²), down to −1 at backscatter, where a₃ = −a₂ makes the light independent of
    /// which plane through the exact backward direction is taken. A phase function alone says
    /// nothing more.
    pub fn unpolarising(nu: f64) -> ReducedMatrix {
        let a3 = 2.0 * nu / (1.0 + nu * nu);
        ReducedMatrix {
            b1: 0.0,
            a2: 1.0,
            a3,
            a4: a3,
            b2: 0.0,
        }
    }

    /// Air at scattering cosine `nu` with depolarisation ratio `rho` (Hansen & Travis 1974,
    /// eq. 2.15): a₁ = ¾Δ(1+ν²) + 1 − Δ, b₁ = −¾Δ(1−ν²), a₂ = ¾Δ(1+ν²), a₃ = 3/2·Δν,
    /// a₄ = 3/2·ΔΔ′ν, with Δ = (1−ρ)/(1+ρ/2) and Δ′ = (1−2ρ)/(1−ρ). Its a₁ is
    /// `phase::rayleigh` times 4π.
    pub fn rayleigh(nu: f64, rho: f64) -> ReducedMatrix {
        let delta = (1.0 - rho) / (1.0 + 0.5 * rho);
        let delta_prime = (1.0 - 2.0 * rho) / (1.0 - rho);
        let nu2 = (nu * nu).min(1.0);
        let a1 = 0.75 * delta * (1.0 + nu2) + 1.0 - delta;
        ReducedMatrix {
            b1: -0.75 * delta * (1.0 - nu2) / a1,
            a2: 0.75 * delta * (1.0 + nu2) / a1,
            a3: 1.5 * delta * nu / a1,
            a4: 1.5 * delta * delta_prime * nu / a1,
            b2: 0.0,
        }
    }

    pub fn to_mueller(&self) -> Mueller {
        let ReducedMatrix { b1, a2, a3, a4, b2 } = *self;
        [
            [1.0, b1, 0.0, 0.0],
            [b1, a2, 0.0, 0.0],
            [0.0, 0.0, a3, b2],
            [0.0, 0.0, -b2, a4],
        ]
    }
}

/// The product `a · b`.
pub fn product(a: &Mueller, b: &Mueller) -> Mueller {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum()))
}

/// `m · s`.
pub fn apply(m: &Mueller, s: [f64; 4]) -> [f64; 4] {
    std::array::from_fn(|i| (0..4).map(|k| m[i][k] * s[k]).sum())
}

/// The matrix taking a Stokes vector from a frame (e₁, e₂) to the frame (e₁′, e₂′) of the same
/// light with e₁′ = cos ψ·e₁ + sin ψ·e₂: Q′ = Q cos 2ψ + U sin 2ψ, U′ = −Q sin 2ψ + U cos 2ψ.
pub fn rotation(psi: f64) -> Mueller {
    let (s, c) = (2.0 * psi).sin_cos();
    [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, c, s, 0.0],
        [0.0, -s, c, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// `m · rotation(psi)`: only the middle two columns change.
pub fn then_rotate(m: &Mueller, psi: f64) -> Mueller {
    let (s, c) = (2.0 * psi).sin_cos();
    let mut out = *m;
    for row in out.iter_mut() {
        let (q, u) = (row[1], row[2]);
        row[1] = q * c - u * s;
        row[2] = q * s + u * c;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Air's matrix: its first row and column give `rayleigh_degree`; without depolarisation
    /// it is the classic dipole (a₂ = 1, a₃ = a₄ = 2ν/(1+ν²)); its a₁ is the phase function.
    #[test]
    fn air_matrix_is_hansen_and_travis() {
        let rho = 0.0279;
        for nu in [-1.0, -0.6, 0.0, 0.3, 1.0] {
            let m = ReducedMatrix::rayleigh(nu, rho);
            assert!(
                (-m.b1 - super::super::rayleigh_degree(nu, rho)).abs() < 1e-12,
                "{nu}"
            );
            let ideal = ReducedMatrix::rayleigh(nu, 0.0);
            let expected = 2.0 * nu / (1.0 + nu * nu);
            assert!((ideal.a2 - 1.0).abs() < 1e-12 && (ideal.a3 - expected).abs() < 1e-12);
            assert!((ideal.a4 - expected).abs() < 1e-12);
            // A matrix of a physical scatterer never makes light more than fully polarised:
            // for unpolarised light in, the out degree is |b₁| ≤ 1; and a₂, a₃, a₄ ≤ 1.
            assert!(m.b1.abs() <= 1.0 && m.a2 <= 1.0 && m.a3.abs() <= 1.0 && m.a4.abs() <= 1.0);
        }
        // a₁ over ν integrates the phase's 4π normalisation: ¾Δ(1+ν²) + 1 − Δ averages to 1.
        let delta = (1.0 - rho) / (1.0 + 0.5 * rho);
        let a1 = |nu: f64| 0.75 * delta * (1.0 + nu * nu) + 1.0 - delta;
        let n = 2000;
        let mean: f64 = (0..n)
            .map(|k| a1(-1.0 + (k as f64 + 0.5) * 2.0 / n as f64))
            .sum::<f64>()
            / n as f64;
        assert!((mean - 1.0).abs() < 1e-6, "{mean}");
        let p = crate::phase::rayleigh(0.4, rho) * 4.0 * std::f64::consts::PI;
        assert!((a1(0.4) - p).abs() < 1e-12);
    }

    /// At exact backscatter every plane through the direction will do: a matrix with a₃ = −a₂
    /// there gives the same light whichever is taken (a plane turned by φ turns both frames by
    /// φ, and L(φ)·F·L(φ) = F when a₃ = −a₂, b₂ = 0), as air's, a sphere's and the aerosols'
    /// without a polarising phase do.
    #[test]
    fn every_matrix_is_independent_of_the_plane_at_backscatter() {
        for m in [
            ReducedMatrix::rayleigh(-1.0, 0.03),
            ReducedMatrix::unpolarising(-1.0),
        ] {
            let f = m.to_mueller();
            for phi in [0.3, 1.1, -0.7] {
                let turned = product(&product(&rotation(phi), &f), &rotation(phi));
                for i in 0..4 {
                    for j in 0..4 {
                        assert!((turned[i][j] - f[i][j]).abs() < 1e-12, "{m:?} {phi}");
                    }
                }
            }
        }
        assert_eq!(ReducedMatrix::unpolarising(1.0).a3, 1.0);
    }

    /// Rotations compose, a half turn is no turn (a Stokes frame and its opposite describe the
    /// same light), and `then_rotate` is the product by a rotation.
    #[test]
    fn rotations_compose_and_a_half_turn_is_none() {
        let (a, b) = (0.3, -1.1);
        let ab = product(&rotation(a), &rotation(b));
        let m = rotation(a + b);
        let half = rotation(std::f64::consts::PI);
        let r = ReducedMatrix::rayleigh(0.2, 0.03).to_mueller();
        let rotated = then_rotate(&r, a);
        let expected = product(&r, &rotation(a));
        for i in 0..4 {
            for j in 0..4 {
                assert!((ab[i][j] - m[i][j]).abs() < 1e-12);
                assert!((half[i][j] - IDENTITY[i][j]).abs() < 1e-12);
                assert!((rotated[i][j] - expected[i][j]).abs() < 1e-12);
            }
        }
        // Light polarised along e₁ (Q = 1) seen from a frame turned by +45° lies at −45° from
        // the new e₁: U = −1.
        assert!(
            (apply(&rotation(std::f64::consts::FRAC_PI_4), [1.0, 1.0, 0.0, 0.0])[2] + 1.0).abs()
                < 1e-12
        );
    }
}
