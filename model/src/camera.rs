//! Cameras and projections: which ray each pixel sees, in planet-centred coordinates (m).
//!
//! The world frame is the local frame at the scene's origin on the ground: +z up, +y north,
//! +x east; the planet's centre is at (0, 0, −R). The sun direction is fixed in that frame. A
//! camera may be moved `back_km` over the planet's surface against its heading (Leenman's orbit
//! views); its own local frame then turns with the surface.

use crate::geometry::{Ray, direction_from_angles};
use crate::methods::shared::sun_disk::SunInView;
use crate::scene::CameraSettings;
use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

/// How pixels map to directions.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum Projection {
    /// Pinhole camera with the scene's vertical field of view.
    #[default]
    Perspective,
    /// Equidistant fisheye of the upper hemisphere: zenith at the centre, horizon on the
    /// inscribed circle, the camera's heading at the top.
    Fisheye,
    /// Equirectangular panorama: azimuth across (heading at the centre), elevation up.
    Panorama,
}

/// A camera placed in the world.
#[derive(Debug, Clone, Copy)]
pub struct Camera {
    /// Position relative to the planet's centre, m.
    pub position: DVec3,
    /// Local frame at the camera: columns east, north, up.
    pub frame: DMat3,
    pub heading_deg: f64,
    pub pitch_deg: f64,
    pub fov_deg: f64,
    pub projection: Projection,
}

/// What the rays of a pixel row end on (`Camera::rows_see`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sees {
    Sky,
    Ground,
    Both,
}

impl Camera {
    /// Places the camera of `settings` over a planet of radius `planet_radius_m`.
    pub fn new(settings: &CameraSettings, planet_radius_m: f64, projection: Projection) -> Camera {
        let r = planet_radius_m + settings.altitude_m;
        // Rotate about the axis perpendicular to the heading: moving "back" by the angle back/R.
        let angle = settings.back_km * 1000.0 / planet_radius_m;
        let heading = direction_from_angles(0.0, settings.heading_deg);
        let axis = DVec3::Z.cross(heading);
        let rotation = if angle != 0.0 {
            DMat3::from_axis_angle(axis.normalize(), -angle)
        } else {
            DMat3::IDENTITY
        };
        let up = rotation * DVec3::Z;
        Camera {
            position: up * r,
            frame: rotation,
            heading_deg: settings.heading_deg,
            pitch_deg: settings.pitch_deg,
            fov_deg: settings.fov_deg,
            projection,
        }
    }

    /// The world position of the camera measured from the scene origin's planet centre.
    pub fn local_to_world(&self, local: DVec3) -> DVec3 {
        self.frame * local
    }

    /// The ray through pixel (x, y) (0 ≤ x < width, top row y = 0) at sub-pixel offset (u, v)
    /// ∈ [0, 1)², or None where the projection shows nothing (outside the fisheye circle).
    pub fn ray(&self, x: f64, y: f64, width: u32, height: u32) -> Option<Ray> {
        let (w, h) = (width as f64, height as f64);
        let local = match self.projection {
            Projection::Perspective => {
                let tan_half = (self.fov_deg.to_radians() * 0.5).tan();
                let sx = (2.0 * x / w - 1.0) * tan_half * w / h;
                let sy = (1.0 - 2.0 * y / h) * tan_half;
                let [forward, right, up] = self.perspective_axes();
                let dir = (forward + right * sx + up * sy).normalize();
                return Some(Ray::new(self.position, dir));
            }
            Projection::Fisheye => {
                let size = w.min(h);
                let dx = (2.0 * x - w) / size;
                let dy = (h - 2.0 * y) / size;
                let rho = dx.hypot(dy);
                if rho > 1.0 {
                    return None;
                }
                let elevation = 90.0 * (1.0 - rho);
                let azimuth = self.heading_deg + dx.atan2(dy).to_degrees();
                direction_from_angles(elevation, azimuth)
            }
            Projection::Panorama => {
                let azimuth = self.heading_deg + (x / w - 0.5) * 360.0;
                let elevation = 90.0 - y / h * 180.0;
                direction_from_angles(elevation, azimuth)
            }
        };
        Some(Ray::new(self.position, self.frame * local))
    }

    /// The perspective view's forward, right and up directions in world coordinates: a
    /// pixel's ray is forward + right·sx + up·sy, normalised (sx, sy: the pixel's offset from
    /// the centre in units of the focal length). Computed once per frame for the GPU too.
    pub fn perspective_axes(&self) -> [DVec3; 3] {
        let forward = direction_from_angles(self.pitch_deg, self.heading_deg);
        let right = direction_from_angles(0.0, self.heading_deg + 90.0);
        let up = right.cross(forward);
        [forward, right, up].map(|v| self.frame * v)
    }

    /// Where the world direction `dir` falls in a view of `width` × `height`: pixel
    /// coordinates (x to the right, y down; inverse of [`Camera::ray`]), or None where the
    /// projection does not show it (behind a perspective camera, below the fisheye's horizon).
    pub fn project(&self, dir: DVec3, width: u32, height: u32) -> Option<(f64, f64)> {
        let (w, h) = (width as f64, height as f64);
        let local = self.frame.transpose() * dir.normalize();
        let elevation = local.z.clamp(-1.0, 1.0).asin().to_degrees();
        let azimuth = local.x.atan2(local.y).to_degrees() - self.heading_deg;
        match self.projection {
            Projection::Perspective => {
                let tan_half = (self.fov_deg.to_radians() * 0.5).tan();
                let forward = direction_from_angles(self.pitch_deg, self.heading_deg);
                let right = direction_from_angles(0.0, self.heading_deg + 90.0);
                let up = right.cross(forward);
                let z = local.dot(forward);
                if z <= 0.0 {
                    return None;
                }
                let (sx, sy) = (local.dot(right) / z, local.dot(up) / z);
                Some((
                    (sx / (tan_half * w / h) + 1.0) * 0.5 * w,
                    (1.0 - sy / tan_half) * 0.5 * h,
                ))
            }
            Projection::Fisheye => {
                if elevation < 0.0 {
                    return None;
                }
                let size = w.min(h);
                let rho = 1.0 - elevation / 90.0;
                let a = azimuth.to_radians();
                Some((
                    0.5 * (w + rho * a.sin() * size),
                    0.5 * (h - rho * a.cos() * size),
                ))
            }
            Projection::Panorama => Some((
                ((azimuth / 360.0 + 0.5).rem_euclid(1.0)) * w,
                (90.0 - elevation) / 180.0 * h,
            )),
        }
    }

    /// Whether any part of a view of `width` × `height` sees the ground of a planet of radius
    /// `planet_radius_m`: the nadir in the view, or a point of its border below the horizon
    /// (the lowest direction of a view lies on its border unless the nadir is inside).
    pub fn shows_ground(&self, planet_radius_m: f64, width: u32, height: u32) -> bool {
        let up = self.position.normalize();
        let (w, h) = (f64::from(width), f64::from(height));
        if self
            .project(-up, width, height)
            .is_some_and(|(x, y)| (0.0..=w).contains(&x) && (0.0..=h).contains(&y))
        {
            return true;
        }
        let sin_horizon = (planet_radius_m / self.position.length()).min(1.0);
        let mu_horizon = -(1.0 - sin_horizon * sin_horizon).sqrt();
        // A margin for the GPU, whose f32 rays graze the horizon a little differently.
        let below = |x: f64, y: f64| {
            self.ray(x, y, width, height)
                .is_some_and(|r| r.direction.dot(up) < mu_horizon + 1e-4)
        };
        (0..=width).any(|i| below(f64::from(i), 0.0) || below(f64::from(i), h))
            || (0..=height).any(|j| below(0.0, f64::from(j)) || below(w, f64::from(j)))
    }

    /// What each pixel row of a view of `width` × `height` sees of a planet of radius
    /// `planet_radius_m`: sky alone, ground alone or both (a margin wide of the horizon, for
    /// the GPU's f32 rays), so that a renderer can draw rows of sky without the ground's
    /// work and rows of ground without the sky's. Along a row of a perspective view the
    /// zenith cosine is extreme at its middle and its ends (the right axis is level), and a
    /// panorama's rows are level, so three rays settle each row; a fisheye's rows, when the
    /// view shows the ground at all, are taken to see both.
    pub fn rows_see(&self, planet_radius_m: f64, width: u32, height: u32) -> Vec<Sees> {
        let rows = height as usize;
        if !self.shows_ground(planet_radius_m, width, height) {
            return vec![Sees::Sky; rows];
        }
        if self.projection == Projection::Fisheye {
            return vec![Sees::Both; rows];
        }
        let up = self.position.normalize();
        let sin_horizon = (planet_radius_m / self.position.length()).min(1.0);
        let mu_horizon = -(1.0 - sin_horizon * sin_horizon).sqrt();
        const MARGIN: f64 = 1e-3;
        let w = f64::from(width);
        (0..height)
            .map(|j| {
                let y = f64::from(j) + 0.5;
                let mus = [0.0, 0.5 * w, w]
                    .map(|x| self.ray(x, y, width, height).map(|r| r.direction.dot(up)));
                let (lo, hi) = mus
                    .iter()
                    .flatten()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &m| {
                        (lo.min(m), hi.max(m))
                    });
                if lo > mu_horizon + MARGIN {
                    Sees::Sky
                } else if hi < mu_horizon - MARGIN {
                    Sees::Ground
                } else {
                    Sees::Both
                }
            })
            .collect()
    }

    /// Where the sun's centre falls in a view and how wide a pixel is there: what every
    /// pixel's share of the sun's disk is measured from; None where the view cannot show it.
    pub fn sun_in_view(&self, sun: DVec3, width: u32, height: u32) -> Option<SunInView> {
        let (x, y) = self.project(sun, width, height)?;
        let axes = self.pixel_axes_at(x, y, width, height);
        // A sun at the edge of what a projection shows (on the image plane of a camera looking
        // at right angles to it) lands far away on pixels of no size: it is not in the view.
        let far = 1e6 * f64::from(width.max(height));
        if !(x.abs() < far && y.abs() < far && axes.x.length() > 0.0 && axes.y.length() > 0.0) {
            return None;
        }
        Some(SunInView {
            x,
            y,
            pixel_width_rad: axes.x.length(),
            pixel_height_rad: axes.y.length(),
            wrap_width: match self.projection {
                Projection::Panorama => width as f64,
                _ => 0.0,
            },
        })
    }

    /// The pixel centred at (x, y) on the sky: the world vectors across its width and its
    /// height (their lengths are its angular width and height, rad); None where the projection
    /// shows nothing there.
    pub fn pixel_axes(&self, x: f64, y: f64, width: u32, height: u32) -> Option<PixelAxes> {
        self.ray(x, y, width, height)?;
        Some(self.pixel_axes_at(x, y, width, height))
    }

    /// "Up" in the picture at the view's point (x, y) for the ray `dir` through it: the unit
    /// vector perpendicular to `dir` towards the camera's up in a perspective view, else towards
    /// the rays half a pixel above (against the row index); the meridian plane's up (or north,
    /// or east) where that fails. The frame of the polarisation the views show (twin of
    /// `image_up` in `shaders/views/polarisation.wgsl`).
    pub fn image_up(&self, x: f64, y: f64, width: u32, height: u32, dir: DVec3) -> DVec3 {
        let d = match self.projection {
            Projection::Perspective => self.perspective_axes()[2],
            _ => -self.pixel_axes_at(x, y, width, height).y,
        };
        (d - dir * dir.dot(d)).try_normalize().unwrap_or_else(|| {
            crate::polarisation::meridian_frame(dir, self.position.normalize()).0
        })
    }

    /// [`Camera::pixel_axes`] anywhere: where a side of the pixel falls outside the projection
    /// (the fisheye's rim) the difference is taken one-sided.
    fn pixel_axes_at(&self, x: f64, y: f64, width: u32, height: u32) -> PixelAxes {
        let dir = |x: f64, y: f64| self.ray(x, y, width, height).map(|r| r.direction);
        let across = |dx: f64, dy: f64| match (
            dir(x + 0.5 * dx, y + 0.5 * dy),
            dir(x - 0.5 * dx, y - 0.5 * dy),
            dir(x, y),
        ) {
            (Some(p), Some(m), _) => p - m,
            (Some(p), None, Some(c)) => 2.0 * (p - c),
            (None, Some(m), Some(c)) => 2.0 * (c - m),
            _ => DVec3::ZERO,
        };
        PixelAxes {
            x: across(1.0, 0.0),
            y: across(0.0, 1.0),
        }
    }

    /// The share (0–1) of pixel (x, y)'s square that the projection shows: 1 except across
    /// the fisheye's rim, where it is the exact area of the square inside the circle.
    pub fn pixel_coverage(&self, x: u32, y: u32, width: u32, height: u32) -> f64 {
        if self.projection != Projection::Fisheye {
            return 1.0;
        }
        let (w, h) = (width as f64, height as f64);
        let size = w.min(h);
        // The pixel in the coordinates where the fisheye is the unit disk (as in `ray`).
        let (x0, x1) = (
            (2.0 * x as f64 - w) / size,
            (2.0 * (x + 1) as f64 - w) / size,
        );
        let (y0, y1) = (
            (h - 2.0 * (y + 1) as f64) / size,
            (h - 2.0 * y as f64) / size,
        );
        let farthest = x0.abs().max(x1.abs()).hypot(y0.abs().max(y1.abs()));
        let nearest = (x0.max(0.0) + x1.min(0.0)).hypot(y0.max(0.0) + y1.min(0.0));
        if farthest <= 1.0 {
            1.0
        } else if nearest >= 1.0 {
            0.0
        } else {
            (disk_rectangle_area(x0, x1, y0, y1) / ((x1 - x0) * (y1 - y0))).clamp(0.0, 1.0)
        }
    }
}

/// Area of the rectangle [x0, x1] × [y0, y1] inside the unit disk, exactly: the width of the
/// overlap at abscissa x is min(y1, s) − max(y0, −s) with s = √(1 − x²), integrated in closed
/// form between the abscissas where a bound of the rectangle meets the circle.
fn disk_rectangle_area(x0: f64, x1: f64, y0: f64, y1: f64) -> f64 {
    let (a, b) = (x0.max(-1.0), x1.min(1.0));
    if a >= b || y0 >= 1.0 || y1 <= -1.0 {
        return 0.0;
    }
    // ∫ √(1 − x²) dx.
    let under_arc = |x: f64| 0.5 * (x * (1.0 - x * x).max(0.0).sqrt() + x.clamp(-1.0, 1.0).asin());
    let mut cuts = vec![a, b];
    for y in [y0, y1] {
        if y.abs() < 1.0 {
            let c = (1.0 - y * y).sqrt();
            cuts.extend([-c, c].into_iter().filter(|&t| t > a && t < b));
        }
    }
    cuts.sort_by(f64::total_cmp);
    let mut area = 0.0;
    for piece in cuts.windows(2) {
        let (p, q) = (piece[0], piece[1]);
        let m = 0.5 * (p + q);
        let s = (1.0 - m * m).max(0.0).sqrt();
        // On each piece each bound is either the rectangle's side or the arc throughout (the
        // arc where it touches a side at the middle: a tangent side).
        let arc = under_arc(q) - under_arc(p);
        let top = if s <= y1 { arc } else { y1 * (q - p) };
        let bottom = if -s >= y0 { -arc } else { y0 * (q - p) };
        if s.min(y1) > (-s).max(y0) {
            area += top - bottom;
        }
    }
    area
}

/// A pixel's extent on the sky: world vectors across its width and height, rad long.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PixelAxes {
    pub x: DVec3,
    pub y: DVec3,
}

impl PixelAxes {
    /// Solid angle, sr.
    pub fn solid_angle(&self) -> f64 {
        self.x.cross(self.y).length()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    const R: f64 = 6_360_000.0;

    fn settings(alt: f64) -> CameraSettings {
        CameraSettings {
            altitude_m: alt,
            heading_deg: 0.0,
            pitch_deg: 0.0,
            fov_deg: 60.0,
            back_km: 0.0,
            polariser_deg: None,
        }
    }

    /// Every pixel of a row that `rows_see` calls sky sees the sky and every pixel of a row
    /// it calls ground sees the ground, over altitudes, pitches, fields of view and the
    /// projections; views with a horizon have rows of both and rows of one alone.
    #[test]
    fn rows_see_what_each_of_their_pixels_sees() {
        let (w, h) = (96u32, 54u32);
        let mut split = 0;
        for projection in [
            Projection::Perspective,
            Projection::Panorama,
            Projection::Fisheye,
        ] {
            for alt in [0.0, 1.0, 2000.0, 80_000.0, 400_000.0, 4e7] {
                for pitch in [-90.0, -60.0, -10.0, -0.2, 0.0, 5.0, 45.0, 90.0] {
                    for fov in [1.0, 60.0, 150.0] {
                        let mut s = settings(alt);
                        (s.pitch_deg, s.fov_deg, s.heading_deg) = (pitch, fov, 30.0);
                        let c = Camera::new(&s, R, projection);
                        let rows = c.rows_see(R, w, h);
                        assert_eq!(rows.len(), h as usize);
                        let altitude = c.position.length() - R;
                        let up = c.position.normalize();
                        for (j, seen) in rows.iter().enumerate() {
                            for i in 0..w {
                                let (x, y) = (f64::from(i) + 0.5, j as f64 + 0.5);
                                let Some(ray) = c.ray(x, y, w, h) else {
                                    continue;
                                };
                                let ground = crate::geometry::hits_ground(
                                    altitude,
                                    ray.direction.dot(up),
                                    R,
                                );
                                let ok = match seen {
                                    Sees::Sky => !ground,
                                    Sees::Ground => ground,
                                    Sees::Both => true,
                                };
                                assert!(
                                    ok,
                                    "{projection:?} {alt} m pitch {pitch} fov {fov}: row {j} ({seen:?}) pixel {i}"
                                );
                            }
                        }
                        if rows.contains(&Sees::Sky) && rows.contains(&Sees::Ground) {
                            split += 1;
                        }
                    }
                }
            }
        }
        assert!(split > 20, "{split} views split into sky and ground rows");
    }

    /// The pixels' solid angles add up to what the projection covers.
    #[test]
    fn pixel_solid_angles_add_up_to_the_projection() {
        let mut s = settings(10.0);
        s.fov_deg = 90.0;
        let (w, h) = (160, 90);
        let half_y = 45f64.to_radians();
        let half_x = (half_y.tan() * 160.0 / 90.0).atan();
        for (projection, total) in [
            (
                Projection::Perspective,
                4.0 * (half_x.sin() * half_y.sin()).asin(),
            ),
            // The sky dome in the inscribed circle; the panorama the whole sphere.
            (Projection::Fisheye, 2.0 * PI),
            (Projection::Panorama, 4.0 * PI),
        ] {
            let c = Camera::new(&s, R, projection);
            let sum: f64 = (0..w * h)
                .filter_map(|i| {
                    let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
                    Some(c.pixel_axes(x, y, w, h)?.solid_angle())
                })
                .sum();
            assert!(
                (sum / total - 1.0).abs() < 0.02,
                "{projection:?}: {sum} sr, expected {total}"
            );
        }
    }

    /// Found by `atmoscope stress`: the sun at the nadir seen by a camera looking level landed
    /// at 1e16 pixels on a pixel of no size, and the disk's share came out NaN.
    #[test]
    fn a_sun_at_right_angles_to_the_view_is_not_in_it() {
        let c = Camera::new(&settings(10.0), R, Projection::Perspective);
        for elevation in [-90.0, 90.0] {
            let sun = direction_from_angles(elevation, 250.0);
            assert_eq!(c.sun_in_view(sun, 5, 5), None, "{elevation}°");
        }
    }

    #[test]
    fn the_ground_is_in_a_view_that_looks_below_the_horizon() {
        let ground = |altitude_m: f64, pitch_deg: f64, projection| {
            let mut s = settings(altitude_m);
            s.pitch_deg = pitch_deg;
            Camera::new(&s, R, projection).shows_ground(R, 64, 36)
        };
        // 60° of field: the lower edge at pitch − 30° (corners a little lower).
        assert!(!ground(2.0, 40.0, Projection::Perspective));
        assert!(ground(2.0, 20.0, Projection::Perspective));
        assert!(ground(2.0, -90.0, Projection::Perspective));
        // From 400 km the horizon dips 20°.
        assert!(!ground(400_000.0, 15.0, Projection::Perspective));
        assert!(ground(400_000.0, 5.0, Projection::Perspective));
        assert!(!ground(2.0, 0.0, Projection::Fisheye));
        assert!(ground(2.0, 0.0, Projection::Panorama));
    }

    #[test]
    fn project_inverts_ray_in_every_projection() {
        let mut s = settings(500.0);
        s.heading_deg = 130.0;
        s.pitch_deg = 20.0;
        for projection in [
            Projection::Perspective,
            Projection::Fisheye,
            Projection::Panorama,
        ] {
            let c = Camera::new(&s, R, projection);
            for (x, y) in [(10.5, 20.5), (80.0, 45.0), (150.25, 3.75)] {
                let Some(ray) = c.ray(x, y, 160, 90) else {
                    continue;
                };
                let (px, py) = c.project(ray.direction, 160, 90).expect("shown");
                assert!(
                    (px - x).abs() < 1e-6 && (py - y).abs() < 1e-6,
                    "{projection:?}: ({x}, {y}) came back as ({px}, {py})"
                );
            }
        }
    }

    #[test]
    fn perspective_centre_looks_along_heading_and_pitch() {
        let mut s = settings(10.0);
        s.heading_deg = 90.0;
        s.pitch_deg = 30.0;
        let c = Camera::new(&s, R, Projection::Perspective);
        let ray = c.ray(50.0, 50.0, 100, 100).unwrap();
        let expected = direction_from_angles(30.0, 90.0);
        assert!((ray.direction - expected).length() < 1e-12);
        assert!((ray.origin.length() - (R + 10.0)).abs() < 1e-6);
    }

    /// The fisheye's pixels cover the circle: whole inside, nothing outside, and across the
    /// rim the share a fine grid of sub-pixel points finds inside; together π/4 of the square.
    #[test]
    fn fisheye_pixels_cover_exactly_the_circle() {
        for (w, h) in [(32, 32), (41, 23)] {
            let cam = Camera::new(&settings(1.0), R, Projection::Fisheye);
            let mut total = 0.0;
            let mut rim = 0;
            for y in 0..h {
                for x in 0..w {
                    let c = cam.pixel_coverage(x, y, w, h);
                    total += c;
                    if c > 0.0 && c < 1.0 {
                        rim += 1;
                        let n = 200;
                        let inside = (0..n * n)
                            .filter(|k| {
                                let (u, v) = ((k % n) as f64 + 0.5, (k / n) as f64 + 0.5);
                                let (px, py) = (x as f64 + u / n as f64, y as f64 + v / n as f64);
                                cam.ray(px, py, w, h).is_some()
                            })
                            .count();
                        let grid = inside as f64 / (n * n) as f64;
                        assert!(
                            (c - grid).abs() < 2e-3,
                            "{w}×{h} ({x}, {y}): {c} vs grid {grid}"
                        );
                    } else {
                        // A pixel wholly in or out: its centre says which.
                        let centre = cam.ray(x as f64 + 0.5, y as f64 + 0.5, w, h).is_some();
                        assert_eq!(c, if centre { 1.0 } else { 0.0 }, "{w}×{h} ({x}, {y})");
                    }
                }
            }
            let size = w.min(h) as f64;
            assert!(rim > 0);
            assert!(
                (total - PI / 4.0 * size * size).abs() < 1e-9 * size * size,
                "{w}×{h}: {total}"
            );
        }
        let perspective = Camera::new(&settings(1.0), R, Projection::Perspective);
        assert_eq!(perspective.pixel_coverage(0, 0, 8, 8), 1.0);
    }

    #[test]
    fn fisheye_centre_is_the_zenith_and_corners_are_empty() {
        let c = Camera::new(&settings(1.0), R, Projection::Fisheye);
        assert!((c.ray(50.0, 50.0, 100, 100).unwrap().direction - DVec3::Z).length() < 1e-12);
        assert!(c.ray(0.0, 0.0, 100, 100).is_none());
        let top = c.ray(50.0, 0.0, 100, 100).unwrap().direction;
        assert!(
            (top - DVec3::Y).length() < 1e-12,
            "heading north at the top edge: {top}"
        );
    }

    #[test]
    fn moving_back_keeps_altitude_and_turns_the_frame() {
        let mut s = settings(100_000.0);
        s.back_km = 1000.0;
        let c = Camera::new(&s, R, Projection::Perspective);
        assert!((c.position.length() - (R + 100_000.0)).abs() < 1e-6);
        assert!(
            c.position.y < -900_000.0,
            "moved south, against the northward heading: {}",
            c.position
        );
        let up = c.position.normalize();
        assert!((c.frame * DVec3::Z - up).length() < 1e-12);
    }
}
