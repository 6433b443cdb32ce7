//! Leenman (2025), "A visual and performance comparison of atmospheric scattering models"
//! (master's thesis), §10.1–10.2 and §11.2.9, after Jodie's (2019) shader: the flat
//! homogeneous atmosphere bent onto the sphere. The whole view ray is one slab whose optical
//! depth grows linearly from the sun's at the camera to the view's at the far end, integrated
//! in closed form; every depth is the chord through a homogeneous shell one scale height thick
//! at the density of its starting point. No tables, no march, no higher orders, no Earth
//! shadow in the sky — one closed form per pixel.
//!
//! The medium is the scene's, as the analytic models see it: air and aerosol as fitted
//! exponentials, ozone as a shell (Leenman's is a constant shell between 17.5 and 32.5 km; ours
//! sits at the scene's ozone centroid). The sky pass is `shared::segments_sky` with one
//! segment.

use super::shared::segments_sky::{FLAT_SEGMENTS, Segments};
use super::shared::{Params, TableSpec, Viewpoint};
use super::{Domain, SkyModel};

/// The method has no tables.
pub const TABLES: [TableSpec; 0] = [];

/// As single scattering's (`nishita`'s): ground, plane and space views in daylight; no AOD
/// range. Leenman notes the slab breaks down looking down from high up and near sunrise.
pub const DOMAIN: Domain = Domain {
    note: "ground, plane and space views in daylight; one analytic slab of single scattering per pixel, poorest looking down from high up and at sunrise",
    ..super::nishita::DOMAIN
};

/// The registry's constructor (no table depends on the viewpoint).
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    Box::new(Segments::new(params, FLAT_SEGMENTS))
}
