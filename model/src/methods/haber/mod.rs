//! Haber, Magnor & Seidel (2005), "Physically based simulation of twilight phenomena" (ACM
//! Transactions on Graphics 24(4)): the twilight sky as multiple scattering gathered order by
//! order over a discretised atmosphere. The paper divides the atmosphere into cells, stores at
//! each the radiance scattered into a set of directions, lights the cells by the sun through
//! the atmosphere and then lets them exchange light, one scattering order per iteration, until
//! the orders add little; the view gathers the cells' light along its rays.
//!
//! Here the cells are the intensity volume's (`shared::intensity_volume`): in a spherically
//! symmetric atmosphere a cell is known by its altitude and the sun's zenith cosine there, and
//! its directions are fixed in its local frame, so each order is one table over (μ_s, h) per
//! direction. Order 1 is the sunlight through the transmittance table, Earth's shadow
//! included; each order after it is gathered from the one before along every cell's rays, the
//! ground lit by the sky of the order before. The volume sums the orders 1 to the scene's count
//! (`render.scattering_orders`); the view march adds single scattering from the sun (the
//! `nishita` row's nested march) and gathers one order more from the volume, so a view sees
//! that count plus one. What the paper adds that is left out here: the refraction of the
//! sunlight's path (the sun's rays are straight) and its water droplets (the scene's aerosol
//! stands for them).

use super::nishita_96::{IntensityVolume, with_higher_orders};
use super::shared::intensity_volume::{self, compute_next, compute_single};
use super::shared::single_scattering_sky::SUN_ROUTE_TABLE;
use super::shared::transmittance::compute_transmittance_lut;
use super::shared::{Params, TableSpec, Viewpoint, moving_sky};
use super::{Domain, SkyModel};

/// The transmittance table; the volume (the sum of the orders), its last order and the order
/// before it; then the way to the sun and the moving sky.
pub const TABLES: [TableSpec; 6] = [
    super::shared::transmittance::TABLE,
    intensity_volume::TABLE,
    intensity_volume::DELTA,
    intensity_volume::PREVIOUS,
    SUN_ROUTE_TABLE,
    moving_sky::TABLE,
];

/// Twilight, its purpose, and the day before it: the sun down to 18° below the horizon (the
/// end of astronomical twilight), from the ground, planes and space; aerosol up to AOD 0.5,
/// where its sky stays within 25 % of the path tracer's on average (`atmoscope bench aod`).
pub const DOMAIN: Domain = Domain {
    max_altitude_m: f64::INFINITY,
    min_sun_elevation_deg: -18.0,
    note: "ground, plane and space views from daylight through twilight to the sun 18° below the horizon; multiple scattering gathered order by order; no refraction",
    max_aod550: 0.5,
    refuses: false,
};

/// The view's constants: `nishita-96`'s.
pub use super::nishita_96::constants;

/// The registry's constructor (no table depends on the viewpoint).
pub fn build(p: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    let transmittance = compute_transmittance_lut(p);
    let first = compute_single(p, &transmittance);
    let (mut volume, mut previous, mut delta) = (first.clone(), first.clone(), first);
    for _ in 2..=p.scattering_orders {
        previous = delta;
        delta = compute_next(p, &previous);
        volume = volume.plus(&delta);
    }
    with_higher_orders(
        p,
        IntensityVolume {
            transmittance,
            volume,
            others: vec![
                (intensity_volume::DELTA.id, delta),
                (intensity_volume::PREVIOUS.id, previous),
            ],
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::direction_from_angles;
    use crate::methods::shared::Lut;
    use crate::methods::shared::optics::tests::params;
    use glam::DVec3;

    /// In daylight and with the sun below the horizon the sky of many orders is brighter than
    /// that of two; the orders fade, and each order the loop adds is added to the volume.
    #[test]
    fn twilight_brightens_with_the_orders() {
        let p = params().with_scattering_orders(3);
        let vp = Viewpoint { h: 10.0, mu_s: 0.0 };
        let (two, many) = (super::super::nishita_96::build(&p, vp), build(&p, vp));
        let position = DVec3::new(0.0, 0.0, p.bottom_radius_m + 10.0);
        for sun_elevation in [5.0, -3.0, -8.0] {
            let sun = direction_from_angles(sun_elevation, 0.0);
            for (elevation, azimuth) in [(80.0, 120.0), (10.0, 180.0), (5.0, 0.0)] {
                let dir = direction_from_angles(elevation, azimuth);
                let (a, b) = (
                    two.radiance(0, (position, 10.0), dir, sun),
                    many.radiance(0, (position, 10.0), dir, sun),
                );
                for i in 0..4 {
                    assert!(
                        b[i] > a[i] * 1.01,
                        "sun {sun_elevation}°, view {elevation}° {azimuth}° lane {i}: {} vs {}",
                        b[i],
                        a[i]
                    );
                }
            }
        }
        let [volume, delta, previous] =
            ["intensity-volume", "delta-intensity", "previous-intensity"]
                .map(|id| many.table(id).expect("haber's tables"));
        // The last order is fainter than the one before on the whole (not along every ray:
        // near the horizon a ray's optical depth passes 1).
        let total = |lut: &Lut| -> f64 { lut.data.iter().map(|t| t[0]).sum() };
        assert!(total(delta) < total(previous) && total(delta) > 0.0);
        // One order more adds its last order to the volume, and the order before it is the
        // last of one order fewer.
        let more = build(&p.clone().with_scattering_orders(4), vp);
        let [more_volume, more_delta, more_previous] =
            ["intensity-volume", "delta-intensity", "previous-intensity"]
                .map(|id| more.table(id).expect("haber's tables"));
        assert_eq!(more_previous, delta);
        for ((m, v), d) in more_volume
            .data
            .iter()
            .zip(&volume.data)
            .zip(&more_delta.data)
        {
            for l in 0..4 {
                assert!((m[l] - (v[l] + d[l])).abs() <= 1e-12 * m[l].abs().max(1e-30));
            }
        }
        assert!(total(more_delta) < total(delta));
    }
}
