//! The CIE standard general sky's pass: the type's f(χ)·φ(Z) times each lane's radiance per
//! unit of it for the sky, the Lambertian ground's radiance for the ground. Twin of
//! `shaders/cie_standard_sky/sky.wgsl`, reading the rows of [`super::batch_rows`].

use super::{ROW_ABCD, ROW_E, ROW_GROUND, ROW_SCALE};
use crate::geometry::hits_ground;
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

/// The radiance of one batch seen from `position` (m from the planet's centre, altitude `h`)
/// along the unit direction `dir`, with the sun in direction `sun`, from the batch's rows.
pub fn radiance(
    p: &Params,
    rows: &BatchRows,
    (position, h): (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
) -> Lanes {
    let mu = dir.dot(position.normalize());
    if hits_ground(h, mu, p.bottom_radius_m) {
        return rows[ROW_GROUND];
    }
    sky(rows, mu, dir.dot(sun))
}
