//! The path tracer's vector mode: what a path carries to give the Stokes vector of the light it
//! brings to the camera (Hansen & Travis 1974, §2.4; the frames of `polarisation::mueller`).
//!
//! Traced backwards from the camera, a path meets scattering matrices in the order opposite to
//! the light's. It carries per lane the product P of the matrices (each over its phase
//! function, which the lane's scalar weight already holds) and of the rotations between frames,
//! from the camera's meridian frame to the frame its current segment's light is referred to.
//! Light reaching that segment with Stokes vector S there reaches the camera as P·S, so every
//! contribution the scalar tracer makes becomes its scalar value times P·S/I: the estimate
//! stays unbiased in every component, and the scalar tracer's choices (directions, roulette)
//! need not change.

use super::LANES;
use crate::polarisation::mueller::{self, IDENTITY, Mueller, ReducedMatrix};
use glam::DVec3;

/// A path's Mueller products and its current segment's frame.
pub(super) struct PathStokes {
    /// e₁ of the current segment's frame; e₂ = direction × e₁ (the segment's direction away
    /// from the camera, against the light).
    e1: DVec3,
    products: [Mueller; LANES],
}

/// Where a scattering plane meets the current segment: its normal and the angle ψ that turns
/// the plane's frame of the outgoing light into the segment's frame.
#[derive(Debug, Clone, Copy)]
pub(super) struct Plane {
    normal: DVec3,
    psi: f64,
}

impl PathStokes {
    /// A path leaving the camera with its light referred to the frame whose e₁ is `e1`.
    pub fn new(e1: DVec3) -> PathStokes {
        PathStokes {
            e1,
            products: [IDENTITY; LANES],
        }
    }

    /// The plane in which light arriving along −`incoming` (`incoming` points back towards
    /// where it comes from) is scattered into the current segment, which runs along `direction`.
    pub fn plane(&self, direction: DVec3, incoming: DVec3) -> Plane {
        let n = direction.cross(incoming);
        // Forward or backward scattering: any plane through the direction will do; the
        // segment's own e₂ makes ψ zero.
        let normal = if n.length_squared() > 1e-24 {
            n.normalize()
        } else {
            direction.cross(self.e1).normalize()
        };
        let e1_out = normal.cross(direction);
        Plane {
            normal,
            psi: self.e1.dot(normal).atan2(self.e1.dot(e1_out)),
        }
    }

    /// The Stokes vector at the camera of light scattered into the current segment with the
    /// Stokes vector (`i`, `q`, 0, 0) referred to `plane` (unpolarised light scattered once:
    /// q = b₁·i), on `lane`.
    pub fn scattered(&self, lane: usize, plane: Plane, i: f64, q: f64) -> [f64; 4] {
        let (s, c) = (2.0 * plane.psi).sin_cos();
        mueller::apply(&self.products[lane], [i, q * c, -q * s, 0.0])
    }

    /// The Stokes vector at the camera of unpolarised light of radiance `i` arriving along the
    /// current segment (the ground's), on `lane`.
    pub fn unpolarised(&self, lane: usize, i: f64) -> [f64; 4] {
        std::array::from_fn(|k| self.products[lane][k][0] * i)
    }

    /// The path scatters into the current segment (running along `direction`) out of a new
    /// one running along `next`, by `matrices` (one per lane): the new segment becomes current.
    pub fn scatter(&mut self, direction: DVec3, next: DVec3, matrices: [ReducedMatrix; LANES]) {
        let plane = self.plane(direction, next);
        for (p, m) in self.products.iter_mut().zip(matrices) {
            *p = mueller::product(&mueller::then_rotate(p, plane.psi), &m.to_mueller());
        }
        self.e1 = plane.normal.cross(next);
    }

    /// The path reflects off the Lambertian ground, which depolarises, into a segment running
    /// along `next`.
    pub fn depolarise(&mut self, next: DVec3) {
        for p in self.products.iter_mut() {
            for row in p.iter_mut() {
                row[1..].fill(0.0);
            }
        }
        let (t, _) = super::basis(next);
        self.e1 = t;
    }
}
