//! The CIE standard general sky's pass: the type's f(χ)·φ(Z) times each lane's radiance per
//! unit of it for the sky, the Lambertian ground's radiance for the ground. Twin of
//! `shaders/cie_standard_sky/sky.wgsl`, reading the rows of [`super::batch_rows`].

use super::{ROW_ABCD, ROW_E, ROW_GROUND, ROW_SCALE};
use crate::methods::shared::sun_rows::ground_or_sky;
use crate::methods::shared::{BatchRows, Lanes, Params};
use glam::DVec3;
use std::f64::consts::FRAC_PI_2;

/// The sky's radiance per lane along a direction of zenith cosine `mu` at cosine `nu` from the
/// sun.
pub fn sky(rows: &BatchRows, mu: f64, nu: f64) -> Lanes {
    let [a, b, c, d] = rows[ROW_ABCD].0;
    let e = rows[ROW_E][0];
    let chi = nu.clamp(-1.0, 1.0).acos();
    let gradation = if mu > 0.0 {
        1.0 + a * (b / mu).exp()
    } else {
        1.0
    };
    let indicatrix = 1.0 + c * ((d * chi).exp() - (d * FRAC_PI_2).exp()) + e * chi.cos().powi(2);
    rows[ROW_SCALE] * (gradation * indicatrix).max(0.0)
}

/// The radiance of one batch seen from `at` (position m from the planet's centre, altitude m)
/// along the unit direction `dir`, with the sun in direction `sun`, from the batch's rows.
pub fn radiance(p: &Params, rows: &BatchRows, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
    ground_or_sky(p, rows, at, (dir, sun), ROW_GROUND, sky)
}
