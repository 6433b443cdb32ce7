//! Hillaire (2020), "A Scalable and Production Ready Sky and Atmosphere Rendering Technique":
//! the f64 CPU twin of the GPU passes in `shaders/hillaire/`. Same parameterisations, same
//! step counts and the same arithmetic, so the GPU lookup tables can be checked texel by texel.
//!
//! Tables (each a function `compute_*`, each looked up by a `*_texel_from_*` /
//! `*_from_texel` pair of mappings):
//! - transmittance (h, mu) with Bruneton's (2017) mapping;
//! - multiple scattering Ψ_ms (h, mu_s): second order with an isotropic phase, summed as the
//!   geometric series 1/(1 − f_ms) (paper §5.5), ground bounce included;
//! - ground irradiance (mu_s): sky irradiance on the ground per unit solar irradiance, for the
//!   planet's ground lit by the sky (our addition; the paper lights only with the sun);
//! - sky view (azimuth from the sun, view zenith) at the camera's altitude, with the paper's
//!   quadratic latitude mapping that puts texels near the horizon;
//! - aerial perspective: in-scattering and transmittance along the directions that reach the
//!   ground, in distance slices. The paper stores it in camera froxels; we store it in the sky
//!   view's sun-aligned frame so that turning the camera or changing projection never rebuilds it.
//!
//! A camera above the atmosphere ray-marches every pixel (paper §6). Positions are handled as
//! altitude h with r² − R² = h(2R + h), which stays accurate in f32 at 1 m above the ground.
//! The sun disk is limb darkened; Earth's shadow comes from a penumbra over the sun's disk.

use crate::atmosphere::Atmosphere;
use crate::camera::{Camera, Projection};
use crate::constants::{SUN_ANGULAR_RADIUS_RAD, SUN_LIMB_DARKENING_U};
use crate::geometry::direction_from_angles;
use crate::phase;
use crate::scene::{AerosolPhase, Quality, Scene, WavelengthSet};
use crate::wavelengths::{LANES, WavelengthBatch, batches, to_linear_srgb};
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Four lanes (wavelengths) of one batch.
pub type Lanes = [f64; LANES];

/// Transmittance table size (mu, h): Hillaire's 256 × 64.
pub const TRANSMITTANCE_SIZE: [u32; 2] = [256, 64];
/// Multiple-scattering table size (mu_s, h): 32 × 32 as in the paper.
pub const MULTIPLE_SCATTERING_SIZE: [u32; 2] = [32, 32];
/// Ground irradiance table size (mu_s).
pub const GROUND_IRRADIANCE_SIZE: u32 = 64;
/// Sky-view table size (azimuth, zenith): 192 × 108 as in the paper; the height is even so that
/// the horizon falls between two rows and lookups never blend sky with ground.
pub const SKY_VIEW_SIZE: [u32; 2] = [192, 108];
/// Aerial-perspective volume (azimuth, zenith below the horizon, distance slices).
pub const AERIAL_PERSPECTIVE_SIZE: [u32; 3] = [32, 32, 32];
/// Distance covered by the aerial-perspective slices, m; farther ground uses the sky view.
pub const AERIAL_PERSPECTIVE_MAX_DISTANCE_M: f64 = 128_000.0;
/// Samples of the density profile table, spaced as h = H·x² (dense near the ground).
pub const PROFILE_SAMPLES: u32 = 256;
/// Directions of the multiple-scattering integral: an 8 × 8 stratified sphere (paper: 64).
pub const MULTIPLE_SCATTERING_DIRECTIONS_SQRT: u32 = 8;
/// Directions of the ground irradiance integral: 8 (cosine-weighted zenith) × 16 (azimuth).
pub const GROUND_IRRADIANCE_DIRECTIONS: [u32; 2] = [8, 16];
/// Optical thickness below which a segment's in-scattering weight uses its series expansion.
pub const SMALL_OPTICAL_THICKNESS: f64 = 1e-4;

/// Ray-marching sample counts, set by the scene's quality.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Steps {
    pub transmittance: u32,
    pub multiple_scattering: u32,
    pub ground_irradiance: u32,
    pub sky_view: u32,
    pub aerial_perspective_per_slice: u32,
    /// Per-pixel march when the camera is above the atmosphere.
    pub ray_march: u32,
}

impl Steps {
    pub fn for_quality(q: Quality) -> Steps {
        let k = match q {
            Quality::Low => 1,
            Quality::Medium => 2,
            Quality::High => 4,
        };
        Steps {
            transmittance: 32 * k,
            multiple_scattering: 10 * k,
            ground_irradiance: 12 * k,
            sky_view: 16 * k,
            aerial_perspective_per_slice: k,
            ray_march: 48 * k,
        }
    }
}

/// The optics of one batch of four wavelengths; coefficients are per unit of the profile.
#[derive(Debug, Clone, PartialEq)]
pub struct BatchOptics {
    pub colour: WavelengthBatch,
    /// Rayleigh scattering at the reference air density, m⁻¹.
    pub rayleigh_scattering: Lanes,
    pub rayleigh_depolarisation: Lanes,
    /// Ozone absorption at the reference ozone density, m⁻¹.
    pub ozone_absorption: Lanes,
    /// Aerosol scattering per unit of the aerosol profile (m⁻¹ per m⁻¹), i.e. AOD·SSA.
    pub aerosol_scattering: Lanes,
    /// Aerosol absorption per unit of the aerosol profile, AOD·(1 − SSA).
    pub aerosol_absorption: Lanes,
    pub aerosol_g: Lanes,
    /// Extraterrestrial solar irradiance, W·m⁻²·nm⁻¹.
    pub solar_irradiance: Lanes,
    pub ground_albedo: Lanes,
}

/// Everything the passes read that depends only on the atmosphere and the wavelength set: the
/// f64 original of the GPU's uniforms and storage buffers.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    pub bottom_radius_m: f64,
    pub top_radius_m: f64,
    pub aerosol_phase: AerosolPhase,
    /// Relative air, relative ozone and aerosol (m⁻¹) densities at h = H·(i/(n−1))², and 0.
    pub profile: Vec<[f64; 4]>,
    pub batches: Vec<BatchOptics>,
    pub steps: Steps,
}

impl Params {
    pub fn new(atm: &Atmosphere, set: WavelengthSet, quality: Quality) -> Params {
        let thickness = atm.thickness_m();
        let air_ref = atm.air_density_m3(0.0).max(f64::MIN_POSITIVE);
        let n = PROFILE_SAMPLES as usize;
        let heights: Vec<f64> = (0..n)
            .map(|i| thickness * (i as f64 / (n - 1) as f64).powi(2))
            .collect();
        let ozone_ref = heights
            .iter()
            .map(|&h| atm.ozone_density_m3(h))
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        let profile = heights
            .iter()
            .map(|&h| {
                let d = atm.densities(h);
                [
                    d.air_m3 / air_ref,
                    d.ozone_m3 / ozone_ref,
                    d.aerosol_per_m,
                    0.0,
                ]
            })
            .collect();
        let solar = atm.solar_spectrum;
        let batches = batches(set)
            .into_iter()
            .map(|colour| {
                let optics = colour.wavelengths_nm.map(|w| atm.optics(w));
                let lanes = |f: &dyn Fn(usize) -> f64| -> Lanes { std::array::from_fn(f) };
                let solar_irradiance = lanes(&|i| match colour.bandwidth_nm {
                    Some(width) => solar.irradiance(colour.wavelengths_nm[i], width),
                    None => solar.spectrum().sample(colour.wavelengths_nm[i]),
                });
                BatchOptics {
                    rayleigh_scattering: lanes(&|i| optics[i].rayleigh_cross_section_m2 * air_ref),
                    rayleigh_depolarisation: lanes(&|i| optics[i].rayleigh_depolarisation),
                    ozone_absorption: lanes(&|i| optics[i].ozone_cross_section_m2 * ozone_ref),
                    aerosol_scattering: lanes(&|i| {
                        optics[i].aerosol_optical_depth * optics[i].aerosol_ssa
                    }),
                    aerosol_absorption: lanes(&|i| {
                        optics[i].aerosol_optical_depth * (1.0 - optics[i].aerosol_ssa)
                    }),
                    aerosol_g: lanes(&|i| optics[i].aerosol_g),
                    solar_irradiance,
                    ground_albedo: [atm.ground_albedo; LANES],
                    colour,
                }
            })
            .collect();
        Params {
            bottom_radius_m: atm.bottom_radius_m,
            top_radius_m: atm.top_radius_m,
            aerosol_phase: atm.aerosol_phase,
            profile,
            batches,
            steps: Steps::for_quality(quality),
        }
    }

    pub fn thickness_m(&self) -> f64 {
        self.top_radius_m - self.bottom_radius_m
    }

    /// Profile values at altitude `h` (linear in the table's x = √(h/H)); zero above the top.
    pub fn densities(&self, h: f64) -> [f64; 3] {
        let thickness = self.thickness_m();
        if h > thickness {
            return [0.0; 3];
        }
        let n = self.profile.len();
        let x = (h.max(0.0) / thickness).sqrt() * (n - 1) as f64;
        let i = (x.floor() as usize).min(n - 2);
        let f = x - i as f64;
        let (a, b) = (self.profile[i], self.profile[i + 1]);
        std::array::from_fn(|k| a[k] + (b[k] - a[k]) * f)
    }

    /// Scattering (Rayleigh, aerosol) and extinction coefficients at altitude `h`, m⁻¹.
    pub fn medium(&self, batch: usize, h: f64) -> Medium {
        let [air, ozone, aerosol] = self.densities(h);
        let b = &self.batches[batch];
        let mut m = Medium::default();
        for i in 0..LANES {
            m.rayleigh_scattering[i] = b.rayleigh_scattering[i] * air;
            m.aerosol_scattering[i] = b.aerosol_scattering[i] * aerosol;
            m.extinction[i] = m.rayleigh_scattering[i]
                + m.aerosol_scattering[i]
                + b.ozone_absorption[i] * ozone
                + b.aerosol_absorption[i] * aerosol;
        }
        m
    }

    fn aerosol_phase(&self, nu: f64, g: f64) -> f64 {
        match self.aerosol_phase {
            AerosolPhase::HenyeyGreenstein => phase::henyey_greenstein(nu, g),
            AerosolPhase::CornetteShanks => phase::cornette_shanks(nu, g),
        }
    }
}

/// Local coefficients of one batch, m⁻¹.
#[derive(Debug, Clone, Copy, Default)]
pub struct Medium {
    pub rayleigh_scattering: Lanes,
    pub aerosol_scattering: Lanes,
    pub extinction: Lanes,
}

// ---------------------------------------------------------------------------------------------
// Geometry in (h, mu): every function has a WGSL twin in shaders/common/geometry.wgsl.

/// r² − R² for altitude `h` above a planet of radius `big_r`, cancellation-free.
pub fn rho_squared(h: f64, big_r: f64) -> f64 {
    h * (2.0 * big_r + h)
}

/// Whether the ray from altitude `h` with zenith cosine `mu` hits the ground.
pub fn hits_ground(h: f64, mu: f64, big_r: f64) -> bool {
    let r = big_r + h;
    mu < 0.0 && r * r * mu * mu - rho_squared(h, big_r) >= 0.0
}

/// Distance to the top of the atmosphere (radius `top`) from inside it. Each root is formed
/// without cancellation (the product of the roots is −(top² − r²)), which f32 needs.
pub fn distance_to_top(h: f64, mu: f64, big_r: f64, top: f64) -> f64 {
    let r = big_r + h;
    let rm = r * mu;
    let c = (top - big_r - h) * (top + r);
    let q = (rm * rm + c).max(0.0).sqrt();
    if rm > 0.0 {
        (c / (rm + q)).max(0.0)
    } else {
        -rm + q
    }
}

/// Distance to the ground along a ray that hits it, as (r² − R²)/(−r·mu + √disc) so that short
/// distances near the ground keep their precision in f32.
pub fn distance_to_ground(h: f64, mu: f64, big_r: f64) -> f64 {
    let rm = (big_r + h) * mu;
    let disc = (rm * rm - rho_squared(h, big_r)).max(0.0);
    let denom = -rm + disc.sqrt();
    if denom > 0.0 {
        rho_squared(h, big_r) / denom
    } else {
        0.0
    }
}

/// Distance to where the ray leaves the atmosphere: the ground if it hits it, else the top.
pub fn distance_to_boundary(h: f64, mu: f64, big_r: f64, top: f64) -> f64 {
    if hits_ground(h, mu, big_r) {
        distance_to_ground(h, mu, big_r)
    } else {
        distance_to_top(h, mu, big_r, top)
    }
}

/// Altitude and radius at distance `t` along the ray (h, mu).
pub fn altitude_along(h: f64, mu: f64, t: f64, big_r: f64) -> (f64, f64) {
    let r = big_r + h;
    let r_t = (r * r + t * t + 2.0 * r * mu * t).max(0.0).sqrt();
    let h_t = (rho_squared(h, big_r) + t * (t + 2.0 * r * mu)) / (r_t + big_r);
    (h_t, r_t)
}

/// (1 − e^(−σ·dt))/σ per lane: the in-scattering weight of a segment with constant source.
pub fn segment_weight(extinction: Lanes, dt: f64) -> Lanes {
    extinction.map(|s| {
        let x = s * dt;
        if x < SMALL_OPTICAL_THICKNESS {
            dt * (1.0 - 0.5 * x)
        } else {
            (1.0 - (-x).exp()) / s
        }
    })
}

// ---------------------------------------------------------------------------------------------
// Tables.

/// A table of `layers` batches, each `depth` × `height` × `width` texels of four lanes.
#[derive(Debug, Clone, PartialEq)]
pub struct Lut {
    pub width: usize,
    pub height: usize,
    pub depth: usize,
    pub layers: usize,
    pub data: Vec<Lanes>,
}

impl Lut {
    fn build(
        width: u32,
        height: u32,
        depth: u32,
        layers: usize,
        f: impl Fn(usize, usize, usize, usize) -> Lanes + Sync,
    ) -> Lut {
        let (w, h, d) = (width as usize, height as usize, depth as usize);
        let data = (0..layers * d * h * w)
            .into_par_iter()
            .map(|i| f(i / (d * h * w), (i / (h * w)) % d, (i / w) % h, i % w))
            .collect();
        Lut {
            width: w,
            height: h,
            depth: d,
            layers,
            data,
        }
    }

    /// Texel (x, y, z) of `layer`.
    pub fn texel(&self, layer: usize, x: usize, y: usize, z: usize) -> Lanes {
        self.data[((layer * self.depth + z) * self.height + y) * self.width + x]
    }

    /// Bilinear interpolation at fractional texel coordinates (clamped to the table), slice z.
    pub fn bilinear(&self, layer: usize, fx: f64, fy: f64, z: usize) -> Lanes {
        let (x0, x1, tx) = split(fx, self.width);
        let (y0, y1, ty) = split(fy, self.height);
        let a = lerp(
            self.texel(layer, x0, y0, z),
            self.texel(layer, x1, y0, z),
            tx,
        );
        let b = lerp(
            self.texel(layer, x0, y1, z),
            self.texel(layer, x1, y1, z),
            tx,
        );
        lerp(a, b, ty)
    }

    /// Trilinear interpolation at fractional texel coordinates (clamped to the table).
    pub fn trilinear(&self, layer: usize, fx: f64, fy: f64, fz: f64) -> Lanes {
        let (z0, z1, tz) = split(fz, self.depth);
        lerp(
            self.bilinear(layer, fx, fy, z0),
            self.bilinear(layer, fx, fy, z1),
            tz,
        )
    }
}

fn split(f: f64, n: usize) -> (usize, usize, f64) {
    let f = f.clamp(0.0, (n - 1) as f64);
    let i0 = f.floor() as usize;
    let i1 = (i0 + 1).min(n - 1);
    (i0, i1, f - i0 as f64)
}

fn lerp(a: Lanes, b: Lanes, t: f64) -> Lanes {
    std::array::from_fn(|i| a[i] + (b[i] - a[i]) * t)
}

fn add(a: Lanes, b: Lanes) -> Lanes {
    std::array::from_fn(|i| a[i] + b[i])
}

fn mul(a: Lanes, b: Lanes) -> Lanes {
    std::array::from_fn(|i| a[i] * b[i])
}

fn scale(a: Lanes, k: f64) -> Lanes {
    a.map(|v| v * k)
}

// ---- transmittance ----

/// Fractional texel coordinates of (h, mu) in the transmittance table (Bruneton 2017 §4.1).
pub fn transmittance_texel_from_h_mu(p: &Params, h: f64, mu: f64) -> (f64, f64) {
    let (big_r, top) = (p.bottom_radius_m, p.top_radius_m);
    let big_h = rho_squared(p.thickness_m(), big_r).sqrt();
    let rho = rho_squared(h.max(0.0), big_r).sqrt();
    let d = distance_to_top(h, mu, big_r, top);
    let d_min = p.thickness_m() - h;
    let d_max = rho + big_h;
    let x_mu = (d - d_min) / (d_max - d_min).max(1e-9);
    let x_r = rho / big_h;
    let [w, hh] = TRANSMITTANCE_SIZE;
    (x_mu * (w - 1) as f64, x_r * (hh - 1) as f64)
}

/// (h, mu) of the transmittance texel at fractional coordinates (fx, fy).
pub fn transmittance_h_mu_from_texel(p: &Params, fx: f64, fy: f64) -> (f64, f64) {
    let big_r = p.bottom_radius_m;
    let [w, hh] = TRANSMITTANCE_SIZE;
    let (x_mu, x_r) = (fx / (w - 1) as f64, fy / (hh - 1) as f64);
    let big_h = rho_squared(p.thickness_m(), big_r).sqrt();
    let rho = big_h * x_r;
    let h = rho * rho / ((rho * rho + big_r * big_r).sqrt() + big_r);
    let r = big_r + h;
    let d_min = p.thickness_m() - h;
    let d_max = rho + big_h;
    let d = d_min + x_mu * (d_max - d_min);
    let mu = if d <= 0.0 {
        1.0
    } else {
        ((big_h * big_h - rho * rho - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0)
    };
    (h, mu)
}

/// The transmittance table: exp(−∫ extinction) from (h, mu) to the top, midpoint rule on
/// quadratically spaced segments (dense where the air is dense).
pub fn compute_transmittance_lut(p: &Params) -> Lut {
    let [w, h] = TRANSMITTANCE_SIZE;
    Lut::build(w, h, 1, p.batches.len(), |layer, _, y, x| {
        let (h, mu) = transmittance_h_mu_from_texel(p, x as f64, y as f64);
        compute_transmittance(p, layer, h, mu)
    })
}

fn compute_transmittance(p: &Params, layer: usize, h: f64, mu: f64) -> Lanes {
    let big_r = p.bottom_radius_m;
    let t_max = distance_to_top(h, mu, big_r, p.top_radius_m);
    let n = p.steps.transmittance;
    let mut depth = [0.0; LANES];
    for i in 0..n {
        let (t0, t1) = Spacing::Quadratic.segment(0.0, t_max, i, n);
        let (h_t, _) = altitude_along(h, mu, 0.5 * (t0 + t1), big_r);
        let m = p.medium(layer, h_t);
        depth = add(depth, scale(m.extinction, t1 - t0));
    }
    depth.map(|d| (-d).exp())
}

/// Looks up the transmittance from (h, mu) to the top.
pub fn transmittance(p: &Params, t: &Lut, layer: usize, h: f64, mu: f64) -> Lanes {
    let (fx, fy) = transmittance_texel_from_h_mu(p, h, mu);
    t.bilinear(layer, fx, fy, 0)
}

/// Transmittance to the sun from (h, mu_s), times the visible fraction of the sun's disk above
/// the horizon (Earth's shadow with its penumbra, as in Bruneton 2017).
pub fn sun_transmittance(p: &Params, t: &Lut, layer: usize, h: f64, mu_s: f64) -> Lanes {
    let big_r = p.bottom_radius_m;
    let r = big_r + h;
    let sin_h = big_r / r;
    let cos_h = -(1.0 - sin_h * sin_h).max(0.0).sqrt();
    let edge = sin_h * SUN_ANGULAR_RADIUS_RAD;
    let visible = smoothstep(-edge, edge, mu_s - cos_h);
    scale(transmittance(p, t, layer, h, mu_s), visible)
}

fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

// ---- multiple scattering ----

/// Fractional texel coordinates of (h, mu_s) in the multiple-scattering table.
pub fn multiple_scattering_texel_from_h_mu_s(p: &Params, h: f64, mu_s: f64) -> (f64, f64) {
    let [w, hh] = MULTIPLE_SCATTERING_SIZE;
    (
        (mu_s * 0.5 + 0.5) * (w - 1) as f64,
        (h / p.thickness_m()) * (hh - 1) as f64,
    )
}

/// (h, mu_s) of the multiple-scattering texel at fractional coordinates (fx, fy).
pub fn multiple_scattering_h_mu_s_from_texel(p: &Params, fx: f64, fy: f64) -> (f64, f64) {
    let [w, hh] = MULTIPLE_SCATTERING_SIZE;
    (
        fy / (hh - 1) as f64 * p.thickness_m(),
        (fx / (w - 1) as f64 * 2.0 - 1.0).clamp(-1.0, 1.0),
    )
}

/// Direction `i` of an n × n stratified grid over the sphere (uniform in mu and azimuth).
fn sphere_direction(i: u32, n: u32) -> DVec3 {
    let mu = 1.0 - 2.0 * ((i / n) as f64 + 0.5) / n as f64;
    let phi = 2.0 * PI * ((i % n) as f64 + 0.5) / n as f64;
    let s = (1.0 - mu * mu).max(0.0).sqrt();
    DVec3::new(s * phi.cos(), s * phi.sin(), mu)
}

fn local_sun(mu_s: f64) -> DVec3 {
    DVec3::new((1.0 - mu_s * mu_s).max(0.0).sqrt(), 0.0, mu_s)
}

/// Ψ_ms per unit solar irradiance (sr⁻¹): L_2nd/(1 − f_ms), paper eq. 5–10.
pub fn compute_multiple_scattering_lut(p: &Params, t: &Lut) -> Lut {
    let [w, h] = MULTIPLE_SCATTERING_SIZE;
    Lut::build(w, h, 1, p.batches.len(), |layer, _, y, x| {
        let (h, mu_s) = multiple_scattering_h_mu_s_from_texel(p, x as f64, y as f64);
        compute_multiple_scattering(p, t, layer, h, mu_s)
    })
}

fn compute_multiple_scattering(p: &Params, t: &Lut, layer: usize, h: f64, mu_s: f64) -> Lanes {
    let big_r = p.bottom_radius_m;
    let r = big_r + h;
    let sun = local_sun(mu_s);
    let n_dir = MULTIPLE_SCATTERING_DIRECTIONS_SQRT;
    let isotropic = 1.0 / (4.0 * PI);
    let albedo = p.batches[layer].ground_albedo;
    let mut l_2nd = [0.0; LANES];
    let mut f_ms = [0.0; LANES];
    for d in 0..n_dir * n_dir {
        let omega = sphere_direction(d, n_dir);
        let (mu, nu) = (omega.z, omega.dot(sun));
        let ground = hits_ground(h, mu, big_r);
        let t_max = if ground {
            distance_to_ground(h, mu, big_r)
        } else {
            distance_to_top(h, mu, big_r, p.top_radius_m)
        };
        let n = p.steps.multiple_scattering;
        let mut throughput = [1.0; LANES];
        for s in 0..n {
            let (t0, t1) = Spacing::Quadratic.segment(0.0, t_max, s, n);
            let (ts, dt) = (0.5 * (t0 + t1), t1 - t0);
            let (h_t, r_t) = altitude_along(h, mu, ts, big_r);
            let mu_s_t = (r * mu_s + ts * nu) / r_t;
            let m = p.medium(layer, h_t);
            let weight = mul(throughput, segment_weight(m.extinction, dt));
            let sca = add(m.rayleigh_scattering, m.aerosol_scattering);
            let sun_t = sun_transmittance(p, t, layer, h_t, mu_s_t);
            for i in 0..LANES {
                l_2nd[i] += weight[i] * sca[i] * isotropic * sun_t[i];
                f_ms[i] += weight[i] * sca[i];
                throughput[i] *= (-m.extinction[i] * dt).exp();
            }
        }
        if ground {
            let mu_s_g = (r * mu_s + t_max * nu) / big_r;
            let sun_t = sun_transmittance(p, t, layer, 0.0, mu_s_g);
            for i in 0..LANES {
                l_2nd[i] += throughput[i] * sun_t[i] * mu_s_g.max(0.0) * albedo[i] / PI;
            }
        }
    }
    let count = (n_dir * n_dir) as f64;
    std::array::from_fn(|i| (l_2nd[i] / count) / (1.0 - f_ms[i] / count))
}

/// Looks up Ψ_ms at (h, mu_s).
pub fn multiple_scattering(p: &Params, ms: &Lut, layer: usize, h: f64, mu_s: f64) -> Lanes {
    let (fx, fy) = multiple_scattering_texel_from_h_mu_s(p, h, mu_s);
    ms.bilinear(layer, fx, fy, 0)
}

// ---- in-scattering along a ray ----

/// How samples are spread along a march.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Spacing {
    Uniform,
    /// t ∝ s²: dense near the start (the camera), as in the paper's sky-view march.
    Quadratic,
    /// Dense near the end: rays from space down to the ground.
    QuadraticToEnd,
}

impl Spacing {
    /// Segment `i` of `n` over [t_start, t_end].
    pub fn segment(self, t_start: f64, t_end: f64, i: u32, n: u32) -> (f64, f64) {
        let length = t_end - t_start;
        let at = |s: f64| {
            let x = s / n as f64;
            match self {
                Spacing::Uniform => t_start + length * x,
                Spacing::Quadratic => t_start + length * x * x,
                Spacing::QuadraticToEnd => t_end - length * (1.0 - x) * (1.0 - x),
            }
        };
        (at(i as f64), at(i as f64 + 1.0))
    }
}

/// In-scattered radiance (per unit solar irradiance) and transmittance along the ray from
/// (h, mu) over [0, t_max], with the sun at zenith cosine `mu_s` and view–sun cosine `nu`.
#[allow(clippy::too_many_arguments)]
pub fn integrate_inscattering(
    p: &Params,
    t_lut: &Lut,
    ms: &Lut,
    layer: usize,
    (h, mu, mu_s, nu): (f64, f64, f64, f64),
    (t_start, t_end): (f64, f64),
    steps: u32,
    spacing: Spacing,
) -> (Lanes, Lanes) {
    let big_r = p.bottom_radius_m;
    let r = big_r + h;
    let b = &p.batches[layer];
    let rayleigh_phase = b
        .rayleigh_depolarisation
        .map(|rho| phase::rayleigh(nu, rho));
    let aerosol_phase = b.aerosol_g.map(|g| p.aerosol_phase(nu, g));
    let mut inscattered = [0.0; LANES];
    let mut throughput = [1.0; LANES];
    for s in 0..steps {
        let (t0, t1) = spacing.segment(t_start, t_end, s, steps);
        let dt = t1 - t0;
        let ts = 0.5 * (t0 + t1);
        let (h_t, r_t) = altitude_along(h, mu, ts, big_r);
        let mu_s_t = ((r * mu_s + ts * nu) / r_t).clamp(-1.0, 1.0);
        let m = p.medium(layer, h_t);
        let sun_t = sun_transmittance(p, t_lut, layer, h_t, mu_s_t);
        let psi = multiple_scattering(p, ms, layer, h_t, mu_s_t);
        let weight = mul(throughput, segment_weight(m.extinction, dt));
        for i in 0..LANES {
            let source = (m.rayleigh_scattering[i] * rayleigh_phase[i]
                + m.aerosol_scattering[i] * aerosol_phase[i])
                * sun_t[i]
                + (m.rayleigh_scattering[i] + m.aerosol_scattering[i]) * psi[i];
            inscattered[i] += weight[i] * source;
            throughput[i] *= (-m.extinction[i] * dt).exp();
        }
    }
    (inscattered, throughput)
}

// ---- ground irradiance ----

/// Fractional texel coordinate of mu_s in the ground irradiance table.
pub fn ground_irradiance_texel_from_mu_s(mu_s: f64) -> f64 {
    (mu_s * 0.5 + 0.5) * (GROUND_IRRADIANCE_SIZE - 1) as f64
}

/// mu_s of the ground irradiance texel at fractional coordinate fx.
pub fn ground_irradiance_mu_s_from_texel(fx: f64) -> f64 {
    (fx / (GROUND_IRRADIANCE_SIZE - 1) as f64 * 2.0 - 1.0).clamp(-1.0, 1.0)
}

/// Sky irradiance on horizontal ground per unit solar irradiance, by cosine-weighted
/// stratified directions over the upper hemisphere (E = π·mean L).
pub fn compute_ground_irradiance_lut(p: &Params, t: &Lut, ms: &Lut) -> Lut {
    Lut::build(
        GROUND_IRRADIANCE_SIZE,
        1,
        1,
        p.batches.len(),
        |layer, _, _, x| {
            let mu_s = ground_irradiance_mu_s_from_texel(x as f64);
            compute_ground_irradiance(p, t, ms, layer, mu_s)
        },
    )
}

fn compute_ground_irradiance(p: &Params, t: &Lut, ms: &Lut, layer: usize, mu_s: f64) -> Lanes {
    let [n_theta, n_phi] = GROUND_IRRADIANCE_DIRECTIONS;
    let sun = local_sun(mu_s);
    let mut sum = [0.0; LANES];
    for i in 0..n_theta {
        let mu = ((i as f64 + 0.5) / n_theta as f64).sqrt();
        let s = (1.0 - mu * mu).sqrt();
        for j in 0..n_phi {
            let phi = 2.0 * PI * (j as f64 + 0.5) / n_phi as f64;
            let nu = DVec3::new(s * phi.cos(), s * phi.sin(), mu).dot(sun);
            let t_max = distance_to_top(0.0, mu, p.bottom_radius_m, p.top_radius_m);
            let (l, _) = integrate_inscattering(
                p,
                t,
                ms,
                layer,
                (0.0, mu, mu_s, nu),
                (0.0, t_max),
                p.steps.ground_irradiance,
                Spacing::Quadratic,
            );
            sum = add(sum, l);
        }
    }
    scale(sum, PI / (n_theta * n_phi) as f64)
}

/// Looks up the sky irradiance on the ground per unit solar irradiance.
pub fn ground_irradiance(gi: &Lut, layer: usize, mu_s: f64) -> Lanes {
    gi.bilinear(layer, ground_irradiance_texel_from_mu_s(mu_s), 0.0, 0)
}

// ---- sky view ----

/// Where the camera is, for the tables that depend on it: altitude and the sun's zenith cosine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Viewpoint {
    pub h: f64,
    pub mu_s: f64,
}

/// Angle between the nadir and the horizon seen from altitude `h` (β in the paper).
pub fn horizon_beta(h: f64, big_r: f64) -> f64 {
    big_r.atan2(rho_squared(h.max(0.0), big_r).sqrt())
}

/// Fractional texel coordinates of (azimuth from the sun φ ∈ [0, π], view zenith θ ∈ [0, π])
/// in the sky-view table at altitude `h`. Rows above the middle are sky, below are ground.
pub fn sky_view_texel_from_angles(p: &Params, h: f64, phi: f64, theta: f64) -> (f64, f64) {
    let beta = horizon_beta(h, p.bottom_radius_m);
    let theta_h = PI - beta;
    let v = if theta < theta_h {
        0.5 * (1.0 - (1.0 - theta / theta_h).max(0.0).sqrt())
    } else {
        0.5 + 0.5 * ((theta - theta_h) / beta).clamp(0.0, 1.0).sqrt()
    };
    let u = (phi / PI).clamp(0.0, 1.0).sqrt();
    let [w, hh] = SKY_VIEW_SIZE;
    (u * (w - 1) as f64, v * (hh - 1) as f64)
}

/// (φ, θ) of the sky-view texel at fractional coordinates (fx, fy) for altitude `h`.
pub fn sky_view_angles_from_texel(p: &Params, h: f64, fx: f64, fy: f64) -> (f64, f64) {
    let beta = horizon_beta(h, p.bottom_radius_m);
    let theta_h = PI - beta;
    let [w, hh] = SKY_VIEW_SIZE;
    let (u, v) = (fx / (w - 1) as f64, fy / (hh - 1) as f64);
    let theta = if v < 0.5 {
        let c = 1.0 - 2.0 * v;
        theta_h * (1.0 - c * c)
    } else {
        let c = 2.0 * v - 1.0;
        theta_h + beta * c * c
    };
    (PI * u * u, theta)
}

fn direction_from_phi_theta(phi: f64, theta: f64) -> DVec3 {
    DVec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

/// Sky-view table: in-scattered radiance (W·m⁻²·sr⁻¹·nm⁻¹) to the top or the ground.
pub fn compute_sky_view_lut(p: &Params, t: &Lut, ms: &Lut, vp: Viewpoint) -> Lut {
    let [w, h] = SKY_VIEW_SIZE;
    Lut::build(w, h, 1, p.batches.len(), |layer, _, y, x| {
        let (phi, theta) = sky_view_angles_from_texel(p, vp.h, x as f64, y as f64);
        let omega = direction_from_phi_theta(phi, theta);
        let (mu, nu) = (omega.z, omega.dot(local_sun(vp.mu_s)));
        let big_r = p.bottom_radius_m;
        let t_max = distance_to_boundary(vp.h, mu, big_r, p.top_radius_m);
        let (l, _) = integrate_inscattering(
            p,
            t,
            ms,
            layer,
            (vp.h, mu, vp.mu_s, nu),
            (0.0, t_max),
            p.steps.sky_view,
            Spacing::Quadratic,
        );
        mul(l, p.batches[layer].solar_irradiance)
    })
}

/// Looks up the sky view; `ground` picks the half of the table (never blended across).
pub fn sky_view(
    p: &Params,
    sv: &Lut,
    layer: usize,
    h: f64,
    phi: f64,
    theta: f64,
    ground: bool,
) -> Lanes {
    let (fx, fy) = sky_view_texel_from_angles(p, h, phi, theta);
    let half = (SKY_VIEW_SIZE[1] / 2) as f64;
    let fy = if ground {
        fy.max(half)
    } else {
        fy.min(half - 1.0)
    };
    sv.bilinear(layer, fx, fy, 0)
}

// ---- aerial perspective ----

/// Fractional texel coordinates (x, y) of a ground-bound direction in the aerial-perspective
/// volume: φ as in the sky view, θ over [θ_horizon, π] with the same quadratic spacing.
/// Rows sit at cell centres so that none is the horizon ray itself (whose ground hit is a coin
/// toss between f32 and f64).
pub fn aerial_perspective_texel_from_angles(
    p: &Params,
    h: f64,
    phi: f64,
    theta: f64,
) -> (f64, f64) {
    let beta = horizon_beta(h, p.bottom_radius_m);
    let v = ((theta - (PI - beta)) / beta).clamp(0.0, 1.0).sqrt();
    let u = (phi / PI).clamp(0.0, 1.0).sqrt();
    let [w, hh, _] = AERIAL_PERSPECTIVE_SIZE;
    (u * (w - 1) as f64, v * hh as f64 - 0.5)
}

/// (φ, θ) of the aerial-perspective column at fractional coordinates (fx, fy).
pub fn aerial_perspective_angles_from_texel(p: &Params, h: f64, fx: f64, fy: f64) -> (f64, f64) {
    let beta = horizon_beta(h, p.bottom_radius_m);
    let [w, hh, _] = AERIAL_PERSPECTIVE_SIZE;
    let (u, v) = (fx / (w - 1) as f64, (fy + 0.5) / hh as f64);
    (PI * u * u, PI - beta + beta * v * v)
}

/// Distance (m) at the far end of slice `k`: D·((k + 1)/K)².
pub fn aerial_perspective_slice_distance(k: u32) -> f64 {
    let n = AERIAL_PERSPECTIVE_SIZE[2] as f64;
    AERIAL_PERSPECTIVE_MAX_DISTANCE_M * ((k as f64 + 1.0) / n).powi(2)
}

/// Fractional slice coordinate of distance `d`; negative before the first slice's end.
pub fn aerial_perspective_slice_from_distance(d: f64) -> f64 {
    let n = AERIAL_PERSPECTIVE_SIZE[2] as f64;
    (d / AERIAL_PERSPECTIVE_MAX_DISTANCE_M).max(0.0).sqrt() * n - 1.0
}

/// The aerial-perspective volume: (in-scattered radiance, transmittance) from the camera to the
/// end of each slice, stopping at the ground.
pub fn compute_aerial_perspective(p: &Params, t: &Lut, ms: &Lut, vp: Viewpoint) -> (Lut, Lut) {
    let [w, hh, d] = AERIAL_PERSPECTIVE_SIZE;
    let big_r = p.bottom_radius_m;
    // One march per column, as on the GPU; then split into the two volumes.
    let columns: Vec<Vec<(Lanes, Lanes)>> = (0..p.batches.len() * (w * hh) as usize)
        .into_par_iter()
        .map(|i| {
            let layer = i / (w * hh) as usize;
            let (y, x) = ((i / w as usize) % hh as usize, i % w as usize);
            let (phi, theta) = aerial_perspective_angles_from_texel(p, vp.h, x as f64, y as f64);
            let omega = direction_from_phi_theta(phi, theta);
            let (mu, nu) = (omega.z, omega.dot(local_sun(vp.mu_s)));
            let t_limit = distance_to_boundary(vp.h, mu, big_r, p.top_radius_m);
            let e = p.batches[layer].solar_irradiance;
            let mut inscattered = [0.0; LANES];
            let mut throughput = [1.0; LANES];
            let mut start = 0.0;
            (0..d)
                .map(|k| {
                    let end = aerial_perspective_slice_distance(k).min(t_limit);
                    if end > start {
                        let (l, tr) = integrate_inscattering(
                            p,
                            t,
                            ms,
                            layer,
                            (vp.h, mu, vp.mu_s, nu),
                            (start, end),
                            p.steps.aerial_perspective_per_slice,
                            Spacing::Uniform,
                        );
                        inscattered = add(inscattered, mul(throughput, mul(l, e)));
                        throughput = mul(throughput, tr);
                        start = end;
                    }
                    (inscattered, throughput)
                })
                .collect()
        })
        .collect();
    let pick = |which: usize| Lut {
        width: w as usize,
        height: hh as usize,
        depth: d as usize,
        layers: p.batches.len(),
        data: (0..p.batches.len() * (d * hh * w) as usize)
            .map(|i| {
                let (w, hh, d) = (w as usize, hh as usize, d as usize);
                let layer = i / (d * hh * w);
                let (z, y, x) = ((i / (hh * w)) % d, (i / w) % hh, i % w);
                let c = &columns[(layer * hh + y) * w + x][z];
                if which == 0 { c.0 } else { c.1 }
            })
            .collect(),
    };
    (pick(0), pick(1))
}

/// Looks up (in-scattered radiance, transmittance) at distance `d` along a ground-bound
/// direction; before the first slice it blends from (0, 1).
#[allow(clippy::too_many_arguments)]
pub fn aerial_perspective(
    p: &Params,
    inscattering: &Lut,
    transmittance: &Lut,
    layer: usize,
    h: f64,
    phi: f64,
    theta: f64,
    d: f64,
) -> (Lanes, Lanes) {
    let (fx, fy) = aerial_perspective_texel_from_angles(p, h, phi, theta);
    let fz = aerial_perspective_slice_from_distance(d);
    let s = inscattering.trilinear(layer, fx, fy, fz.max(0.0));
    let tr = transmittance.trilinear(layer, fx, fy, fz.max(0.0));
    if fz >= 0.0 {
        (s, tr)
    } else {
        let k = fz + 1.0;
        (scale(s, k), lerp([1.0; LANES], tr, k))
    }
}

// ---- the view ----

/// Every table of the method for one atmosphere and viewpoint.
#[derive(Debug, Clone)]
pub struct Tables {
    pub transmittance: Lut,
    pub multiple_scattering: Lut,
    pub ground_irradiance: Lut,
    pub sky_view: Lut,
    pub aerial_perspective_inscattering: Lut,
    pub aerial_perspective_transmittance: Lut,
    pub viewpoint: Viewpoint,
}

impl Tables {
    pub fn compute(p: &Params, vp: Viewpoint) -> Tables {
        let transmittance = compute_transmittance_lut(p);
        let multiple_scattering = compute_multiple_scattering_lut(p, &transmittance);
        let ground_irradiance =
            compute_ground_irradiance_lut(p, &transmittance, &multiple_scattering);
        let sky_view = compute_sky_view_lut(p, &transmittance, &multiple_scattering, vp);
        let (ap_s, ap_t) = compute_aerial_perspective(p, &transmittance, &multiple_scattering, vp);
        Tables {
            transmittance,
            multiple_scattering,
            ground_irradiance,
            sky_view,
            aerial_perspective_inscattering: ap_s,
            aerial_perspective_transmittance: ap_t,
            viewpoint: vp,
        }
    }
}

/// Radiance of the sun's disk in direction `dir` (0 outside it), per unit solar irradiance:
/// limb darkened with the linear law I(μ′) ∝ 1 − u(1 − μ′), normalised to the disk's mean.
pub fn sun_disk(dir: DVec3, sun: DVec3) -> f64 {
    if dir.dot(sun) <= 0.0 {
        return 0.0;
    }
    let gamma = dir.cross(sun).length().min(1.0).asin();
    if gamma >= SUN_ANGULAR_RADIUS_RAD {
        return 0.0;
    }
    let x = gamma / SUN_ANGULAR_RADIUS_RAD;
    let mu_prime = (1.0 - x * x).sqrt();
    let limb = (1.0 - SUN_LIMB_DARKENING_U * (1.0 - mu_prime)) / (1.0 - SUN_LIMB_DARKENING_U / 3.0);
    let half = 0.5 * SUN_ANGULAR_RADIUS_RAD;
    let solid_angle = 4.0 * PI * half.sin() * half.sin();
    limb / solid_angle
}

/// Radiance of the sunlit, skylit Lambertian ground at a point where the sun's zenith cosine
/// is `mu_s_g`, per lane (W·m⁻²·sr⁻¹·nm⁻¹).
fn ground_radiance(p: &Params, tables: &Tables, layer: usize, mu_s_g: f64) -> Lanes {
    let b = &p.batches[layer];
    let sun_t = sun_transmittance(p, &tables.transmittance, layer, 0.0, mu_s_g);
    let sky = ground_irradiance(&tables.ground_irradiance, layer, mu_s_g);
    std::array::from_fn(|i| {
        b.ground_albedo[i] / PI * b.solar_irradiance[i] * (sun_t[i] * mu_s_g.max(0.0) + sky[i])
    })
}

/// The radiance of one batch seen from `position` (m from the planet's centre, altitude `h`)
/// along the unit direction `dir`, with the sun in direction `sun`.
pub fn radiance(
    p: &Params,
    tables: &Tables,
    layer: usize,
    (position, h): (DVec3, f64),
    dir: DVec3,
    sun: DVec3,
) -> Lanes {
    let big_r = p.bottom_radius_m;
    let top = p.top_radius_m;
    let thickness = p.thickness_m();
    let e = p.batches[layer].solar_irradiance;
    let r = big_r + h;
    let up = position.normalize();
    let (mu, mu_s, nu) = (dir.dot(up), sun.dot(up), dir.dot(sun));
    let disk = sun_disk(dir, sun);
    if h <= thickness {
        let dir_t = dir - up * mu;
        let sun_t = sun - up * mu_s;
        let l = dir_t.length() * sun_t.length();
        let cos_phi = if l > 1e-12 { dir_t.dot(sun_t) / l } else { 1.0 };
        let phi = cos_phi.clamp(-1.0, 1.0).acos();
        let theta = mu.clamp(-1.0, 1.0).acos();
        if hits_ground(h, mu, big_r) {
            let d = distance_to_ground(h, mu, big_r);
            let mu_s_g = ((r * mu_s + d * nu) / big_r).clamp(-1.0, 1.0);
            let lg = ground_radiance(p, tables, layer, mu_s_g);
            let (s, tr) = if d < AERIAL_PERSPECTIVE_MAX_DISTANCE_M {
                aerial_perspective(
                    p,
                    &tables.aerial_perspective_inscattering,
                    &tables.aerial_perspective_transmittance,
                    layer,
                    h,
                    phi,
                    theta,
                    d,
                )
            } else {
                let mu_g = ((r * mu + d) / big_r).clamp(-1.0, 1.0);
                let t_g = transmittance(p, &tables.transmittance, layer, 0.0, -mu_g);
                let t_c = transmittance(p, &tables.transmittance, layer, h, -mu);
                let tr = std::array::from_fn(|i| (t_g[i] / t_c[i].max(1e-30)).min(1.0));
                (
                    sky_view(p, &tables.sky_view, layer, h, phi, theta, true),
                    tr,
                )
            };
            add(s, mul(tr, lg))
        } else {
            let s = sky_view(p, &tables.sky_view, layer, h, phi, theta, false);
            let tr = transmittance(p, &tables.transmittance, layer, h, mu);
            std::array::from_fn(|i| s[i] + tr[i] * e[i] * disk)
        }
    } else {
        // Above the atmosphere: march from where the ray enters it.
        let disc = r * r * mu * mu - (h - thickness) * (r + top);
        if mu >= 0.0 || disc < 0.0 {
            return e.map(|e| e * disk);
        }
        let t_entry = -r * mu - disc.sqrt();
        let mu_e = ((r * mu + t_entry) / top).clamp(-1.0, 1.0);
        let mu_s_e = ((r * mu_s + t_entry * nu) / top).clamp(-1.0, 1.0);
        let ground = hits_ground(thickness, mu_e, big_r);
        let t_max = if ground {
            distance_to_ground(thickness, mu_e, big_r)
        } else {
            distance_to_top(thickness, mu_e, big_r, top)
        };
        let (s, tr) = integrate_inscattering(
            p,
            &tables.transmittance,
            &tables.multiple_scattering,
            layer,
            (thickness, mu_e, mu_s_e, nu),
            (0.0, t_max),
            p.steps.ray_march,
            if ground {
                Spacing::QuadraticToEnd
            } else {
                Spacing::Uniform
            },
        );
        let behind = if ground {
            let mu_s_g = ((top * mu_s_e + t_max * nu) / big_r).clamp(-1.0, 1.0);
            ground_radiance(p, tables, layer, mu_s_g)
        } else {
            e.map(|e| e * disk)
        };
        std::array::from_fn(|i| s[i] * e[i] + tr[i] * behind[i])
    }
}

/// The scene's viewpoint for the sky-view and aerial-perspective tables.
pub fn viewpoint(scene: &Scene, camera: &Camera) -> Viewpoint {
    let a = scene.sun.angles();
    let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
    Viewpoint {
        h: scene.camera.altitude_m,
        mu_s: sun.dot(camera.position.normalize()),
    }
}

/// CPU render of a whole view: linear sRGB per pixel (row-major, top row first; zero where the
/// projection shows nothing), sampled at pixel centres.
pub fn render(scene: &Scene, projection: Projection, width: u32, height: u32) -> Vec<[f64; 3]> {
    let atm = Atmosphere::new(&scene.atmosphere);
    let p = Params::new(&atm, scene.render.wavelengths, scene.render.quality);
    let camera = Camera::new(&scene.camera, atm.bottom_radius_m, projection);
    let tables = Tables::compute(&p, viewpoint(scene, &camera));
    render_with(&p, &tables, scene, &camera, width, height)
}

/// CPU render with tables already computed.
pub fn render_with(
    p: &Params,
    tables: &Tables,
    scene: &Scene,
    camera: &Camera,
    width: u32,
    height: u32,
) -> Vec<[f64; 3]> {
    let a = scene.sun.angles();
    let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
    let colours: Vec<WavelengthBatch> = p.batches.iter().map(|b| b.colour.clone()).collect();
    (0..width * height)
        .into_par_iter()
        .map(|i| {
            let (x, y) = (i % width, i / width);
            match camera.ray(x as f64 + 0.5, y as f64 + 0.5, width, height) {
                None => [0.0; 3],
                Some(ray) => {
                    let lanes: Vec<Lanes> = (0..p.batches.len())
                        .map(|layer| {
                            radiance(
                                p,
                                tables,
                                layer,
                                (ray.origin, scene.camera.altitude_m),
                                ray.direction,
                                sun,
                            )
                        })
                        .collect();
                    to_linear_srgb(&colours, &lanes)
                }
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    fn params() -> Params {
        let scene = Scene::default();
        Params::new(
            &Atmosphere::new(&scene.atmosphere),
            WavelengthSet::Spectral4,
            Quality::Medium,
        )
    }

    #[test]
    fn transmittance_mapping_round_trips() {
        let p = params();
        for &(h, mu) in &[
            (0.0, 1.0),
            (0.0, 0.001),
            (10_000.0, 0.3),
            (50_000.0, -0.05),
            (99_000.0, 0.9),
        ] {
            let (fx, fy) = transmittance_texel_from_h_mu(&p, h, mu);
            let (h2, mu2) = transmittance_h_mu_from_texel(&p, fx, fy);
            assert!((h2 - h).abs() < 1e-6 * (1.0 + h), "h {h} -> {h2}");
            assert!((mu2 - mu).abs() < 1e-9, "mu {mu} -> {mu2} at h {h}");
        }
    }

    #[test]
    fn multiple_scattering_and_ground_mappings_round_trip() {
        let p = params();
        for &(h, mu_s) in &[(0.0, -1.0), (1234.0, 0.2), (100_000.0, 1.0)] {
            let (fx, fy) = multiple_scattering_texel_from_h_mu_s(&p, h, mu_s);
            let (h2, mu_s2) = multiple_scattering_h_mu_s_from_texel(&p, fx, fy);
            assert!((h2 - h).abs() < 1e-6 && (mu_s2 - mu_s).abs() < 1e-12);
            let mu_s3 = ground_irradiance_mu_s_from_texel(ground_irradiance_texel_from_mu_s(mu_s));
            assert!((mu_s3 - mu_s).abs() < 1e-12);
        }
    }

    #[test]
    fn sky_view_and_aerial_perspective_mappings_round_trip() {
        let p = params();
        for &h in &[1.0, 1000.0, 60_000.0] {
            let beta = horizon_beta(h, p.bottom_radius_m);
            for &(phi, theta) in &[
                (0.0, 0.0),
                (0.3, 1.0),
                (2.0, PI - beta - 1e-3),
                (3.0, PI - 0.5 * beta),
                (PI, PI),
            ] {
                let (fx, fy) = sky_view_texel_from_angles(&p, h, phi, theta);
                let (phi2, theta2) = sky_view_angles_from_texel(&p, h, fx, fy);
                assert!(
                    (phi2 - phi).abs() < 1e-9 && (theta2 - theta).abs() < 1e-9,
                    "h {h}: ({phi}, {theta}) -> ({phi2}, {theta2})"
                );
                let ground = theta > PI - beta;
                let half = (SKY_VIEW_SIZE[1] / 2) as f64;
                assert_eq!(
                    fy >= half - 0.5,
                    ground,
                    "the horizon splits the rows at h {h}"
                );
                if ground {
                    let (fx, fy) = aerial_perspective_texel_from_angles(&p, h, phi, theta);
                    let (phi3, theta3) = aerial_perspective_angles_from_texel(&p, h, fx, fy);
                    assert!((phi3 - phi).abs() < 1e-9 && (theta3 - theta).abs() < 1e-9);
                }
            }
        }
        for k in 0..AERIAL_PERSPECTIVE_SIZE[2] {
            let f = aerial_perspective_slice_from_distance(aerial_perspective_slice_distance(k));
            assert!((f - k as f64).abs() < 1e-9);
        }
    }

    #[test]
    fn zenith_transmittance_matches_the_exact_optical_depth() {
        let scene = Scene::default();
        let atm = Atmosphere::new(&scene.atmosphere);
        let p = Params::new(&atm, WavelengthSet::Spectral4, Quality::High);
        let t = compute_transmittance_lut(&p);
        for (lane, &w) in p.batches[0].colour.wavelengths_nm.iter().enumerate() {
            for &(h, mu) in &[(0.0, 1.0), (0.0, 0.2), (5000.0, 0.5)] {
                let ray = crate::geometry::Ray::new(
                    DVec3::new(0.0, 0.0, atm.bottom_radius_m + h),
                    DVec3::new((1.0_f64 - mu * mu).sqrt(), 0.0, mu),
                );
                let exact = (-atm.optical_depth(&atm.optics(w), &ray).total()).exp();
                let lut = transmittance(&p, &t, 0, h, mu)[lane];
                assert!(
                    (lut - exact).abs() < 2e-3,
                    "{w} nm, h {h}, mu {mu}: LUT {lut} vs exact {exact}"
                );
            }
        }
    }

    #[test]
    fn the_sun_disk_integrates_to_one() {
        let sun = DVec3::Z;
        let n = 400;
        let a = SUN_ANGULAR_RADIUS_RAD;
        let mut sum = 0.0;
        // Rings of the disk: ∫ L dΩ = Σ L(γ)·2π sin γ dγ.
        for i in 0..n {
            let gamma = (i as f64 + 0.5) / n as f64 * a;
            let dir = DVec3::new(gamma.sin(), 0.0, gamma.cos());
            sum += sun_disk(dir, sun) * 2.0 * PI * gamma.sin() * a / n as f64;
        }
        assert!((sum - 1.0).abs() < 1e-3, "{sum}");
        assert_eq!(sun_disk(DVec3::X, sun), 0.0);
    }

    #[test]
    fn the_clear_sky_is_blue_the_ground_is_lit_and_space_is_black() {
        let mut scene = Scene::default();
        scene.render.quality = Quality::Low;
        let atm = Atmosphere::new(&scene.atmosphere);
        let p = Params::new(&atm, WavelengthSet::Spectral4, Quality::Low);
        let camera = Camera::new(&scene.camera, atm.bottom_radius_m, Projection::Perspective);
        let tables = Tables::compute(&p, viewpoint(&scene, &camera));
        let a = scene.sun.angles();
        let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
        let colours = [p.batches[0].colour.clone()];
        let look = |dir: DVec3| {
            let l = radiance(
                &p,
                &tables,
                0,
                (camera.position, scene.camera.altitude_m),
                dir.normalize(),
                sun,
            );
            to_linear_srgb(&colours, &[l])
        };
        let zenith = look(DVec3::Z);
        assert!(
            zenith[2] > zenith[0] && zenith[2] > 0.0,
            "blue zenith: {zenith:?}"
        );
        let ground = look(DVec3::new(0.0, 1.0, -1.0));
        assert!(ground.iter().all(|&c| c > 0.0), "lit ground: {ground:?}");
        // From 1000 km up, looking away from the planet, only the black sky remains.
        let mut space = scene.clone();
        space.camera.altitude_m = 1.0e6;
        let cam = Camera::new(&space.camera, atm.bottom_radius_m, Projection::Perspective);
        let l = radiance(
            &p,
            &tables,
            0,
            (cam.position, 1.0e6),
            DVec3::new(0.3, 0.0, 1.0).normalize(),
            sun,
        );
        assert_eq!(l, [0.0; 4]);
        let earth = radiance(&p, &tables, 0, (cam.position, 1.0e6), -DVec3::Z, sun);
        assert!(earth.iter().all(|&v| v > 0.0 && v.is_finite()), "{earth:?}");
    }
}
