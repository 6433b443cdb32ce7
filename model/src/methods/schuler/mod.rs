//! Schuler (2012), "An Approximation to the Chapman Grazing-Incidence Function for Atmospheric
//! Scattering" (GPU Pro 3), as Leenman (2025) compares it: Nishita's per-pixel single
//! scattering with the inner march towards the sun replaced by a closed form — each
//! constituent's optical depth is its density at the sample times its scale height times
//! Schuler's rational approximation of the Chapman function, c / ((c − 1)·μ + 1) with
//! c = √(πx/2), mirrored through the ray's lowest point below the horizontal. A frame costs
//! one closed form per view sample instead of a march; no tables of the atmosphere (but the
//! moving sky of views in motion, `shared::moving_sky`), no higher orders.
//!
//! The closed form holds for exponential profiles: the way to the sun sees the scene's medium
//! as fitted exponentials and an ozone shell (`shared::exponential`); the view march reads the
//! scene's own profile. The sky pass is the table-free single-scattering models'
//! (`shared::single_scattering_sky`).

use super::shared::single_scattering_sky::{self, Way};
use super::shared::{Params, TableSpec, Viewpoint};
use super::{Domain, SkyModel};

/// The method's one table: the moving sky its views in motion are drawn from on a software
/// GPU (`shared::moving_sky`).
pub const TABLES: [TableSpec; 1] = [super::shared::moving_sky::TABLE];

/// The domain of single scattering (as `nishita`'s): the Chapman form itself holds to the
/// horizon (within 14 % of the exponential's optical depth at worst, near 88°).
pub const DOMAIN: Domain = super::nishita::DOMAIN;

/// The domain with Hillaire's higher orders added (the `schuler-ms` row): as `nishita-ms`'s
/// but for aerosol, up to AOD 0.3 (`atmoscope bench aod`): at 0.5 the low sun sits on the 25 %
/// bound, closer to it than a quick check's noise can tell apart, where `nishita-ms`,
/// marching the exact optical depth, stays clearly inside.
pub const DOMAIN_MS: Domain = Domain {
    max_aod550: 0.3,
    ..super::nishita::DOMAIN_MS
};

/// The registry's constructor (no table depends on the viewpoint).
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    single_scattering_sky::build(params, Way::SchulerChapman, false)
}

/// The constructor of the `schuler-ms` row: with Hillaire's multiple-scattering table.
pub fn build_ms(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    single_scattering_sky::build(params, Way::SchulerChapman, true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::shared::optics::tests::params;
    use crate::methods::shared::single_scattering_sky::{Rule, SunRoute};

    /// Towards a sun from the zenith to 3° high, from the ground and a plane, the closed
    /// form's optical depth stays near the fine march through the scene's own medium: from the
    /// ground within 3 % down to 45°, 5 % at 20° and 15 % to 3° (the Chapman form's error near the
    /// horizon); from 10 km within 25 % (there the exponential fit of the air above is also
    /// 7–10 % short).
    #[test]
    fn the_chapman_way_to_the_sun_follows_the_march() {
        let p = params();
        let closed = SunRoute::new(&p, Way::SchulerChapman);
        let mut fine = SunRoute::new(&p, Way::March(Rule::Midpoint));
        fine.intervals = 4096;
        for (h, elevation_deg, bound) in [
            (0.0, 90.0f64, 0.03),
            (0.0, 45.0, 0.03),
            (0.0, 20.0, 0.05),
            (0.0, 5.0, 0.15),
            (0.0, 3.0, 0.15),
            (10_000.0, 60.0, 0.25),
            (10_000.0, 3.0, 0.25),
        ] {
            let mu_s = elevation_deg.to_radians().sin();
            let (a, b) = (
                closed.optical_depth(&p, 0, h, mu_s),
                fine.optical_depth(&p, 0, h, mu_s),
            );
            for i in 0..4 {
                assert!(
                    (a[i] / b[i] - 1.0).abs() < bound,
                    "h {h} sun {elevation_deg}°: {a:?} vs {b:?}"
                );
            }
        }
    }
}
