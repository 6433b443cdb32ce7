//! The sky pass of Leenman's (2025) analytic single-scattering models (`flat`, `raymarched`):
//! the view ray cut into a few equal segments, each integrated in closed form as a slab whose
//! optical depth — towards the viewer plus towards the sun — changes linearly from one end to
//! the other (his eq. 55, after Jodie's 2019 flat homogeneous atmosphere):
//!
//! L = E · Σ_segments σ_s(seg)·P(ν) · (e^{−A} − e^{−B}) / (B − A),
//!
//! with σ_s(seg) the segment's scattering optical depth per constituent, A and B the view depth
//! from the camera plus the sun depth at the segment's ends. Every optical depth — along the
//! view as towards the sun — is the homogeneous-shell chord on the exponential medium
//! ([`super::exponential::homogeneous_shell`]); a depth between two points of the view ray is
//! the difference of their chords to infinity. `flat` takes one segment, `raymarched` five
//! (Leenman's count). As in his models, the sun's ray ignores the planet (no Earth shadow in
//! the sky) and there are no higher orders; the sunlit ground behind is the table-free models'.
//! From above the atmosphere the ray starts where it enters. Twin of
//! `shaders/shared/segments_sky.wgsl`.

use super::exponential::{ExponentialMedium, homogeneous_shell};
use super::ray::camera_coords;
use super::single_scattering_sky::{SunRoute, Way};
use super::{Lanes, Lut, Params, aerosol_phase, rayleigh_phase};
use crate::geometry::{altitude_along, distance_to_ground, distance_to_top};
use glam::DVec3;
use std::f64::consts::PI;

/// Segments of `flat` (Jodie's single slab) and of `raymarched` (Leenman's choice of five).
pub const FLAT_SEGMENTS: u32 = 1;
pub const RAYMARCHED_SEGMENTS: u32 = 5;

/// Below this difference of optical depth the slab integral takes its limit e^{−A}(1 − d/2).
pub const SMALL_DEPTH_DIFFERENCE: f64 = 1e-4;

/// The values the GPU reads from `globals.model`: (segments, 0, the homogeneous shell's way
/// code, 0), then the fitted exponential medium.
pub fn constants(p: &Params, segments: u32) -> [f64; 12] {
    let mut c = [0.0; 12];
    c[..4].copy_from_slice(&[f64::from(segments), 0.0, Way::HomogeneousShell.code(), 0.0]);
    c[4..].copy_from_slice(&ExponentialMedium::fit(p).constants());
    c
}

/// ∫₀¹ e^{−(A + (B − A)t)} dt.
pub fn slab(a: f64, b: f64) -> f64 {
    let d = b - a;
    if d.abs() < SMALL_DEPTH_DIFFERENCE {
        (-a).exp() * (1.0 - 0.5 * d)
    } else {
        ((-a).exp() - (-b).exp()) / d
    }
}

/// Homogeneous-shell columns from a point to infinity along a direction, or between two points:
/// air and aerosol (profile units × m) and the ozone shell's path (relative density × m).
#[derive(Debug, Clone, Copy, Default)]
struct Columns {
    air: f64,
    aerosol: f64,
    ozone: f64,
}

impl Columns {
    /// `self` less `other`, never negative (the shell's chords are approximations).
    fn less(self, other: Columns) -> Columns {
        Columns {
            air: (self.air - other.air).max(0.0),
            aerosol: (self.aerosol - other.aerosol).max(0.0),
            ozone: (self.ozone - other.ozone).max(0.0),
        }
    }

    fn plus(self, other: Columns) -> Columns {
        Columns {
            air: self.air + other.air,
            aerosol: self.aerosol + other.aerosol,
            ozone: self.ozone + other.ozone,
        }
    }
}

/// Leenman's segment-integral sky.
pub struct Segments {
    pub params: Params,
    pub segments: u32,
    /// The homogeneous-shell way to the sun, and the fitted medium.
    pub route: SunRoute,
}

impl Segments {
    pub fn new(p: &Params, segments: u32) -> Segments {
        Segments {
            params: p.clone(),
            segments,
            route: SunRoute::new(p, Way::HomogeneousShell),
        }
    }

    /// The columns from altitude `h` along zenith cosine `mu` to infinity.
    fn columns(&self, h: f64, mu: f64) -> Columns {
        let m = &self.route.medium;
        let big_r = self.params.bottom_radius_m;
        Columns {
            air: m.air.at_ground * homogeneous_shell(h, mu, m.air.scale_height_m, big_r),
            aerosol: m.aerosol.at_ground
                * homogeneous_shell(h, mu, m.aerosol.scale_height_m, big_r),
            ozone: m.ozone_path(big_r, h, mu),
        }
    }

    /// The optical depth per lane of batch `layer` of columns `c`.
    fn depth(&self, layer: usize, c: Columns) -> Lanes {
        let b = &self.params.batches[layer];
        Lanes::from_fn(|i| {
            b.rayleigh_scattering[i] * c.air
                + b.ozone_absorption[i] * c.ozone
                + (b.aerosol_scattering[i] + b.aerosol_absorption[i]) * c.aerosol
        })
    }

    /// The columns between distances `t_a` < `t_b` along the ray from altitude `h0` at zenith
    /// cosine `mu0`: the difference of the chords to infinity ahead where the ray climbs,
    /// behind (the reversed ray, from the lower, denser end) where it descends, split at its
    /// lowest point — a chord from the higher, thinner end would be the shorter one.
    fn between(&self, h0: f64, mu0: f64, t_a: f64, t_b: f64) -> Columns {
        let big_r = self.params.bottom_radius_m;
        let r0 = big_r + h0;
        let at = |t: f64| {
            let (h, r) = altitude_along(h0, mu0, t, big_r);
            (h, ((r0 * mu0 + t) / r).clamp(-1.0, 1.0))
        };
        let ((h_a, mu_a), (h_b, mu_b)) = (at(t_a), at(t_b));
        let lowest = -r0 * mu0;
        if lowest <= t_a {
            self.columns(h_a, mu_a).less(self.columns(h_b, mu_b))
        } else if lowest >= t_b {
            self.columns(h_b, -mu_b).less(self.columns(h_a, -mu_a))
        } else {
            let (h_t, _) = at(lowest);
            let through = self.columns(h_t, 0.0);
            through
                .less(self.columns(h_a, -mu_a))
                .plus(through.less(self.columns(h_b, mu_b)))
        }
    }

    /// Optical depth per lane of batch `layer` between distances `t_a` < `t_b` along the ray
    /// from altitude `h0` at zenith cosine `mu0`, as the slabs see it (Leenman's flat
    /// transmittance).
    pub fn optical_depth_between(
        &self,
        layer: usize,
        h0: f64,
        mu0: f64,
        t_a: f64,
        t_b: f64,
    ) -> Lanes {
        self.depth(layer, self.between(h0, mu0, t_a, t_b))
    }

    /// The radiance of one batch seen from `position` (m from the planet's centre, altitude
    /// `h`) along the unit direction `dir`, with the sun in direction `sun` (the disk not
    /// included).
    pub fn radiance(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
        let p = &self.params;
        let big_r = p.bottom_radius_m;
        let Some(c) = camera_coords(p, at, dir, sun) else {
            return Lanes::ZERO;
        };
        let b = &p.batches[layer];
        let (phase_r, phase_a) = (
            rayleigh_phase(p, layer, c.nu),
            aerosol_phase(p, layer, c.nu),
        );
        let r0 = big_r + c.h;
        let t_max = if c.ground {
            distance_to_ground(c.h, c.mu, big_r)
        } else {
            distance_to_top(c.h, c.mu, big_r, p.top_radius_m)
        };
        // The sun's depth and zenith cosine at distance t along the ray.
        let sun_at = |t: f64| {
            let (h_t, r_t) = altitude_along(c.h, c.mu, t, big_r);
            let mu_s_t = ((r0 * c.mu_s + t * c.nu) / r_t).clamp(-1.0, 1.0);
            (self.depth(layer, self.columns(h_t, mu_s_t)), mu_s_t)
        };
        let (mut sun_a, mut mu_s_end) = sun_at(0.0);
        let mut depth = [0.0; 4];
        let mut l = [0.0; 4];
        let dt = t_max / f64::from(self.segments);
        for s in 1..=self.segments {
            let (t_a, t_b) = (f64::from(s - 1) * dt, f64::from(s) * dt);
            let seg = self.between(c.h, c.mu, t_a, t_b);
            let step = self.depth(layer, seg);
            let (sun_b, mu_s_b) = sun_at(t_b);
            for i in 0..4 {
                let scattering = b.rayleigh_scattering[i] * seg.air * phase_r[i]
                    + b.aerosol_scattering[i] * seg.aerosol * phase_a[i];
                let (a, bb) = (depth[i] + sun_a[i], depth[i] + step[i] + sun_b[i]);
                l[i] += b.solar_irradiance[i] * scattering * slab(a, bb);
                depth[i] += step[i];
            }
            sun_a = sun_b;
            mu_s_end = mu_s_b;
        }
        if c.ground {
            let sun_g = self.route.transmittance(p, layer, 0.0, mu_s_end);
            for i in 0..4 {
                let ground =
                    b.ground_albedo[i] / PI * b.solar_irradiance[i] * sun_g[i] * mu_s_end.max(0.0);
                l[i] += (-depth[i]).exp() * ground;
            }
        }
        Lanes(l)
    }
}

impl crate::methods::SkyModel for Segments {
    fn params(&self) -> &Params {
        &self.params
    }

    fn radiance(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
        Segments::radiance(self, layer, at, dir, sun)
    }

    fn table(&self, _: &str) -> Option<&Lut> {
        None
    }

    fn sun(&self, layer: usize, h: f64, mu_s: f64, disk: Lanes) -> Lanes {
        self.route.sun_disk(&self.params, layer, h, mu_s, disk)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::shared::optics::tests::params;

    /// The slab integral is its quadrature, on both sides of its small-difference limit.
    #[test]
    fn the_slab_integral_is_the_mean_of_the_exponential() {
        for (a, b) in [
            (0.3, 0.3),
            (0.3, 0.30001),
            (0.1, 2.0),
            (2.0, 0.1),
            (0.0, 5.0),
        ] {
            let n = 100_000;
            let quadrature = (0..n)
                .map(|k| {
                    let t = (k as f64 + 0.5) / n as f64;
                    (-(a + (b - a) * t)).exp()
                })
                .sum::<f64>()
                / n as f64;
            assert!(
                (slab(a, b) / quadrature - 1.0).abs() < 1e-8,
                "{a} {b}: {} vs {quadrature}",
                slab(a, b)
            );
        }
    }

    /// Looking straight up with the sun overhead the slab is exact for its own medium: one
    /// segment and five give the same sky, and it matches the integral of the fitted
    /// exponentials' single scattering along the vertical (Rayleigh phase at ν = 1), within the
    /// shell chords' error at the top of the atmosphere.
    #[test]
    fn the_zenith_under_a_zenith_sun_is_the_exponential_single_scattering() {
        let p = params();
        let up = DVec3::Z;
        let at = (DVec3::new(0.0, 0.0, p.bottom_radius_m + 1.0), 1.0);
        let flat = Segments::new(&p, FLAT_SEGMENTS);
        let raymarched = Segments::new(&p, RAYMARCHED_SEGMENTS);
        let (l1, l5) = (
            flat.radiance(0, at, up, up),
            raymarched.radiance(0, at, up, up),
        );
        let m = &flat.route.medium;
        let b = &p.batches[0];
        let (phase_r, phase_a) = (rayleigh_phase(&p, 0, 1.0), aerosol_phase(&p, 0, 1.0));
        let n = 20_000;
        let top = p.thickness_m();
        for i in 0..4 {
            // Along the vertical the view and the sun see the same column above each height:
            // the integrand σ_s(h)·e^{−τ(0, h)}·e^{−τ(h, ∞)} = σ_s(h)·e^{−τ(0, ∞)}.
            let ext = |h: f64| {
                b.rayleigh_scattering[i] * m.air.at_ground * (-h / m.air.scale_height_m).exp()
                    + (b.aerosol_scattering[i] + b.aerosol_absorption[i])
                        * m.aerosol.at_ground
                        * (-h / m.aerosol.scale_height_m).exp()
            };
            let dz = top / n as f64;
            let mut total = 0.0;
            let mut scattered = 0.0;
            for k in 0..n {
                let h = (k as f64 + 0.5) * dz;
                total += ext(h) * dz;
                scattered += (b.rayleigh_scattering[i]
                    * m.air.at_ground
                    * (-h / m.air.scale_height_m).exp()
                    * phase_r[i]
                    + b.aerosol_scattering[i]
                        * m.aerosol.at_ground
                        * (-h / m.aerosol.scale_height_m).exp()
                        * phase_a[i])
                    * dz;
            }
            let ozone = b.ozone_absorption[i] * m.ozone_path(p.bottom_radius_m, 0.0, 1.0);
            let want = b.solar_irradiance[i] * scattered * (-(total + ozone)).exp();
            assert!(
                (l1[i] / want - 1.0).abs() < 0.01,
                "lane {i}: {} vs {want}",
                l1[i]
            );
            assert!(
                (l5[i] / l1[i] - 1.0).abs() < 0.01,
                "lane {i}: {} vs {}",
                l5[i],
                l1[i]
            );
        }
    }

    /// Between two points of a ray the shell's columns follow the exponential's integral, on
    /// rays that climb, descend to the ground and dip through their lowest point: within 3 %
    /// where the ray is steep, 15 % along grazing stretches (the chord's error at the horizon).
    #[test]
    fn columns_between_two_points_follow_the_integral_climbing_descending_and_through_the_lowest_point()
     {
        let p = params();
        let model = Segments::new(&p, RAYMARCHED_SEGMENTS);
        let m = &model.route.medium;
        let big_r = p.bottom_radius_m;
        let exact = |h0: f64, mu0: f64, t_a: f64, t_b: f64| {
            let n = 20_000;
            let dt = (t_b - t_a) / n as f64;
            (0..n)
                .map(|k| {
                    let (h, _) = altitude_along(h0, mu0, t_a + (k as f64 + 0.5) * dt, big_r);
                    (-h / m.air.scale_height_m).exp() * dt
                })
                .sum::<f64>()
        };
        for (h0, mu0, t_a, t_b, bound) in [
            (1.0, 0.5, 0.0, 20_000.0, 0.03),
            // From a plane down to the ground: the reversed chords.
            (10_000.0, -0.5, 0.0, 10_000.0, 0.03),
            (10_000.0, -0.5, 10_000.0, 19_000.0, 0.03),
            // A limb ray from 30 km through its lowest point (about 10 km) and up again.
            (30_000.0, -0.08, 100_000.0, 700_000.0, 0.15),
        ] {
            let got = model.between(h0, mu0, t_a, t_b).air / m.air.at_ground;
            let want = exact(h0, mu0, t_a, t_b);
            assert!(
                (got / want - 1.0).abs() < bound,
                "h0 {h0} mu0 {mu0} [{t_a}, {t_b}]: {got} vs {want}"
            );
        }
    }
}
