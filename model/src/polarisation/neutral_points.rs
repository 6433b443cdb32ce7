//! The neutral points of skylight: directions where the light is unpolarised although the sky
//! around is not (Arago 1809 above the antisolar point, Babinet 1840 above the sun, Brewster 1842
//! below it; Coulson 1988, ch. 5). Single scattering alone has its only zeros at the sun and the
//! antisolar point; light scattered more than once moves them off, by about 15–25° in a clear
//! sky, more in haze and at twilight.
//!
//! A view's Stokes field (Q, U in one smooth frame, such as "up" in the picture) vanishes at a
//! neutral point in both components at once: [`zeros`] finds such points between pixel
//! centres, [`kind`] names them by where they lie from the sun.

use glam::DVec3;

/// Which neutral point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Above the antisolar point.
    Arago,
    /// Above the sun.
    Babinet,
    /// Below the sun.
    Brewster,
    /// Below the antisolar point (seen from a height, or over a bright ground).
    BelowAntisun,
}

impl Kind {
    pub fn label(self) -> &'static str {
        match self {
            Kind::Arago => "Arago",
            Kind::Babinet => "Babinet",
            Kind::Brewster => "Brewster",
            Kind::BelowAntisun => "below the antisun",
        }
    }
}

/// A neutral point found in a view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeutralPoint {
    pub kind: Kind,
    /// Where in the view, pixels (x right, y down; a pixel's centre at +0.5).
    pub x: f64,
    pub y: f64,
    /// Its elevation above the horizon and its angle from the sun, degrees.
    pub elevation_deg: f64,
    pub from_sun_deg: f64,
}

/// Closer to the sun or the antisolar point than this (degrees) a zero is theirs, not a
/// neutral point: single scattering's own, placed by the planes through a square of pixel
/// centres to within about a pixel (2° on a 96-pixel dome). The neutral points lie 8° or more
/// away.
pub const MIN_ANGLE_FROM_SUN_DEG: f64 = 3.0;

/// The points between the pixel centres of a `width` × `height` field where Q and U (row-major,
/// one per pixel, `None` outside the view) both vanish: in each square of four neighbouring
/// centres where both change sign, the zero of the plane fitted to each through the corners,
/// where it falls inside the square. Pixel coordinates with a centre at +0.5.
pub fn zeros(qu: &[Option<[f64; 2]>], width: usize, height: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for y in 0..height.saturating_sub(1) {
        for x in 0..width.saturating_sub(1) {
            let corners = [(0, 0), (1, 0), (0, 1), (1, 1)]
                .map(|(dx, dy)| qu[(y + dy) * width + x + dx].map(|v| (dx as f64, dy as f64, v)));
            let Some(c) = corners.into_iter().collect::<Option<Vec<_>>>() else {
                continue;
            };
            let changes = |k: usize| {
                let lo = c.iter().map(|p| p.2[k]).fold(f64::INFINITY, f64::min);
                let hi = c.iter().map(|p| p.2[k]).fold(f64::NEG_INFINITY, f64::max);
                lo <= 0.0 && hi >= 0.0 && hi > lo
            };
            if !(changes(0) && changes(1)) {
                continue;
            }
            // Least-squares planes v = a + b·dx + c·dy over the four corners: with corners at 0
            // and 1, b and c are the mean differences across, a the mean less their halves.
            let plane = |k: usize| {
                let v = |i: usize| c[i].2[k];
                let b = 0.5 * ((v(1) - v(0)) + (v(3) - v(2)));
                let cc = 0.5 * ((v(2) - v(0)) + (v(3) - v(1)));
                let a = 0.25 * (v(0) + v(1) + v(2) + v(3)) - 0.5 * b - 0.5 * cc;
                (a, b, cc)
            };
            let ((a1, b1, c1), (a2, b2, c2)) = (plane(0), plane(1));
            let det = b1 * c2 - b2 * c1;
            if det.abs() < 1e-300 {
                continue;
            }
            let dx = (-a1 * c2 + a2 * c1) / det;
            let dy = (-b1 * a2 + b2 * a1) / det;
            let at = (x as f64 + 0.5 + dx, y as f64 + 0.5 + dy);
            // A zero on an edge or a corner is found by each square it bounds: once is enough.
            let known = |p: &(f64, f64)| (p.0 - at.0).hypot(p.1 - at.1) < 0.5;
            if (0.0..=1.0).contains(&dx) && (0.0..=1.0).contains(&dy) && !out.iter().any(known) {
                out.push(at);
            }
        }
    }
    out
}

/// Which neutral point a zero in direction `dir` is, with the sun in direction `sun` and the
/// local zenith `zenith` (unit vectors): None within [`MIN_ANGLE_FROM_SUN_DEG`] of the sun or
/// the antisolar point.
pub fn kind(dir: DVec3, sun: DVec3, zenith: DVec3) -> Option<Kind> {
    let from_sun = dir.dot(sun).clamp(-1.0, 1.0).acos().to_degrees();
    if from_sun < MIN_ANGLE_FROM_SUN_DEG || from_sun > 180.0 - MIN_ANGLE_FROM_SUN_DEG {
        return None;
    }
    let above = |target: DVec3| dir.dot(zenith) > target.dot(zenith);
    Some(
        match (
            from_sun < 90.0,
            above(if from_sun < 90.0 { sun } else { -sun }),
        ) {
            (true, true) => Kind::Babinet,
            (true, false) => Kind::Brewster,
            (false, true) => Kind::Arago,
            (false, false) => Kind::BelowAntisun,
        },
    )
}

/// The neutral points of a view's Stokes field (Q, U per pixel as for [`zeros`]), with
/// `direction(x, y)` the view's ray at a point of the view.
pub fn find(
    qu: &[Option<[f64; 2]>],
    width: usize,
    height: usize,
    direction: impl Fn(f64, f64) -> Option<DVec3>,
    sun: DVec3,
    zenith: DVec3,
) -> Vec<NeutralPoint> {
    zeros(qu, width, height)
        .into_iter()
        .filter_map(|(x, y)| {
            let dir = direction(x, y)?;
            Some(NeutralPoint {
                kind: kind(dir, sun, zenith)?,
                x,
                y,
                elevation_deg: dir.dot(zenith).clamp(-1.0, 1.0).asin().to_degrees(),
                from_sun_deg: dir.dot(sun).clamp(-1.0, 1.0).acos().to_degrees(),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::direction_from_angles;

    /// A synthetic field with zeros where they were put: Q ∝ (x − x₀)(x − x₁), U ∝ (y − y₀),
    /// vanishing together at (x₀, y₀) and (x₁, y₀), found within a fiftieth of a pixel; a field with no
    /// common zero (U never vanishes) has none; pixels outside the view are skipped.
    #[test]
    fn zeros_are_found_where_a_synthetic_field_vanishes() {
        let (w, h) = (40, 30);
        let (x0, x1, y0) = (10.3, 27.8, 14.6);
        let field = |u_offset: f64| -> Vec<Option<[f64; 2]>> {
            (0..w * h)
                .map(|i| {
                    let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
                    Some([0.01 * (x - x0) * (x - x1), 0.2 * (y - y0) + u_offset])
                })
                .collect()
        };
        let mut found = zeros(&field(0.0), w, h);
        found.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert_eq!(found.len(), 2, "{found:?}");
        // The plane through a square's corners is exact for U and for Q across x within the
        // square only to its curvature: within a fiftieth of a pixel.
        assert!(
            (found[0].0 - x0).abs() < 0.02 && (found[0].1 - y0).abs() < 1e-9,
            "{found:?}"
        );
        assert!(
            (found[1].0 - x1).abs() < 0.02 && (found[1].1 - y0).abs() < 1e-9,
            "{found:?}"
        );
        assert!(zeros(&field(100.0), w, h).is_empty());
        // A zero on a pixel centre is a corner of four squares: found once.
        let on_centre: Vec<Option<[f64; 2]>> = (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
                Some([x - 20.5, y - 14.5])
            })
            .collect();
        assert_eq!(zeros(&on_centre, w, h), vec![(20.5, 14.5)]);
        let mut holed = field(0.0);
        holed[14 * w + 10] = None;
        assert_eq!(zeros(&holed, w, h).len(), 1);
    }

    /// Names by place: with the sun 30° up in the south, a zero 20° above it is Babinet's, 20°
    /// below Brewster's, 20° above the antisolar point Arago's, and one at the sun none.
    #[test]
    fn neutral_points_are_named_by_where_they_lie_from_the_sun() {
        let (sun, zenith) = (direction_from_angles(30.0, 180.0), DVec3::Z);
        assert_eq!(
            kind(direction_from_angles(50.0, 180.0), sun, zenith),
            Some(Kind::Babinet)
        );
        assert_eq!(
            kind(direction_from_angles(10.0, 180.0), sun, zenith),
            Some(Kind::Brewster)
        );
        assert_eq!(
            kind(direction_from_angles(-10.0, 0.0), sun, zenith),
            Some(Kind::Arago)
        );
        assert_eq!(
            kind(direction_from_angles(-50.0, 0.0), sun, zenith),
            Some(Kind::BelowAntisun)
        );
        assert_eq!(kind(sun, sun, zenith), None);
        assert_eq!(kind(-sun, sun, zenith), None);
    }
}
