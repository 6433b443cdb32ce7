//! Progressive path-traced images: the reference renders every method is compared with.
//!
//! Each pass adds a number of paths to every pixel (rows in parallel with rayon); each path's
//! random stream is keyed by (seed, pixel, sample index), so a render is the same for a given
//! seed whatever the thread count or pass sizes. Per pixel it keeps CIE XYZ and the sum of
//! squares of luminance for a standard error, so the noise level is always known. Each path's
//! four wavelengths are drawn by `WavelengthSampler`: stratified in the inverse CDF of x̄+ȳ+z̄
//! plus a floor, so the eye's sensitive band gets most paths while every wavelength of
//! 360–830 nm keeps a non-zero density (the pdf is divided out). Each is then moved to the
//! middle of its cell of [`SpectralCells`], whose optics are tabulated once per render.

use crate::Atmosphere;
use crate::camera::{Camera, Projection};
use crate::colour::{Xyz, cie1931, xyz_to_linear_srgb};
use crate::constants::{MAX_LUMINOUS_EFFICACY_LM_PER_W, VISIBLE_MAX_NM, VISIBLE_MIN_NM};
use crate::geometry::direction_from_angles;
use crate::methods::path_tracer::{
    LANES, LaneOptics, Lanes, PathTracer, PathTracerSettings, Prepared,
};
use crate::methods::rng::Rng;
use crate::scene::Scene;
use rayon::prelude::*;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// Least share of a pixel the projection covers for which paths are drawn inside it only.
const MIN_COVERAGE: f64 = 0.01;

/// Most draws of a point inside a partly covered pixel: at `MIN_COVERAGE`, all miss with a
/// probability of 0.99^10000 ≈ 2e-44.
const MAX_REDRAWS: usize = 10_000;

/// Width of the cells of [`SpectralCells`], nm. Every spectrum the optics interpolate linearly
/// has its samples on whole or half nanometres, so it is linear across each cell.
pub const SPECTRAL_CELL_NM: f64 = 0.1;

/// The optics, extraterrestrial irradiance and colour matching at the middle of every
/// [`SPECTRAL_CELL_NM`] cell of 360–830 nm. A path's wavelengths are moved to the middles of
/// their cells: the estimate becomes the midpoint rule on these cells, within a part per
/// million of the continuous integral (the spectra being linear across a cell, the error is
/// their products' curvature times the cell width squared; a test measures it), and a path's
/// optics cost four look-ups instead of some thirty interpolations in the spectra.
pub struct SpectralCells {
    cells: Vec<SpectralCell>,
}

/// What [`SpectralCells`] holds for the middle of one cell.
struct SpectralCell {
    optics: crate::Optics,
    /// Extraterrestrial solar irradiance, W·m⁻²·nm⁻¹.
    solar_irradiance: f64,
    /// The CIE 1931 colour-matching functions x̄, ȳ, z̄.
    cmf: [f64; 3],
}

impl SpectralCells {
    pub fn new(atmosphere: &Atmosphere) -> SpectralCells {
        let cmf = cie1931();
        let count = ((VISIBLE_MAX_NM - VISIBLE_MIN_NM) / SPECTRAL_CELL_NM).round() as usize;
        let cells = (0..count)
            .map(|k| {
                let w = VISIBLE_MIN_NM + (k as f64 + 0.5) * SPECTRAL_CELL_NM;
                SpectralCell {
                    optics: atmosphere.optics(w),
                    solar_irradiance: atmosphere.solar_irradiance(w, None),
                    cmf: [cmf.x.sample(w), cmf.y.sample(w), cmf.z.sample(w)],
                }
            })
            .collect();
        SpectralCells { cells }
    }

    fn cell(&self, wavelength_nm: f64) -> &SpectralCell {
        let k = ((wavelength_nm - VISIBLE_MIN_NM) / SPECTRAL_CELL_NM).max(0.0) as usize;
        &self.cells[k.min(self.cells.len() - 1)]
    }

    /// The lanes of the cells holding `wavelengths_nm`, and their x̄, ȳ, z̄.
    pub fn lanes(&self, wavelengths_nm: Lanes) -> (LaneOptics, [[f64; 3]; LANES]) {
        let cells = wavelengths_nm.0.map(|w| self.cell(w));
        (
            LaneOptics::from_optics(
                cells.map(|c| c.optics),
                Lanes(cells.map(|c| c.solar_irradiance)),
            ),
            cells.map(|c| c.cmf),
        )
    }
}

/// Draws the wavelengths of a path with density ∝ x̄ + ȳ + z̄ + floor over 360–830 nm.
#[derive(Debug, Clone)]
pub struct WavelengthSampler {
    /// CDF at the 1 nm bin edges 360, 361, …, 830 nm.
    cdf: Vec<f64>,
    /// Density per bin, nm⁻¹.
    pdf: Vec<f64>,
}

impl Default for WavelengthSampler {
    fn default() -> Self {
        let cmf = cie1931();
        let bins = (VISIBLE_MAX_NM - VISIBLE_MIN_NM) as usize;
        let weight: Vec<f64> = (0..bins)
            .map(|k| {
                let w = VISIBLE_MIN_NM + k as f64 + 0.5;
                // The floor (a tenth of ȳ's peak) keeps the tails sampled for spectral bins.
                cmf.x.sample(w) + cmf.y.sample(w) + cmf.z.sample(w) + 0.1
            })
            .collect();
        let total: f64 = weight.iter().sum();
        let pdf: Vec<f64> = weight.iter().map(|w| w / total).collect();
        let mut cdf = vec![0.0];
        for p in &pdf {
            cdf.push(cdf.last().copied().unwrap_or(0.0) + p);
        }
        WavelengthSampler { cdf, pdf }
    }
}

impl WavelengthSampler {
    /// Four wavelengths from one uniform number, stratified in the CDF, with their densities
    /// (nm⁻¹).
    pub fn sample(&self, u: f64) -> (Lanes, Lanes) {
        let mut wavelengths = [0.0; LANES];
        let mut pdf = [0.0; LANES];
        for i in 0..LANES {
            let v = (u + i as f64 / LANES as f64) % 1.0;
            let k = self
                .cdf
                .partition_point(|&c| c <= v)
                .clamp(1, self.pdf.len())
                - 1;
            let frac = (v - self.cdf[k]) / self.pdf[k];
            wavelengths[i] = VISIBLE_MIN_NM + k as f64 + frac.clamp(0.0, 1.0);
            pdf[i] = self.pdf[k];
        }
        (Lanes(wavelengths), Lanes(pdf))
    }
}

/// Accumulated estimates of one pixel: 48 bytes, so that the largest reference (8192²) needs
/// about 3 GB.
#[derive(Debug, Clone, Copy, Default)]
pub struct Pixel {
    pub samples: u64,
    /// Sums of per-path XYZ estimates, W·m⁻²·sr⁻¹.
    pub xyz_sum: [f64; 3],
    /// Sum of squares of the per-path Y estimates.
    pub y_sum_sq: f64,
    /// False for pixels the projection leaves empty.
    pub covered: bool,
}

impl Pixel {
    pub fn xyz(&self) -> Xyz {
        let n = self.samples.max(1) as f64;
        Xyz {
            x: self.xyz_sum[0] / n,
            y: self.xyz_sum[1] / n,
            z: self.xyz_sum[2] / n,
        }
    }

    /// Luminance, cd/m².
    pub fn luminance_cd_m2(&self) -> f64 {
        MAX_LUMINOUS_EFFICACY_LM_PER_W * self.xyz().y
    }

    /// Standard error of the mean Y over the mean Y (0 for an exactly black pixel).
    pub fn relative_standard_error(&self) -> f64 {
        if self.samples < 2 {
            return f64::INFINITY;
        }
        let n = self.samples as f64;
        let mean = self.xyz_sum[1] / n;
        if mean <= 0.0 {
            return 0.0;
        }
        let var = (self.y_sum_sq / n - mean * mean).max(0.0) / (n - 1.0);
        var.sqrt() / mean
    }
}

/// A progressive reference render of one scene and projection.
pub struct ReferenceRender {
    pub width: u32,
    pub height: u32,
    pub seed: u64,
    atmosphere: Atmosphere,
    camera: Camera,
    sun: glam::DVec3,
    settings: PathTracerSettings,
    spectral: SpectralCells,
    /// The tracer's preparation of the atmosphere, for every pass.
    prepared: Arc<Prepared>,
    pixels: Vec<Pixel>,
    /// In the vector mode ([`Self::with_stokes`]), per pixel the sums of the paths' Stokes
    /// vectors weighted by ȳ like Y (I_Y, Q_Y, U_Y, V_Y), W·m⁻²·sr⁻¹, in the pixel's image
    /// frame ([`Self::stokes_y`]).
    stokes: Option<Vec<[f64; 4]>>,
}

impl ReferenceRender {
    pub fn new(
        scene: &Scene,
        projection: Projection,
        width: u32,
        height: u32,
        seed: u64,
        settings: PathTracerSettings,
    ) -> Self {
        let atmosphere = Atmosphere::for_scene(&scene);
        let camera = Camera::new(&scene.camera, atmosphere.bottom_radius_m, projection);
        let sun_angles = scene.sun.angles();
        let sun = direction_from_angles(sun_angles.elevation_deg, sun_angles.azimuth_deg);
        let pixels = vec![Pixel::default(); (width * height) as usize];
        let spectral = SpectralCells::new(&atmosphere);
        let prepared = Arc::new(Prepared::new(&atmosphere));
        ReferenceRender {
            width,
            height,
            seed,
            atmosphere,
            camera,
            sun,
            settings,
            spectral,
            prepared,
            pixels,
            stokes: None,
        }
    }

    /// The same render in the path tracer's vector mode: its luminance and colour come from the
    /// vector mode's I, and [`Self::stokes_y`] gives each pixel's photometric Stokes vector.
    pub fn with_stokes(mut self) -> Self {
        self.stokes = Some(vec![[0.0; 4]; self.pixels.len()]);
        self
    }

    /// Per pixel (row-major, top row first) the mean Stokes vector weighted by ȳ like the
    /// luminance (I_Y = Y), W·m⁻²·sr⁻¹, referred to the image frame: e₁ is "up" in the picture
    /// at the pixel (against its row index), e₂ = view × e₁, "right" in the perspective and
    /// panorama pictures and "left" in the fisheye, which shows the dome as seen from above
    /// (east to the right of north). Unlike the meridian frame it has no singular point at the
    /// zenith, where a pixel's paths would otherwise cancel. None unless [`Self::with_stokes`].
    pub fn stokes_y(&self) -> Option<Vec<[f64; 4]>> {
        let sums = self.stokes.as_ref()?;
        Some(
            sums.iter()
                .zip(&self.pixels)
                .map(|(s, p)| s.map(|v| v / p.samples.max(1) as f64))
                .collect(),
        )
    }

    pub fn pixels(&self) -> &[Pixel] {
        &self.pixels
    }

    /// Samples per pixel so far.
    pub fn samples_per_pixel(&self) -> u64 {
        self.pixels.iter().map(|p| p.samples).max().unwrap_or(0)
    }

    /// Adds `spp` paths to every pixel. Returns false, leaving the pass partly done, when
    /// `cancel` was set meanwhile (what was added stays valid).
    pub fn run_pass(&mut self, spp: u32, cancel: &AtomicBool) -> bool {
        self.run_rows(spp, 0..self.height, cancel)
    }

    /// [`Self::run_pass`] for the pixel rows `rows` only (clamped to the image), so that a pass
    /// can be spread over several calls: each pixel draws its paths from its own index and
    /// count, so a pass run in bands of rows adds exactly what it adds in one go.
    pub fn run_rows(&mut self, spp: u32, rows: std::ops::Range<u32>, cancel: &AtomicBool) -> bool {
        let first = rows.start.min(self.height);
        let end = rows.end.clamp(first, self.height);
        let tracer = PathTracer::with_prepared(
            &self.atmosphere,
            self.sun,
            self.settings,
            self.prepared.clone(),
        );
        let sampler = WavelengthSampler::default();
        let (w, h, seed, camera) = (self.width, self.height, self.seed, self.camera);
        let spectral = &self.spectral;
        let vector = self.stokes.is_some();
        let band = first as usize * w as usize..end as usize * w as usize;
        let stokes_rows: Vec<Option<&mut [[f64; 4]]>> = match self.stokes.as_mut() {
            Some(s) => s[band.clone()].chunks_mut(w as usize).map(Some).collect(),
            None => (first..end).map(|_| None).collect(),
        };
        self.pixels[band]
            .par_chunks_mut(w as usize)
            .zip(stokes_rows)
            .enumerate()
            .for_each(|(row_in_band, (row, mut stokes_row))| {
                let y = first as usize + row_in_band;
                if cancel.load(Ordering::Relaxed) {
                    return;
                }
                for (x, pixel) in row.iter_mut().enumerate() {
                    let index = (y as u64) * w as u64 + x as u64;
                    // Across the fisheye's rim a path drawn outside the circle would add a zero:
                    // noise of the pixel's shape, not of the sky. Paths are drawn inside it
                    // instead and weighed by the share it covers, the same mean. Below
                    // `MIN_COVERAGE` the redraws would cost more than the zeros.
                    let coverage = camera.pixel_coverage(x as u32, y as u32, w, h);
                    let inside_only = (MIN_COVERAGE..1.0).contains(&coverage);
                    let share = if inside_only { coverage } else { 1.0 };
                    for _ in 0..spp {
                        let mut rng = Rng::new(seed, index, pixel.samples);
                        pixel.samples += 1;
                        // The ray and the point of the view it leaves from.
                        let mut drawn = None;
                        for _ in 0..if inside_only { MAX_REDRAWS } else { 1 } {
                            let at = (x as f64 + rng.uniform(), y as f64 + rng.uniform());
                            drawn = camera.ray(at.0, at.1, w, h).map(|r| (r, at));
                            if drawn.is_some() {
                                break;
                            }
                        }
                        let Some((ray, (view_x, view_y))) = drawn else {
                            continue;
                        };
                        pixel.covered = true;
                        let (wavelengths, pdf) = sampler.sample(rng.uniform());
                        let (lanes, cmf) = spectral.lanes(wavelengths);
                        let (l, stokes) = if vector {
                            // The frame: "up" in the picture where the path leaves.
                            let up = camera.image_up(view_x, view_y, w, h, ray.direction);
                            let s = tracer.radiance_stokes(&ray, up, &lanes, &mut rng);
                            (Lanes::from_fn(|i| s[i].i), Some(s))
                        } else {
                            (tracer.radiance(&ray, &lanes, &mut rng), None)
                        };
                        let mut xyz = [0.0; 3];
                        for i in 0..LANES {
                            let v = share * l[i] / (LANES as f64 * pdf[i]);
                            for c in 0..3 {
                                xyz[c] += v * cmf[i][c];
                            }
                        }
                        for c in 0..3 {
                            pixel.xyz_sum[c] += xyz[c];
                        }
                        pixel.y_sum_sq += xyz[1] * xyz[1];
                        if let (Some(s), Some(sum)) =
                            (stokes, stokes_row.as_mut().and_then(|r| r.get_mut(x)))
                        {
                            for i in 0..LANES {
                                let weight = share * cmf[i][1] / (LANES as f64 * pdf[i]);
                                for (k, v) in s[i].to_array().into_iter().enumerate() {
                                    sum[k] += weight * v;
                                }
                            }
                        }
                    }
                }
            });
        !cancel.load(Ordering::Relaxed)
    }

    /// Mean over covered pixels with light of the relative standard error of luminance.
    pub fn mean_relative_error(&self) -> f64 {
        let errors: Vec<f64> = self
            .pixels
            .iter()
            .filter(|p| p.covered && p.xyz_sum[1] > 0.0)
            .map(Pixel::relative_standard_error)
            .collect();
        if errors.is_empty() {
            0.0
        } else {
            errors.iter().sum::<f64>() / errors.len() as f64
        }
    }

    /// Relative standard error of the image's mean luminance (all pixels' estimates pooled).
    pub fn image_relative_error(&self) -> f64 {
        let (mut mean, mut var) = (0.0, 0.0);
        let covered: Vec<&Pixel> = self.pixels.iter().filter(|p| p.covered).collect();
        for p in &covered {
            let n = p.samples.max(2) as f64;
            let m = p.xyz_sum[1] / n;
            mean += m;
            var += (p.y_sum_sq / n - m * m).max(0.0) / (n - 1.0);
        }
        if mean <= 0.0 { 0.0 } else { var.sqrt() / mean }
    }

    /// Linear sRGB per pixel (row-major, top row first), W·m⁻²·sr⁻¹.
    pub fn linear_srgb(&self) -> Vec<[f64; 3]> {
        self.pixels
            .iter()
            .map(|p| xyz_to_linear_srgb(p.xyz()))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A path's wavelengths go to the middles of their cells, with the optics there; and the
    /// midpoint rule on the cells integrates sunlight seen through a long slant path (the
    /// luminance of E·ȳ·e^(−τ) at ten airmasses, where ozone's bands and the air's λ⁻⁴ bend it
    /// most) within a part per million of a rule 64 times finer (3e-8 when written).
    #[test]
    fn cell_middles_carry_their_optics_and_integrate_the_spectra() {
        let atmosphere = Atmosphere::for_scene(&Scene::default());
        let cells = SpectralCells::new(&atmosphere);
        let mut rng = Rng::new(3, 0, 0);
        for _ in 0..1000 {
            let w = VISIBLE_MIN_NM + rng.uniform() * (VISIBLE_MAX_NM - VISIBLE_MIN_NM);
            let (lanes, cmf) = cells.lanes(Lanes::splat(w));
            let middle = lanes.wavelengths_nm[0];
            assert!(
                (middle - w).abs() <= 0.5 * SPECTRAL_CELL_NM + 1e-9,
                "{w} → {middle}"
            );
            assert_eq!(
                lanes.solar_irradiance[0],
                atmosphere.solar_irradiance(middle, None)
            );
            assert_eq!(cmf[0][1], cie1931().y.sample(middle));
        }
        let airmass = 10.0;
        let (air_m2, ozone_m2) = (2.15e29, 8.07e22);
        let f = |o: &crate::Optics, solar: f64, y: f64| {
            let tau = o.rayleigh_cross_section_m2 * air_m2
                + o.ozone_cross_section_m2 * ozone_m2
                + o.aerosol_optical_depth;
            solar * y * (-airmass * tau).exp()
        };
        let coarse: f64 = cells
            .cells
            .iter()
            .map(|c| f(&c.optics, c.solar_irradiance, c.cmf[1]))
            .sum::<f64>()
            * SPECTRAL_CELL_NM;
        let fine_step = SPECTRAL_CELL_NM / 64.0;
        let n = ((VISIBLE_MAX_NM - VISIBLE_MIN_NM) / fine_step).round() as usize;
        let fine: f64 = (0..n)
            .map(|k| {
                let w = VISIBLE_MIN_NM + (k as f64 + 0.5) * fine_step;
                let y = cie1931().y.sample(w);
                f(
                    &atmosphere.optics(w),
                    atmosphere.solar_irradiance(w, None),
                    y,
                )
            })
            .sum::<f64>()
            * fine_step;
        let error = (coarse / fine - 1.0).abs();
        assert!(error < 1e-6, "cells {coarse} against {fine}: {error:e}");
    }

    /// The web explorer spreads a pass over frames in bands of rows: bands in any order, out
    /// of range ones included, add exactly what one pass adds, Stokes sums too.
    #[test]
    fn a_pass_in_bands_of_rows_adds_what_one_pass_adds() {
        let scene = Scene::default();
        let render = || {
            ReferenceRender::new(
                &scene,
                Projection::Fisheye,
                6,
                5,
                9,
                PathTracerSettings::default(),
            )
            .with_stokes()
        };
        let go = AtomicBool::new(false);
        let mut whole = render();
        assert!(whole.run_pass(2, &go));
        let mut banded = render();
        // The last band is reversed: it runs no row.
        let reversed = std::ops::Range { start: 7, end: 2 };
        for rows in [3..9, 0..1, 1..3, reversed] {
            assert!(banded.run_rows(2, rows, &go));
        }
        assert_eq!(banded.samples_per_pixel(), 2);
        for (a, b) in whole.pixels().iter().zip(banded.pixels()) {
            assert_eq!(
                (a.samples, a.xyz_sum, a.y_sum_sq),
                (b.samples, b.xyz_sum, b.y_sum_sq)
            );
        }
        assert_eq!(whole.stokes_y(), banded.stokes_y());
        assert!(whole.pixels().iter().any(|p| p.xyz_sum[1] > 0.0));
    }

    #[test]
    fn a_pixel_fits_in_48_bytes() {
        // 8192² pixels then need about 3 GB (they needed ~30 GB with per-pixel spectra).
        assert!(
            std::mem::size_of::<Pixel>() <= 48,
            "{}",
            std::mem::size_of::<Pixel>()
        );
    }

    #[test]
    fn passes_of_any_size_give_the_same_image_for_a_seed() {
        let mut scene = Scene::default();
        scene.camera.fov_deg = 90.0;
        let never = AtomicBool::new(false);
        let settings = PathTracerSettings::default();
        let mut a = ReferenceRender::new(&scene, Projection::Perspective, 6, 4, 9, settings);
        a.run_pass(4, &never);
        let mut b = ReferenceRender::new(&scene, Projection::Perspective, 6, 4, 9, settings);
        b.run_pass(1, &never);
        b.run_pass(3, &never);
        assert_eq!(a.linear_srgb(), b.linear_srgb());
        assert!(
            a.linear_srgb()
                .iter()
                .all(|c| c.iter().all(|v| v.is_finite()))
        );
        assert!(a.mean_relative_error().is_finite());
    }

    #[test]
    fn the_wavelength_sampler_integrates_exactly() {
        // E[f(λ)/(4·pdf(λ))] summed over the lanes is ∫f; check with f = 1 and f = ȳ.
        let s = WavelengthSampler::default();
        let (mut one, mut y) = (0.0, 0.0);
        let n = 20_000;
        for k in 0..n {
            let (w, p) = s.sample((k as f64 + 0.5) / n as f64);
            for i in 0..LANES {
                assert!((VISIBLE_MIN_NM..=VISIBLE_MAX_NM).contains(&w[i]));
                one += 1.0 / (LANES as f64 * p[i]);
                y += cie1931().y.sample(w[i]) / (LANES as f64 * p[i]);
            }
        }
        assert!((one / n as f64 - 470.0).abs() < 0.01, "{}", one / n as f64);
        assert!(
            (y / n as f64 / 106.857 - 1.0).abs() < 1e-3,
            "{}",
            y / n as f64
        );
    }

    #[test]
    fn cancelling_stops_a_pass() {
        let scene = Scene::default();
        let cancel = AtomicBool::new(true);
        let mut r = ReferenceRender::new(
            &scene,
            Projection::Fisheye,
            8,
            8,
            1,
            PathTracerSettings::default(),
        );
        assert!(!r.run_pass(100, &cancel));
        assert_eq!(r.samples_per_pixel(), 0);
    }

    /// A pixel across the fisheye's rim, drawn inside the circle and weighed by its coverage,
    /// has the mean of paths drawn over the whole pixel with zeros outside, and less noise.
    #[test]
    fn rim_pixels_keep_their_mean_and_lose_the_noise_of_their_shape() {
        let scene = Scene::default();
        let settings = PathTracerSettings {
            max_order: Some(1),
            ..PathTracerSettings::default()
        };
        let size = 12;
        let mut r = ReferenceRender::new(&scene, Projection::Fisheye, size, size, 5, settings);
        let spp = 6000;
        r.run_pass(spp, &AtomicBool::new(false));
        let tracer = PathTracer::new(&r.atmosphere, r.sun, settings);
        let cmf = cie1931();
        let sampler = WavelengthSampler::default();
        let mut checked = 0;
        for (k, pixel) in r.pixels().iter().enumerate() {
            let (x, y) = ((k as u32 % size), (k as u32 / size));
            let coverage = r.camera.pixel_coverage(x, y, size, size);
            if !(0.1..0.7).contains(&coverage) {
                continue;
            }
            // The whole pixel, zeros outside the circle.
            let (mut sum, mut sum_sq) = (0.0, 0.0);
            for n in 0..spp as u64 {
                let mut rng = Rng::new(99, k as u64, n);
                let (jx, jy) = (rng.uniform(), rng.uniform());
                let (wavelengths, pdf) = sampler.sample(rng.uniform());
                let Some(ray) = r.camera.ray(x as f64 + jx, y as f64 + jy, size, size) else {
                    continue;
                };
                let lanes = LaneOptics::new(&r.atmosphere, wavelengths);
                let l = tracer.radiance(&ray, &lanes, &mut rng);
                let v: f64 = (0..LANES)
                    .map(|i| l[i] * cmf.y.sample(wavelengths[i]) / (LANES as f64 * pdf[i]))
                    .sum();
                sum += v;
                sum_sq += v * v;
            }
            let n = spp as f64;
            let plain = sum / n;
            let plain_se = ((sum_sq / n - plain * plain) / (n - 1.0)).sqrt();
            let rim = pixel.xyz().y;
            let rim_se = pixel.relative_standard_error() * rim;
            let z = (rim - plain) / rim_se.hypot(plain_se);
            assert!(
                z.abs() < 4.0,
                "({x}, {y}) covered {coverage:.2}: {rim} ± {rim_se} vs {plain} ± {plain_se}"
            );
            assert!(
                rim_se / rim < 0.8 * plain_se / plain,
                "({x}, {y}) covered {coverage:.2}: noise {} vs {} over the whole pixel",
                rim_se / rim,
                plain_se / plain
            );
            checked += 1;
        }
        assert!(checked >= 8, "{checked} rim pixels checked");
    }

    /// The vector mode's photometric Stokes vectors: I_Y is the pixel's Y, and with the sun on
    /// the horizon of a clear sky the zenith, 90° from it, is strongly polarised (single
    /// scattering would give 0.94; multiple scattering lowers it) and the horizon towards the
    /// sun far less.
    #[test]
    fn a_vector_render_gives_each_pixel_its_photometric_stokes_vector() {
        let mut scene = Scene::default();
        scene.atmosphere.aerosol.kind = crate::aerosol::AerosolType::None;
        scene.sun = crate::scene::SunSettings::Angles {
            elevation_deg: 0.0,
            azimuth_deg: 0.0,
        };
        let never = AtomicBool::new(false);
        let settings = PathTracerSettings::default();
        let mut r =
            ReferenceRender::new(&scene, Projection::Fisheye, 9, 9, 3, settings).with_stokes();
        r.run_pass(48, &never);
        let stokes = r.stokes_y().expect("vector mode");
        for (s, p) in stokes.iter().zip(r.pixels()) {
            assert!(
                (s[0] - p.xyz().y).abs() <= 1e-12 * p.xyz().y,
                "{s:?} vs {:?}",
                p.xyz()
            );
        }
        let degree = |s: [f64; 4]| s[1].hypot(s[2]) / s[0];
        let zenith = degree(stokes[4 * 9 + 4]);
        assert!(zenith > 0.6 && zenith < 0.94, "{zenith}");
        assert!(
            ReferenceRender::new(&scene, Projection::Fisheye, 9, 9, 3, settings)
                .stokes_y()
                .is_none()
        );
    }

    #[test]
    fn the_sky_is_blue_and_the_fisheye_corners_are_empty() {
        let mut scene = Scene::default();
        scene.atmosphere.aerosol.kind = crate::aerosol::AerosolType::None;
        let never = AtomicBool::new(false);
        let mut r = ReferenceRender::new(
            &scene,
            Projection::Fisheye,
            9,
            9,
            3,
            PathTracerSettings::default(),
        );
        r.run_pass(64, &never);
        let rgb = r.linear_srgb();
        let zenith = rgb[4 * 9 + 4];
        assert!(
            zenith[2] > zenith[0],
            "blue above red at the zenith: {zenith:?}"
        );
        assert!(!r.pixels()[0].covered && rgb[0] == [0.0; 3]);
    }
}
