//! The fits whose passes read rows computed on the CPU for each batch and the sun at the camera
//! (`BatchRows`, read on the GPU as `batches[layer].model`: Hosek–Wilkie, the CIE sky): their
//! CPU twin ([`RowSky`]), which keeps the rows of the last sun it was asked about (every
//! direction of an image shares the sun), and the hemisphere integral their ground takes.

use super::sun_disk::visible_fraction;
use super::{BatchRows, Lanes, Lut, Params};
use crate::methods::SkyModel;
use glam::DVec3;
use std::f64::consts::PI;
use std::sync::{Arc, Mutex};

/// A function giving batch `layer`'s rows for the sun at zenith cosine `mu_s`.
pub type RowsFn = fn(&Params, usize, f64) -> BatchRows;

/// The sky pass's twin: the radiance of a batch from its rows, seen from `at` (position m from
/// the planet's centre, altitude m) along `dir` with the sun in direction `sun`.
pub type RowSkyFn = fn(&Params, &BatchRows, (DVec3, f64), DVec3, DVec3) -> Lanes;

/// The CPU twin of a fit drawn from per-batch rows.
#[derive(Debug)]
pub struct RowSky {
    pub params: Params,
    rows: RowsFn,
    sky: RowSkyFn,
    /// The row that holds the sun's transmittance per lane.
    sun_row: usize,
    /// The turbidity the fit took from the scene.
    turbidity: f64,
    last: Mutex<Option<(f64, Arc<Vec<BatchRows>>)>>,
}

impl RowSky {
    pub fn new(
        params: &Params,
        rows: RowsFn,
        sky: RowSkyFn,
        sun_row: usize,
        turbidity: f64,
    ) -> RowSky {
        RowSky {
            params: params.clone(),
            rows,
            sky,
            sun_row,
            turbidity,
            last: Mutex::new(None),
        }
    }

    /// The rows of every batch with the sun at zenith cosine `mu_s`, computed again only when
    /// the sun changed.
    pub fn rows(&self, mu_s: f64) -> Arc<Vec<BatchRows>> {
        let mut last = self.last.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((at, kept)) = last.as_ref()
            && *at == mu_s
        {
            return kept.clone();
        }
        let p = &self.params;
        let all: Arc<Vec<BatchRows>> = Arc::new(
            (0..p.batches.len())
                .map(|layer| (self.rows)(p, layer, mu_s))
                .collect(),
        );
        *last = Some((mu_s, all.clone()));
        all
    }
}

impl SkyModel for RowSky {
    fn params(&self) -> &Params {
        &self.params
    }

    fn radiance(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
        let rows = self.rows(sun.dot(at.0.normalize()));
        (self.sky)(&self.params, &rows[layer], at, dir, sun)
    }

    fn table(&self, _: &str) -> Option<&Lut> {
        None
    }

    /// The sun's disk through the transmittance of the fit's sun row.
    fn sun(&self, layer: usize, h: f64, mu_s: f64, disk: Lanes) -> Lanes {
        let p = &self.params;
        let rows = self.rows(mu_s);
        let visible = visible_fraction(h, mu_s, p.bottom_radius_m);
        p.batches[layer].solar_irradiance
            * rows[layer][self.sun_row]
            * visible
            * disk.map(|d| d.max(0.0))
    }

    fn turbidity(&self) -> Option<f64> {
        Some(self.turbidity)
    }
}

/// A row-drawn fit's radiance seen from `position` (m from the planet's centre, altitude `h`)
/// along the unit direction `dir` with the sun in direction `sun`: row `ground_row` where the
/// ray meets the ground, else `sky(rows, μ, ν)` of the view's zenith cosine μ and its cosine ν
/// with the sun.
pub fn ground_or_sky(
    p: &Params,
    rows: &BatchRows,
    (position, h): (DVec3, f64),
    (dir, sun): (DVec3, DVec3),
    ground_row: usize,
    sky: impl Fn(&BatchRows, f64, f64) -> Lanes,
) -> Lanes {
    let mu = dir.dot(position.normalize());
    if crate::geometry::hits_ground(h, mu, p.bottom_radius_m) {
        return rows[ground_row];
    }
    sky(rows, mu, dir.dot(sun))
}

/// ∫ L(μ, γ)·μ dω over the upper hemisphere, the sun at zenith cosine `mu_s`, for a sky
/// `radiance(μ, γ)` of the view's zenith cosine μ and its angle γ (rad) from the sun: the
/// midpoint rule over `steps` = [zenith cosines, azimuths], the azimuths over 0–π counted twice
/// (the sky is symmetric about the sun's vertical).
pub fn hemisphere_irradiance(
    mu_s: f64,
    steps: [usize; 2],
    radiance: impl Fn(f64, f64) -> f64,
) -> f64 {
    let [n_mu, n_phi] = steps;
    let sin_s = (1.0 - mu_s * mu_s).max(0.0).sqrt();
    let mut sum = 0.0;
    for i in 0..n_mu {
        let mu = (i as f64 + 0.5) / n_mu as f64;
        let sin_v = (1.0 - mu * mu).sqrt();
        for j in 0..n_phi {
            let phi = (j as f64 + 0.5) / n_phi as f64 * PI;
            let gamma = (mu * mu_s + sin_v * sin_s * phi.cos())
                .clamp(-1.0, 1.0)
                .acos();
            sum += radiance(mu, gamma) * mu;
        }
    }
    sum / n_mu as f64 * (2.0 * PI / n_phi as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A uniform sky of radiance 1 gives π; one brighter towards the zenith as cos θ gives 2π/3
    /// (∫ μ² dω); the midpoint rule holds them within 0.2 % at 24 × 24 directions.
    #[test]
    fn the_hemisphere_integral_is_exact_for_simple_skies() {
        for mu_s in [1.0, 0.5, 0.0] {
            let uniform = hemisphere_irradiance(mu_s, [24, 24], |_, _| 1.0);
            assert!((uniform / PI - 1.0).abs() < 2e-3, "{uniform}");
            let graded = hemisphere_irradiance(mu_s, [24, 24], |mu, _| mu);
            assert!((graded / (2.0 * PI / 3.0) - 1.0).abs() < 2e-3, "{graded}");
        }
    }
}
