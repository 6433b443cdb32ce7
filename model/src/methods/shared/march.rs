//! How ray marches place their samples and weigh their segments; WGSL twins in
//! `shaders/common/geometry.wgsl`.

use super::Lanes;

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
