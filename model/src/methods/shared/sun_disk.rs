//! The sun's disk: angular size and limb darkening by wavelength from `crate::constants`
//! (Hestroffer & Magnan 1998: the limb is darker in the blue, so the disk's edge reddens).

use super::Lanes;
use crate::constants::{
    SUN_ANGULAR_RADIUS_RAD, SUN_LIMB_ALPHA_BREAK_PER_UM, SUN_LIMB_ALPHA_LONG, SUN_LIMB_ALPHA_SHORT,
};
use glam::DVec3;
use std::f64::consts::PI;

/// Radiance of the sun's disk in the single direction `dir` (0 outside it) at each of
/// `wavelengths_nm`, per unit solar irradiance, sr⁻¹: limb darkened, normalised to the disk's
/// mean.
pub fn sun_disk(dir: DVec3, sun: DVec3, wavelengths_nm: &Lanes) -> Lanes {
    match disk_offset(dir, sun) {
        Some(gamma) => wavelengths_nm
            .map(|w| limb(gamma / SUN_ANGULAR_RADIUS_RAD, limb_exponent(w)) / sun_solid_angle()),
        None => Lanes::ZERO,
    }
}

/// Whether the direction `dir` falls on the sun's disk.
pub fn in_sun_disk(dir: DVec3, sun: DVec3) -> bool {
    disk_offset(dir, sun).is_some()
}

/// Angle (rad) between `dir` and the sun's centre where it is inside the disk.
fn disk_offset(dir: DVec3, sun: DVec3) -> Option<f64> {
    if dir.dot(sun) <= 0.0 {
        return None;
    }
    let gamma = dir.cross(sun).length().min(1.0).asin();
    (gamma < SUN_ANGULAR_RADIUS_RAD).then_some(gamma)
}

/// Exponent α of the limb darkening I(μ′)/I(1) = μ′^α at `wavelength_nm` (300–1100 nm).
pub fn limb_exponent(wavelength_nm: f64) -> f64 {
    let per_um = 1000.0 / wavelength_nm;
    let [a, b] = if per_um < SUN_LIMB_ALPHA_BREAK_PER_UM {
        SUN_LIMB_ALPHA_LONG
    } else {
        SUN_LIMB_ALPHA_SHORT
    };
    a + b * per_um
}

/// The sun's solid angle, sr.
fn sun_solid_angle() -> f64 {
    let half = 0.5 * SUN_ANGULAR_RADIUS_RAD;
    4.0 * PI * half.sin() * half.sin()
}

/// Limb darkening with exponent `alpha` at the fraction `x` of the disk's radius, normalised to
/// the disk's mean (the mean of μ′^α over the disk is 2/(α + 2)).
fn limb(x: f64, alpha: f64) -> f64 {
    (1.0 - x * x).max(0.0).sqrt().powf(alpha) * (alpha + 2.0) / 2.0
}

/// Where the sun's centre falls in a view: its pixel coordinates (x to the right, y down, pixel
/// centres at half-integers) and the angular width and height of a pixel there, rad. The
/// sun is 0.27° across, so around it the image is a plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunInView {
    pub x: f64,
    pub y: f64,
    pub pixel_width_rad: f64,
    pub pixel_height_rad: f64,
    /// The view's width in pixels when it wraps around (a panorama), else 0.
    pub wrap_width: f64,
}

impl SunInView {
    /// Radiance of the sun's disk averaged over the pixel centred at (x, y) at each of
    /// `wavelengths_nm`, per unit solar irradiance, sr⁻¹: [`Self::pixel`] then
    /// [`DiskInPixel::radiance`].
    pub fn disk_in_pixel(&self, x: f64, y: f64, wavelengths_nm: &Lanes) -> Lanes {
        self.pixel(x, y)
            .map_or(Lanes::ZERO, |d| d.radiance(wavelengths_nm))
    }

    /// How the sun's disk covers the pixel centred at (x, y), None where it does not reach it.
    /// Every pixel measures the sun from the same centre, so its energy summed over the pixels
    /// is kept however small the pixels are against it or where it falls (it vanished between
    /// pixel centres when point-sampled).
    ///
    /// A pixel as wide as the sun's radius or less sees the overlap of the sun with a disk of
    /// the pixel's area, its limb darkening averaged over that overlap ring by ring; a pixel
    /// twice as wide or more, the share of the sun between its edges across times the share
    /// between its edges along (these shares sum to exactly one over the pixels); in between
    /// the two are blended. Within 4 % of the sun's energy over any pixel size and offset.
    pub fn pixel(&self, x: f64, y: f64) -> Option<DiskInPixel> {
        let a = SUN_ANGULAR_RADIUS_RAD;
        let (wx, wy) = (self.pixel_width_rad, self.pixel_height_rad);
        let mut dx = x - self.x;
        if self.wrap_width > 0.0 {
            dx -= self.wrap_width * (dx / self.wrap_width).round();
        }
        let (ox, oy) = (dx * wx, (y - self.y) * wy);
        let gamma = ox.hypot(oy);
        if gamma >= a + wx + wy {
            return None;
        }
        let sr = wx * wy;
        let blend = smoothstep(1.0, 2.0, sr.sqrt() / a);
        let p = (sr / PI).sqrt();
        let mut d = DiskInPixel {
            blend,
            ..DiskInPixel::default()
        };
        if blend < 1.0 {
            d.overlap = disk_overlap(a, p, gamma) / (PI * a * a) / sr;
            (d.ring_x, d.ring_weight) = limb_rings(gamma, p);
        }
        if blend > 0.0 {
            let inside = |w: f64, o: f64| chord_share(0.5 * w + o) - chord_share(-0.5 * w + o);
            d.unresolved = inside(wx, ox) * inside(wy, oy) / sr;
        }
        Some(d)
    }

    /// The pixels of a `width` × `height` view the disk can reach: columns x0..x1 and rows
    /// y0..y1 (ends excluded) holding every pixel that [`Self::pixel`] reaches, so that a
    /// renderer can draw the disk over those alone. A box that wraps around a panorama's edge
    /// spans the whole width. None when no pixel of the view is reached.
    pub fn pixel_box(&self, width: u32, height: u32) -> Option<[u32; 4]> {
        let (wx, wy) = (self.pixel_width_rad, self.pixel_height_rad);
        let reach = SUN_ANGULAR_RADIUS_RAD + wx + wy;
        // One pixel more each way: the box is on pixel edges, the test on pixel centres.
        let (hx, hy) = (reach / wx + 1.0, reach / wy + 1.0);
        let (w, h) = (f64::from(width), f64::from(height));
        let (y0, y1) = ((self.y - hy).floor().max(0.0), (self.y + hy).ceil().min(h));
        let (mut x0, mut x1) = ((self.x - hx).floor(), (self.x + hx).ceil());
        if self.wrap_width > 0.0 {
            let centre = self.x - w * (self.x / w).floor();
            (x0, x1) = (centre - hx, centre + hx);
            if x0.floor() < 0.0 || x1.ceil() > w {
                (x0, x1) = (0.0, w);
            }
        }
        let (x0, x1) = (x0.floor().max(0.0), x1.ceil().min(w));
        // Outside the view: no pixel to draw over.
        if !(x0 < x1 && y0 < y1) {
            return None;
        }
        Some([x0 as u32, y0 as u32, x1 as u32, y1 as u32])
    }
}

/// The sun's disk over one pixel, apart from wavelength (from [`SunInView::pixel`]): the
/// geometry is the same at every wavelength, only the limb darkening differs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DiskInPixel {
    /// Overlap of the sun with a disk of the pixel's area, per pixel solid angle, sr⁻¹.
    overlap: f64,
    /// The sun's share between the pixel's edges, per pixel solid angle, sr⁻¹.
    unresolved: f64,
    /// 0 where the pixel resolves the disk, 1 where it is twice as wide as the sun's radius.
    blend: f64,
    /// Radii of the rings over which the limb darkening is averaged, fractions of the sun's
    /// radius (0–1), and their weights (summing to 1 where the pixel's disk meets the sun's).
    ring_x: [f64; LIMB_RINGS],
    ring_weight: [f64; LIMB_RINGS],
}

impl DiskInPixel {
    /// Radiance at each of `wavelengths_nm` (300–1100 nm), per unit solar irradiance, sr⁻¹.
    pub fn radiance(&self, wavelengths_nm: &Lanes) -> Lanes {
        wavelengths_nm.map(|w| {
            let alpha = limb_exponent(w);
            let l: f64 = (self.ring_x.iter().zip(&self.ring_weight))
                .map(|(&x, &weight)| weight * limb(x, alpha))
                .sum();
            let resolved = l * self.overlap;
            resolved + (self.unresolved - resolved) * self.blend
        })
    }
}

/// Rings over which a pixel averages the limb darkening: four, at the midpoints of the radii
/// the pixel's disk spans, keep the sun's energy within 4 % over pixel sizes and offsets and
/// give the point value for pixels much smaller than the sun.
pub const LIMB_RINGS: usize = 4;

/// The rings (radii as fractions of the sun's, and weights) over which a disk of radius `p`
/// whose centre is `gamma` from the sun's (rad) averages the limb darkening: each ring weighs
/// the length of its arc inside the pixel's disk.
fn limb_rings(gamma: f64, p: f64) -> ([f64; LIMB_RINGS], [f64; LIMB_RINGS]) {
    let a = SUN_ANGULAR_RADIUS_RAD;
    let (r0, r1) = ((gamma - p).max(0.0), (gamma + p).min(a));
    let mut x = [0.0; LIMB_RINGS];
    let mut weight = [0.0; LIMB_RINGS];
    if r1 <= r0 {
        return (x, weight);
    }
    for (k, (x, weight)) in x.iter_mut().zip(&mut weight).enumerate() {
        let rho = r0 + (k as f64 + 0.5) / LIMB_RINGS as f64 * (r1 - r0);
        // Half the arc of the ring inside the pixel's disk: all of it where the ring lies
        // within that disk.
        let arc = if rho <= p - gamma {
            PI
        } else {
            ((rho * rho + gamma * gamma - p * p) / (2.0 * rho * gamma))
                .clamp(-1.0, 1.0)
                .acos()
        };
        *x = rho / a;
        *weight = arc * rho;
    }
    let total: f64 = weight.iter().sum();
    if total > 0.0 {
        weight.iter_mut().for_each(|w| *w /= total);
    }
    (x, weight)
}

/// Share of the sun's disk whose offset from its centre along an axis is below `s`, rad.
fn chord_share(s: f64) -> f64 {
    let t = (s / SUN_ANGULAR_RADIUS_RAD).clamp(-1.0, 1.0);
    1.0 - (t.acos() - t * (1.0 - t * t).sqrt()) / PI
}

/// Area shared by two disks of radii `a` and `b` whose centres are `d` apart (plane geometry).
pub fn disk_overlap(a: f64, b: f64, d: f64) -> f64 {
    if d >= a + b {
        return 0.0;
    }
    if d <= (a - b).abs() {
        return PI * a.min(b).powi(2);
    }
    let ca = ((d * d + a * a - b * b) / (2.0 * d * a)).clamp(-1.0, 1.0);
    let cb = ((d * d + b * b - a * a) / (2.0 * d * b)).clamp(-1.0, 1.0);
    let k = ((-d + a + b) * (d + a - b) * (d - a + b) * (d + a + b)).max(0.0);
    a * a * ca.acos() + b * b * cb.acos() - 0.5 * k.sqrt()
}

/// Visible fraction of the sun's disk at zenith cosine `mu_s` from altitude `h` above a planet
/// of radius `big_r`: Earth's shadow with its penumbra, as in Bruneton (2017).
pub fn visible_fraction(h: f64, mu_s: f64, big_r: f64) -> f64 {
    let sin_h = big_r / (big_r + h);
    let cos_h = -(1.0 - sin_h * sin_h).max(0.0).sqrt();
    let edge = sin_h * SUN_ANGULAR_RADIUS_RAD;
    smoothstep(-edge, edge, mu_s - cos_h)
}

fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Blue, green, red and near-infrared: both ranges of the limb-darkening fit.
    const WAVELENGTHS: Lanes = Lanes([380.0, 450.0, 550.0, 700.0]);

    /// No pixel outside `pixel_box` gets any of the disk, over pixel sizes from a twentieth of
    /// the sun's radius to a hundred radii, suns inside, at the edges and outside of the
    /// view, and panoramas whose sun wraps around.
    #[test]
    fn the_disk_reaches_no_pixel_outside_its_box() {
        let (width, height) = (40u32, 30u32);
        for size in [0.05, 0.3, 1.0, 2.5, 10.0, 100.0] {
            let p = size * SUN_ANGULAR_RADIUS_RAD;
            for (x, y) in [
                (20.3, 15.7),
                (0.2, 3.0),
                (39.9, 29.5),
                (-3.0, 10.0),
                (45.0, -2.0),
            ] {
                for wrap in [0.0, f64::from(width)] {
                    let sun = SunInView {
                        x,
                        y,
                        pixel_width_rad: p,
                        pixel_height_rad: 0.7 * p,
                        wrap_width: wrap,
                    };
                    let b = sun.pixel_box(width, height);
                    for j in 0..height {
                        for i in 0..width {
                            let inside = b.is_some_and(|[x0, y0, x1, y1]| {
                                (x0..x1).contains(&i) && (y0..y1).contains(&j)
                            });
                            let d = sun.pixel(f64::from(i) + 0.5, f64::from(j) + 0.5);
                            assert!(
                                inside || d.is_none(),
                                "{size} ({x}, {y}) wrap {wrap}: {i} {j}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn the_sun_disk_integrates_to_one() {
        let sun = DVec3::Z;
        let n = 400;
        let a = SUN_ANGULAR_RADIUS_RAD;
        let mut sum = [0.0; 4];
        // Rings of the disk: ∫ L dΩ = Σ L(γ)·2π sin γ dγ.
        for i in 0..n {
            let gamma = (i as f64 + 0.5) / n as f64 * a;
            let dir = DVec3::new(gamma.sin(), 0.0, gamma.cos());
            let l = sun_disk(dir, sun, &WAVELENGTHS);
            for (s, l) in sum.iter_mut().zip(l) {
                *s += l * 2.0 * PI * gamma.sin() * a / n as f64;
            }
        }
        assert!(sum.iter().all(|s| (s - 1.0).abs() < 2e-3), "{sum:?}");
        assert_eq!(sun_disk(DVec3::X, sun, &WAVELENGTHS), Lanes::ZERO);
        assert!(in_sun_disk(sun, sun) && !in_sun_disk(DVec3::X, sun));
    }

    /// Hestroffer & Magnan's exponent: 0.508 at 550 nm, larger in the blue; the disk's centre
    /// is brighter than its mean and its edge redder than its centre (a linear law with one
    /// coefficient for every wavelength would give both the same colour).
    #[test]
    fn the_limb_is_darker_and_redder_than_the_centre() {
        assert!((limb_exponent(550.0) - 0.5079).abs() < 1e-3);
        assert!((limb_exponent(700.0) - 0.3941).abs() < 1e-3);
        assert!(limb_exponent(450.0) > limb_exponent(550.0));
        let sun = DVec3::Z;
        let a = SUN_ANGULAR_RADIUS_RAD;
        let at = |x: f64| {
            sun_disk(
                DVec3::new((x * a).tan(), 0.0, 1.0).normalize(),
                sun,
                &WAVELENGTHS,
            )
        };
        let (centre, edge) = (at(0.0), at(0.95));
        let mean = 1.0 / (2.0 * PI * (1.0 - a.cos()));
        for i in 0..4 {
            assert!(
                centre[i] > mean && edge[i] < 0.75 * centre[i],
                "{centre:?} {edge:?}"
            );
        }
        // Red over blue, relative to the centre: larger at the edge.
        assert!(
            edge[3] / edge[1] > 1.1 * centre[3] / centre[1],
            "{centre:?} {edge:?}"
        );
    }

    /// A pixel centred on the sun as wide as its radius sees the limb law's exact mean over
    /// the disk of the pixel's area: ∫₀^q (1 − x²)^(α/2) 2x dx / q², times (α + 2)/2, not the
    /// law read at one point, which is too dark there.
    #[test]
    fn a_pixel_averages_the_limb_over_the_part_of_the_sun_it_sees() {
        let a = SUN_ANGULAR_RADIUS_RAD;
        let sun = SunInView {
            x: 0.5,
            y: 0.5,
            pixel_width_rad: a,
            pixel_height_rad: a,
            wrap_width: 0.0,
        };
        let got = sun.disk_in_pixel(0.5, 0.5, &WAVELENGTHS);
        let p = (a * a / PI).sqrt();
        let q2 = (p / a).powi(2);
        for (i, w) in WAVELENGTHS.iter().enumerate() {
            let alpha = limb_exponent(*w);
            let e = alpha / 2.0 + 1.0;
            let mean = (1.0 - (1.0 - q2).powf(e)) / (e * q2) * (alpha + 2.0) / 2.0;
            let want = mean * q2 / (a * a);
            assert!(
                (got[i] / want - 1.0).abs() < 5e-3,
                "{w} nm: {} vs {want}",
                got[i]
            );
        }
    }

    /// A grid of square pixels of side `side` (rad) around the sun, its centre at `(ox, oy)`
    /// pixels from a pixel centre: the sun's energy Σ L·Ω over the grid, and the brightest
    /// pixel's radiance.
    fn grid(side: f64, (ox, oy): (f64, f64)) -> (f64, f64) {
        let n = ((4.0 * SUN_ANGULAR_RADIUS_RAD / side).ceil() as i32).max(2);
        let sun = SunInView {
            x: ox + 0.5,
            y: oy + 0.5,
            pixel_width_rad: side,
            pixel_height_rad: side,
            wrap_width: 0.0,
        };
        let (mut energy, mut peak) = (0.0, 0.0_f64);
        for i in -n..=n {
            for j in -n..=n {
                let l = sun.disk_in_pixel(i as f64 + 0.5, j as f64 + 0.5, &WAVELENGTHS);
                energy += l[2] * side * side;
                peak = peak.max(l[2]);
            }
        }
        (energy, peak)
    }

    #[test]
    fn the_sun_keeps_its_energy_over_pixels_of_any_size_and_never_vanishes() {
        let a = SUN_ANGULAR_RADIUS_RAD;
        for side in [
            0.05 * a,
            0.3 * a,
            0.5 * a,
            a,
            1.5 * a,
            2.0 * a,
            10.0 * a,
            100.0 * a,
        ] {
            // Centred on a pixel, on a corner shared by four pixels (an even-sized view looking
            // at the sun), and anywhere between.
            for offset in [(0.0, 0.0), (0.5, 0.5), (0.5, 0.0), (0.23, 0.71)] {
                let (energy, peak) = grid(side, offset);
                assert!(
                    (energy - 1.0).abs() < 0.04,
                    "pixels {:.2} sun radii, offset {offset:?}: energy {energy}",
                    side / a
                );
                assert!(peak > 0.0);
            }
        }
        // A pixel much smaller than the sun sees the point value.
        let small = SunInView {
            x: 0.5,
            y: 0.5,
            pixel_width_rad: 1e-3 * a,
            pixel_height_rad: 1e-3 * a,
            wrap_width: 0.0,
        };
        let at = 300.0; // pixels from the centre: 0.3 sun radii
        let dir = DVec3::new((0.3 * a).tan(), 0.0, 1.0).normalize();
        let point = sun_disk(dir, DVec3::Z, &WAVELENGTHS);
        let averaged = small.disk_in_pixel(0.5 + at, 0.5, &WAVELENGTHS);
        for i in 0..4 {
            assert!(
                (averaged[i] / point[i] - 1.0).abs() < 1e-2,
                "{averaged:?} vs {point:?}"
            );
        }
    }

    #[test]
    fn disks_overlap_as_geometry_says() {
        assert_eq!(disk_overlap(1.0, 2.0, 3.0), 0.0);
        assert!((disk_overlap(1.0, 3.0, 1.0) - PI).abs() < 1e-12);
        // Two unit disks one radius apart share 2π/3 − √3/2.
        let lens = 2.0 * PI / 3.0 - 3f64.sqrt() / 2.0;
        assert!((disk_overlap(1.0, 1.0, 1.0) - lens).abs() < 1e-12);
    }
}
