//! No atmosphere: the black sky of airless space over a ground lit by the unattenuated sun.
//! Leenman (2025) times an "empty" shader to measure what a frame costs before any model's
//! work; this one draws the planet without air, so that it also marks the error of leaving
//! the atmosphere out. In the benchmark it is the cheapest frame and the largest error. One file per pass: [`sky`], twin of
//! `shaders/empty/sky.wgsl`.

pub mod sky;

use super::shared::sun_disk::visible_fraction;
use super::shared::{Lanes, Lut, Params, TableSpec, Viewpoint};
use super::{Domain, SkyModel};
use glam::DVec3;

/// The method has no tables.
pub const TABLES: [TableSpec; 0] = [];

/// A baseline, not a model of the sky (its registry row says so): it draws every view, and
/// none is right.
pub const DOMAIN: Domain = Domain {
    note: "a baseline without air: the sky is black and the ground gets the sun as in space",
    max_aod550: 0.0,
    ..Domain::EVERYWHERE
};

/// The baseline for one atmosphere (of which it uses the sun and the ground alone).
#[derive(Debug, Clone)]
pub struct Empty {
    pub params: Params,
}

impl SkyModel for Empty {
    fn params(&self) -> &Params {
        &self.params
    }

    fn radiance(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
        sky::radiance(&self.params, layer, at, dir, sun)
    }

    fn table(&self, _: &str) -> Option<&Lut> {
        None
    }

    /// The sun's disk at full strength wherever the planet does not hide it.
    fn sun(&self, layer: usize, h: f64, mu_s: f64, disk: Lanes) -> Lanes {
        let p = &self.params;
        let visible = visible_fraction(h, mu_s, p.bottom_radius_m);
        let e = p.batches[layer].solar_irradiance;
        Lanes::from_fn(|i| e[i] * visible * disk[i].max(0.0))
    }
}

/// The registry's constructor.
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    Box::new(Empty {
        params: params.clone(),
    })
}
