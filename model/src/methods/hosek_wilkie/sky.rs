//! Hosek and Wilkie's sky pass: the distribution of the two bands around each lane, scaled by
//! their weighted L_M, for the sky; the Lambertian ground's radiance for the ground. Twin of
//! `shaders/hosek_wilkie/sky.wgsl`, reading the rows of [`super::batch_rows`].

use super::{Configuration, ROW_GROUND, ROW_LOWER, ROW_UPPER, distribution};
use crate::methods::shared::sun_rows::ground_or_sky;
use crate::methods::shared::{BatchRows, Lanes, Params};
use glam::DVec3;

/// The configuration of lane `lane` that starts at row `first`.
fn lane_configuration(rows: &BatchRows, first: usize, lane: usize) -> Configuration {
    std::array::from_fn(|k| rows[first + k][lane])
}

/// The sky's radiance per lane along a direction of zenith cosine `mu` at cosine `nu` from the
/// sun.
pub fn sky(rows: &BatchRows, mu: f64, nu: f64) -> Lanes {
    let gamma = nu.clamp(-1.0, 1.0).acos();
    Lanes::from_fn(|lane| {
        [ROW_LOWER, ROW_UPPER]
            .iter()
            .map(|&first| {
                let c = lane_configuration(rows, first, lane);
                distribution(&c, mu, gamma) * c[9]
            })
            .sum()
    })
}

/// The radiance of one batch seen from `at` (position m from the planet's centre, altitude m)
/// along the unit direction `dir`, with the sun in direction `sun`, from the batch's rows.
pub fn radiance(p: &Params, rows: &BatchRows, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
    ground_or_sky(p, rows, at, (dir, sun), ROW_GROUND, sky)
}
