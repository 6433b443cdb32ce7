//! The spectral path tracer: Atmoscope's ground truth.
//!
//! Each path carries four wavelengths (a hero wavelength and three others, Wilkie et al. 2014).
//! Every segment of a path scatters it somewhere: the vertex it goes on from is drawn from the
//! exponential of the lanes' mean extinction (constant within altitude shells) truncated to
//! the segment, and each lane's weight takes its own transmittance to that vertex (residual
//! ratio tracking) and its scattering coefficient there over the vertex's density, so every
//! wavelength stays unbiased with no null collision and no escape to thin out the higher
//! orders; Rayleigh or aerosol is chosen with spectral tracking's probabilities (Kutz et al.
//! 2017). Absorption is never sampled: it is carried in the weights. A segment that ends on
//! the ground goes on from the ground with the probability that the mean extinction lets light
//! reach it.
//! Next-event estimation to the sun (sampled inside its finite disk, transmittance by residual
//! ratio tracking) is made at a point of every path segment drawn apart from the vertex, for
//! the sunlight scattered once along it. Where sunlight varies along a segment (low sun,
//! twilight, the Earth's shadow) that point is drawn from a density shaped like the segment's
//! single-scattering integrand ([`in_scattering`]). On segments with the sun below part of
//! their horizon, half the vertices a path goes on from are drawn toward where single-scattered
//! light is found (the exponential times the light the guide tabulates by altitude and sun
//! angle): in twilight the rare vertices high up near the sunlit air made most of the noise.
//! Scattering directions come from the phase function, and at low sun a share of them from a
//! guide toward where single-scattered light comes from
//! ([`direction_guide`]). The Lambertian ground gets its own next-event estimate and continues
//! by cosine sampling. All scattering orders, Russian roulette from the second (judging a path
//! by its weight before its latest direction, times the light its vertex can find where the
//! sun is below the vertex's horizon), an optional maximum order (1 = single scattering).
//!
//! The direct solar disk seen by a camera ray is not included: renderers add it analytically.
//! Radiance is spectral radiance for the scene's solar spectrum, W·m⁻²·sr⁻¹·nm⁻¹.
//!
//! The vector mode ([`PathTracer::radiance_stokes`], [`stokes`]) traces the same paths and
//! carries each lane's Mueller products, for the Stokes vector of the light.

use super::rng::Rng;
use crate::atmosphere::{Atmosphere, Densities, Optics};
use crate::constants::SUN_ANGULAR_RADIUS_RAD;
use crate::geometry::{Ray, sphere_distances};
use crate::phase;
use crate::polarisation::Stokes;
use crate::polarisation::mueller::ReducedMatrix;
use glam::DVec3;
use std::f64::consts::PI;
use std::sync::Arc;

mod direction_guide;
mod in_scattering;
mod stokes;

pub use direction_guide::GUIDE_SHARE;

/// Wavelengths carried by one path: a batch's four lanes, as everywhere.
pub use crate::methods::shared::Lanes;
pub use crate::wavelengths::LANES;

/// Altitudes (m) separating the majorant shells: thin where density changes fast, so each
/// shell's densest and thinnest air are close and the control variate below is tight.
const SHELL_ALTITUDES_M: [f64; 28] = [
    0.0, 250.0, 500.0, 1000.0, 1500.0, 2000.0, 2500.0, 3000.0, 4000.0, 5000.0, 6000.0, 7000.0,
    8000.0, 9000.0, 10_000.0, 12_000.0, 14_000.0, 16_000.0, 18_000.0, 20_000.0, 23_000.0, 26_000.0,
    30_000.0, 35_000.0, 40_000.0, 50_000.0, 60_000.0, 80_000.0,
];

/// Weight under which Russian roulette may end a path, from the second order on: it goes on
/// with probability weight / `ROULETTE_WEIGHT` (at most 1), its weight divided by that. Every
/// segment scatters its path (no escapes end it), so paths live long; sparing them down to 0.5
/// rather than 1 lowers the noise more than it adds time, and lower thresholds gain nothing
/// more (noise² × time by threshold in docs/measurements/from-code-comments.md).
const ROULETTE_WEIGHT: f64 = 0.5;

/// The default [`PathTracerSettings::vertex_light_share`]. Deep in twilight the light a vertex
/// can find grows a thousandfold from the ground to 50 km, while the extinction's exponential
/// puts a vertex there once in a few thousand paths: those few carry a small share of the
/// light but most of its second moment, hence most of the noise. Half the vertices drawn
/// toward the light keeps that noise down while the exponential still serves the rest of the
/// segment; larger shares cost noise elsewhere (the shares compared in
/// docs/measurements/from-code-comments.md).
const VERTEX_LIGHT_SHARE: f64 = 0.5;

/// The largest share of vertices drawn toward the light: the exponential must keep some, or
/// stretches that the table puts in the dark would never scatter a path.
const MAX_VERTEX_LIGHT_SHARE: f64 = 0.99;

/// A segment's intervals under the light-seeking density of a path's next vertex
/// ([`PathTracer::light_masses`]).
struct LightMasses {
    /// The single-scattered light at each interval's middle (zero past an optical depth of 30).
    fluence: [f64; MAX_CUTS],
    /// The intervals' masses summed up to and including each.
    cumulative: [f64; MAX_CUTS],
    total: f64,
}

/// Spacing of the density table, m: kilometre breakpoints of the profiles fall on its nodes.
const DENSITY_STEP_M: f64 = 20.0;

/// The atmosphere's densities tabulated every [`DENSITY_STEP_M`], each cell holding its own
/// values just inside both ends and interpolating linearly between them: steps in a profile at
/// a node (the mixing layer's top) stay steps, an exponential with the air's 8 km scale height is
/// within 1e-6 of itself and one with an aerosol's 700 m within 1e-4. Paths look densities up dozens of times each; the profiles' own
/// evaluation (table search and exponential) would be the tracer's largest cost.
struct DensityTable {
    /// Per cell: [air at its bottom, at its top, ozone …, aerosol …].
    cells: Vec<[f64; 6]>,
}

impl DensityTable {
    fn new(atmosphere: &Atmosphere) -> DensityTable {
        let cells = (atmosphere.thickness_m() / DENSITY_STEP_M).ceil().max(1.0) as usize;
        let inside = 1e-6 * DENSITY_STEP_M;
        let cells = (0..cells)
            .map(|k| {
                let z0 = k as f64 * DENSITY_STEP_M;
                let z1 = (z0 + DENSITY_STEP_M).min(atmosphere.thickness_m());
                let (a, b) = (
                    atmosphere.densities(z0 + inside),
                    atmosphere.densities(z1 - inside),
                );
                [
                    a.air_m3,
                    b.air_m3,
                    a.ozone_m3,
                    b.ozone_m3,
                    a.aerosol_per_m,
                    b.aerosol_per_m,
                ]
            })
            .collect();
        DensityTable { cells }
    }

    /// Densities at altitude `h_m` (zero above the top).
    fn at(&self, h_m: f64) -> Densities {
        let f = h_m.max(0.0) / DENSITY_STEP_M;
        let k = f as usize;
        let Some(c) = self.cells.get(k) else {
            return Densities::default();
        };
        let w = f - k as f64;
        Densities {
            air_m3: c[0] + w * (c[1] - c[0]),
            ozone_m3: c[2] + w * (c[3] - c[2]),
            aerosol_per_m: c[4] + w * (c[5] - c[4]),
        }
    }
}

/// Settings of a path-traced estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathTracerSettings {
    /// Highest scattering order counted (volume and ground events); None for all orders.
    pub max_order: Option<u32>,
    /// Angular radius of the sun, radians.
    pub sun_angular_radius_rad: f64,
    /// Largest share (0–1) of scattering directions drawn from the direction guide, toward
    /// where single-scattered light comes from, instead of from the phase function; reached at
    /// vertices with the sun on their horizon or below it ([`GUIDE_SHARE`]); 0 draws every
    /// direction from the phase function. Either way the estimate is unbiased: only its noise
    /// changes.
    pub guide_share: f64,
    /// Whether, at scattering vertices with the sun below their horizon, the Russian roulette
    /// judges a path by its weight times the single-scattered light the guide's slice there
    /// finds (over that product at the path's first vertex, itself with the sun below its
    /// horizon) rather than by its weight alone. Only where the guide is on: with
    /// `guide_share` 0 every path is judged by its weight. Either way the estimate is unbiased:
    /// only its noise changes (at twilight, much).
    pub roulette_by_prospect: bool,
    /// Share (0 to below 1; larger values count as 0.99) of a path's scattering vertices drawn,
    /// on segments where the sun is below some point's horizon, from a density that seeks the
    /// light: the exponential of the extinction times the single-scattered light each stretch
    /// of the segment receives ([`VERTEX_LIGHT_SHARE`]); the rest from the exponential alone,
    /// which keeps every point of the segment possible (the light-seeking density gives none
    /// to stretches its table puts in the dark). 0 draws every vertex from the exponential.
    /// Either way the estimate is unbiased: only its noise changes.
    pub vertex_light_share: f64,
}

impl Default for PathTracerSettings {
    fn default() -> Self {
        PathTracerSettings {
            max_order: None,
            sun_angular_radius_rad: SUN_ANGULAR_RADIUS_RAD,
            guide_share: GUIDE_SHARE,
            roulette_by_prospect: true,
            vertex_light_share: VERTEX_LIGHT_SHARE,
        }
    }
}

/// Densities of each constituent at one bound of a shell.
#[derive(Debug, Clone, Copy)]
struct ShellDensity {
    air_m3: f64,
    ozone_m3: f64,
    aerosol_per_m: f64,
}

impl ShellDensity {
    fn extinction(&self, o: &Optics) -> f64 {
        o.rayleigh_cross_section_m2 * self.air_m3
            + o.ozone_cross_section_m2 * self.ozone_m3
            + o.aerosol_optical_depth * self.aerosol_per_m
    }
}

/// The densest (for the majorant) and thinnest (for the control) air of a shell.
#[derive(Debug, Clone, Copy)]
struct ShellBounds {
    max: ShellDensity,
    min: ShellDensity,
}

/// Per-path tracking coefficients of every shell, m⁻¹.
struct PathMedium {
    /// Majorant of every lane's extinction: spaces the in-scattering proposal's pieces.
    majorant: [f64; SHELL_ALTITUDES_M.len()],
    /// Control extinction per lane (residual ratio tracking): the middle of the shell's bounds,
    /// so that the residual, of either sign, is at most half their spread.
    control: [Lanes; SHELL_ALTITUDES_M.len()],
    /// Majorant of |extinction − control| over the lanes.
    residual_majorant: [f64; SHELL_ALTITUDES_M.len()],
    /// The lanes' mean extinction, roughly (between the bounds): the rate of the exponential
    /// from which each segment's vertex is drawn, the share of light it lets through to the
    /// ground, and the optical depth that the exponential of in-scattering points spreads over a
    /// segment, which then follows the sky's own attenuation instead of the bluest lane's bound.
    in_scattering_rate: [f64; SHELL_ALTITUDES_M.len()],
    /// The lanes' mean Rayleigh and aerosol scattering coefficients, roughly, m⁻¹: with a
    /// segment's phase functions they shape that exponential like its in-scattering.
    rayleigh_scattering: [f64; SHELL_ALTITUDES_M.len()],
    aerosol_scattering: [f64; SHELL_ALTITUDES_M.len()],
}

/// Most shell boundaries a ray can cross, twice each, plus its two ends.
const MAX_CUTS: usize = 2 * SHELL_ALTITUDES_M.len() + 2;

/// The pieces of a ray inside single shells: (start, end, shell), in order along the ray.
struct Intervals {
    items: [(f64, f64, usize); MAX_CUTS],
    len: usize,
}

impl std::ops::Deref for Intervals {
    type Target = [(f64, f64, usize)];
    fn deref(&self) -> &Self::Target {
        &self.items[..self.len]
    }
}

/// An atmosphere prepared for path tracing: shells and their density bounds.
pub struct PathTracer<'a> {
    pub atmosphere: &'a Atmosphere,
    pub settings: PathTracerSettings,
    /// Unit direction to the sun's centre.
    sun: DVec3,
    /// Orthonormal basis around `sun` for sampling the disk.
    sun_basis: (DVec3, DVec3),
    cos_sun_radius: f64,
    prepared: Arc<Prepared>,
}

/// What a path tracer prepares from the atmosphere alone, whatever the sun: built once and
/// shared by the tracers of a render's passes ([`PathTracer::with_prepared`]), which would
/// otherwise build it again for every pass.
pub struct Prepared {
    /// Shell boundary radii, m, increasing, ending at the top of the atmosphere.
    shell_radii: Vec<f64>,
    shells: Vec<ShellBounds>,
    /// Approximate sun transmittance for the in-scattering proposal.
    sun_columns: in_scattering::SunColumns,
    densities: DensityTable,
    /// Densities toward where light comes from, for directions at vertices.
    guide: direction_guide::DirectionGuide,
}

impl Prepared {
    /// Prepares `atmosphere`.
    pub fn new(atmosphere: &Atmosphere) -> Prepared {
        let thickness = atmosphere.thickness_m();
        let mut altitudes: Vec<f64> = SHELL_ALTITUDES_M
            .iter()
            .copied()
            .filter(|&z| z < thickness)
            .collect();
        altitudes.push(thickness);
        let shells = altitudes
            .windows(2)
            .map(|w| {
                // Sample each shell finely (ozone peaks inside one) and widen by a margin so the
                // bounds hold between samples.
                let samples: Vec<_> = (0..=64)
                    .map(|k| atmosphere.densities(w[0] + (w[1] - w[0]) * k as f64 / 64.0))
                    .collect();
                let fold =
                    |f: fn(f64, f64) -> f64,
                     init: f64,
                     g: fn(&crate::atmosphere::Densities) -> f64| {
                        samples.iter().map(g).fold(init, f)
                    };
                ShellBounds {
                    max: ShellDensity {
                        air_m3: 1.02 * fold(f64::max, 0.0, |d| d.air_m3),
                        ozone_m3: 1.05 * fold(f64::max, 0.0, |d| d.ozone_m3),
                        aerosol_per_m: 1.02 * fold(f64::max, 0.0, |d| d.aerosol_per_m),
                    },
                    min: ShellDensity {
                        air_m3: 0.98 * fold(f64::min, f64::INFINITY, |d| d.air_m3),
                        ozone_m3: 0.95 * fold(f64::min, f64::INFINITY, |d| d.ozone_m3),
                        aerosol_per_m: 0.98 * fold(f64::min, f64::INFINITY, |d| d.aerosol_per_m),
                    },
                }
            })
            .collect();
        Prepared {
            shell_radii: altitudes
                .iter()
                .map(|z| atmosphere.bottom_radius_m + z)
                .collect(),
            shells,
            sun_columns: in_scattering::SunColumns::new(atmosphere),
            densities: DensityTable::new(atmosphere),
            guide: direction_guide::DirectionGuide::new(atmosphere),
        }
    }
}

/// Optical properties of the four wavelengths of a path.
#[derive(Debug, Clone, Copy)]
pub struct LaneOptics {
    pub wavelengths_nm: Lanes,
    optics: [Optics; LANES],
    /// Extraterrestrial solar irradiance at the sun's distance, W·m⁻²·nm⁻¹.
    pub solar_irradiance: Lanes,
}

impl LaneOptics {
    /// Optics of the atmosphere at four wavelengths.
    pub fn new(atmosphere: &Atmosphere, wavelengths_nm: Lanes) -> LaneOptics {
        LaneOptics {
            wavelengths_nm,
            optics: wavelengths_nm.0.map(|w| atmosphere.optics(w)),
            solar_irradiance: wavelengths_nm.map(|w| atmosphere.solar_irradiance(w, None)),
        }
    }

    /// Lanes of given optics and extraterrestrial solar irradiance (W·m⁻²·nm⁻¹).
    pub fn from_optics(optics: [Optics; LANES], solar_irradiance: Lanes) -> LaneOptics {
        LaneOptics {
            wavelengths_nm: Lanes(optics.map(|o| o.wavelength_nm)),
            optics,
            solar_irradiance,
        }
    }
}

/// The interval index and distance where the optical depth of the per-shell `rates` (m⁻¹)
/// along `intervals` reaches `target`, or None if the intervals hold less.
fn locate(intervals: &[(f64, f64, usize)], rates: &[f64], target: f64) -> Option<(usize, f64)> {
    let mut acc = 0.0;
    for (k, &(a, b, s)) in intervals.iter().enumerate() {
        let step = rates[s] * (b - a);
        if acc + step >= target && rates[s] > 0.0 {
            return Some((k, (a + (target - acc) / rates[s]).min(b)));
        }
        acc += step;
    }
    None
}

/// Optical depth of `intervals` by the lanes' mean extinction ([`PathMedium::in_scattering_rate`]).
fn mean_depth(intervals: &[(f64, f64, usize)], medium: &PathMedium) -> f64 {
    let rates = &medium.in_scattering_rate;
    intervals.iter().map(|&(a, b, s)| rates[s] * (b - a)).sum()
}

/// Optical depth of the per-shell rates `rates` (m⁻¹) from the start of `intervals` to `t`,
/// and the rate at `t`.
fn depth_to(intervals: &[(f64, f64, usize)], rates: &[f64], t: f64) -> (f64, f64) {
    let mut acc = 0.0;
    for &(a, b, s) in intervals {
        if t <= b {
            return (acc + rates[s] * (t - a).max(0.0), rates[s]);
        }
        acc += rates[s] * (b - a);
    }
    (acc, 0.0)
}

fn basis(n: DVec3) -> (DVec3, DVec3) {
    let a = if n.x.abs() > 0.9 { DVec3::Y } else { DVec3::X };
    let t = n.cross(a).normalize();
    (t, n.cross(t))
}

/// Where a ray meets the atmosphere: the part to march and whether it ends on the ground.
struct Segment {
    start: f64,
    end: f64,
    ground: bool,
}

/// The cosine of a scattering angle drawn from Henyey–Greenstein with asymmetry `g` by
/// inversion of uniform `u`.
fn henyey_greenstein_cosine(g: f64, u: f64) -> f64 {
    if g.abs() < 1e-4 {
        2.0 * u - 1.0
    } else {
        let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
        ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
    }
}

/// The largest of the lanes' weights.
fn max_weight(weight: &Lanes) -> f64 {
    weight.iter().fold(0.0f64, |a, &w| a.max(w))
}

/// A direction at `cos_theta` from unit `axis` (with its `basis`), uniform in azimuth.
fn around(axis: DVec3, (t, b): (DVec3, DVec3), cos_theta: f64, rng: &mut Rng) -> DVec3 {
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let phi = 2.0 * PI * rng.uniform();
    (t * (sin_theta * phi.cos()) + b * (sin_theta * phi.sin()) + axis * cos_theta).normalize()
}

impl<'a> PathTracer<'a> {
    /// Prepares `atmosphere` for paths lit by the sun in unit direction `sun`.
    pub fn new(
        atmosphere: &'a Atmosphere,
        sun: DVec3,
        settings: PathTracerSettings,
    ) -> PathTracer<'a> {
        PathTracer::with_prepared(
            atmosphere,
            sun,
            settings,
            Arc::new(Prepared::new(atmosphere)),
        )
    }

    /// A tracer over `atmosphere` from what was prepared from it before: `prepared` must come
    /// from this same atmosphere (its guide's slices, built on first use, read the tracer's).
    pub fn with_prepared(
        atmosphere: &'a Atmosphere,
        sun: DVec3,
        settings: PathTracerSettings,
        prepared: Arc<Prepared>,
    ) -> PathTracer<'a> {
        let sun = sun.normalize();
        PathTracer {
            atmosphere,
            settings,
            sun,
            sun_basis: basis(sun),
            cos_sun_radius: settings.sun_angular_radius_rad.cos(),
            prepared,
        }
    }

    fn medium(&self, lanes: &LaneOptics) -> PathMedium {
        const N: usize = SHELL_ALTITUDES_M.len();
        let mut medium = PathMedium {
            majorant: [0.0; N],
            control: [Lanes::ZERO; N],
            residual_majorant: [0.0; N],
            in_scattering_rate: [0.0; N],
            rayleigh_scattering: [0.0; N],
            aerosol_scattering: [0.0; N],
        };
        // The lanes' mean Rayleigh cross-section (m²) and aerosol scattering optical depth.
        let mean =
            |f: &dyn Fn(&Optics) -> f64| lanes.optics.iter().map(f).sum::<f64>() / LANES as f64;
        let rayleigh_m2 = mean(&|o| o.rayleigh_cross_section_m2);
        let aerosol_scattering = mean(&|o| o.aerosol_optical_depth * o.aerosol_ssa);
        for (k, shell) in self.prepared.shells.iter().enumerate() {
            let max: Lanes = Lanes::from_fn(|i| shell.max.extinction(&lanes.optics[i]));
            let min: Lanes = Lanes::from_fn(|i| shell.min.extinction(&lanes.optics[i]).min(max[i]));
            medium.majorant[k] = max.iter().fold(0.0f64, |a, &b| a.max(b));
            let middle: Lanes = 0.5 * (max + min);
            medium.residual_majorant[k] =
                (0..LANES).fold(0.0f64, |a, i| a.max(0.5 * (max[i] - min[i])));
            medium.control[k] = middle;
            medium.in_scattering_rate[k] = middle.iter().sum::<f64>() / LANES as f64;
            let (air, aerosol) = (
                0.5 * (shell.max.air_m3 + shell.min.air_m3),
                0.5 * (shell.max.aerosol_per_m + shell.min.aerosol_per_m),
            );
            medium.rayleigh_scattering[k] = air * rayleigh_m2;
            medium.aerosol_scattering[k] = aerosol * aerosol_scattering;
        }
        medium
    }

    fn segment(&self, ray: &Ray) -> Option<Segment> {
        let (r, mu) = ray.r_mu();
        let bottom = self.atmosphere.bottom_radius_m;
        let (t0, t1) = sphere_distances(r, mu, self.atmosphere.top_radius_m)?;
        if t1 <= 0.0 {
            return None;
        }
        let start = t0.max(0.0);
        if mu < 0.0 {
            if let Some((g0, _)) = sphere_distances(r, mu, bottom) {
                if g0 >= start - 1e-6 {
                    return Some(Segment {
                        start,
                        end: g0.max(start),
                        ground: true,
                    });
                }
            }
        }
        if r <= bottom && mu < 0.0 {
            return Some(Segment {
                start,
                end: start,
                ground: true,
            });
        }
        Some(Segment {
            start,
            end: t1,
            ground: false,
        })
    }

    /// The intervals of [start, end] along the ray, each inside one shell, with the shell index.
    fn intervals(&self, ray: &Ray, start: f64, end: f64) -> Intervals {
        let (r, mu) = ray.r_mu();
        // Stack buffers: this runs several times per path, and allocation would dominate its cost.
        // Each cut carries the change of shell index across it: −1 where the ray goes down
        // through a shell boundary (its near root), +1 where it comes back up (its far root).
        let mut cuts = [(0.0f64, 0isize); MAX_CUTS];
        cuts[0] = (start, 0);
        let mut n = 1;
        // The near roots of the shells, outermost first, then the far roots, innermost first,
        // come in order along the ray: no sort, except where rounding near a tangent disagrees.
        let inner = &self.prepared.shell_radii[1..self.prepared.shell_radii.len() - 1];
        let mut far = [0.0f64; MAX_CUTS];
        let mut n_far = 0;
        // The shell just past `start`: the number of boundaries the ray is outside of there,
        // by the same roots that place the cuts (a middle's radius can round across a boundary
        // the ray grazes, and a carried index would keep that error along the whole ray).
        let mut first_shell = 0isize;
        for (k, &radius) in inner.iter().enumerate().rev() {
            if mu >= 0.0 && radius <= r {
                // A ray leaving upward is outside this boundary and every one below from its
                // start on (both roots ≤ 0 ≤ start, exactly so in floating point): no cuts.
                first_shell += k as isize + 1;
                break;
            }
            let Some((a, b)) = sphere_distances(r, mu, radius) else {
                first_shell += 1;
                continue;
            };
            if !(a <= start && start < b) {
                first_shell += 1;
            }
            if a > start && a < end {
                cuts[n] = (a, -1);
                n += 1;
            }
            if b > start && b < end {
                far[n_far] = b;
                n_far += 1;
            }
        }
        for &t in far[..n_far].iter().rev() {
            cuts[n] = (t, 1);
            n += 1;
        }
        cuts[n] = (end, 0);
        n += 1;
        let cuts = &mut cuts[..n];
        // In order, each interval's shell follows from the first one's and the cuts between;
        // where rounding put cuts out of order, each interval's middle decides.
        let ordered = cuts.is_sorted_by(|a, b| a.0 <= b.0);
        if !ordered {
            cuts.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        }
        let mut out = Intervals {
            items: [(0.0, 0.0, 0); MAX_CUTS],
            len: 0,
        };
        let mut shell = first_shell;
        for w in cuts.windows(2) {
            shell += w[0].1;
            let (a, b) = (w[0].0, w[1].0);
            if b > a {
                let s = if ordered {
                    shell.clamp(0, self.prepared.shells.len() as isize - 1) as usize
                } else {
                    self.shell_at(r, mu, 0.5 * (a + b))
                };
                out.items[out.len] = (a, b, s);
                out.len += 1;
            }
        }
        out
    }

    /// The shell holding the point at distance `t` along the ray from (r, mu).
    fn shell_at(&self, r: f64, mu: f64, t: f64) -> usize {
        let radius = crate::geometry::radius_at(r, mu, t);
        self.prepared
            .shell_radii
            .partition_point(|&s| s <= radius)
            .saturating_sub(1)
            .min(self.prepared.shells.len() - 1)
    }

    /// Transmittance along the ray from its origin out of the atmosphere; zero when the ray
    /// meets the ground.
    fn transmittance(
        &self,
        ray: &Ray,
        lanes: &LaneOptics,
        medium: &PathMedium,
        rng: &mut Rng,
    ) -> Lanes {
        let Some(seg) = self.segment(ray) else {
            return Lanes::ONE;
        };
        if seg.ground {
            return Lanes::ZERO;
        }
        let intervals = self.intervals(ray, seg.start, seg.end);
        self.ratio_track(ray, &intervals, seg.end, lanes, medium, rng)
    }

    /// A direction inside the solar disk, uniformly over its solid angle.
    fn sample_sun(&self, rng: &mut Rng) -> DVec3 {
        let cos_theta = 1.0 - rng.uniform() * (1.0 - self.cos_sun_radius);
        around(self.sun, self.sun_basis, cos_theta, rng)
    }

    /// Transmittance along `ray` over the given intervals up to distance `until`, by residual
    /// ratio tracking (Novák et al. 2014): the control extinction's part exactly, the residual
    /// by ratio tracking against its own small majorant, so a tight majorant does not turn the
    /// estimate into a coin toss. The control is the middle of the shell's bounds rather than
    /// their least: the residual's factors then lie either side of 1, one estimate's relative
    /// variance along a grazing ray falls to a quarter or less and it takes half the collisions.
    fn ratio_track(
        &self,
        ray: &Ray,
        intervals: &[(f64, f64, usize)],
        until: f64,
        lanes: &LaneOptics,
        medium: &PathMedium,
        rng: &mut Rng,
    ) -> Lanes {
        let mut tau_control = Lanes::ZERO;
        let mut ratio = Lanes::ONE;
        // Residual majorant optical depth to the next tentative collision, carried from shell
        // to shell (the exponential is memoryless): one draw per collision, not one per shell.
        let mut tau_left = None;
        for &(a, b, shell) in intervals {
            if a >= until {
                break;
            }
            let b = b.min(until);
            let control = medium.control[shell];
            for i in 0..LANES {
                tau_control[i] += control[i] * (b - a);
            }
            let m = medium.residual_majorant[shell];
            if m <= 0.0 {
                continue;
            }
            let mut t = a;
            loop {
                let tau = *tau_left.get_or_insert_with(|| -(1.0 - rng.uniform()).ln());
                if tau >= (b - t) * m {
                    tau_left = Some(tau - (b - t) * m);
                    break;
                }
                t += tau / m;
                tau_left = None;
                let d =
                    self.prepared
                        .densities
                        .at((ray.origin + ray.direction * t).length()
                            - self.atmosphere.bottom_radius_m);
                for (i, o) in lanes.optics.iter().enumerate() {
                    ratio[i] *= 1.0 - (o.coefficients(&d).extinction() - control[i]) / m;
                }
            }
        }
        Lanes::from_fn(|i| (ratio[i] * (-tau_control[i]).exp()).max(0.0))
    }

    /// A distance along a segment at which the path scatters next, with its density (m⁻¹):
    /// drawn from the exponential of the lanes' mean extinction truncated to the segment, so
    /// that every path scatters (none escapes, none meets a null collision) nearly where
    /// light would; the lanes' own transmittances and coefficients go into the weight. Where
    /// the sun is below some point's horizon, a share of vertices
    /// ([`PathTracerSettings::vertex_light_share`]) comes instead from that exponential times
    /// the light each stretch of the segment receives ([`Self::light_masses`]), in a one-sample
    /// mixture. None where the segment holds no medium. `tau` is the segment's optical depth
    /// by that mean extinction ([`mean_depth`]).
    fn scattering_point(
        &self,
        ray: &Ray,
        intervals: &[(f64, f64, usize)],
        medium: &PathMedium,
        tau: f64,
        rng: &mut Rng,
    ) -> Option<(f64, f64)> {
        let rates = &medium.in_scattering_rate;
        // exp_m1 and ln_1p keep a thin segment's chances exact.
        let p_any = -(-tau).exp_m1();
        if !(p_any > 0.0) {
            return None;
        }
        let light = self.light_masses(ray, intervals, rates);
        let share = if light.is_some() {
            self.settings.vertex_light_share.min(MAX_VERTEX_LIGHT_SHARE)
        } else {
            0.0
        };
        let (k, t) = match &light {
            Some(l) if rng.uniform() < share => {
                // An interval by its mass, then a point inside it from the exponential
                // truncated to it.
                let u = rng.uniform() * l.total;
                let k = l.cumulative[..intervals.len()]
                    .partition_point(|&c| c <= u)
                    .min(intervals.len() - 1);
                let (a, b, s) = intervals[k];
                let step = rates[s] * (b - a);
                let f = -(-rng.uniform() * -(-step).exp_m1()).ln_1p();
                let t = if step > 0.0 {
                    a + (b - a) * f / step
                } else {
                    a
                };
                (k, t)
            }
            _ => locate(intervals, rates, -(-rng.uniform() * p_any).ln_1p())?,
        };
        let t = t.clamp(intervals[k].0, intervals[k].1);
        let (depth, rate) = depth_to(intervals, rates, t);
        let mut pdf = rate * (-depth).exp() / p_any;
        if let Some(l) = &light {
            pdf = (1.0 - share) * pdf + share * l.fluence[k] * rate * (-depth).exp() / l.total;
        }
        (pdf > 0.0).then_some((t, pdf))
    }

    /// The mass of each of a segment's intervals under the light-seeking density of a
    /// path's next vertex: the exponential of the `rates` (the lanes' mean extinction) times the
    /// single-scattered light at the interval's middle ([`Self::fluence_at`]). None where the
    /// share of such vertices is zero (or not a number), where the sun is above every point's
    /// horizon (the light then varies little along a segment) or where the segment finds no
    /// light.
    fn light_masses(
        &self,
        ray: &Ray,
        intervals: &[(f64, f64, usize)],
        rates: &[f64],
    ) -> Option<LightMasses> {
        if !(self.settings.vertex_light_share > 0.0) {
            return None;
        }
        // x · sun is linear along a straight segment: lowest at one of its ends.
        let (first, last) = (intervals.first()?, intervals.last()?);
        let at = |t: f64| ray.origin + ray.direction * t;
        if at(first.0).dot(self.sun) >= 0.0 && at(last.1).dot(self.sun) >= 0.0 {
            return None;
        }
        let mut l = LightMasses {
            fluence: [0.0; MAX_CUTS],
            cumulative: [0.0; MAX_CUTS],
            total: 0.0,
        };
        // exp(−depth) at the start of each interval, carried from one to the next.
        let mut transmitted = 1.0;
        for (k, &(a, b, s)) in intervals.iter().enumerate() {
            // Past an optical depth of 30 no light found is worth a point.
            if transmitted > 1e-13 {
                let f = self.fluence_at(at(0.5 * (a + b)));
                let absorbed = -(-rates[s] * (b - a)).exp_m1();
                l.fluence[k] = f;
                l.total += f * transmitted * absorbed;
                transmitted *= 1.0 - absorbed;
            }
            l.cumulative[k] = l.total;
        }
        (l.total > 0.0).then_some(l)
    }

    /// Radiance arriving at `ray.origin` from `-ray.direction` (the sky seen along the ray,
    /// without the direct solar disk), at the four wavelengths of `lanes`.
    ///
    /// Each path segment contributes the sunlight scattered once anywhere along it (one point
    /// drawn from a truncated exponential shaped like the lanes' in-scattering, or from the
    /// segment's proposal where sunlight varies along it; ratio-tracked transmittances to it)
    /// and, where the segment ends on the ground, the ground's direct sunlight. The path then
    /// goes on from the ground or from a point of the segment ([`Self::scattering_point`]),
    /// so segment k carries scattering order k and no order is counted twice.
    pub fn radiance(&self, ray: &Ray, lanes: &LaneOptics, rng: &mut Rng) -> Lanes {
        let out = self.trace(ray, lanes, None, rng);
        Lanes::from_fn(|i| out[i][0])
    }

    /// The vector mode: the Stokes vector (I, Q, U, V) of [`Self::radiance`]'s light at the four
    /// wavelengths of `lanes`, referred to the frame whose e₁ is `e_up` (a unit vector
    /// perpendicular to `ray.direction`; e₂ = direction × e₁): the meridian frame of
    /// `polarisation::meridian_frame` for a direction in the sky, "up" in the picture for an
    /// image. Each path carries its Mueller products ([`stokes`]): air scatters by Hansen &
    /// Travis's matrix, a Mie aerosol by its type's, the Henyey–Greenstein and Cornette–Shanks
    /// aerosols without polarising ([`ReducedMatrix::unpolarising`]), the ground depolarises.
    /// The same paths as the scalar mode's for a seed, so their I differ by polarisation's
    /// effect alone.
    pub fn radiance_stokes(
        &self,
        ray: &Ray,
        e_up: DVec3,
        lanes: &LaneOptics,
        rng: &mut Rng,
    ) -> [Stokes; LANES] {
        self.trace(ray, lanes, Some(stokes::PathStokes::new(e_up)), rng)
            .map(|[i, q, u, v]| Stokes { i, q, u, v })
    }

    /// [`Self::radiance`], or with `polar` the Stokes vector of [`Self::radiance_stokes`]; in
    /// the scalar mode only I (the first element) is filled.
    fn trace(
        &self,
        ray: &Ray,
        lanes: &LaneOptics,
        mut polar: Option<stokes::PathStokes>,
        rng: &mut Rng,
    ) -> [[f64; 4]; LANES] {
        let medium = self.medium(lanes);
        let majorants = &medium.majorant;
        let mut radiance = [[0.0; 4]; LANES];
        let mut weight = Lanes::ONE;
        let mut ray = *ray;
        let max_order = self.settings.max_order.unwrap_or(u32::MAX);
        // The ground's albedo at the lanes' wavelengths.
        let albedo = lanes
            .wavelengths_nm
            .map(|w| self.atmosphere.ground_albedo_at(w, None));
        let reflects = albedo.iter().any(|&a| a > 0.0);
        let bottom = self.atmosphere.bottom_radius_m;
        let mut order = 0u32;
        // The light the path's first vertex can find, times its weight there: what the
        // roulette measures a later vertex's prospects against where the sun is below its
        // horizon.
        let mut prospect_first = 0.0;
        loop {
            let Some(seg) = self.segment(&ray) else { break };
            order += 1;
            let intervals = self.intervals(&ray, seg.start, seg.end);
            // Majorant optical depth over the segment, for the in-scattering point.
            let tau_total: f64 = intervals
                .iter()
                .map(|&(a, b, s)| majorants[s] * (b - a))
                .sum();
            if let Some((t, pdf)) =
                self.in_scattering_point(&ray, &intervals, &medium, tau_total, lanes, rng)
            {
                let x = ray.origin + ray.direction * t;
                let d = self.prepared.densities.at(x.length() - bottom);
                let view_t = self.ratio_track(&ray, &intervals, t, lanes, &medium, rng);
                let s_dir = self.sample_sun(rng);
                let sun_t = self.transmittance(&Ray::new(x, s_dir), lanes, &medium, rng);
                let nu = ray.direction.dot(s_dir);
                let plane = polar.as_ref().map(|p| p.plane(ray.direction, s_dir));
                for i in 0..LANES {
                    let o = &lanes.optics[i];
                    let c = o.coefficients(&d);
                    let (rayleigh, aerosol) = (
                        c.rayleigh_scattering * self.phase(0, o, nu),
                        c.aerosol_scattering * self.phase(1, o, nu),
                    );
                    let source = rayleigh + aerosol;
                    let Some((p, plane)) = polar.as_ref().zip(plane) else {
                        radiance[i][0] +=
                            weight[i] * view_t[i] * source * lanes.solar_irradiance[i] * sun_t[i]
                                / pdf;
                        continue;
                    };
                    // Sunlight is unpolarised: each constituent turns it into (1, b₁, 0, 0)
                    // times its part, referred to the scattering plane.
                    let across =
                        rayleigh * self.matrix(0, o, nu).b1 + aerosol * self.matrix(1, o, nu).b1;
                    let scale = weight[i] * view_t[i] * lanes.solar_irradiance[i] * sun_t[i] / pdf;
                    let s = p.scattered(i, plane, source, across);
                    (0..4).for_each(|k| radiance[i][k] += scale * s[k]);
                }
            }
            // The lanes' transmittances to the ground, where its sunlight needed them.
            let mut to_ground = None;
            if seg.ground {
                let g = (ray.origin + ray.direction * seg.end).normalize() * (bottom + 1e-3);
                let s_dir = self.sample_sun(rng);
                let cos_s = g.normalize().dot(s_dir);
                if cos_s > 0.0 && reflects {
                    let view_t = self.ratio_track(&ray, &intervals, seg.end, lanes, &medium, rng);
                    let sun_t = self.transmittance(&Ray::new(g, s_dir), lanes, &medium, rng);
                    for i in 0..LANES {
                        let l = weight[i] * view_t[i] * albedo[i] / PI
                            * cos_s
                            * lanes.solar_irradiance[i]
                            * sun_t[i];
                        match &polar {
                            Some(p) => {
                                let s = p.unpolarised(i, l);
                                (0..4).for_each(|k| radiance[i][k] += s[k]);
                            }
                            None => radiance[i][0] += l,
                        }
                    }
                    to_ground = Some(view_t);
                }
            }
            if order >= max_order {
                break;
            }
            // The path goes on from the ground, with the probability that the lanes' mean
            // extinction lets light through to it, or else from a point of the segment drawn
            // apart from the in-scattering point, from the sky's own attenuation
            // ([`Self::scattering_point`]). Not delta tracking: its null collisions, escapes and
            // per-lane probabilities would make the weights of every order above random.
            let tau_mean = mean_depth(&intervals, &medium);
            let p_ground = if seg.ground && reflects {
                (-tau_mean).exp()
            } else {
                0.0
            };
            // The weight by which the roulette below judges the path.
            let judged = if p_ground > 0.0 && rng.uniform() < p_ground {
                let view_t = match to_ground {
                    Some(view_t) => view_t,
                    None => self.ratio_track(&ray, &intervals, seg.end, lanes, &medium, rng),
                };
                for i in 0..LANES {
                    weight[i] *= view_t[i] * albedo[i] / p_ground;
                }
                let n = (ray.origin + ray.direction * seg.end).normalize();
                // Cosine-weighted direction over the ground's upper hemisphere.
                let (t, b) = basis(n);
                let r = rng.uniform().sqrt();
                let phi = 2.0 * PI * rng.uniform();
                let dir =
                    t * (r * phi.cos()) + b * (r * phi.sin()) + n * (1.0 - r * r).max(0.0).sqrt();
                ray = Ray::new(n * (bottom + 1e-3), dir);
                if let Some(p) = polar.as_mut() {
                    p.depolarise(dir);
                }
                max_weight(&weight)
            } else if let Some((t, pdf)) =
                self.scattering_point(&ray, &intervals, &medium, tau_mean, rng)
            {
                let x = ray.origin + ray.direction * t;
                let d = self.prepared.densities.at(x.length() - bottom);
                let view_t = self.ratio_track(&ray, &intervals, t, lanes, &medium, rng);
                let coefficients = lanes.optics.map(|o| o.coefficients(&d));
                let sigma = [
                    coefficients.map(|c| c.rayleigh_scattering),
                    coefficients.map(|c| c.aerosol_scattering),
                ];
                // Rayleigh or aerosol with spectral tracking's probabilities (Kutz et al.
                // 2017): by the lanes' largest weighted coefficients.
                let score = sigma.map(|s| {
                    (0..LANES).fold(0.0f64, |acc, i| acc.max(weight[i] * view_t[i] * s[i]))
                });
                let total = score[0] + score[1];
                if !(total > 0.0) {
                    break;
                }
                let constituent = usize::from(rng.uniform() * total >= score[0]);
                let p = (1.0 - p_ground) * pdf * score[constituent] / total;
                for i in 0..LANES {
                    weight[i] *= view_t[i] * sigma[constituent][i] / p;
                }
                // The roulette below judges the path by its weight before this direction: a
                // direction the guide draws often has a low weight because it was likely, not
                // because the light it leads to is faint, and judging it after would end most
                // guided paths and multiply the survivors' weights, more noise than unguided
                // paths have.
                let guide = self.guide(x);
                let mut judged = max_weight(&weight);
                // With the sun below a vertex's horizon, the light it can find varies by
                // orders of magnitude with its height and the sun's depression, and so does
                // what a path's weight is worth there: the roulette then judges the weight
                // times that light (the fluence of the guide's slice) against the same product
                // at the path's first vertex, so that paths where little is to be found tend to
                // end and those where much is to go on, in the spirit of adjoint-driven
                // roulette (Vorba and Křivánek 2016). Otherwise a path kept in the dark below
                // the twilight arch that found it late, spared with a weight near 1, brought a
                // thousand times the pixel's mean. With the sun above the horizon that light
                // varies little and judging by it costs more time than the noise it saves,
                // so it is not done there. A slice with no light (its bins' middles in the full
                // shadow) says nothing of what a path may still find beyond it: the weight alone
                // judges there, as it does wherever the first vertex had the sun above its
                // horizon, or the guide is off.
                let sun_below = self.settings.roulette_by_prospect && x.dot(self.sun) < 0.0;
                if let Some((_, frame)) = guide.as_ref().filter(|_| sun_below) {
                    let prospect = judged * self.fluence(frame);
                    if order == 1 {
                        prospect_first = prospect;
                    } else if prospect_first > 0.0 && prospect > 0.0 {
                        let ratio = prospect / prospect_first;
                        if ratio.is_finite() {
                            judged = ratio;
                        }
                    }
                }
                let dir =
                    self.scattered(constituent, ray.direction, guide, lanes, &mut weight, rng);
                if let Some(p) = polar.as_mut() {
                    let nu = ray.direction.dot(dir);
                    let matrices = lanes.optics.map(|o| self.matrix(constituent, &o, nu));
                    p.scatter(ray.direction, dir, matrices);
                }
                ray = Ray::new(x, dir);
                judged
            } else {
                break;
            };
            if order >= 2 {
                let survive = (judged / ROULETTE_WEIGHT).min(1.0);
                if survive <= 0.0 || rng.uniform() >= survive {
                    break;
                }
                weight.iter_mut().for_each(|w| *w /= survive);
            }
        }
        radiance
    }

    /// A direction after scattering by `constituent` at a vertex of a path arriving along
    /// `incoming`, from the vertex's direction guide (its [`Self::guide`]) or the phase
    /// function, with `weight` multiplied by each lane's phase over the density it was drawn
    /// with.
    fn scattered(
        &self,
        constituent: usize,
        incoming: DVec3,
        guide: Option<(f64, direction_guide::Frame)>,
        lanes: &LaneOptics,
        weight: &mut Lanes,
        rng: &mut Rng,
    ) -> DVec3 {
        let dir = match &guide {
            Some((share, frame)) if rng.uniform() < *share => self.guide_sample(frame, rng),
            _ => self.sample_phase(constituent, &lanes.optics[0], incoming, rng),
        };
        let nu = incoming.dot(dir);
        let mut pdf = self.sampling_pdf(constituent, &lanes.optics[0], nu);
        if let Some((share, frame)) = &guide {
            pdf = share * self.guide_pdf(frame, dir) + (1.0 - share) * pdf;
        }
        for i in 0..LANES {
            weight[i] *= self.phase(constituent, &lanes.optics[i], nu) / pdf;
        }
        dir
    }

    /// The scattering matrix of `constituent` over its phase function.
    fn matrix(&self, constituent: usize, optics: &Optics, nu: f64) -> ReducedMatrix {
        if constituent == 0 {
            ReducedMatrix::rayleigh(nu, optics.rayleigh_depolarisation)
        } else {
            self.atmosphere.aerosol_matrix(optics, nu)
        }
    }

    fn phase(&self, constituent: usize, optics: &Optics, nu: f64) -> f64 {
        if constituent == 0 {
            phase::rayleigh(nu, optics.rayleigh_depolarisation)
        } else {
            self.atmosphere.aerosol_phase(optics, nu)
        }
    }

    /// Density (sr⁻¹) with which `sample_phase` draws a direction at cosine `nu`.
    fn sampling_pdf(&self, constituent: usize, optics: &Optics, nu: f64) -> f64 {
        if constituent == 0 {
            phase::rayleigh(nu, optics.rayleigh_depolarisation)
        } else {
            phase::henyey_greenstein(nu, optics.aerosol_g)
        }
    }

    /// A new direction after scattering by `constituent`, with density proportional to its
    /// phase function (Rayleigh by rejection, aerosols by Henyey–Greenstein inversion, with
    /// Cornette–Shanks and the tabulated Mie phase handled through the weight ratio of `phase`).
    fn sample_phase(
        &self,
        constituent: usize,
        optics: &Optics,
        incoming: DVec3,
        rng: &mut Rng,
    ) -> DVec3 {
        let cos_theta = if constituent == 0 {
            let bound = phase::rayleigh(1.0, optics.rayleigh_depolarisation);
            loop {
                let c = 2.0 * rng.uniform() - 1.0;
                if rng.uniform() * bound <= phase::rayleigh(c, optics.rayleigh_depolarisation) {
                    break c;
                }
            }
        } else {
            henyey_greenstein_cosine(optics.aerosol_g, rng.uniform())
        };
        around(incoming, basis(incoming), cos_theta, rng)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::AtmosphereSettings;

    /// Each interval's shell, carried from cut to cut, is the shell of its middle, for rays
    /// from the ground, the sky and on shell boundaries, up, down, level and grazing them; the
    /// intervals tile the segment.
    #[test]
    fn intervals_carry_the_shell_of_their_middle() {
        let atmosphere = Atmosphere::new(&AtmosphereSettings::default());
        let tracer = PathTracer::new(&atmosphere, DVec3::Z, PathTracerSettings::default());
        let bottom = atmosphere.bottom_radius_m;
        let mut rng = Rng::new(7, 0, 0);
        let mut checked = 0;
        for k in 0..4000 {
            let h = match k % 4 {
                0 => 0.5,
                1 => rng.uniform() * 20_000.0,
                2 => rng.uniform() * atmosphere.thickness_m(),
                // On a boundary, where a middle's radius rounds across it.
                _ => SHELL_ALTITUDES_M[k % SHELL_ALTITUDES_M.len()],
            };
            // Every kind of direction, and some a hair below the horizon (grazing shells).
            let mu = match k % 3 {
                0 => -1e-4 * rng.uniform(),
                1 => -1e-8 * rng.uniform(),
                _ => 2.0 * rng.uniform() - 1.0,
            };
            let ray = Ray::new(
                DVec3::new(0.0, 0.0, bottom + h),
                DVec3::new((1.0 - mu * mu).sqrt(), 0.0, mu),
            );
            let Some(seg) = tracer.segment(&ray) else {
                continue;
            };
            let (r, mu) = ray.r_mu();
            let intervals = tracer.intervals(&ray, seg.start, seg.end);
            assert_eq!(intervals[0].0, seg.start);
            assert_eq!(intervals[intervals.len() - 1].1, seg.end);
            for w in intervals.windows(2) {
                assert_eq!(w[0].1, w[1].0, "intervals meet");
            }
            for &(a, b, shell) in intervals.iter() {
                // A middle whose radius lies within a micrometre of a boundary (a grazing
                // ray's) may round to either side of it.
                let radius = crate::geometry::radius_at(r, mu, 0.5 * (a + b));
                let clear = tracer
                    .prepared
                    .shell_radii
                    .iter()
                    .all(|&s| (radius - s).abs() > 1e-6);
                if clear {
                    let middle = tracer.shell_at(r, mu, 0.5 * (a + b));
                    assert_eq!(shell, middle, "h {h}, mu {mu}: [{a}, {b}]");
                    checked += 1;
                }
            }
        }
        assert!(checked > 40_000, "{checked}");
    }

    /// The default atmosphere with rural haze.
    fn rural() -> Atmosphere {
        let mut s = AtmosphereSettings::default();
        s.aerosol.kind = crate::aerosol::AerosolType::Rural;
        Atmosphere::new(&s)
    }

    /// A ray from altitude `h` (m), `elevation_deg` above the horizontal.
    fn ray_at(atmosphere: &Atmosphere, h: f64, elevation_deg: f64) -> Ray {
        let e = elevation_deg.to_radians();
        Ray::new(
            DVec3::new(0.0, 0.0, atmosphere.bottom_radius_m + h),
            DVec3::new(e.cos(), 0.0, e.sin()),
        )
    }

    /// The vertex a path goes on from is drawn with the density `scattering_point` reports: the
    /// mean of σ(t)/pdf(t) over its draws, σ a lane's extinction, is the optical depth of the
    /// whole segment and of its near half by the density's own depth (a density that were off
    /// in some shells would miss one or the other), on rays up, level, down to the ground and
    /// from space, through haze. (The extinction is what the vertex's weight divides by the
    /// density; the length alone, with the rare draws in the thin air above, has too heavy a
    /// tail to judge by.)
    ///
    /// With the sun 12° below the horizon the same holds for the density that draws half the
    /// vertices toward the light, which every one of these segments then uses.
    #[test]
    fn scattering_points_are_drawn_with_the_density_they_report() {
        let atmosphere = rural();
        let lanes = LaneOptics::new(&atmosphere, Lanes([450.0, 520.0, 600.0, 700.0]));
        let optics = &lanes.optics[1];
        let bottom = atmosphere.bottom_radius_m;
        let mut rng = Rng::new(13, 0, 0);
        let n = 40_000;
        let twilight = crate::geometry::direction_from_angles(-12.0, 30.0);
        for (sun, h, elevation_deg) in [DVec3::Z, twilight].into_iter().flat_map(|sun| {
            [
                (10.0, 60.0),
                (1500.0, 0.0),
                (9000.0, -20.0),
                (200_000.0, -15.0),
            ]
            .map(|(h, e)| (sun, h, e))
        }) {
            let tracer = PathTracer::new(&atmosphere, sun, PathTracerSettings::default());
            let medium = tracer.medium(&lanes);
            let ray = ray_at(&atmosphere, h, elevation_deg);
            let seg = tracer.segment(&ray).unwrap();
            let intervals = tracer.intervals(&ray, seg.start, seg.end);
            let total = mean_depth(&intervals, &medium);
            let light = tracer.light_masses(&ray, &intervals, &medium.in_scattering_rate);
            assert_eq!(light.is_some(), sun == twilight, "{h} m, {elevation_deg}°");
            let (k, half) = locate(&intervals, &medium.in_scattering_rate, 0.5 * total).unwrap();
            let half = half.clamp(intervals[k].0, intervals[k].1);
            let (mut sums, mut squares) = ([0.0; 2], [0.0; 2]);
            for _ in 0..n {
                let (t, pdf) = tracer
                    .scattering_point(&ray, &intervals, &medium, total, &mut rng)
                    .unwrap();
                assert!(
                    (seg.start..=seg.end).contains(&t),
                    "{t} outside the segment"
                );
                let x = ray.origin + ray.direction * t;
                let sigma = optics
                    .coefficients(&atmosphere.densities(x.length() - bottom))
                    .extinction();
                for (j, g) in [sigma, if t < half { sigma } else { 0.0 }]
                    .into_iter()
                    .enumerate()
                {
                    sums[j] += g / pdf;
                    squares[j] += (g / pdf).powi(2);
                }
            }
            for (j, until) in [seg.end, half].into_iter().enumerate() {
                let exact = atmosphere
                    .optical_depth_between(optics, &ray, seg.start, until)
                    .total();
                let mean = sums[j] / n as f64;
                let se = ((squares[j] / n as f64 - mean * mean) / (n - 1) as f64).sqrt();
                assert!(
                    (mean - exact).abs() < 4.0 * se + 1e-3 * exact,
                    "{h} m, {elevation_deg}°, to {until} m: {mean} ± {se} vs {exact}"
                );
            }
        }
    }

    /// Residual ratio tracking about the middle of each shell's extinction bounds gives the
    /// exact transmittance on average, with less than half the relative variance of tracking the
    /// residual above the shell's least extinction (the relative variance of one estimate is
    /// e^(∫r²/m) − 1 for a residual r under a majorant m: with r spread over [−m, m] rather than
    /// [0, m] and m halved, ∫r²/m halves; when written, 0.14–0.31 of it), on grazing rays
    /// through haze where a low sun's light comes from.
    #[test]
    fn ratio_tracking_about_the_shells_middle_is_unbiased_and_quieter() {
        let atmosphere = rural();
        let tracer = PathTracer::new(&atmosphere, DVec3::Z, PathTracerSettings::default());
        let lanes = LaneOptics::new(&atmosphere, Lanes([450.0, 520.0, 600.0, 700.0]));
        let medium = tracer.medium(&lanes);
        // The same medium with the control at each shell's least extinction.
        let mut lowest = tracer.medium(&lanes);
        for (k, shell) in tracer.prepared.shells.iter().enumerate() {
            let (min, max): (Lanes, Lanes) = (
                Lanes::from_fn(|i| shell.min.extinction(&lanes.optics[i])),
                Lanes::from_fn(|i| shell.max.extinction(&lanes.optics[i])),
            );
            lowest.control[k] = min;
            lowest.residual_majorant[k] = (0..LANES).fold(0.0f64, |a, i| a.max(max[i] - min[i]));
        }
        let n = 20_000;
        for (h, elevation_deg) in [(300.0, 0.0), (2000.0, 2.0), (8000.0, -1.0)] {
            let ray = ray_at(&atmosphere, h, elevation_deg);
            let seg = tracer.segment(&ray).unwrap();
            let intervals = tracer.intervals(&ray, seg.start, seg.end);
            let mut rng = Rng::new(11, 0, 0);
            let mut relative_variance = [[0.0; LANES]; 2];
            for (m, medium) in [&medium, &lowest].into_iter().enumerate() {
                let (mut sum, mut sum_sq) = ([0.0; LANES], [0.0; LANES]);
                for _ in 0..n {
                    let t = tracer.ratio_track(&ray, &intervals, seg.end, &lanes, medium, &mut rng);
                    for i in 0..LANES {
                        sum[i] += t[i];
                        sum_sq[i] += t[i] * t[i];
                    }
                }
                for i in 0..LANES {
                    let exact = (-atmosphere.optical_depth(&lanes.optics[i], &ray).total()).exp();
                    let mean = sum[i] / n as f64;
                    let variance = sum_sq[i] / n as f64 - mean * mean;
                    let se = (variance / (n - 1) as f64).sqrt();
                    assert!(
                        (mean - exact).abs() < 4.0 * se + 1e-4 * exact,
                        "{h} m, {elevation_deg}°, {} nm, control {m}: {mean} ± {se} vs {exact}",
                        lanes.wavelengths_nm[i]
                    );
                    relative_variance[m][i] = variance / (mean * mean);
                }
            }
            for i in 0..LANES {
                let [middle, least] = relative_variance.map(|v| v[i]);
                assert!(
                    middle < 0.5 * least,
                    "{h} m, {elevation_deg}°, {} nm: relative variance {middle:e} vs {least:e}",
                    lanes.wavelengths_nm[i]
                );
            }
        }
    }

    #[test]
    fn the_density_table_follows_the_profiles_and_keeps_their_steps() {
        let mut s = AtmosphereSettings::default();
        s.aerosol.kind = crate::aerosol::AerosolType::Urban;
        let atmosphere = Atmosphere::new(&s);
        let table = DensityTable::new(&atmosphere);
        // Linear between nodes 20 m apart: (20 m / H)²/8 of an exponential with scale height H.
        let close = |a: f64, b: f64| (a - b).abs() <= 2e-4 * b.abs() + 1e-30;
        for k in 0..4000 {
            let h = 0.37 + k as f64 * 24.9;
            let (t, d) = (table.at(h), atmosphere.densities(h));
            assert!(
                close(t.air_m3, d.air_m3)
                    && (t.ozone_m3 - d.ozone_m3).abs() <= 2e-4 * d.ozone_m3 + 1e12
                    && close(t.aerosol_per_m, d.aerosol_per_m),
                "{h} m: {t:?} vs {d:?}"
            );
        }
        // The mixing layer ends in a step at 2 km, which interpolation must not smear.
        let top = crate::aerosol::MIXING_LAYER_TOP_M;
        for h in [top - 0.5, top + 0.5] {
            let (t, d) = (table.at(h), atmosphere.densities(h));
            assert!(close(t.aerosol_per_m, d.aerosol_per_m), "{h} m");
        }
        assert_eq!(
            table.at(atmosphere.thickness_m() + 1.0),
            Densities::default()
        );
    }
}
