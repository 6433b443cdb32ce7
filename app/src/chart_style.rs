//! How the benchmarks' charts tell models apart: one colour per family of method (the
//! registry's `Family`, from Okabe and Ito's colour-blind-safe palette), one marker shape per
//! model within its family, and point labels placed where they cover no other label or marker.

use atmoscope_model::methods::Family;

/// One colour per `Family::ALL`, as sRGB bytes, dark enough to read on white. Hues that lie
/// close (blue and sky blue, vermillion and orange) go to families whose points lie apart on
/// the charts (tables against intensity volumes, marches against analytic fits).
pub const FAMILY_COLOURS: [[u8; 3]; 8] = [
    [0, 114, 178],   // blue
    [213, 94, 0],    // vermillion
    [0, 158, 115],   // bluish green
    [204, 121, 167], // reddish purple
    [86, 180, 233],  // sky blue
    [230, 159, 0],   // orange
    [110, 110, 110], // grey
    [0, 0, 0],       // black
];

/// The marker shapes, filled then open.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    Circle,
    Triangle,
    Square,
    Cross,
    Ring,
    OpenTriangle,
    OpenSquare,
}

pub const MARKERS: [Marker; 7] = [
    Marker::Circle,
    Marker::Triangle,
    Marker::Square,
    Marker::Cross,
    Marker::Ring,
    Marker::OpenTriangle,
    Marker::OpenSquare,
];

/// A model's colour and marker on a chart.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Style {
    pub colour: [u8; 3],
    pub marker: Marker,
}

/// The style of `model` (a registry id): its family's colour and its marker within the family.
/// A model this build does not know (results from elsewhere) is grey, its marker by `index`.
pub fn style(model: &str, index: usize) -> Style {
    match Family::style_of(model) {
        Some((family, within)) => Style {
            colour: FAMILY_COLOURS[family % FAMILY_COLOURS.len()],
            marker: MARKERS[within % MARKERS.len()],
        },
        None => Style {
            colour: FAMILY_COLOURS[6],
            marker: MARKERS[index % MARKERS.len()],
        },
    }
}

/// An axis-aligned box in pixels: left, top, width, height.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PixelBox {
    pub x: i32,
    pub y: i32,
    pub w: i32,
    pub h: i32,
}

impl PixelBox {
    fn overlaps(&self, o: &PixelBox) -> bool {
        self.x < o.x + o.w && o.x < self.x + self.w && self.y < o.y + o.h && o.y < self.y + self.h
    }

    fn inside(&self, area: &PixelBox) -> bool {
        self.x >= area.x
            && self.y >= area.y
            && self.x + self.w <= area.x + area.w
            && self.y + self.h <= area.y + area.h
    }
}

/// Places a label `sizes[i]` (width, height in pixels) beside each point `points[i]`: right of
/// it, else left, above or below, the first place that lies in `area` and covers no marker
/// (a square of half-side `marker_radius` round each point) and no label placed before it.
/// A label with no free place is left out (None): the legend and the tables still name it.
pub fn place_labels(
    points: &[(i32, i32)],
    sizes: &[(i32, i32)],
    marker_radius: i32,
    area: PixelBox,
) -> Vec<Option<PixelBox>> {
    let r = marker_radius;
    let markers: Vec<PixelBox> = points
        .iter()
        .map(|&(x, y)| PixelBox {
            x: x - r,
            y: y - r,
            w: 2 * r,
            h: 2 * r,
        })
        .collect();
    let mut placed: Vec<PixelBox> = Vec::new();
    points
        .iter()
        .zip(sizes)
        .map(|(&(x, y), &(w, h))| {
            let gap = r + 3;
            let candidates = [
                (x + gap, y - h / 2),
                (x - gap - w, y - h / 2),
                (x - w / 2, y - gap - h),
                (x - w / 2, y + gap),
            ];
            let free = candidates
                .iter()
                .map(|&(x, y)| PixelBox { x, y, w, h })
                .find(|b| {
                    b.inside(&area)
                        && !markers.iter().any(|m| m.overlaps(b))
                        && !placed.iter().any(|p| p.overlaps(b))
                })?;
            placed.push(free);
            Some(free)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use atmoscope_model::methods::MODELS;

    #[test]
    fn every_model_has_a_style_of_its_own() {
        let styles: Vec<Style> = MODELS.iter().map(|m| style(m.id, 0)).collect();
        for (i, a) in styles.iter().enumerate() {
            for (j, b) in styles.iter().enumerate().skip(i + 1) {
                assert_ne!(a, b, "{} and {} share a style", MODELS[i].id, MODELS[j].id);
            }
        }
        // Families apart by colour.
        assert_ne!(style("hillaire", 0).colour, style("nishita", 0).colour);
        assert_eq!(style("hillaire", 0).colour, style("bruneton", 0).colour);
        assert_eq!(style("no-such-model", 3).marker, MARKERS[3]);
    }

    #[test]
    fn placed_labels_cover_no_marker_and_no_other_label() {
        // A cluster of points, as the quick benchmark's spectral sets draw them.
        let points: Vec<(i32, i32)> = (0..12)
            .map(|i| (100 + (i % 4) * 9, 100 + (i / 4) * 7))
            .collect();
        let sizes = vec![(60, 12); points.len()];
        let area = PixelBox {
            x: 0,
            y: 0,
            w: 400,
            h: 300,
        };
        let placed = place_labels(&points, &sizes, 5, area);
        let boxes: Vec<PixelBox> = placed.iter().flatten().copied().collect();
        assert!(boxes.len() >= 2, "some labels fit: {placed:?}");
        assert!(
            boxes.len() < points.len(),
            "a crowd cannot be labelled whole"
        );
        for (i, b) in boxes.iter().enumerate() {
            assert!(b.inside(&area));
            for o in &boxes[i + 1..] {
                assert!(!b.overlaps(o), "{b:?} overlaps {o:?}");
            }
            for &(x, y) in &points {
                let m = PixelBox {
                    x: x - 5,
                    y: y - 5,
                    w: 10,
                    h: 10,
                };
                assert!(!b.overlaps(&m), "{b:?} covers the marker at ({x}, {y})");
            }
        }
        // A lone point gets its label on the right.
        let lone = place_labels(&[(50, 50)], &[(40, 12)], 5, area);
        assert_eq!(
            lone,
            vec![Some(PixelBox {
                x: 58,
                y: 44,
                w: 40,
                h: 12
            })]
        );
    }
}
