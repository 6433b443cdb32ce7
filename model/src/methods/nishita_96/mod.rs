//! Nishita, Dobashi, Kaneda & Yamashita (1996), "Display Method of the Sky Color Taking into
//! Account Multiple Scattering" (Pacific Graphics): single scattering plus the second order,
//! gathered from precomputed "intensity volumes" of the once-scattered light.
//!
//! The single scattering is the `nishita` row's: every pixel marches its view ray and, at each
//! sample, the ray to the sun (midpoint rule). The second order is the paper's: the light
//! scattered once is stored per point of the atmosphere for a fixed set of directions
//! (`shared::intensity_volume`, computed once per atmosphere through the transmittance
//! table), and every sample of the view march gathers it through the Rayleigh and the aerosol
//! phase functions towards the view. The ground behind the view is lit by the sun and by the
//! skylight of the once-scattered light. No third and higher orders: the sky is still darker
//! than the path tracer's, by less than single scattering's. The view march takes the
//! `nishita` row's samples, so that the two rows differ by the second order alone.

use super::shared::intensity_volume::{self, gathered, sky_irradiance};
use super::shared::single_scattering_sky::{
    self, HigherOrders, Rule, SingleScattering, SunRoute, Way,
};
use super::shared::transmittance::compute_transmittance_lut;
use super::shared::{Lanes, Lut, Params, TableSpec, Viewpoint, moving_sky};
use super::{Domain, SkyModel};

/// The way to the sun: the `nishita` row's nested march.
pub const WAY: Way = Way::March(Rule::Midpoint);

/// The transmittance table and the intensity volume of order 1, then the way to the sun and
/// the moving sky built from it (views in motion on a software GPU, `shared::moving_sky`).
pub const TABLES: [TableSpec; 4] = [
    super::shared::transmittance::TABLE,
    intensity_volume::TABLE,
    single_scattering_sky::SUN_ROUTE_TABLE,
    moving_sky::TABLE,
];

/// Daylight views from anywhere, and aerosol up to AOD 0.3, where the sky of two orders stays
/// within 25 % of the path tracer's on average (`atmoscope bench aod`).
pub const DOMAIN: Domain = Domain {
    note: "ground, plane and space views in daylight; single and second-order scattering, so the sky lacks what the third and higher orders add and twilight, lit by them, is outside",
    max_aod550: 0.3,
    ..super::nishita::DOMAIN
};

/// The values the GPU reads from `globals.model`: the table-free sky's by [`WAY`].
pub fn constants(p: &Params) -> [f64; 12] {
    single_scattering_sky::constants(p, WAY)
}

/// The light of the orders in `volume` as a single-scattering model's higher orders: gathered
/// at each view sample, and the skylight on the ground.
pub struct IntensityVolume {
    pub transmittance: Lut,
    /// The sum of the orders gathered from ([`intensity_volume::TABLE`]).
    pub volume: Lut,
    /// The model's other tables by id (`haber`'s last two orders).
    pub others: Vec<(&'static str, Lut)>,
}

impl HigherOrders for IntensityVolume {
    fn source(&self, p: &Params, layer: usize, at: (f64, f64), mu: f64, nu: f64) -> (Lanes, Lanes) {
        gathered(p, &self.volume, layer, at, mu, nu)
    }

    fn ground_irradiance(&self, p: &Params, layer: usize, mu_s_g: f64) -> Lanes {
        sky_irradiance(p, &self.volume, layer, mu_s_g)
    }

    fn table(&self, id: &str) -> Option<&Lut> {
        match id {
            "transmittance" => Some(&self.transmittance),
            "intensity-volume" => Some(&self.volume),
            _ => self.others.iter().find(|(o, _)| *o == id).map(|(_, t)| t),
        }
    }
}

/// A single-scattering sky by [`WAY`], with the `nishita` row's samples and `higher` orders.
pub fn with_higher_orders(p: &Params, higher: IntensityVolume) -> Box<dyn SkyModel> {
    Box::new(SingleScattering {
        params: p.clone(),
        view_steps: single_scattering_sky::steps(p).0,
        sun_path: SunRoute::new(p, WAY),
        higher_orders: Box::new(higher),
    })
}

/// The registry's constructor (no table depends on the viewpoint).
pub fn build(p: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    let transmittance = compute_transmittance_lut(p);
    let volume = intensity_volume::compute_single(p, &transmittance);
    with_higher_orders(
        p,
        IntensityVolume {
            transmittance,
            volume,
            others: Vec::new(),
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::direction_from_angles;
    use crate::methods::shared::optics::tests::params;
    use glam::DVec3;

    /// The second order adds light everywhere in the sky and on the ground, most where the
    /// single-scattered light is faint (away from the sun) and most at blue wavelengths, and
    /// less than the single scattering it is gathered from in a clear daylight sky, as the path
    /// tracer's own second order does (`probe --max-order 2` over `--max-order 1`; the
    /// figures are in docs/measurements/tests-2026-12-08.md).
    #[test]
    fn the_second_order_adds_light_below_the_first() {
        let p = params();
        let vp = Viewpoint { h: 10.0, mu_s: 0.5 };
        let (single, both) = (super::super::nishita::build(&p, vp), build(&p, vp));
        let position = DVec3::new(0.0, 0.0, p.bottom_radius_m + 10.0);
        let sun = direction_from_angles(30.0, 0.0);
        // The share the second order adds per lane (Spectral4's lanes: 640, 580, 510, 450 nm).
        let added = |elevation: f64, azimuth: f64| {
            let dir = direction_from_angles(elevation, azimuth);
            let (a, b) = (
                single.radiance(0, (position, 10.0), dir, sun),
                both.radiance(0, (position, 10.0), dir, sun),
            );
            [0, 1, 2, 3].map(|i| b[i] / a[i] - 1.0)
        };
        for (elevation, azimuth) in [(80.0, 120.0), (20.0, 180.0), (5.0, 10.0), (-10.0, 90.0)] {
            let share = added(elevation, azimuth);
            for (i, s) in share.iter().enumerate() {
                assert!(
                    (0.02..1.0).contains(s),
                    "{elevation}° {azimuth}° lane {i}: adds {s:.3}"
                );
            }
            // Most in the blue: the share grows from the longest wavelength to the shortest.
            assert!(
                share.windows(2).all(|w| w[1] > w[0]),
                "{elevation}° {azimuth}°: {share:.3?}"
            );
        }
        // Most where faint: opposite the sun at least half as much again as beside it.
        let (faint, bright) = (added(20.0, 180.0), added(5.0, 10.0));
        for i in 0..4 {
            assert!(
                faint[i] > 1.5 * bright[i],
                "lane {i}: {:.3} opposite the sun, {:.3} beside it",
                faint[i],
                bright[i]
            );
        }
    }
}
