//! Single scattering with the optical depth towards the sun integrated by the trapezoid rule:
//! the baseline against which Gałaj et al. (2021) measure their transmittance approximations.
//! The sky pass is the table-free single-scattering models' (`shared::single_scattering_sky`),
//! with the same sample counts as `nishita`; the two differ only in the rule along the sun's
//! ray — the trapezoid rule's samples include both ends, so the point being lit, where the air
//! is densest along a rising ray, is sampled itself. No tables and no higher orders. This
//! module is the way to the sun, twin of `shaders/trapezoid/common.wgsl`.

use super::shared::single_scattering_sky::{SingleScattering, SunPath, steps};
use super::shared::sun::visible_fraction;
use super::shared::{Lanes, Params, TableSpec, Viewpoint};
use super::{Domain, SkyModel};
use crate::geometry::{altitude_along, distance_to_top};

/// The method has no tables.
pub const TABLES: [TableSpec; 0] = [];

/// The domain of single scattering (as `nishita`'s).
pub const DOMAIN: Domain = super::nishita::DOMAIN;

/// Optical depth per lane from altitude `h` (m) along zenith cosine `mu` to the top of the
/// atmosphere by the trapezoid rule over `intervals` equal intervals.
pub fn optical_depth(p: &Params, layer: usize, h: f64, mu: f64, intervals: u32) -> Lanes {
    let d = distance_to_top(h, mu, p.bottom_radius_m, p.top_radius_m);
    let dt = d / f64::from(intervals);
    let mut depth = [0.0; 4];
    for s in 0..=intervals {
        let (h_t, _) = altitude_along(h, mu, f64::from(s) * dt, p.bottom_radius_m);
        let w = if s == 0 || s == intervals { 0.5 } else { 1.0 };
        let m = p.medium(layer, h_t);
        for (d, e) in depth.iter_mut().zip(m.extinction) {
            *d += w * e * dt;
        }
    }
    depth
}

/// Transmittance per lane from altitude `h` (m) towards the sun at zenith cosine `mu_s`
/// through [`optical_depth`], times the visible fraction of the sun's disk (0, and no
/// integral, behind the planet).
pub fn sun_transmittance(p: &Params, layer: usize, h: f64, mu_s: f64, intervals: u32) -> Lanes {
    let visible = visible_fraction(h, mu_s, p.bottom_radius_m);
    if visible <= 0.0 {
        return [0.0; 4];
    }
    optical_depth(p, layer, h, mu_s, intervals).map(|d| (-d).exp() * visible)
}

/// The trapezoid rule towards the sun.
pub struct Trapezoid {
    pub intervals: u32,
}

impl SunPath for Trapezoid {
    fn transmittance(&self, p: &Params, layer: usize, h: f64, mu_s: f64) -> Lanes {
        sun_transmittance(p, layer, h, mu_s, self.intervals)
    }
}

/// The registry's constructor.
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    let (view_steps, sun_steps) = steps(params);
    Box::new(SingleScattering {
        params: params.clone(),
        view_steps,
        sun_path: Trapezoid {
            intervals: sun_steps,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::nishita;
    use crate::methods::shared::optics::tests::params;
    use crate::methods::shared::transmittance::{compute_transmittance_lut, transmittance};

    #[test]
    fn the_trapezoid_rule_converges_to_the_table_and_differs_from_the_midpoint_rule() {
        let p = params();
        let table = compute_transmittance_lut(&p);
        for (h, mu_s) in [(0.0, 1.0), (0.0, 0.3), (5_000.0, 0.1), (30_000.0, 0.6)] {
            let fine = sun_transmittance(&p, 0, h, mu_s, 4096);
            let looked_up = transmittance(&p, &table, 0, h, mu_s);
            for (f, t) in fine.iter().zip(looked_up) {
                assert!((f / t - 1.0).abs() < 0.01, "h {h} mu_s {mu_s}: {f} vs {t}");
            }
        }
        // With few intervals the two rules err on opposite sides of a density that falls
        // with height (convex): the trapezoid too dark, the midpoint too bright.
        let exact = sun_transmittance(&p, 0, 0.0, 0.5, 4096)[0];
        let trapezoid = sun_transmittance(&p, 0, 0.0, 0.5, 8)[0];
        let midpoint = nishita::sun_transmittance(&p, 0, 0.0, 0.5, 8);
        assert!(
            trapezoid < exact && midpoint[0] > exact,
            "{trapezoid} {exact} {midpoint:?}"
        );
    }
}
