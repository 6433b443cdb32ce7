//! Where along a path segment to look for sunlight scattered into the path.
//!
//! The point is drawn from an exponential whose rate in each shell is the lanes' in-scattering
//! there — scattering times phase, the phase being the same all along a straight ray — scaled
//! so that the segment holds the optical depth of their mean extinction: where sunlight is the
//! same all along the segment this follows the single-scattering integrand. (The majorant's
//! exponential falls as fast as the bluest lane's bound: along a level ray it would put most
//! points within a few kilometres and give the rare far ones weights many times the mean. The
//! extinction's own exponential, without the phase, would put as many points in the thin air
//! above as in the aerosol's forward peak below, with the sun ahead.) It still
//! wastes most points where light does not come from: in the Earth's shadow at low sun. So
//! each segment whose sunlight varies gets a piecewise-constant density shaped like its
//! single-scattering integrand — scattering times phase, the view's transmittance and the
//! sun's — constant on each of a few sub-intervals at the larger of its values at the
//! sub-interval's two ends, from wavelength-independent sun columns ([`SunColumns`]). That
//! density is only a proposal: the point's contribution is still weighed with ratio-tracked
//! transmittances and divided by the density it was drawn with, so the estimate stays unbiased.
//! A share of points is drawn from the exponential above (one-sample mixture, Veach 1997
//! §9.2), which keeps the density positive wherever the proposal's approximations say too
//! little: the tabulated sun, the view's optical depth summed piece by piece from each piece's
//! far end, and a peak inside a piece that both its ends miss (a grazing ray's lowest point).

use super::{Intervals, LANES, LaneOptics, PathMedium, PathTracer, depth_to};
use crate::Atmosphere;
use crate::constants::SUN_ANGULAR_RADIUS_RAD;
use crate::geometry::{Ray, altitude_along, distance_to_top, hits_ground, rho_squared};
use crate::methods::rng::Rng;
use crate::methods::shared::sun_disk::visible_fraction;
use glam::DVec3;

/// Sub-intervals of a segment's proposal density.
const SUB_INTERVALS: usize = 16;

/// Share of in-scattering points drawn from the exponential rather than the proposal.
const DEFENSIVE_SHARE: f64 = 0.15;

/// Least ratio of the sun's transmittance between points of a segment below which it gets the
/// proposal.
const SUNLIGHT_SPREAD: f64 = 0.5;

/// Least cosine of the sun's zenith angle at a segment's ends and lowest point for the shortcut
/// of `sunlight_varies`: far above the sun's angular radius, so that its whole disk is in sight
/// at every point of the segment and the columns toward it are those of a ray going up.
const HIGH_SUN_MU_S: f64 = 0.2;

/// Rows of the sun-column table: x_r = ρ/H, Bruneton's altitude mapping (dense near the
/// ground, where the columns change fastest).
const COLUMNS_ROWS: usize = 64;

/// Columns of the sun-column table by μ_s, the sun's zenith cosine: `COLUMNS_FINE` intervals
/// evenly from the table's least μ_s ([`MuSAxis`]) to [`MU_S_KNEE`], where the columns change
/// fastest (the horizon's air mass of about 40 falls to 5 within 11°), then `COLUMNS_COARSE`
/// evenly up to 1. Indexed by μ_s itself rather than Bruneton's x_mu, whose distance to the
/// top of the atmosphere is a chain of a square root and two divisions: the proposal looks
/// the sun up 17 times per segment, and that chain would be most of the look-up's time.
const COLUMNS_FINE: usize = 96;
const COLUMNS_COARSE: usize = 32;
const COLUMNS_MU_S: usize = COLUMNS_FINE + COLUMNS_COARSE + 1;

/// Least μ_s of the table where the atmosphere's top sees no lower sun: below the horizon of
/// a 100 km top on the Earth (−0.175).
const MU_S_LEAST: f64 = -0.2;

/// μ_s from which the table's columns are coarse.
const MU_S_KNEE: f64 = 0.2;

/// Midpoint-rule steps per tabulated column (quadratic spacing, dense near the start).
const COLUMN_STEPS: usize = 64;

/// The sun-column table's μ_s axis: from [`MU_S_LEAST`], or lower where a higher top or a
/// smaller planet sees the sun lower (the horizon of the top, less the sun's radius), so
/// that every sun with any of its disk in sight lies inside.
#[derive(Clone, Copy)]
struct MuSAxis {
    least: f64,
    /// Fine columns per unit of μ_s.
    fine: f64,
}

impl MuSAxis {
    fn new(big_r: f64, top: f64) -> MuSAxis {
        let least = MU_S_LEAST.min(horizon_mu(top - big_r, big_r) - SUN_ANGULAR_RADIUS_RAD);
        MuSAxis {
            least,
            fine: COLUMNS_FINE as f64 / (MU_S_KNEE - least),
        }
    }

    /// The table's fractional column of `mu_s` (0 at the least μ_s).
    fn column(self, mu_s: f64) -> f64 {
        const COARSE: f64 = COLUMNS_COARSE as f64 / (1.0 - MU_S_KNEE);
        if mu_s < MU_S_KNEE {
            (mu_s - self.least) * self.fine
        } else {
            COLUMNS_FINE as f64 + (mu_s - MU_S_KNEE) * COARSE
        }
    }

    /// The μ_s of the table's column `x`: the inverse of [`MuSAxis::column`].
    fn mu_s(self, x: usize) -> f64 {
        if x <= COLUMNS_FINE {
            self.least + (MU_S_KNEE - self.least) * x as f64 / COLUMNS_FINE as f64
        } else {
            MU_S_KNEE + (1.0 - MU_S_KNEE) * (x - COLUMNS_FINE) as f64 / COLUMNS_COARSE as f64
        }
    }
}

/// Columns of air (m⁻²), ozone (m⁻²) and the aerosol profile (dimensionless) from a point to
/// the top of the atmosphere along the sun's ray, or the horizon's where the sun's centre is
/// below it, tabulated over (x_r, μ_s): with any wavelength's cross-sections they give an
/// approximate transmittance to the sun. Stored in f32 to keep the table in a core's cache
/// (single precision is far finer than the proposal needs).
pub(super) struct SunColumns {
    big_r: f64,
    top: f64,
    /// ρ at the top of the atmosphere, m.
    big_h: f64,
    mu_s_axis: MuSAxis,
    columns: Vec<[f32; 3]>,
}

impl SunColumns {
    pub(super) fn new(atmosphere: &Atmosphere) -> SunColumns {
        let (big_r, top) = (atmosphere.bottom_radius_m, atmosphere.top_radius_m);
        let big_h = rho_squared(top - big_r, big_r).sqrt();
        let mu_s_axis = MuSAxis::new(big_r, top);
        let mut columns = Vec::with_capacity(COLUMNS_ROWS * COLUMNS_MU_S);
        for y in 0..COLUMNS_ROWS {
            let rho = big_h * y as f64 / (COLUMNS_ROWS - 1) as f64;
            let h = (rho * rho / ((rho * rho + big_r * big_r).sqrt() + big_r)).min(top - big_r);
            for x in 0..COLUMNS_MU_S {
                let mu_s = mu_s_axis.mu_s(x);
                let mu = if hits_ground(h, mu_s, big_r) {
                    horizon_mu(h, big_r)
                } else {
                    mu_s
                };
                let length = distance_to_top(h, mu, big_r, top);
                let mut column = [0.0f64; 3];
                for k in 0..COLUMN_STEPS {
                    let f = |k: usize| length * (k as f64 / COLUMN_STEPS as f64).powi(2);
                    let (t0, t1) = (f(k), f(k + 1));
                    let (h_t, _) = altitude_along(h, mu, 0.5 * (t0 + t1), big_r);
                    let d = atmosphere.densities(h_t);
                    column[0] += d.air_m3 * (t1 - t0);
                    column[1] += d.ozone_m3 * (t1 - t0);
                    column[2] += d.aerosol_per_m * (t1 - t0);
                }
                columns.push(column.map(|c| c as f32));
            }
        }
        SunColumns {
            big_r,
            top,
            big_h,
            mu_s_axis,
            columns,
        }
    }

    /// The columns straight up from the ground: the largest of any point with the sun overhead.
    pub(super) fn vertical(&self) -> [f64; 3] {
        // Row 0 is the ground, the last column μ_s = 1.
        self.columns[COLUMNS_MU_S - 1].map(f64::from)
    }

    /// The visible share of the sun's disk at zenith cosine `mu_s` from altitude `h`, and the
    /// columns to the top along the sun's ray (the horizon's where the sun's centre is below it).
    pub(super) fn towards_sun(&self, h: f64, mu_s: f64) -> (f64, [f64; 3]) {
        let visible = visible_fraction(h, mu_s, self.big_r);
        if visible <= 0.0 {
            return (0.0, [0.0; 3]);
        }
        let h = h.clamp(0.0, self.top - self.big_r);
        let rho = rho_squared(h, self.big_r).sqrt();
        let last_row = (COLUMNS_ROWS - 1) as f64;
        let fy = (rho / self.big_h * last_row).min(last_row - 1e-9);
        let fx = self
            .mu_s_axis
            .column(mu_s)
            .clamp(0.0, (COLUMNS_MU_S - 1) as f64 - 1e-9);
        let (x0, y0) = (fx as usize, fy as usize);
        let (ax, ay) = (fx - x0 as f64, fy - y0 as f64);
        // Written out rather than per component through a closure: this runs 17 times per
        // proposal, on the hot path of every low-sun segment.
        let below = &self.columns[y0 * COLUMNS_MU_S + x0..y0 * COLUMNS_MU_S + x0 + 2];
        let above = &self.columns[(y0 + 1) * COLUMNS_MU_S + x0..(y0 + 1) * COLUMNS_MU_S + x0 + 2];
        let mut column = [0.0; 3];
        for c in 0..3 {
            let [b0, b1, a0, a1] =
                [below[0][c], below[1][c], above[0][c], above[1][c]].map(f64::from);
            column[c] = (1.0 - ay) * ((1.0 - ax) * b0 + ax * b1) + ay * ((1.0 - ax) * a0 + ax * a1);
        }
        (visible, column)
    }
}

/// Zenith cosine of the horizon from altitude `h` (m): the ray that grazes the ground.
fn horizon_mu(h: f64, big_r: f64) -> f64 {
    -(1.0 - (big_r / (big_r + h)).powi(2)).max(0.0).sqrt()
}

/// The four lanes' optics averaged: the proposal is one density for every lane, shaped like
/// their mean integrand.
struct GreyOptics {
    /// Cross-sections, m²: Rayleigh, ozone.
    rayleigh_m2: f64,
    ozone_m2: f64,
    /// Aerosol extinction and scattering optical depths (vertical, ground to top).
    aerosol_extinction: f64,
    aerosol_scattering: f64,
}

impl GreyOptics {
    fn new(lanes: &LaneOptics) -> GreyOptics {
        let mean = |f: &dyn Fn(&crate::Optics) -> f64| {
            lanes.optics.iter().map(f).sum::<f64>() / LANES as f64
        };
        GreyOptics {
            rayleigh_m2: mean(&|o| o.rayleigh_cross_section_m2),
            ozone_m2: mean(&|o| o.ozone_cross_section_m2),
            aerosol_extinction: mean(&|o| o.aerosol_optical_depth),
            aerosol_scattering: mean(&|o| o.aerosol_optical_depth * o.aerosol_ssa),
        }
    }

    fn depth(&self, column: &[f64; 3]) -> f64 {
        self.rayleigh_m2 * column[0]
            + self.ozone_m2 * column[1]
            + self.aerosol_extinction * column[2]
    }
}

/// The proposal density of one segment: sub-interval edges (distances along the ray) and the
/// cumulative share of the density up to each edge.
struct Proposal {
    edges: [f64; SUB_INTERVALS + 1],
    cdf: [f64; SUB_INTERVALS + 1],
}

impl Proposal {
    /// Density (m⁻¹) at distance `t` inside the segment.
    fn pdf(&self, t: f64) -> f64 {
        let j = self.edges[1..SUB_INTERVALS]
            .partition_point(|&e| e <= t)
            .min(SUB_INTERVALS - 1);
        let width = self.edges[j + 1] - self.edges[j];
        if width > 0.0 {
            (self.cdf[j + 1] - self.cdf[j]) / width
        } else {
            0.0
        }
    }

    fn sample(&self, u: f64) -> f64 {
        let j = self.cdf[1..SUB_INTERVALS]
            .partition_point(|&c| c <= u)
            .min(SUB_INTERVALS - 1);
        let mass = self.cdf[j + 1] - self.cdf[j];
        let f = if mass > 0.0 {
            ((u - self.cdf[j]) / mass).clamp(0.0, 1.0)
        } else {
            0.5
        };
        self.edges[j] + f * (self.edges[j + 1] - self.edges[j])
    }
}

impl PathTracer<'_> {
    /// A distance along `ray` inside its segment `intervals` at which to estimate the sunlight
    /// scattered into it, with the density (m⁻¹) it was drawn with; None when the segment holds
    /// no medium. `tau_total` is the segment's majorant optical depth.
    pub(super) fn in_scattering_point(
        &self,
        ray: &Ray,
        intervals: &Intervals,
        medium: &PathMedium,
        tau_total: f64,
        lanes: &LaneOptics,
        rng: &mut Rng,
    ) -> Option<(f64, f64)> {
        let (first, last) = (intervals.first()?, intervals.last()?);
        let phases = self.mean_phases(ray, lanes);
        let rates = &self.in_scattering_rates(intervals, medium, phases);
        let tau_rates: f64 = intervals.iter().map(|&(a, b, s)| rates[s] * (b - a)).sum();
        let p_rates = 1.0 - (-tau_rates).exp();
        if p_rates <= 0.0 || tau_total <= 0.0 {
            return None;
        }
        let grey = GreyOptics::new(lanes);
        let proposal = if self.sunlight_varies(ray, intervals, &grey) {
            self.proposal(ray, intervals, &medium.majorant, tau_total, phases, &grey)
        } else {
            None
        };
        let share = if proposal.is_some() {
            DEFENSIVE_SHARE
        } else {
            1.0
        };
        let t = match &proposal {
            Some(p) if rng.uniform() >= share => p.sample(rng.uniform()),
            _ => {
                let target = -(1.0 - rng.uniform() * p_rates).ln();
                let (k, t) = super::locate(intervals, rates, target)?;
                t.clamp(intervals[k].0, intervals[k].1)
            }
        };
        let t = t.clamp(first.0, last.1);
        let (depth, rate) = depth_to(intervals, rates, t);
        let pdf_exponential = rate * (-depth).exp() / p_rates;
        let pdf =
            share * pdf_exponential + (1.0 - share) * proposal.as_ref().map_or(0.0, |p| p.pdf(t));
        (pdf > 0.0).then_some((t, pdf))
    }

    /// The lanes' mean Rayleigh and aerosol phase functions (sr⁻¹) between the sun and `ray`,
    /// the same all along it.
    fn mean_phases(&self, ray: &Ray, lanes: &LaneOptics) -> (f64, f64) {
        let nu = ray.direction.dot(self.sun);
        let mean_phase = |c| {
            lanes
                .optics
                .iter()
                .map(|o| self.phase(c, o, nu))
                .sum::<f64>()
                / LANES as f64
        };
        (mean_phase(0), mean_phase(1))
    }

    /// Per-shell rates of the exponential along a segment: the shells' in-scattering
    /// (scattering times phase, the phase being the same all along a straight ray), scaled to
    /// the segment's extinction optical depth, so that points go where light is scattered
    /// toward the ray (with the sun ahead, into the aerosol's forward peak low down rather than
    /// the thin air above) while spreading over the segment as its attenuation does. Where the
    /// segment scatters nothing, the extinction itself.
    /// `(phase_rayleigh, phase_aerosol)` are the segment's [`Self::mean_phases`].
    fn in_scattering_rates(
        &self,
        intervals: &Intervals,
        medium: &PathMedium,
        (phase_rayleigh, phase_aerosol): (f64, f64),
    ) -> [f64; super::SHELL_ALTITUDES_M.len()] {
        let mut rates = [0.0; super::SHELL_ALTITUDES_M.len()];
        let (mut extinction_depth, mut source_depth) = (0.0, 0.0);
        for &(a, b, s) in intervals.iter() {
            rates[s] = medium.rayleigh_scattering[s] * phase_rayleigh
                + medium.aerosol_scattering[s] * phase_aerosol;
            extinction_depth += medium.in_scattering_rate[s] * (b - a);
            source_depth += rates[s] * (b - a);
        }
        if !(source_depth > 0.0 && source_depth.is_finite()) {
            return medium.in_scattering_rate;
        }
        let scale = extinction_depth / source_depth;
        rates.iter_mut().for_each(|r| *r *= scale);
        rates
    }

    /// Whether the sun's transmittance along the segment (at its ends and lowest point) varies by
    /// more than [`SUNLIGHT_SPREAD`]: where it does not, the exponential already
    /// follows the integrand well and the proposal costs more than it saves.
    fn sunlight_varies(&self, ray: &Ray, intervals: &Intervals, grey: &GreyOptics) -> bool {
        let (Some(first), Some(last)) = (intervals.first(), intervals.last()) else {
            return false;
        };
        let lowest = -ray.origin.dot(ray.direction);
        let points = [first.0, last.1, lowest].map(|t| ray.origin + ray.direction * t);
        // The lowest point counts only inside the segment: else it is one of its ends (nearly
        // every segment rises or falls all along), and the look-up would be done twice.
        let inside = first.0 < lowest && lowest < last.1;
        let points = &points[..if inside { 3 } else { 2 }];
        // With the sun high over every point, no column toward it exceeds the vertical one from
        // the ground over μ_s (an upward ray only steepens through the shells): where even that
        // leaves more than SUNLIGHT_SPREAD of the sunlight, the table need not be read (most
        // segments under a high sun end here).
        if self.sun_high_over(points, grey) {
            return false;
        }
        self.tabulated_sunlight_varies(points, grey)
    }

    /// Whether the sun stands so high over every point that even the vertical column from the
    /// ground, over the least μ_s, leaves more than [`SUNLIGHT_SPREAD`] of its light.
    fn sun_high_over(&self, points: &[DVec3], grey: &GreyOptics) -> bool {
        let mu_s_least = points
            .iter()
            .map(|x| x.dot(self.sun) / x.length())
            .fold(1.0f64, f64::min);
        mu_s_least > HIGH_SUN_MU_S
            && (-grey.depth(&self.prepared.sun_columns.vertical()) / mu_s_least).exp()
                >= SUNLIGHT_SPREAD
    }

    /// Whether the tabulated sunlight at `points` varies by more than [`SUNLIGHT_SPREAD`].
    fn tabulated_sunlight_varies(&self, points: &[DVec3], grey: &GreyOptics) -> bool {
        let (mut least, mut most) = (f64::INFINITY, 0.0f64);
        for &x in points {
            let r = x.length();
            let (visible, column) = self
                .prepared
                .sun_columns
                .towards_sun(r - self.atmosphere.bottom_radius_m, x.dot(self.sun) / r);
            let sunlight = visible * (-grey.depth(&column)).exp();
            least = least.min(sunlight);
            most = most.max(sunlight);
        }
        least < SUNLIGHT_SPREAD * most
    }

    /// The segment's proposal density, None where it holds no light by its own estimate;
    /// `phases` are its [`Self::mean_phases`].
    fn proposal(
        &self,
        ray: &Ray,
        intervals: &Intervals,
        majorants: &[f64],
        tau_total: f64,
        (phase_rayleigh, phase_aerosol): (f64, f64),
        grey: &GreyOptics,
    ) -> Option<Proposal> {
        let (start, end) = (intervals.first()?.0, intervals.last()?.1);
        let length = end - start;
        if length <= 0.0 || tau_total <= 0.0 {
            return None;
        }
        // Edges equally spaced in the mean of the majorant optical depth and the distance, both
        // normalised: dense where the air is, without leaving long thin stretches to one piece.
        let mut edges = [end; SUB_INTERVALS + 1];
        edges[0] = start;
        // Reciprocals once, rather than four divisions per interval.
        let (per_depth, per_length) = (0.5 / tau_total, 0.5 / length);
        let mut depth = 0.0;
        let mut j = 1;
        for &(a, b, s) in intervals.iter() {
            let slope = majorants[s] * per_depth + per_length;
            let s_a = depth * per_depth + (a - start) * per_length;
            let s_b = s_a + slope * (b - a);
            while j < SUB_INTERVALS && (j as f64 / SUB_INTERVALS as f64) <= s_b {
                edges[j] = (a + (j as f64 / SUB_INTERVALS as f64 - s_a) / slope).clamp(a, b);
                j += 1;
            }
            depth += majorants[s] * (b - a);
        }
        let bottom = self.atmosphere.bottom_radius_m;
        // The integrand at `t`, the far end of a piece `width` long that starts at the view's
        // grey optical depth `view_depth`, and the view's grey optical depth from the segment's
        // start to `t` (the piece's share taken at the grey extinction at `t`).
        let at = |t: f64, view_depth: f64, width: f64| {
            let x = ray.origin + ray.direction * t;
            let r = x.length();
            let h = r - bottom;
            let d = self.prepared.densities.at(h);
            let (visible, column) = self
                .prepared
                .sun_columns
                .towards_sun(h, x.dot(self.sun) / r);
            let rayleigh = grey.rayleigh_m2 * d.air_m3;
            let extinction =
                rayleigh + grey.ozone_m2 * d.ozone_m3 + grey.aerosol_extinction * d.aerosol_per_m;
            let view_depth = view_depth + extinction * width;
            let source = rayleigh * phase_rayleigh
                + grey.aerosol_scattering * d.aerosol_per_m * phase_aerosol;
            let lit = if visible > 0.0 {
                source * visible * (-(grey.depth(&column) + view_depth)).exp()
            } else {
                0.0
            };
            (lit, view_depth)
        };
        // Each piece's density is the larger of the integrand at its two ends. Across the
        // terminator the integrand changes by orders of magnitude within a piece; taken at the
        // piece's middle, in the shadow, it would leave the sunlit end to the defensive share,
        // with weights hundreds of times the mean. The integrand at an edge, with the view's
        // transmittance, serves the pieces on both its sides: one exponential per edge rather
        // than three per piece, on the hot path at low sun.
        let mut cdf = [0.0; SUB_INTERVALS + 1];
        let (mut left, mut view_depth) = at(edges[0], 0.0, 0.0);
        for k in 0..SUB_INTERVALS {
            let width = edges[k + 1] - edges[k];
            let right;
            (right, view_depth) = at(edges[k + 1], view_depth, width);
            cdf[k + 1] = cdf[k] + left.max(right) * width;
            left = right;
        }
        let total = cdf[SUB_INTERVALS];
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        cdf.iter_mut().for_each(|c| *c /= total);
        Some(Proposal { edges, cdf })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aerosol::AerosolType;
    use crate::lanes::Lanes;
    use crate::methods::path_tracer::PathTracerSettings;
    use crate::scene::AtmosphereSettings;

    /// The shortcut for a high sun skips the table only where the table too finds the sunlight
    /// even: over triples of points anywhere in the lowest 60 km, up to 300 km apart, in clear
    /// air and in haze up to AOD 2, with the sun from 12° to overhead.
    #[test]
    fn the_high_sun_shortcut_skips_only_segments_with_even_sunlight() {
        let (mut skipped, mut uneven) = (0, 0);
        for (kind, aod550) in [
            (AerosolType::None, 0.0),
            (AerosolType::Rural, 0.3),
            (AerosolType::Urban, 2.0),
        ] {
            let mut settings = AtmosphereSettings::default();
            settings.aerosol.kind = kind;
            settings.aerosol.aod550 = aod550;
            let atmosphere = Atmosphere::new(&settings);
            let big_r = atmosphere.bottom_radius_m;
            let lanes = LaneOptics::new(&atmosphere, Lanes([400.0, 450.0, 550.0, 700.0]));
            let grey = GreyOptics::new(&lanes);
            let mut rng = Rng::new(11, 0, 0);
            for elevation_deg in [12.0f64, 20.0, 30.0, 45.0, 60.0, 90.0] {
                let e = elevation_deg.to_radians();
                let sun = DVec3::new(e.cos(), 0.0, e.sin());
                let tracer = PathTracer::new(&atmosphere, sun, PathTracerSettings::default());
                for _ in 0..3000 {
                    let points = [(); 3].map(|_| {
                        let (a, b) = (0.024 * (rng.uniform() - 0.5), 0.024 * (rng.uniform() - 0.5));
                        let h = 60_000.0 * rng.uniform().powi(2);
                        DVec3::new(a.sin(), b.sin(), a.cos() * b.cos()).normalize() * (big_r + h)
                    });
                    let varies = tracer.tabulated_sunlight_varies(&points, &grey);
                    uneven += usize::from(varies);
                    if tracer.sun_high_over(&points, &grey) {
                        skipped += 1;
                        assert!(
                            !varies,
                            "{kind:?} {aod550}, sun {elevation_deg}°: {points:?}"
                        );
                    }
                }
            }
        }
        // Neither side vacuous: in thick haze the shortcut never applies.
        assert!(
            skipped > 5000 && uneven > 1000,
            "{skipped} skipped, {uneven} uneven"
        );
    }

    /// The sun's transmittance from the table and from the exact quadrature, at altitude `h`
    /// (m) with the sun `elevation_deg` up, for the lanes' grey optics.
    fn table_and_exact(
        atmosphere: &Atmosphere,
        columns: &SunColumns,
        h: f64,
        elevation_deg: f64,
    ) -> (f64, f64) {
        let lanes = LaneOptics::new(atmosphere, Lanes([450.0, 550.0, 650.0, 750.0]));
        let grey = GreyOptics::new(&lanes);
        let optics = crate::Optics {
            rayleigh_cross_section_m2: grey.rayleigh_m2,
            ozone_cross_section_m2: grey.ozone_m2,
            aerosol_optical_depth: grey.aerosol_extinction,
            ..lanes.optics[1]
        };
        let mu_s = f64::to_radians(elevation_deg).sin();
        let point = DVec3::new(0.0, 0.0, atmosphere.bottom_radius_m + h);
        let sun = DVec3::new((1.0 - mu_s * mu_s).sqrt(), 0.0, mu_s);
        let exact = atmosphere.transmittance_to_sun(&optics, point, sun);
        let (visible, column) = columns.towards_sun(h, mu_s);
        (visible * (-grey.depth(&column)).exp(), exact)
    }

    /// The tabulated columns give the sun's transmittance the exact quadrature gives, within a
    /// few per cent where it matters (the proposal only needs its shape).
    #[test]
    fn sun_columns_give_the_exact_transmittance() {
        let atmosphere = Atmosphere::new(&AtmosphereSettings::default());
        let columns = SunColumns::new(&atmosphere);
        for h in [0.0, 1500.0, 12_000.0, 45_000.0] {
            for elevation_deg in [90.0, 30.0, 8.0, 2.0, 0.5] {
                let (table, exact) = table_and_exact(&atmosphere, &columns, h, elevation_deg);
                assert!(
                    (table - exact).abs() <= 0.03 * exact + 1e-4,
                    "h {h} m, sun {elevation_deg}°: table {table} vs exact {exact}"
                );
            }
        }
        // Deep in the Earth's shadow there is no sunlight at all.
        assert_eq!(columns.towards_sun(1000.0, -0.2).0, 0.0);
    }

    /// Suns below the horizontal but above the horizon, whose rays pass a lowest point and
    /// climb again: from 12 and 45 km with the sun 2° and 5° down, within 3 %; and from 300 km
    /// under a 1000 km top with the sun 16.5° down, beyond the μ_s of −0.2 that covers a
    /// 100 km top (its ray passes 26 km over the ground, so the column of μ_s −0.2, which
    /// passes 167 km up, would leave all the light). The table's rows and columns spread over
    /// ten times the height there, and its lowest point moves about 17 km from row to row:
    /// within 35 %, a proposal's shape.
    #[test]
    fn sun_columns_hold_suns_below_the_horizontal() {
        let high = AtmosphereSettings {
            top_km: 1000.0,
            ..AtmosphereSettings::default()
        };
        for (settings, h, elevation_deg, bound) in [
            (AtmosphereSettings::default(), 12_000.0, -2.0, 0.03),
            (AtmosphereSettings::default(), 45_000.0, -2.0, 0.03),
            (AtmosphereSettings::default(), 45_000.0, -5.0, 0.03),
            (high, 300_000.0, -16.5, 0.35),
        ] {
            let atmosphere = Atmosphere::new(&settings);
            let columns = SunColumns::new(&atmosphere);
            let (table, exact) = table_and_exact(&atmosphere, &columns, h, elevation_deg);
            assert!(
                exact < 0.95 && (table - exact).abs() <= bound * exact + 1e-4,
                "h {h} m, sun {elevation_deg}°: table {table} vs exact {exact}"
            );
        }
    }
}
