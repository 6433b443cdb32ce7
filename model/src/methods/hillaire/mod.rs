//! Hillaire (2020), "A Scalable and Production Ready Sky and Atmosphere Rendering Technique":
//! the f64 CPU twin of the GPU passes in `shaders/hillaire/`. Same parameterisations, same
//! step counts and the same arithmetic, so the GPU lookup tables can be checked texel by texel.
//!
//! One file per pass, each the twin of `shaders/hillaire/<pass>.wgsl`; the march they share is
//! here (twin of `shaders/hillaire/common.wgsl`). Tables (each a function `compute_*`, each
//! looked up by a `*_texel_from_*` / `*_from_texel` pair of mappings):
//! - transmittance (h, mu) with Bruneton's (2017) mapping (shared by the table-based models);
//! - multiple scattering Ψ_ms (h, mu_s): second order with an isotropic phase, summed as the
//!   geometric series 1/(1 − f_ms) (paper §5.5), ground bounce included;
//! - ground irradiance (mu_s): sky irradiance on the ground per unit solar irradiance, for the
//!   planet's ground lit by the sky (our addition; the paper lights only with the sun);
//! - sky view (azimuth from the sun, view zenith) at the camera's altitude, with the paper's
//!   quadratic latitude mapping that puts texels near the horizon;
//! - aerial perspective: in-scattering and transmittance along the directions that reach the
//!   ground, in distance slices. The paper stores it in camera froxels; we store it in the sky
//!   view's sun-aligned frame so that turning the camera or changing projection never rebuilds it.
//!
//! A camera above the atmosphere ray-marches every pixel (paper §6). Positions are handled as
//! altitude h with r² − R² = h(2R + h), which stays accurate in f32 at 1 m above the ground.
//! The sun disk is limb darkened; Earth's shadow comes from a penumbra over the sun's disk.

pub mod aerial_perspective;
pub mod ground_irradiance;
pub mod multiple_scattering;
pub mod sky;
pub mod sky_view;

pub use super::shared::transmittance::{
    TRANSMITTANCE_SIZE, compute_transmittance_lut, sun_transmittance, transmittance,
    transmittance_h_mu_from_texel, transmittance_texel_from_h_mu,
};
pub use super::shared::{
    BatchOptics, Lanes, Lut, Medium, PROFILE_SAMPLES, Params, SMALL_OPTICAL_THICKNESS, Spacing,
    Steps, Viewpoint, segment_weight, sun_disk, viewpoint,
};
pub use aerial_perspective::{
    AERIAL_PERSPECTIVE_MAX_DISTANCE_M, AERIAL_PERSPECTIVE_SIZE, aerial_perspective,
    aerial_perspective_angles_from_texel, aerial_perspective_slice_distance,
    aerial_perspective_slice_from_distance, aerial_perspective_texel_from_angles,
    compute_aerial_perspective,
};
pub use ground_irradiance::{
    GROUND_IRRADIANCE_DIRECTIONS, GROUND_IRRADIANCE_SIZE, compute_ground_irradiance_lut,
    ground_irradiance, ground_irradiance_mu_s_from_texel, ground_irradiance_texel_from_mu_s,
};
pub use multiple_scattering::{
    MULTIPLE_SCATTERING_DIRECTIONS_SQRT, MULTIPLE_SCATTERING_SIZE, compute_multiple_scattering_lut,
    multiple_scattering, multiple_scattering_h_mu_s_from_texel,
    multiple_scattering_texel_from_h_mu_s,
};
pub use sky::radiance;
pub use sky_view::{
    SKY_VIEW_SIZE, compute_sky_view_lut, sky_view, sky_view_angles_from_texel,
    sky_view_texel_from_angles,
};

use super::shared::{self, TableSpec};
use super::{Domain, SkyModel};
use glam::DVec3;

/// Every view, but a limited amount of aerosol: multiple scattering of the second order and
/// above is gathered with an isotropic phase function (Ψ_ms = L₂/(1 − f_ms)), which loses the
/// aerosol's forward peak, so hazy skies come out too dark.
pub const DOMAIN: Domain = Domain {
    max_aod550: 0.2,
    ..Domain::EVERYWHERE
};

/// Every table of the method, in pass order.
pub const TABLES: [TableSpec; 6] = [
    shared::transmittance::TABLE,
    multiple_scattering::TABLE,
    ground_irradiance::TABLE,
    sky_view::TABLE,
    aerial_perspective::INSCATTERING,
    aerial_perspective::TRANSMITTANCE,
];

/// In-scattered radiance (per unit solar irradiance) and transmittance along the ray from
/// (h, mu) over [t_start, t_end], the higher orders from the Ψ_ms table `ms` (paper eq. 11).
#[allow(clippy::too_many_arguments)]
pub fn integrate_inscattering(
    p: &Params,
    t_lut: &Lut,
    ms: &Lut,
    layer: usize,
    ray: (f64, f64, f64, f64),
    segment: (f64, f64),
    steps: u32,
    spacing: Spacing,
) -> (Lanes, Lanes) {
    let psi = |h_t, mu_s_t| multiple_scattering(p, ms, layer, h_t, mu_s_t);
    shared::march::march_inscattering(p, t_lut, layer, ray, segment, steps, spacing, psi)
}

// ---- the sun-zenith axis of the Ψ_ms and ground-irradiance tables ----

pub use super::shared::mu_s_axis::{
    MU_S_AXIS_MU_S, MU_S_AXIS_U, mu_s_axis_coordinate, mu_s_axis_mu_s,
};

// ---- the view ----

/// Every table of the method for one atmosphere and viewpoint.
#[derive(Debug, Clone)]
pub struct Tables {
    /// The optics the tables were computed for.
    pub params: Params,
    pub transmittance: Lut,
    pub multiple_scattering: Lut,
    pub ground_irradiance: Lut,
    pub sky_view: Lut,
    pub aerial_perspective_inscattering: Lut,
    pub aerial_perspective_transmittance: Lut,
    pub viewpoint: Viewpoint,
}

impl Tables {
    pub fn compute(p: &Params, vp: Viewpoint) -> Tables {
        let transmittance = compute_transmittance_lut(p);
        let multiple_scattering = compute_multiple_scattering_lut(p, &transmittance);
        let ground_irradiance =
            compute_ground_irradiance_lut(p, &transmittance, &multiple_scattering);
        let sky_view = compute_sky_view_lut(p, &transmittance, &multiple_scattering, vp);
        let (ap_s, ap_t) = compute_aerial_perspective(p, &transmittance, &multiple_scattering, vp);
        Tables {
            params: p.clone(),
            transmittance,
            multiple_scattering,
            ground_irradiance,
            sky_view,
            aerial_perspective_inscattering: ap_s,
            aerial_perspective_transmittance: ap_t,
            viewpoint: vp,
        }
    }
}

impl SkyModel for Tables {
    fn params(&self) -> &Params {
        &self.params
    }

    fn radiance(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
        sky::radiance(&self.params, self, layer, at, dir, sun)
    }

    fn table(&self, id: &str) -> Option<&Lut> {
        Some(match id {
            "transmittance" => &self.transmittance,
            "multiple-scattering" => &self.multiple_scattering,
            "ground-irradiance" => &self.ground_irradiance,
            "sky-view" => &self.sky_view,
            "aerial-perspective-inscattering" => &self.aerial_perspective_inscattering,
            "aerial-perspective-transmittance" => &self.aerial_perspective_transmittance,
            _ => return None,
        })
    }
}

/// Builds the method's CPU twin for `params` seen from `vp` (the registry's constructor).
pub fn build(params: &Params, vp: Viewpoint) -> Box<dyn SkyModel> {
    Box::new(Tables::compute(params, vp))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::Atmosphere;
    use crate::camera::{Camera, Projection};
    use crate::geometry::direction_from_angles;
    use crate::scene::{Quality, Scene, WavelengthSet};
    use crate::wavelengths::to_linear_srgb;

    #[test]
    fn the_clear_sky_is_blue_the_ground_is_lit_and_space_is_black() {
        let mut scene = Scene::default();
        scene.render.quality = Quality::Low;
        let atm = Atmosphere::for_scene(&scene);
        let p = Params::new(&atm, WavelengthSet::Spectral4, Quality::Low);
        let camera = Camera::new(&scene.camera, atm.bottom_radius_m, Projection::Perspective);
        let tables = Tables::compute(&p, viewpoint(&scene, &camera));
        let a = scene.sun.angles();
        let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
        let colours = [p.batches[0].colour.clone()];
        let look = |dir: DVec3| {
            let l = radiance(
                &p,
                &tables,
                0,
                (camera.position, scene.camera.altitude_m),
                dir.normalize(),
                sun,
            );
            to_linear_srgb(&colours, &[l])
        };
        let zenith = look(DVec3::Z);
        assert!(
            zenith[2] > zenith[0] && zenith[2] > 0.0,
            "blue zenith: {zenith:?}"
        );
        let ground = look(DVec3::new(0.0, 1.0, -1.0));
        assert!(ground.iter().all(|&c| c > 0.0), "lit ground: {ground:?}");
        // From 1000 km up, looking away from the planet, only the black sky remains.
        let mut space = scene.clone();
        space.camera.altitude_m = 1.0e6;
        let cam = Camera::new(&space.camera, atm.bottom_radius_m, Projection::Perspective);
        let l = radiance(
            &p,
            &tables,
            0,
            (cam.position, 1.0e6),
            DVec3::new(0.3, 0.0, 1.0).normalize(),
            sun,
        );
        assert_eq!(l, Lanes::ZERO);
        let earth = radiance(&p, &tables, 0, (cam.position, 1.0e6), -DVec3::Z, sun);
        assert!(earth.iter().all(|&v| v > 0.0 && v.is_finite()), "{earth:?}");
    }
}
