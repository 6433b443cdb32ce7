//! Nishita et al. (1993), "Display of the Earth Taking into Account Atmospheric Scattering"
//! (SIGGRAPH), in the per-pixel form O'Neil (2005, GPU Gems 2, ch. 16) brought to the GPU:
//! single scattering by nested quadrature, with no tables of the atmosphere. Each pixel marches
//! its view ray; at every sample a second march of midpoint samples along the ray towards the
//! sun gives the optical depth to the sun. A frame costs view steps × sun steps medium
//! evaluations per pixel and batch, and no change of the atmosphere costs more than a frame
//! (a software GPU draws views in motion from the moving sky, `shared::moving_sky`). There are no higher orders:
//! the sky lacks what multiple scattering adds, and the ground is lit by the sun alone.
//!
//! The medium (profiles, cross-sections, phase functions, sun) is the scene's, shared with
//! every other model, so that comparisons measure the method. The sky pass is the table-free
//! single-scattering models' (`shared::single_scattering_sky`); this module chooses the
//! midpoint rule for the way to the sun.

use super::shared::single_scattering_sky::{self, Rule, Way};
use super::shared::{Params, TableSpec, Viewpoint};
use super::{Domain, SkyModel};

/// The method's tables, for views in motion on a software GPU alone: its way to the sun
/// tabulated and the moving sky built from it (`shared::moving_sky`).
pub const TABLES: [TableSpec; 2] = super::shared::single_scattering_sky::TABLES_NESTED;

/// Where the model is meant to work: anywhere with the sun up. Below the horizon the sky is
/// lit by light scattered more than once, which the model leaves out; above it the sky lacks
/// the higher orders too (more than 25 % below the path tracer's radiance even in clean air,
/// `atmoscope bench aod`), so no aerosol amount is inside its AOD range.
pub const DOMAIN: Domain = Domain {
    max_altitude_m: f64::INFINITY,
    min_sun_elevation_deg: 0.0,
    note: "ground, plane and space views in daylight; single scattering only, so the sky lacks what higher orders add and twilight, lit by them, is outside",
    max_aod550: 0.0,
    refuses: false,
};

/// The domain with Hillaire's higher orders added (the `nishita-ms` row): daylight views, and
/// aerosol up to AOD 0.5, where the sky stays within 25 % of the path tracer's
/// (`atmoscope bench aod`): the single scattering, marched per pixel with the exact phase
/// functions, carries aerosol's forward peak.
pub const DOMAIN_MS: Domain = Domain {
    note: "ground, plane and space views in daylight; Hillaire's isotropic higher orders added to single scattering",
    max_aod550: 0.5,
    ..DOMAIN
};

/// The registry's constructor (no table depends on the viewpoint).
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    single_scattering_sky::build(params, Way::March(Rule::Midpoint), false)
}

/// The constructor of the `nishita-ms` row: with Hillaire's multiple-scattering table.
pub fn build_ms(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    single_scattering_sky::build(params, Way::March(Rule::Midpoint), true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::Atmosphere;
    use crate::geometry::{Ray, direction_from_angles};
    use crate::lanes::Lanes;
    use crate::methods::shared::optics::tests::params;
    use crate::methods::shared::single_scattering_sky::{SunRoute, Way, sun_transmittance};
    use crate::methods::shared::transmittance::{compute_transmittance_lut, transmittance};
    use crate::methods::single_scattering;
    use crate::scene::{Quality, Scene, WavelengthSet};
    use glam::DVec3;

    #[test]
    fn the_nested_march_agrees_with_the_transmittance_table() {
        let p = params();
        let table = compute_transmittance_lut(&p);
        for (h, mu_s) in [(0.0, 1.0), (0.0, 0.3), (5_000.0, 0.1), (30_000.0, 0.6)] {
            let marched = sun_transmittance(&p, 0, h, mu_s, 4096, Rule::Midpoint);
            let looked_up = transmittance(&p, &table, 0, h, mu_s);
            for (m, t) in marched.iter().zip(looked_up) {
                assert!((m / t - 1.0).abs() < 0.01, "h {h} mu_s {mu_s}: {m} vs {t}");
            }
        }
        // Behind the planet the sun is gone, and above the atmosphere nothing dims it.
        assert_eq!(
            sun_transmittance(&p, 0, 0.0, -0.2, 16, Rule::Midpoint),
            Lanes::ZERO
        );
        let route = SunRoute::new(&p, Way::March(Rule::Midpoint));
        assert_eq!(
            route.seen_from(&p, 0, p.thickness_m() + 1_000.0, 0.5),
            Lanes::ONE
        );
    }

    /// With fine steps the nested march is the exact single scattering it approximates.
    #[test]
    fn the_nested_march_converges_to_exact_single_scattering() {
        let scene = Scene::default();
        let atm = Atmosphere::for_scene(&scene);
        let mut p = Params::new(&atm, WavelengthSet::SpectralN(4), Quality::High);
        p.steps.sky_view = 256;
        let position = DVec3::new(0.0, 0.0, p.bottom_radius_m + 100.0);
        let sun = direction_from_angles(30.0, 0.0);
        for (elevation, azimuth) in [(60.0, 0.0), (10.0, 90.0), (2.0, 180.0), (-10.0, 30.0)] {
            let dir = direction_from_angles(elevation, azimuth);
            let marched = build(
                &p,
                Viewpoint {
                    h: 100.0,
                    mu_s: 0.5,
                },
            )
            .radiance(0, (position, 100.0), dir, sun);
            let ray = Ray::new(position, dir);
            for (i, &w) in p.batches[0].colour.wavelengths_nm.iter().enumerate() {
                // Per unit sunlight: the set's sunlight is a band's, the exact one a point's.
                let exact = single_scattering::radiance(&atm, &ray, sun, w)
                    / atm.solar_irradiance(w, None)
                    * p.batches[0].solar_irradiance[i];
                assert!(
                    (marched[i] / exact - 1.0).abs() < 0.02,
                    "{elevation}° {azimuth}° {w} nm: {} vs {exact}",
                    marched[i]
                );
            }
        }
    }

    /// Hillaire's higher orders add light everywhere, and its tables are the model's.
    #[test]
    fn the_ms_row_adds_hillaires_higher_orders() {
        let p = params();
        let vp = Viewpoint { h: 10.0, mu_s: 0.5 };
        let (single, with_ms) = (build(&p, vp), build_ms(&p, vp));
        assert!(single.table("multiple-scattering").is_none());
        assert!(
            with_ms.table("multiple-scattering").is_some()
                && with_ms.table("transmittance").is_some()
        );
        let position = DVec3::new(0.0, 0.0, p.bottom_radius_m + 10.0);
        let sun = direction_from_angles(20.0, 0.0);
        for elevation in [80.0, 30.0, 5.0] {
            let dir = direction_from_angles(elevation, 120.0);
            let (a, b) = (
                single.radiance(0, (position, 10.0), dir, sun),
                with_ms.radiance(0, (position, 10.0), dir, sun),
            );
            for i in 0..4 {
                assert!(b[i] > a[i] * 1.02, "{elevation}°: {} vs {}", b[i], a[i]);
            }
        }
    }
}
