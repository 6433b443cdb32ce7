//! The sun's disk: angular size and limb darkening from `crate::constants`.

use crate::constants::{SUN_ANGULAR_RADIUS_RAD, SUN_LIMB_DARKENING_U};
use glam::DVec3;
use std::f64::consts::PI;

/// Radiance of the sun's disk in the single direction `dir` (0 outside it), per unit solar
/// irradiance, sr⁻¹: limb darkened with the linear law I(μ′) ∝ 1 − u(1 − μ′), normalised to
/// the disk's mean.
pub fn sun_disk(dir: DVec3, sun: DVec3) -> f64 {
    if dir.dot(sun) <= 0.0 {
        return 0.0;
    }
    let gamma = dir.cross(sun).length().min(1.0).asin();
    if gamma >= SUN_ANGULAR_RADIUS_RAD {
        return 0.0;
    }
    limb(gamma / SUN_ANGULAR_RADIUS_RAD) / sun_solid_angle()
}

/// The sun's solid angle, sr.
fn sun_solid_angle() -> f64 {
    let half = 0.5 * SUN_ANGULAR_RADIUS_RAD;
    4.0 * PI * half.sin() * half.sin()
}

/// Linear limb darkening at the fraction `x` of the disk's radius, normalised to its mean.
fn limb(x: f64) -> f64 {
    (1.0 - SUN_LIMB_DARKENING_U * (1.0 - (1.0 - x * x).sqrt())) / (1.0 - SUN_LIMB_DARKENING_U / 3.0)
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
    /// Radiance of the sun's disk averaged over the pixel centred at (x, y), per unit solar
    /// irradiance, sr⁻¹. Every pixel measures the sun from the same centre, so its energy
    /// summed over the pixels is kept however small the pixels are against it or where it
    /// falls (it vanished between pixel centres when point-sampled).
    ///
    /// A pixel as wide as the sun's radius or less sees the overlap of the sun with a disk of
    /// the pixel's area, limb darkening read a little inside the pixel's centre; a pixel twice
    /// as wide or more, the share of the sun between its edges across times the share between
    /// its edges along (these shares sum to exactly one over the pixels); in between the two
    /// are blended. Within 5 % of the sun's energy over any pixel size and offset.
    pub fn disk_in_pixel(&self, x: f64, y: f64) -> f64 {
        let a = SUN_ANGULAR_RADIUS_RAD;
        let (wx, wy) = (self.pixel_width_rad, self.pixel_height_rad);
        let mut dx = x - self.x;
        if self.wrap_width > 0.0 {
            dx -= self.wrap_width * (dx / self.wrap_width).round();
        }
        let (ox, oy) = (dx * wx, (y - self.y) * wy);
        let gamma = ox.hypot(oy);
        if gamma >= a + wx + wy {
            return 0.0;
        }
        let sr = wx * wy;
        let blend = smoothstep(1.0, 2.0, sr.sqrt() / a);
        let resolved = if blend < 1.0 {
            let p = (sr / PI).sqrt();
            let l = limb(((gamma - SUN_LIMB_INSET * p).max(0.0) / a).min(1.0));
            let fade = (p / a).min(1.0);
            (l + (1.0 - l) * fade) * disk_overlap(a, p, gamma) / (PI * a * a) / sr
        } else {
            0.0
        };
        let unresolved = if blend > 0.0 {
            let inside = |w: f64, o: f64| chord_share(0.5 * w + o) - chord_share(-0.5 * w + o);
            inside(wx, ox) * inside(wy, oy) / sr
        } else {
            0.0
        };
        resolved + (unresolved - resolved) * blend
    }

    /// The pixels of a `width` × `height` view the disk can reach: columns x0..x1 and rows
    /// y0..y1 (ends excluded) holding every pixel whose `disk_in_pixel` is not zero, so that a
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

/// How far inside the pixel's centre (in pixel radii) limb darkening is read: the overlap lies
/// towards the sun's centre (measured best over pixel sizes and offsets).
pub const SUN_LIMB_INSET: f64 = 0.3;

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
                            let d = sun.disk_in_pixel(f64::from(i) + 0.5, f64::from(j) + 0.5);
                            assert!(inside || d == 0.0, "{size} ({x}, {y}) wrap {wrap}: {i} {j}");
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
                let l = sun.disk_in_pixel(i as f64 + 0.5, j as f64 + 0.5);
                energy += l * side * side;
                peak = peak.max(l);
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
                    (energy - 1.0).abs() < 0.05,
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
        let point = sun_disk(DVec3::new((0.3 * a).tan(), 0.0, 1.0).normalize(), DVec3::Z);
        let averaged = small.disk_in_pixel(0.5 + at, 0.5);
        assert!(
            (averaged / point - 1.0).abs() < 1e-2,
            "{averaged} vs {point}"
        );
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
