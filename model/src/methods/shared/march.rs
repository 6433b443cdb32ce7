//! How ray marches place their samples and weigh their segments, and the in-scattering march
//! every table-based model shares; WGSL twins in `shaders/common/geometry.wgsl` and
//! `shaders/common/march.wgsl`.

use super::transmittance::sun_transmittance;
use super::{Lanes, Lut, Params};
use crate::geometry::altitude_along;
use crate::phase;
use crate::wavelengths::LANES;

/// Optical thickness below which a segment's in-scattering weight uses its series expansion.
pub const SMALL_OPTICAL_THICKNESS: f64 = 1e-4;

/// (1 − e^(−σ·dt))/σ per lane: the in-scattering weight of a segment with constant source.
pub fn segment_weight(extinction: Lanes, dt: f64) -> Lanes {
    extinction.map(|s| {
        let x = s * dt;
        if x < SMALL_OPTICAL_THICKNESS {
            dt * (1.0 - 0.5 * x)
        } else {
            (1.0 - (-x).exp()) / s
        }
    })
}

/// How samples are spread along a march.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Spacing {
    Uniform,
    /// t ∝ s²: dense near the start (the camera), as in the paper's sky-view march.
    Quadratic,
    /// Dense near the end: rays from space down to the ground.
    QuadraticToEnd,
}

impl Spacing {
    /// Segment `i` of `n` over [t_start, t_end].
    pub fn segment(self, t_start: f64, t_end: f64, i: u32, n: u32) -> (f64, f64) {
        let length = t_end - t_start;
        let at = |s: f64| {
            let x = s / n as f64;
            match self {
                Spacing::Uniform => t_start + length * x,
                Spacing::Quadratic => t_start + length * x * x,
                Spacing::QuadraticToEnd => t_end - length * (1.0 - x) * (1.0 - x),
            }
        };
        (at(i as f64), at(i as f64 + 1.0))
    }
}

/// In-scattered radiance (per unit solar irradiance) and transmittance along the ray from
/// (h, mu) over [t_start, t_end], with the sun at zenith cosine `mu_s` and view–sun cosine `nu`:
/// midpoint samples, single scattering through the transmittance table `t`, plus the model's
/// isotropic higher-order term `psi(h, mu_s)` (sr⁻¹) times the local scattering coefficient.
#[allow(clippy::too_many_arguments)]
pub fn march_inscattering(
    p: &Params,
    t: &Lut,
    layer: usize,
    (h, mu, mu_s, nu): (f64, f64, f64, f64),
    (t_start, t_end): (f64, f64),
    steps: u32,
    spacing: Spacing,
    psi: impl Fn(f64, f64) -> Lanes,
) -> (Lanes, Lanes) {
    let big_r = p.bottom_radius_m;
    let r = big_r + h;
    let b = &p.batches[layer];
    let rayleigh_phase = b
        .rayleigh_depolarisation
        .map(|rho| phase::rayleigh(nu, rho));
    let aerosol_phase = p.aerosol_phase(layer, nu);
    let mut inscattered = Lanes::ZERO;
    let mut throughput = Lanes::ONE;
    for s in 0..steps {
        let (t0, t1) = spacing.segment(t_start, t_end, s, steps);
        let dt = t1 - t0;
        let ts = 0.5 * (t0 + t1);
        // A point past the ground (the aerial-perspective columns march on through it, so
        // that rows interpolate smoothly) takes the ground's medium and light.
        let (h_t, r_t) = altitude_along(h, mu, ts, big_r);
        let (h_t, r_t) = (h_t.max(0.0), r_t.max(big_r));
        let mu_s_t = ((r * mu_s + ts * nu) / r_t).clamp(-1.0, 1.0);
        let m = p.medium(layer, h_t);
        let sun_t = sun_transmittance(p, t, layer, h_t, mu_s_t);
        let psi = psi(h_t, mu_s_t);
        let weight = throughput * segment_weight(m.extinction, dt);
        for i in 0..LANES {
            let source = m.rayleigh_scattering[i] * (rayleigh_phase[i] * sun_t[i] + psi[i])
                + m.aerosol_scattering[i] * (aerosol_phase[i] * sun_t[i] + psi[i]);
            inscattered[i] += weight[i] * source;
            throughput[i] *= (-m.extinction[i] * dt).exp();
        }
    }
    (inscattered, throughput)
}
