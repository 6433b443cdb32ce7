//! The moving sky of the marches per pixel (Nishita's, the trapezoid rule's, Schuler's and
//! Gałaj's, with or without Ψ_ms): the model's own radiance, sky and sunlit ground, at the
//! directions of Hillaire's (2020, §5.3) sky-view grid at the camera's altitude. A software GPU
//! draws a view in motion from it: a march costs 10–300 table look-ups a pixel there, and a
//! 192 × 108 table of marches, rebuilt only when the camera's altitude or the sun's elevation
//! moves, is a fraction of a frame's pixels. The still frame after the motion marches every
//! pixel again, so exports and still views are the model itself. Twin of
//! `shaders/shared/moving_sky.wgsl` (the table) and `shaders/views/moving_sky_radiance.wgsl`
//! (the look-up).

use super::{Lanes, Lut, TableSpec, Viewpoint, direction_from_phi_theta, local_sun};
use crate::geometry::hits_ground;
use crate::methods::hillaire::sky_view::{self, sky_view_angles_from_texel};
use crate::methods::{Inputs, SkyModel};
use glam::DVec3;

/// The moving sky: on Hillaire's sky-view grid (its size, axes and texel descriptions), rebuilt
/// with the viewpoint, built for frames in motion alone.
pub const TABLE: TableSpec = TableSpec {
    id: "moving-sky",
    label: "moving sky (built for frames in motion on a software GPU)",
    // The model's radiance, the ground's included.
    invalidated_by: Inputs::ATMOSPHERE
        .union(Inputs::VIEWPOINT)
        .union(Inputs::GROUND_ALBEDO),
    transmittance: false,
    ..sky_view::TABLE
};

/// The moving sky of `model` at viewpoint `vp`: its radiance (W·m⁻²·sr⁻¹·nm⁻¹) at each
/// texel's direction, seen from altitude `vp.h` (m) with the sun at zenith cosine `vp.mu_s`.
pub fn compute_lut(model: &dyn SkyModel, vp: Viewpoint) -> Lut {
    let p = model.params();
    let at = (DVec3::Z * (p.bottom_radius_m + vp.h), vp.h);
    let sun = local_sun(vp.mu_s);
    Lut::from_spec(&TABLE, p.batches.len(), |layer, _, y, x| {
        let (phi, theta) = sky_view_angles_from_texel(p, vp.h, x as f64, y as f64);
        model.radiance_in_motion(layer, at, direction_from_phi_theta(phi, theta), sun)
    })
}

/// The moving sky `lut` looked up along the unit world direction `dir` from altitude `h` (m),
/// `up` being the local vertical and `sun` the sun's unit direction: the sky half of the table
/// or the ground half, as the direction sees one or the other.
pub fn radiance(
    model: &dyn SkyModel,
    lut: &Lut,
    layer: usize,
    h: f64,
    up: DVec3,
    dir: DVec3,
    sun: DVec3,
) -> Lanes {
    let p = model.params();
    let (phi, theta) = super::sun_relative_angles(up, dir, sun);
    let ground = hits_ground(h, dir.dot(up), p.bottom_radius_m);
    sky_view::sky_view(p, lut, layer, h, phi, theta, ground)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::shared::optics::tests::params;
    use crate::methods::shared::single_scattering_sky::{self, Rule, Way};

    /// At its texels the look-up gives the march it tabulates itself (`radiance_in_motion`),
    /// and between them, away from the sun, the horizon and the limb, it stays within a few
    /// per cent of it.
    #[test]
    fn the_moving_sky_is_the_march_at_its_texels_and_close_between_them() {
        let p = params();
        let model = single_scattering_sky::build(&p, Way::March(Rule::Midpoint), false);
        let vp = Viewpoint { h: 30.0, mu_s: 0.3 };
        let lut = compute_lut(&*model, vp);
        let up = DVec3::Z;
        let sun = local_sun(vp.mu_s);
        let at = (up * (p.bottom_radius_m + vp.h), vp.h);
        for (x, y) in [(0, 0), (57, 20), (120, 53), (120, 54), (191, 107)] {
            let (phi, theta) = sky_view_angles_from_texel(&p, vp.h, x as f64, y as f64);
            let dir = direction_from_phi_theta(phi, theta);
            let looked_up = radiance(&*model, &lut, 0, vp.h, up, dir, sun);
            let marched = model.radiance_in_motion(0, at, dir, sun);
            for k in 0..4 {
                let e = (looked_up[k] - marched[k]).abs() / marched[k].abs().max(1e-30);
                assert!(
                    e < 1e-9,
                    "texel ({x}, {y}) lane {k}: {looked_up:?} vs {marched:?}"
                );
            }
        }
        let mut worst: f64 = 0.0;
        for (phi_deg, elevation_deg) in [(100.0, 30.0), (150.0, 60.0), (170.0, -30.0), (90.0, 10.0)]
        {
            let (phi, theta) = (
                f64::to_radians(phi_deg),
                f64::to_radians(90.0 - elevation_deg),
            );
            let dir = direction_from_phi_theta(phi, theta);
            let looked_up = radiance(&*model, &lut, 0, vp.h, up, dir, sun);
            let marched = model.radiance_in_motion(0, at, dir, sun);
            for k in 0..4 {
                worst = worst.max((looked_up[k] - marched[k]).abs() / marched[k]);
            }
        }
        assert!(worst < 0.03, "between texels: {worst}");
    }

    /// The nested marches' moving sky takes their way to the sun from its table: the same
    /// radiance as marching it to about a per cent (most at a low sun near the horizon, where
    /// the sun's rays graze the table's first columns), and a closed form's is its own radiance
    /// exactly.
    #[test]
    fn the_nested_marches_move_with_their_way_to_the_sun_tabulated() {
        let p = params();
        let up = DVec3::Z;
        let at = (up * (p.bottom_radius_m + 30.0), 30.0);
        let rows = [
            (Way::March(Rule::Midpoint), 0.0075),
            (Way::GalajSpline, 0.004),
            (Way::March(Rule::Trapezoid), 0.015),
            (Way::SchulerChapman, 0.0),
        ];
        for (way, bound) in rows {
            let model = single_scattering_sky::build(&p, way, false);
            assert_eq!(
                model
                    .table(single_scattering_sky::SUN_ROUTE_TABLE.id)
                    .is_some(),
                way.tabulated_in_motion(),
                "{way:?}"
            );
            let mut worst: f64 = 0.0;
            for sun_elevation_deg in [30.0, 4.0] {
                let sun = local_sun(f64::to_radians(sun_elevation_deg).sin());
                for (phi_deg, elevation_deg) in [
                    (0.0, 2.0),
                    (40.0, 20.0),
                    (120.0, 60.0),
                    (180.0, 5.0),
                    (90.0, -10.0),
                ] {
                    let dir = direction_from_phi_theta(
                        f64::to_radians(phi_deg),
                        f64::to_radians(90.0 - elevation_deg),
                    );
                    let moving = model.radiance_in_motion(0, at, dir, sun);
                    let still = model.radiance(0, at, dir, sun);
                    for k in 0..4 {
                        worst = worst.max((moving[k] - still[k]).abs() / still[k]);
                    }
                }
            }
            eprintln!("{way:?}: worst {worst:.2e}");
            assert!(worst <= bound, "{way:?}: {worst}");
        }
    }
}
