//! Which way a path turns at a scattering vertex: toward where the light comes from.
//!
//! A path's next segment contributes the sunlight scattered once along it and the sunlit
//! ground at its end, so the ideal density for its direction follows the phase function times
//! that single-scattered radiance. The phase function alone ignores the radiance, which at low
//! sun is concentrated in a thin arch of sunlit air above the horizon toward the sun and in
//! daylight still varies several-fold between the zenith, the horizon and the ground: the few
//! paths that turn the right way carry weights tens to hundreds of times the mean, most of a
//! twilight image's noise. A guide in the spirit of path guiding (Vorba et al. 2014), but
//! computed ahead from the atmosphere rather than learned from paths: for each vertex altitude
//! and local sun elevation, a piecewise-constant density over (cosine of zenith angle, azimuth
//! from the sun), proportional to a coarse march of the single-scattered radiance seen in
//! three directions across each cell's zenith band (three wavelengths, the
//! wavelength-independent sun columns). Its slices are built on first use, since a scene's
//! vertices meet few local sun elevations. Each slice's whole light (its fluence), interpolated
//! between the slices' middles into a table by altitude and μ_s, also tells the path tracer
//! where along a segment a vertex finds light.
//! It is a proposal only: the vertex draws from it in a one-sample mixture with the phase
//! function (balance heuristic, Veach 1997 §9.2) and weighs by the mixture's density, so the
//! estimate stays unbiased and no direction's weight grows by more than 1 / (1 − share) over
//! what phase sampling alone gave it. It is used only with the sun low at the vertex
//! ([`GUIDE_MU_S`]): with the sun high the sky's light is broad and the phase function does as
//! well.

use super::{PathTracer, basis};
use crate::atmosphere::Optics;
use crate::geometry::{Ray, sphere_distances};
use crate::methods::rng::Rng;
use glam::DVec3;
use std::f64::consts::PI;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicU64, Ordering};

/// Nodes of the fluence table ([`PathTracer::fluence_at`]): altitude rows 500 m apart on the
/// Earth, from the ground to the top, and columns of the sun's zenith cosine from −1 to 1
/// (0.45° apart at the horizon). A segment looks it up once for each of its intervals, so the
/// look-up must be cheaper than the slices' own (a search of the altitude bins, an arcsine and
/// four slices).
const FLUENCE_ROWS: usize = 201;
const FLUENCE_COLUMNS: usize = 257;

/// Altitude bins of the guide, m: a vertex uses the slice of the bin it lies in, computed at
/// the bin's middle. Dense low down, where most vertices are, and 3 to 5 km apart from 12 to
/// 50 km, where in twilight the sunlit air seen from a vertex moves fast with its height:
/// coarser bins there blur the twilight arch the guide is meant to find.
const ALTITUDE_EDGES_M: [f64; 21] = [
    0.0, 500.0, 1000.0, 2000.0, 3000.0, 5000.0, 8000.0, 12_000.0, 15_000.0, 18_000.0, 21_000.0,
    25_000.0, 30_000.0, 35_000.0, 40_000.0, 45_000.0, 50_000.0, 60_000.0, 70_000.0, 85_000.0,
    100_000.0,
];

/// Width of the local sun elevation bins, degrees: narrow enough that the Earth's shadow moves
/// by less than a bin's worth of sky between a slice and its vertices.
const ELEVATION_STEP_DEG: f64 = 2.0;
const ELEVATION_BINS: usize = (180.0 / ELEVATION_STEP_DEG) as usize;

/// Edges of the bins in the cosine of the zenith angle: narrow near the horizon and down to
/// the horizon's dip seen from 50 km, where the twilight arch, the haze and the sunlit limb
/// lie.
const COS_ZENITH_EDGES: [f64; 24] = [
    -1.0, -0.6, -0.3, -0.2, -0.15, -0.12, -0.1, -0.08, -0.06, -0.05, -0.04, -0.03, -0.02, -0.01,
    0.0, 0.01, 0.02, 0.04, 0.08, 0.15, 0.3, 0.5, 0.75, 1.0,
];
const ZENITH_BINS: usize = COS_ZENITH_EDGES.len() - 1;

/// Bins in the azimuth from the sun, over [0, π]: the sky is symmetric about the sun's vertical
/// plane, so each bin stands for two mirror cells.
const AZIMUTH_BINS: usize = 12;
const CELLS: usize = ZENITH_BINS * AZIMUTH_BINS;

/// Directions across a cell's zenith band whose radiance the cell takes the mean of: a band of
/// sunlit air narrower than the cell is seen whether or not it crosses the cell's middle.
const CELL_DIRECTIONS: usize = 3;

/// Steps of the radiance march per cell (quadratic spacing, dense near the vertex).
const MARCH_STEPS: usize = 24;

/// Wavelengths of the march, nm: the guide is one density for every lane.
const GUIDE_WAVELENGTHS_NM: [f64; 3] = [450.0, 550.0, 650.0];

/// Share of a slice's mass spread evenly over its solid angle, so that a cell whose middle
/// direction misses a bright feature still draws some directions.
const FLOOR_SHARE: f64 = 0.02;

/// The default [`super::PathTracerSettings::guide_share`]: half the directions from the
/// guide, half from the phase function, which keeps every direction's weight within twice the
/// phase function's while the guide still finds the twilight arch (the shares compared are in
/// docs/measurements/from-code-comments.md).
pub const GUIDE_SHARE: f64 = 0.5;

/// Cosine of the sun's zenith angle at a vertex above which no direction is drawn from the
/// guide (about 17° of elevation): higher, the sky's light is spread widely enough that the
/// phase function alone does as well, and the guide would only add noise. Below it the share
/// grows linearly to its most at the horizon.
const GUIDE_MU_S: f64 = 0.3;

/// One slice: the cumulative mass of the cells, zenith bin major.
struct Slice {
    cdf: [f64; CELLS + 1],
    /// The single-scattered radiance over the whole sphere, without the floor (W·m⁻²·nm⁻¹
    /// summed over the guide's wavelengths): zero where no light reaches the slice.
    fluence: f64,
}

/// The guide's lazily built slices, one per (altitude bin, sun elevation bin); boxed, since a
/// scene uses few of them.
pub(super) struct DirectionGuide {
    slices: Vec<OnceLock<Box<Slice>>>,
    optics: [Optics; GUIDE_WAVELENGTHS_NM.len()],
    solar_irradiance: [f64; GUIDE_WAVELENGTHS_NM.len()],
    ground_albedo: [f64; GUIDE_WAVELENGTHS_NM.len()],
    /// The slices' fluence interpolated at the table's nodes, as f64 bits: NaN until a thread
    /// first needs the node, which every thread would fill with the same value.
    fluence_nodes: Vec<AtomicU64>,
    /// Altitude between the table's rows, m.
    fluence_step_m: f64,
}

/// A vertex's local frame: its up, the sun's horizontal direction and the third axis, with the
/// slice it draws from.
pub(super) struct Frame {
    up: DVec3,
    sun_horizontal: DVec3,
    side: DVec3,
    slice: usize,
}

impl DirectionGuide {
    pub(super) fn new(atmosphere: &crate::Atmosphere) -> DirectionGuide {
        DirectionGuide {
            slices: (0..(ALTITUDE_EDGES_M.len() - 1) * ELEVATION_BINS)
                .map(|_| OnceLock::new())
                .collect(),
            optics: GUIDE_WAVELENGTHS_NM.map(|w| atmosphere.optics(w)),
            solar_irradiance: GUIDE_WAVELENGTHS_NM.map(|w| atmosphere.solar_irradiance(w, None)),
            ground_albedo: GUIDE_WAVELENGTHS_NM.map(|w| atmosphere.ground_albedo_at(w, None)),
            fluence_nodes: (0..FLUENCE_ROWS * FLUENCE_COLUMNS)
                .map(|_| AtomicU64::new(f64::NAN.to_bits()))
                .collect(),
            fluence_step_m: atmosphere.thickness_m() / (FLUENCE_ROWS - 1) as f64,
        }
    }
}

/// Solid angle (sr) of a cell in zenith band `z`, its mirror image across the sun's vertical
/// plane included (the guide draws azimuths on one side and mirrors half of them).
fn cell_solid_angle(z: usize) -> f64 {
    2.0 * (COS_ZENITH_EDGES[z + 1] - COS_ZENITH_EDGES[z]) * PI / AZIMUTH_BINS as f64
}

/// The bin of `x` among increasing `edges` (clamped to the first and last bins).
fn bin(edges: &[f64], x: f64) -> usize {
    edges[1..edges.len() - 1].partition_point(|&e| e <= x)
}

impl PathTracer<'_> {
    /// The share of directions drawn from the guide at vertex `x` ([`GUIDE_MU_S`]) and the
    /// guide's frame there; None where the share is zero.
    pub(super) fn guide(&self, x: DVec3) -> Option<(f64, Frame)> {
        let r = x.length();
        let up = x / r;
        let mu_s = up.dot(self.sun).clamp(-1.0, 1.0);
        let share = self.settings.guide_share * (1.0 - mu_s / GUIDE_MU_S).clamp(0.0, 1.0);
        (share > 0.0).then(|| (share, self.frame(r, up, mu_s)))
    }

    /// The guide's frame at vertex `x`, whatever the share there.
    #[cfg(test)]
    pub(super) fn guide_frame(&self, x: DVec3) -> Frame {
        let r = x.length();
        let up = x / r;
        self.frame(r, up, up.dot(self.sun).clamp(-1.0, 1.0))
    }

    /// The frame at radius `r` (m) with unit `up`, the sun at zenith cosine `mu_s`.
    fn frame(&self, r: f64, up: DVec3, mu_s: f64) -> Frame {
        let horizontal = self.sun - up * mu_s;
        // With the sun at the vertex's zenith or nadir any azimuth will do: the sky is then
        // the same all around.
        let sun_horizontal = if horizontal.length_squared() > 1e-12 {
            horizontal.normalize()
        } else {
            basis(up).0
        };
        Frame {
            up,
            sun_horizontal,
            side: up.cross(sun_horizontal),
            slice: self.slice_index(r, mu_s),
        }
    }

    /// The slice of a vertex at radius `r` (m) with the sun at zenith cosine `mu_s`.
    fn slice_index(&self, r: f64, mu_s: f64) -> usize {
        let h = r - self.atmosphere.bottom_radius_m;
        let elevation_deg = mu_s.asin().to_degrees();
        let e = (((elevation_deg + 90.0) / ELEVATION_STEP_DEG) as usize).min(ELEVATION_BINS - 1);
        bin(&ALTITUDE_EDGES_M, h) * ELEVATION_BINS + e
    }

    /// The single-scattered light reaching point `x`, interpolated in the guide's fluence
    /// table.
    pub(super) fn fluence_at(&self, x: DVec3) -> f64 {
        let guide = &self.prepared.guide;
        let r = x.length();
        let fr = ((r - self.atmosphere.bottom_radius_m) / guide.fluence_step_m)
            .clamp(0.0, (FLUENCE_ROWS - 1) as f64);
        let fc = ((x.dot(self.sun) / r + 1.0) * 0.5 * (FLUENCE_COLUMNS - 1) as f64)
            .clamp(0.0, (FLUENCE_COLUMNS - 1) as f64);
        let (i, j) = (
            (fr as usize).min(FLUENCE_ROWS - 2),
            (fc as usize).min(FLUENCE_COLUMNS - 2),
        );
        let (wr, wc) = (fr - i as f64, fc - j as f64);
        let node = |i: usize, j: usize| {
            let cell = &guide.fluence_nodes[i * FLUENCE_COLUMNS + j];
            let v = f64::from_bits(cell.load(Ordering::Relaxed));
            if !v.is_nan() {
                return v;
            }
            let h = i as f64 * guide.fluence_step_m;
            let mu_s = j as f64 / (FLUENCE_COLUMNS - 1) as f64 * 2.0 - 1.0;
            let v = self.slices_fluence(h, mu_s);
            cell.store(v.to_bits(), Ordering::Relaxed);
            v
        };
        (1.0 - wr) * ((1.0 - wc) * node(i, j) + wc * node(i, j + 1))
            + wr * ((1.0 - wc) * node(i + 1, j) + wc * node(i + 1, j + 1))
    }

    /// The slices' fluence at altitude `h` (m) and sun zenith cosine `mu_s`, interpolated
    /// between their middles.
    fn slices_fluence(&self, h: f64, mu_s: f64) -> f64 {
        // Between the slices' middles: altitude bins' middles, sun elevation bins' middles.
        let n = ALTITUDE_EDGES_M.len() - 1;
        let middle = |i: usize| 0.5 * (ALTITUDE_EDGES_M[i] + ALTITUDE_EDGES_M[i + 1]);
        let i = (0..n - 1).rev().find(|&i| middle(i) <= h).unwrap_or(0);
        let fh = ((h - middle(i)) / (middle(i + 1) - middle(i))).clamp(0.0, 1.0);
        let e = (mu_s.asin().to_degrees() + 90.0) / ELEVATION_STEP_DEG - 0.5;
        let j = (e.floor().max(0.0) as usize).min(ELEVATION_BINS - 2);
        let fe = (e - j as f64).clamp(0.0, 1.0);
        let f = |i: usize, j: usize| self.guide_slice(i * ELEVATION_BINS + j).fluence;
        (1.0 - fh) * ((1.0 - fe) * f(i, j) + fe * f(i, j + 1))
            + fh * ((1.0 - fe) * f(i + 1, j) + fe * f(i + 1, j + 1))
    }

    fn guide_slice(&self, slice: usize) -> &Slice {
        self.prepared.guide.slices[slice].get_or_init(|| Box::new(self.build_slice(slice)))
    }

    /// The single-scattered light reaching the middle of the slice of a vertex with `frame`
    /// (its altitude bin and 2° sun elevation bin) from every direction: roughly what a path
    /// going on from there can find, up to a factor the same everywhere.
    pub(super) fn fluence(&self, frame: &Frame) -> f64 {
        self.guide_slice(frame.slice).fluence
    }

    /// A direction drawn from the guide at a vertex with `frame`.
    pub(super) fn guide_sample(&self, frame: &Frame, rng: &mut Rng) -> DVec3 {
        let cdf = &self.guide_slice(frame.slice).cdf;
        let u = rng.uniform() * cdf[CELLS];
        let cell = cdf[1..CELLS].partition_point(|&c| c <= u);
        let (z, a) = (cell / AZIMUTH_BINS, cell % AZIMUTH_BINS);
        let c0 = COS_ZENITH_EDGES[z];
        let cos_zenith = c0 + rng.uniform() * (COS_ZENITH_EDGES[z + 1] - c0);
        let mut phi = (a as f64 + rng.uniform()) * PI / AZIMUTH_BINS as f64;
        if rng.uniform() < 0.5 {
            phi = -phi;
        }
        frame_direction(frame, cos_zenith, phi)
    }

    /// Density (sr⁻¹) with which [`Self::guide_sample`] draws `dir` at a vertex with `frame`.
    pub(super) fn guide_pdf(&self, frame: &Frame, dir: DVec3) -> f64 {
        let cdf = &self.guide_slice(frame.slice).cdf;
        let cos_zenith = frame.up.dot(dir);
        let phi = dir
            .dot(frame.side)
            .atan2(dir.dot(frame.sun_horizontal))
            .abs();
        let z = bin(&COS_ZENITH_EDGES, cos_zenith);
        let a = ((phi / PI * AZIMUTH_BINS as f64) as usize).min(AZIMUTH_BINS - 1);
        let cell = z * AZIMUTH_BINS + a;
        (cdf[cell + 1] - cdf[cell]) / cdf[CELLS] / cell_solid_angle(z)
    }

    /// The slice's cells: the mean single-scattered radiance in [`CELL_DIRECTIONS`] directions
    /// across each cell's zenith band (at its middle azimuth) from the middle of its altitude
    /// bin under the middle of its sun elevation bin, times the cell's solid angle, plus the
    /// floor.
    fn build_slice(&self, slice: usize) -> Slice {
        let (k_h, k_e) = (slice / ELEVATION_BINS, slice % ELEVATION_BINS);
        let h = (0.5 * (ALTITUDE_EDGES_M[k_h] + ALTITUDE_EDGES_M[k_h + 1]))
            .min(self.atmosphere.thickness_m());
        let elevation = ((k_e as f64 + 0.5) * ELEVATION_STEP_DEG - 90.0).to_radians();
        let sun = DVec3::new(elevation.cos(), 0.0, elevation.sin());
        let x = DVec3::new(0.0, 0.0, self.atmosphere.bottom_radius_m + h);
        let frame = Frame {
            up: DVec3::Z,
            sun_horizontal: DVec3::X,
            side: DVec3::Y,
            slice,
        };
        let mut mass = [0.0; CELLS];
        for z in 0..ZENITH_BINS {
            for a in 0..AZIMUTH_BINS {
                let phi = (a as f64 + 0.5) * PI / AZIMUTH_BINS as f64;
                let cell = z * AZIMUTH_BINS + a;
                let m = (0..CELL_DIRECTIONS)
                    .map(|q| {
                        let f = (q as f64 + 0.5) / CELL_DIRECTIONS as f64;
                        let cos_zenith = COS_ZENITH_EDGES[z]
                            + f * (COS_ZENITH_EDGES[z + 1] - COS_ZENITH_EDGES[z]);
                        self.single_scattered(x, frame_direction(&frame, cos_zenith, phi), sun)
                    })
                    .sum::<f64>()
                    / CELL_DIRECTIONS as f64
                    * cell_solid_angle(z);
                mass[cell] = if m.is_finite() { m.max(0.0) } else { 0.0 };
            }
        }
        // A slice with no light (the sun far below) is uniform over the sphere.
        let total: f64 = mass.iter().sum();
        let mut cdf = [0.0; CELLS + 1];
        for cell in 0..CELLS {
            let solid_angle = cell_solid_angle(cell / AZIMUTH_BINS);
            let floor = if total > 0.0 {
                FLOOR_SHARE * total * solid_angle / (4.0 * PI)
            } else {
                solid_angle
            };
            cdf[cell + 1] = cdf[cell] + (1.0 - FLOOR_SHARE) * mass[cell] + floor;
        }
        Slice {
            cdf,
            fluence: total,
        }
    }

    /// Single-scattered radiance (plus the sunlit ground's) reaching `x` from `dir` under a sun
    /// in unit direction `sun`, summed over the guide's wavelengths: a coarse midpoint march.
    fn single_scattered(&self, x: DVec3, dir: DVec3, sun: DVec3) -> f64 {
        let big_r = self.atmosphere.bottom_radius_m;
        let ray = Ray::new(x, dir);
        let (r, mu) = ray.r_mu();
        let ground = if mu < 0.0 {
            sphere_distances(r, mu, big_r)
                .map(|(t, _)| t)
                .filter(|&t| t >= 0.0)
        } else {
            None
        };
        let Some(length) = ground.or_else(|| {
            sphere_distances(r, mu, self.atmosphere.top_radius_m).map(|(_, t)| t.max(0.0))
        }) else {
            return 0.0;
        };
        let nu = dir.dot(sun);
        let guide = &self.prepared.guide;
        let phases = guide
            .optics
            .map(|o| (self.phase(0, &o, nu), self.phase(1, &o, nu)));
        let mut depth = [0.0; GUIDE_WAVELENGTHS_NM.len()];
        let mut radiance = [0.0; GUIDE_WAVELENGTHS_NM.len()];
        let sun_transmittance = |p: DVec3, depth: &[f64]| -> [f64; GUIDE_WAVELENGTHS_NM.len()] {
            let r_p = p.length();
            let (visible, column) = self
                .prepared
                .sun_columns
                .towards_sun(r_p - big_r, p.dot(sun) / r_p);
            std::array::from_fn(|i| {
                let o = &guide.optics[i];
                let tau = o.rayleigh_cross_section_m2 * column[0]
                    + o.ozone_cross_section_m2 * column[1]
                    + o.aerosol_optical_depth * column[2];
                visible * (-(tau + depth[i])).exp()
            })
        };
        for k in 0..MARCH_STEPS {
            let f = |k: usize| length * (k as f64 / MARCH_STEPS as f64).powi(2);
            let (t0, t1) = (f(k), f(k + 1));
            let p = x + dir * (0.5 * (t0 + t1));
            let d = self.prepared.densities.at(p.length() - big_r);
            let coefficients = guide.optics.map(|o| o.coefficients(&d));
            // Half the step's own extinction, so the step's light is dimmed to its middle.
            for (i, c) in coefficients.iter().enumerate() {
                depth[i] += 0.5 * c.extinction() * (t1 - t0);
            }
            let transmittance = sun_transmittance(p, &depth);
            for (i, c) in coefficients.iter().enumerate() {
                let source =
                    c.rayleigh_scattering * phases[i].0 + c.aerosol_scattering * phases[i].1;
                radiance[i] += source * transmittance[i] * (t1 - t0);
                depth[i] += 0.5 * c.extinction() * (t1 - t0);
            }
        }
        if ground.is_some() {
            let g = x + dir * length;
            let mu_g = (g.normalize().dot(sun)).max(0.0);
            let transmittance = sun_transmittance(g, &depth);
            for i in 0..radiance.len() {
                radiance[i] += guide.ground_albedo[i] / PI * mu_g * transmittance[i];
            }
        }
        (0..radiance.len())
            .map(|i| radiance[i] * guide.solar_irradiance[i])
            .sum()
    }
}

/// The direction at `cos_zenith` and azimuth `phi` (radians from the sun's side) in `frame`.
fn frame_direction(frame: &Frame, cos_zenith: f64, phi: f64) -> DVec3 {
    let sin_zenith = (1.0 - cos_zenith * cos_zenith).max(0.0).sqrt();
    (frame.up * cos_zenith
        + (frame.sun_horizontal * phi.cos() + frame.side * phi.sin()) * sin_zenith)
        .normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Atmosphere;
    use crate::geometry::direction_from_angles;
    use crate::methods::path_tracer::PathTracerSettings;
    use crate::scene::AtmosphereSettings;

    /// The guide's density integrates to one over the sphere, and its samples follow it: the
    /// share of samples in each of 36 regions (nine bands of the zenith angle's cosine by four
    /// quadrants of azimuth, none aligned with the guide's cells, so a wrong spread inside a
    /// cell or a lost mirror side shows) is the density's integral over it. The integrals are by
    /// a fine midpoint grid in the vertex's frame, through `guide_pdf`'s own inversion of
    /// directions.
    #[test]
    fn the_guide_density_is_normalised_and_matches_its_samples() {
        let atm = Atmosphere::new(&AtmosphereSettings::default());
        for sun_elevation in [15.0, 3.0, -5.0] {
            let sun = direction_from_angles(sun_elevation, 30.0);
            let pt = PathTracer::new(&atm, sun, PathTracerSettings::default());
            let x = DVec3::new(1e4, -2e4, atm.bottom_radius_m + 1500.0);
            let frame = pt.guide_frame(x);
            let region = |d: DVec3| {
                let band = (((frame.up.dot(d) + 1.0) * 4.5) as usize).min(8);
                let phi = d.dot(frame.side).atan2(d.dot(frame.sun_horizontal));
                let quadrant = (((phi + PI) / (0.5 * PI)) as usize).min(3);
                band * 4 + quadrant
            };
            let (nc, nphi) = (2700, 720);
            let mut integral = [0.0; 36];
            for i in 0..nc {
                let c = -1.0 + (i as f64 + 0.5) * 2.0 / nc as f64;
                for j in 0..nphi {
                    let phi = -PI + (j as f64 + 0.5) * 2.0 * PI / nphi as f64;
                    let dir = frame_direction(&frame, c, phi);
                    integral[region(dir)] +=
                        pt.guide_pdf(&frame, dir) * (2.0 / nc as f64) * (2.0 * PI / nphi as f64);
                }
            }
            let total: f64 = integral.iter().sum();
            assert!(
                (total - 1.0).abs() < 2e-3,
                "sun {sun_elevation}°: ∫ pdf = {total}"
            );
            let mut rng = Rng::new(3, 0, 0);
            let n = 200_000;
            let mut hits = [0.0; 36];
            for _ in 0..n {
                hits[region(pt.guide_sample(&frame, &mut rng))] += 1.0 / n as f64;
            }
            for (k, (&hit, &expected)) in hits.iter().zip(&integral).enumerate() {
                let tolerance = 5.0 * (expected / n as f64).sqrt() + 1e-3;
                assert!(
                    (hit - expected).abs() < tolerance,
                    "sun {sun_elevation}°, region {k}: sampled share {hit}, density's {expected}"
                );
            }
        }
    }

    /// At low sun the guide leans toward the sun: just above the horizon, its density toward
    /// the sun is several times its density away from it (the twilight arch against the
    /// Earth's shadow), and with the sun overhead it is nearly the same all around (its slice
    /// is built for the sun in the middle of its 2° bin, 1° from the zenith).
    #[test]
    fn the_guide_leans_toward_the_sun_when_it_is_low() {
        let atm = Atmosphere::new(&AtmosphereSettings::default());
        let x = DVec3::new(0.0, 0.0, atm.bottom_radius_m + 700.0);
        let ratio = |elevation: f64| {
            let sun = direction_from_angles(elevation, 0.0);
            let pt = PathTracer::new(&atm, sun, PathTracerSettings::default());
            let frame = pt.guide_frame(x);
            let toward = pt.guide_pdf(&frame, direction_from_angles(0.5, 5.0));
            let away = pt.guide_pdf(&frame, direction_from_angles(0.5, 175.0));
            toward / away
        };
        for elevation in [3.0, -3.0, -6.0] {
            let r = ratio(elevation);
            assert!(r > 3.0, "sun {elevation}°: toward / away {r}");
        }
        let r = ratio(90.0);
        assert!((r - 1.0).abs() < 0.1, "sun overhead: toward / away {r}");
    }
}
