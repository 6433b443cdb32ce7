//! Single scattering with the optical depth towards the sun integrated by the trapezoid rule:
//! the baseline against which Gałaj et al. (2021) measure their transmittance approximations.
//! The sky pass is the table-free single-scattering models' (`shared::single_scattering_sky`),
//! with the same sample counts as `nishita`; the two differ only in the rule along the sun's
//! ray — the trapezoid rule's samples include both ends, so the point being lit, where the air
//! is densest along a rising ray, is sampled itself. No tables but those of views in motion
//! (the `sun-route` table and the moving sky, `shared::moving_sky`), and no higher orders.
//! This module chooses that rule.

use super::shared::single_scattering_sky::{self, Rule, Way};
use super::shared::{Params, TableSpec, Viewpoint};
use super::{Domain, SkyModel};

/// The method's tables, for views in motion on a software GPU alone: its way to the sun
/// tabulated and the moving sky built from it (`shared::moving_sky`), as `nishita`'s.
pub const TABLES: [TableSpec; 2] = single_scattering_sky::TABLES_NESTED;

/// The domain of single scattering (as `nishita`'s).
pub const DOMAIN: Domain = super::nishita::DOMAIN;

/// The domain with Hillaire's higher orders added (the `trapezoid-ms` row): AOD up to 0.2
/// (`atmoscope bench aod`; the trapezoid rule's darker haze costs it against the midpoint
/// rule's 0.5).
pub const DOMAIN_MS: Domain = Domain {
    max_aod550: 0.2,
    ..super::nishita::DOMAIN_MS
};

/// The registry's constructor (no table depends on the viewpoint).
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    single_scattering_sky::build(params, Way::March(Rule::Trapezoid), false)
}

/// The constructor of the `trapezoid-ms` row: with Hillaire's multiple-scattering table.
pub fn build_ms(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    single_scattering_sky::build(params, Way::March(Rule::Trapezoid), true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::shared::optics::tests::params;
    use crate::methods::shared::single_scattering_sky::sun_transmittance;
    use crate::methods::shared::transmittance::{compute_transmittance_lut, transmittance};

    #[test]
    fn the_trapezoid_rule_converges_to_the_table_and_differs_from_the_midpoint_rule() {
        let p = params();
        let table = compute_transmittance_lut(&p);
        for (h, mu_s) in [(0.0, 1.0), (0.0, 0.3), (5_000.0, 0.1), (30_000.0, 0.6)] {
            let fine = sun_transmittance(&p, 0, h, mu_s, 4096, Rule::Trapezoid);
            let looked_up = transmittance(&p, &table, 0, h, mu_s);
            for (f, t) in fine.iter().zip(looked_up) {
                assert!((f / t - 1.0).abs() < 0.01, "h {h} mu_s {mu_s}: {f} vs {t}");
            }
        }
        // With few intervals the two rules err on opposite sides of a density that falls
        // with height (convex): the trapezoid too dark, the midpoint too bright.
        let exact = sun_transmittance(&p, 0, 0.0, 0.5, 4096, Rule::Trapezoid)[0];
        let trapezoid = sun_transmittance(&p, 0, 0.0, 0.5, 8, Rule::Trapezoid)[0];
        let midpoint = sun_transmittance(&p, 0, 0.0, 0.5, 8, Rule::Midpoint);
        assert!(
            trapezoid < exact && midpoint[0] > exact,
            "{trapezoid} {exact} {midpoint:?}"
        );
    }
}
