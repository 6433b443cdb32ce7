//! Gałaj, Pietrusiak, Galewski, Ledzion, Wojciechowski (2021), "Hybrid Integration Method for
//! Sunlight Atmospheric Scattering" (IEEE Access 9), their Taylor-series transmittance: single
//! scattering marched along the view ray as in `trapezoid` (their baseline), with the optical
//! depth towards the sun from one closed form per constituent instead of an inner march. Along
//! the sun's ray the altitude is replaced by its expansion of order 1 + a about the point a
//! fraction b of the way to the top of the atmosphere, the Jacobian taken there as constant, so
//! that the integral of an exponential density is a difference of two exponentials
//! (`shared::exponential::galaj_taylor`); a = b = 0.45 from the authors' grid search
//! (`atmoscope bench transmittance` repeats the search for the scene's atmosphere).
//!
//! The closed form holds for exponential profiles: the way to the sun sees the scene's medium
//! as fitted exponentials and an ozone shell (`shared::exponential`); the view march reads the
//! scene's own profile. The constant Jacobian fails along grazing rays through a thin layer —
//! aerosol's optical depth towards a sun 10° high comes out about four times too large — so
//! the model's domain keeps the sun high.

use super::shared::single_scattering_sky::{self, Way};
use super::shared::{Params, TableSpec, Viewpoint};
use super::{Domain, SkyModel};

/// The method's one table: the moving sky its views in motion are drawn from on a software
/// GPU (`shared::moving_sky`).
pub const TABLES: [TableSpec; 1] = [super::shared::moving_sky::TABLE];

/// Daylight with the sun at least 30° high, where the aerosol's Taylor optical depth stays
/// within 25 % of the exponential's (air's within 2 % at 60°).
pub const DOMAIN: Domain = Domain {
    min_sun_elevation_deg: 30.0,
    note: "ground, plane and space views with the sun at least 30° high: single scattering only, and the Taylor integral overshoots along grazing sun rays through aerosol",
    ..super::nishita::DOMAIN
};

/// The domain with Hillaire's higher orders added (the `galaj-taylor-ms` row): AOD up to 0.04
/// by the registry's criterion, which asks for a sun 5° high too, where the Taylor overshoot
/// darkens low sunlight more with every bit of aerosol (`atmoscope bench aod`); with the sun
/// 30° high, inside the domain, the sky stays within 25 % up to AOD 0.5.
pub const DOMAIN_MS: Domain = Domain {
    min_sun_elevation_deg: 30.0,
    note: "ground, plane and space views with the sun at least 30° high; Hillaire's isotropic higher orders added to single scattering",
    max_aod550: 0.04,
    ..super::nishita::DOMAIN_MS
};

/// The registry's constructor (no table depends on the viewpoint).
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    single_scattering_sky::build(params, Way::GalajTaylor, false)
}

/// The constructor of the `galaj-taylor-ms` row: with Hillaire's multiple-scattering table.
pub fn build_ms(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    single_scattering_sky::build(params, Way::GalajTaylor, true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::shared::optics::tests::params;
    use crate::methods::shared::single_scattering_sky::{Rule, SunRoute};

    /// Towards a high sun the Taylor form's optical depth stays near the fine march through
    /// the scene's own medium (from the ground within 4 % at 45° and above, 12 % at 30°; from
    /// 10 km within 12 %, the exponential fit's shortfall there); towards a low sun from the
    /// ground it overshoots — twice the optical depth at 10°, ten times at 5° — and darkens the
    /// sun, never brightens it.
    #[test]
    fn the_taylor_way_to_the_sun_follows_the_march_with_the_sun_high() {
        let p = params();
        let taylor = SunRoute::new(&p, Way::GalajTaylor);
        let mut fine = SunRoute::new(&p, Way::March(Rule::Midpoint));
        fine.intervals = 4096;
        for (h, elevation_deg, bound) in [
            (0.0, 90.0f64, 0.04),
            (0.0, 45.0, 0.04),
            (0.0, 30.0, 0.12),
            (10_000.0, 60.0, 0.12),
            (10_000.0, 5.0, 0.12),
        ] {
            let mu_s = elevation_deg.to_radians().sin();
            let (a, b) = (
                taylor.optical_depth(&p, 0, h, mu_s),
                fine.optical_depth(&p, 0, h, mu_s),
            );
            for i in 0..4 {
                assert!(
                    (a[i] / b[i] - 1.0).abs() < bound,
                    "h {h} sun {elevation_deg}°: {a:?} vs {b:?}"
                );
            }
        }
        for elevation_deg in [10.0f64, 5.0, 3.0] {
            let mu_s = elevation_deg.to_radians().sin();
            let (a, b) = (
                taylor.optical_depth(&p, 0, 0.0, mu_s),
                fine.optical_depth(&p, 0, 0.0, mu_s),
            );
            for i in 0..4 {
                assert!(a[i] > 1.5 * b[i], "sun {elevation_deg}°: {a:?} vs {b:?}");
            }
        }
    }
}
