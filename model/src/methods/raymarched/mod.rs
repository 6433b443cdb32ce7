//! Leenman (2025), "A visual and performance comparison of atmospheric scattering models"
//! (master's thesis), §10.4 and §11.2.10: the view ray cut into five segments, each integrated
//! in closed form as a slab whose optical depth (towards the camera plus towards the sun)
//! changes linearly between its ends (his eq. 55), with every depth the chord through a
//! homogeneous shell one scale height thick (§10.2). It replaces the naive integrator of
//! Terrell's (2016) shader; five is Leenman's trade of quality against steps. No tables, no
//! higher orders, no Earth shadow in the sky.
//!
//! The medium is the scene's, as the analytic models see it: air and aerosol as fitted
//! exponentials, ozone as a shell at the scene's ozone centroid (Leenman's: a constant shell
//! between 17.5 and 32.5 km). The sky pass is `shared::segments_sky` with five segments.

use super::shared::segments_sky::{RAYMARCHED_SEGMENTS, Segments};
use super::shared::{Params, TableSpec, Viewpoint};
use super::{Domain, SkyModel};

/// The method has no tables.
pub const TABLES: [TableSpec; 0] = [];

/// As single scattering's (`nishita`'s): ground, plane and space views in daylight; no AOD
/// range.
pub const DOMAIN: Domain = Domain {
    note: "ground, plane and space views in daylight; five analytic slabs of single scattering per pixel",
    ..super::nishita::DOMAIN
};

/// The registry's constructor (no table depends on the viewpoint).
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    Box::new(Segments::new(params, RAYMARCHED_SEGMENTS))
}
