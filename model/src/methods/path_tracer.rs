//! The spectral path tracer: Atmoscope's ground truth.
//!
//! Each path carries four wavelengths (a hero wavelength and three others spaced evenly over
//! 360–830 nm, Wilkie et al. 2014). Free flights use delta tracking against a majorant that is
//! constant within altitude shells; with several wavelengths the collision type (Rayleigh
//! scattering, aerosol scattering, null) is chosen with spectral tracking probabilities (Kutz et
//! al. 2017), so every wavelength stays unbiased. Absorption is never sampled: its share of the
//! extinction is carried in the weights. At each scattering event the sun is sampled inside its
//! finite disk (next-event estimation) with ratio-tracked transmittance; the Lambertian ground
//! gets the same treatment and continues by cosine sampling. All scattering orders, Russian
//! roulette after the third, an optional maximum order (1 = single scattering).
//!
//! The direct solar disk seen by a camera ray is not included: renderers add it analytically.
//! Radiance is spectral radiance for the scene's solar spectrum, W·m⁻²·sr⁻¹·nm⁻¹.

use super::rng::Rng;
use crate::atmosphere::{Atmosphere, Optics};
use crate::constants::{SUN_ANGULAR_RADIUS_RAD, VISIBLE_MAX_NM, VISIBLE_MIN_NM};
use crate::geometry::{Ray, sphere_distances};
use crate::phase;
use crate::scene::AerosolPhase;
use glam::DVec3;
use std::f64::consts::PI;

/// Wavelengths carried by one path.
pub const LANES: usize = 4;
/// A value per wavelength of a path.
pub type Lanes = [f64; LANES];

/// Altitudes (m) separating the majorant shells; denser low down, where density changes fast.
const SHELL_ALTITUDES_M: [f64; 16] = [
    0.0, 250.0, 500.0, 1000.0, 1500.0, 2000.0, 3000.0, 4500.0, 6500.0, 9000.0, 12_000.0, 16_000.0,
    21_000.0, 28_000.0, 40_000.0, 60_000.0,
];

/// Settings of a path-traced estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathTracerSettings {
    /// Highest scattering order counted (volume and ground events); None for all orders.
    pub max_order: Option<u32>,
    /// Angular radius of the sun, radians.
    pub sun_angular_radius_rad: f64,
}

impl Default for PathTracerSettings {
    fn default() -> Self {
        PathTracerSettings {
            max_order: None,
            sun_angular_radius_rad: SUN_ANGULAR_RADIUS_RAD,
        }
    }
}

/// Densest values of each constituent within a shell.
#[derive(Debug, Clone, Copy)]
struct ShellMax {
    air_m3: f64,
    ozone_m3: f64,
    aerosol_per_m: f64,
}

/// An atmosphere prepared for path tracing: shells and their density bounds.
pub struct PathTracer<'a> {
    pub atmosphere: &'a Atmosphere,
    pub settings: PathTracerSettings,
    /// Shell boundary radii, m, increasing, ending at the top of the atmosphere.
    shell_radii: Vec<f64>,
    shell_max: Vec<ShellMax>,
    /// Unit direction to the sun's centre.
    sun: DVec3,
    /// Orthonormal basis around `sun` for sampling the disk.
    sun_basis: (DVec3, DVec3),
    cos_sun_radius: f64,
}

/// Optical properties of the four wavelengths of a path.
#[derive(Debug, Clone, Copy)]
pub struct LaneOptics {
    pub wavelengths_nm: Lanes,
    optics: [Optics; LANES],
    /// Extraterrestrial solar irradiance, W·m⁻²·nm⁻¹.
    pub solar_irradiance: Lanes,
}

impl LaneOptics {
    /// Optics of the atmosphere at four wavelengths.
    pub fn new(atmosphere: &Atmosphere, wavelengths_nm: Lanes) -> LaneOptics {
        let solar = atmosphere.solar_spectrum.spectrum();
        LaneOptics {
            wavelengths_nm,
            optics: wavelengths_nm.map(|w| atmosphere.optics(w)),
            solar_irradiance: wavelengths_nm.map(|w| solar.sample(w)),
        }
    }
}

/// Wavelengths of a path: the hero from `u` ∈ [0, 1) and three more spaced by a quarter of the
/// visible range, wrapping around. Each is uniformly distributed over 360–830 nm.
pub fn hero_wavelengths(u: f64) -> Lanes {
    let span = VISIBLE_MAX_NM - VISIBLE_MIN_NM;
    std::array::from_fn(|i| VISIBLE_MIN_NM + ((u + i as f64 / LANES as f64) % 1.0) * span)
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

impl<'a> PathTracer<'a> {
    /// Prepares `atmosphere` for paths lit by the sun in unit direction `sun`.
    pub fn new(
        atmosphere: &'a Atmosphere,
        sun: DVec3,
        settings: PathTracerSettings,
    ) -> PathTracer<'a> {
        let thickness = atmosphere.thickness_m();
        let mut altitudes: Vec<f64> = SHELL_ALTITUDES_M
            .iter()
            .copied()
            .filter(|&z| z < thickness)
            .collect();
        altitudes.push(thickness);
        let shell_max = altitudes
            .windows(2)
            .map(|w| {
                // Densities are monotone in most profiles; sample finely for ozone's peak and
                // add a margin so the bound holds between samples.
                let mut m = ShellMax {
                    air_m3: 0.0,
                    ozone_m3: 0.0,
                    aerosol_per_m: 0.0,
                };
                for k in 0..=64 {
                    let d = atmosphere.densities(w[0] + (w[1] - w[0]) * k as f64 / 64.0);
                    m.air_m3 = m.air_m3.max(d.air_m3);
                    m.ozone_m3 = m.ozone_m3.max(d.ozone_m3);
                    m.aerosol_per_m = m.aerosol_per_m.max(d.aerosol_per_m);
                }
                ShellMax {
                    air_m3: m.air_m3 * 1.02,
                    ozone_m3: m.ozone_m3 * 1.05,
                    aerosol_per_m: m.aerosol_per_m * 1.02,
                }
            })
            .collect();
        let sun = sun.normalize();
        PathTracer {
            atmosphere,
            settings,
            shell_radii: altitudes
                .iter()
                .map(|z| atmosphere.bottom_radius_m + z)
                .collect(),
            shell_max,
            sun,
            sun_basis: basis(sun),
            cos_sun_radius: settings.sun_angular_radius_rad.cos(),
        }
    }

    fn majorants(&self, lanes: &LaneOptics) -> Vec<f64> {
        self.shell_max
            .iter()
            .map(|m| {
                lanes.optics.iter().fold(0.0f64, |acc, o| {
                    acc.max(
                        o.rayleigh_cross_section_m2 * m.air_m3
                            + o.ozone_cross_section_m2 * m.ozone_m3
                            + o.aerosol_optical_depth * m.aerosol_per_m,
                    )
                })
            })
            .collect()
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
    fn intervals(&self, ray: &Ray, start: f64, end: f64) -> Vec<(f64, f64, usize)> {
        let (r, mu) = ray.r_mu();
        let mut cuts = vec![start, end];
        for &radius in &self.shell_radii[1..self.shell_radii.len() - 1] {
            if let Some((a, b)) = sphere_distances(r, mu, radius) {
                cuts.extend([a, b].into_iter().filter(|&t| t > start && t < end));
            }
        }
        cuts.sort_by(f64::total_cmp);
        cuts.windows(2)
            .filter(|w| w[1] > w[0])
            .map(|w| {
                let mid = crate::geometry::radius_at(r, mu, 0.5 * (w[0] + w[1]));
                let shell = self
                    .shell_radii
                    .partition_point(|&s| s <= mid)
                    .saturating_sub(1)
                    .min(self.shell_max.len() - 1);
                (w[0], w[1], shell)
            })
            .collect()
    }

    /// Transmittance along the ray from its origin out of the atmosphere by ratio tracking; zero
    /// when the ray meets the ground.
    fn transmittance(
        &self,
        ray: &Ray,
        lanes: &LaneOptics,
        majorants: &[f64],
        rng: &mut Rng,
    ) -> Lanes {
        let Some(seg) = self.segment(ray) else {
            return [1.0; LANES];
        };
        if seg.ground {
            return [0.0; LANES];
        }
        let mut t_lanes = [1.0; LANES];
        for (a, b, shell) in self.intervals(ray, seg.start, seg.end) {
            let m = majorants[shell];
            if m <= 0.0 {
                continue;
            }
            let mut t = a;
            loop {
                t -= (1.0 - rng.uniform()).ln() / m;
                if t >= b {
                    break;
                }
                let x = ray.origin + ray.direction * t;
                let d = self
                    .atmosphere
                    .densities(x.length() - self.atmosphere.bottom_radius_m);
                for (i, o) in lanes.optics.iter().enumerate() {
                    t_lanes[i] *= (1.0 - o.coefficients(&d).extinction() / m).max(0.0);
                }
                if t_lanes.iter().all(|&v| v < 1e-4) {
                    // Unbiased termination of a negligible estimate.
                    if rng.uniform() < 0.5 {
                        return [0.0; LANES];
                    }
                    t_lanes.iter_mut().for_each(|v| *v *= 2.0);
                }
            }
        }
        t_lanes
    }

    /// A direction inside the solar disk, uniformly over its solid angle.
    fn sample_sun(&self, rng: &mut Rng) -> DVec3 {
        let cos_theta = 1.0 - rng.uniform() * (1.0 - self.cos_sun_radius);
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let phi = 2.0 * PI * rng.uniform();
        let (t, b) = self.sun_basis;
        (t * (sin_theta * phi.cos()) + b * (sin_theta * phi.sin()) + self.sun * cos_theta)
            .normalize()
    }

    /// Radiance arriving at `ray.origin` from `-ray.direction` (the sky seen along the ray,
    /// without the direct solar disk), at the four wavelengths of `lanes`.
    pub fn radiance(&self, ray: &Ray, lanes: &LaneOptics, rng: &mut Rng) -> Lanes {
        let majorants = self.majorants(lanes);
        let mut radiance = [0.0; LANES];
        let mut weight = [1.0; LANES];
        let mut ray = *ray;
        let mut order = 0u32;
        let max_order = self.settings.max_order.unwrap_or(u32::MAX);
        let albedo = self.atmosphere.ground_albedo;
        'path: loop {
            let Some(seg) = self.segment(&ray) else { break };
            // Delta tracking with spectral-tracking event probabilities.
            let mut event = None;
            'track: for (a, b, shell) in self.intervals(&ray, seg.start, seg.end) {
                let m = majorants[shell];
                if m <= 0.0 {
                    continue;
                }
                let mut t = a;
                loop {
                    t -= (1.0 - rng.uniform()).ln() / m;
                    if t >= b {
                        break;
                    }
                    let x = ray.origin + ray.direction * t;
                    let d = self
                        .atmosphere
                        .densities(x.length() - self.atmosphere.bottom_radius_m);
                    let mut sigma = [[0.0; LANES]; 3]; // Rayleigh, aerosol scattering, null
                    for (i, o) in lanes.optics.iter().enumerate() {
                        let c = o.coefficients(&d);
                        sigma[0][i] = c.rayleigh_scattering;
                        sigma[1][i] = c.aerosol_scattering;
                        sigma[2][i] = (m - c.extinction()).max(0.0);
                    }
                    let score =
                        sigma.map(|s| (0..LANES).fold(0.0f64, |acc, i| acc.max(weight[i] * s[i])));
                    let total: f64 = score.iter().sum();
                    if total <= 0.0 {
                        break 'path;
                    }
                    let u = rng.uniform() * total;
                    let e = if u < score[0] {
                        0
                    } else if u < score[0] + score[1] {
                        1
                    } else {
                        2
                    };
                    let p = score[e] / total;
                    for i in 0..LANES {
                        weight[i] *= sigma[e][i] / (m * p);
                    }
                    if e < 2 {
                        event = Some((x, e));
                        break 'track;
                    }
                }
            }
            let (x, normal) = match event {
                Some((x, constituent)) => {
                    order += 1;
                    // Next-event estimation towards the sun.
                    let s = self.sample_sun(rng);
                    let nu = ray.direction.dot(s);
                    let t_sun = self.transmittance(&Ray::new(x, s), lanes, &majorants, rng);
                    for i in 0..LANES {
                        let p = self.phase(constituent, &lanes.optics[i], nu);
                        radiance[i] += weight[i] * p * lanes.solar_irradiance[i] * t_sun[i];
                    }
                    if order >= max_order {
                        break;
                    }
                    // Continue in a direction drawn from the hero wavelength's phase function.
                    let dir = self.sample_phase(constituent, &lanes.optics[0], ray.direction, rng);
                    let nu_new = ray.direction.dot(dir);
                    let pdf = self.sampling_pdf(constituent, &lanes.optics[0], nu_new);
                    for i in 0..LANES {
                        weight[i] *= self.phase(constituent, &lanes.optics[i], nu_new) / pdf;
                    }
                    ray = Ray::new(x, dir);
                    (x, None)
                }
                None if seg.ground => {
                    order += 1;
                    let x = ray.origin + ray.direction * seg.end;
                    let n = x.normalize();
                    let x = n * (self.atmosphere.bottom_radius_m + 1e-3);
                    let s = self.sample_sun(rng);
                    let cos_s = n.dot(s);
                    if cos_s > 0.0 {
                        let t_sun = self.transmittance(&Ray::new(x, s), lanes, &majorants, rng);
                        for i in 0..LANES {
                            radiance[i] += weight[i] * albedo / PI
                                * cos_s
                                * lanes.solar_irradiance[i]
                                * t_sun[i];
                        }
                    }
                    if order >= max_order || albedo <= 0.0 {
                        break;
                    }
                    weight.iter_mut().for_each(|w| *w *= albedo);
                    (x, Some(n))
                }
                None => break,
            };
            if let Some(n) = normal {
                // Cosine-weighted direction over the ground's upper hemisphere.
                let (t, b) = basis(n);
                let r = rng.uniform().sqrt();
                let phi = 2.0 * PI * rng.uniform();
                let dir =
                    t * (r * phi.cos()) + b * (r * phi.sin()) + n * (1.0 - r * r).max(0.0).sqrt();
                ray = Ray::new(x, dir);
            }
            if order >= 3 {
                let survive = weight.iter().fold(0.0f64, |a, &w| a.max(w)).min(1.0);
                if survive <= 0.0 || rng.uniform() >= survive {
                    break;
                }
                weight.iter_mut().for_each(|w| *w /= survive);
            }
        }
        radiance
    }

    fn phase(&self, constituent: usize, optics: &Optics, nu: f64) -> f64 {
        if constituent == 0 {
            phase::rayleigh(nu, optics.rayleigh_depolarisation)
        } else {
            match self.atmosphere.aerosol_phase {
                AerosolPhase::HenyeyGreenstein => phase::henyey_greenstein(nu, optics.aerosol_g),
                AerosolPhase::CornetteShanks => phase::cornette_shanks(nu, optics.aerosol_g),
            }
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
    /// Cornette–Shanks handled through the weight ratio of `phase`).
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
            let g = optics.aerosol_g;
            if g.abs() < 1e-4 {
                2.0 * rng.uniform() - 1.0
            } else {
                let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * rng.uniform());
                ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
            }
        };
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let phi = 2.0 * PI * rng.uniform();
        let (t, b) = basis(incoming);
        (t * (sin_theta * phi.cos()) + b * (sin_theta * phi.sin()) + incoming * cos_theta)
            .normalize()
    }
}
