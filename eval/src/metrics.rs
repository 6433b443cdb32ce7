//! Error metrics between a test image and a reference, both linear sRGB radiance
//! (W·m⁻²·sr⁻¹, row-major): RMSE and relative RMSE of radiance and of luminance; mean and
//! 95th-percentile CIEDE2000 of the display-referred images (a fixed exposure and tone map,
//! reported with the figures); LDR-FLIP (Andersson et al. 2020, NVIDIA's implementation through
//! `nv-flip`) on those display images; and HDR-FLIP (Andersson et al. 2021): LDR-FLIP under the
//! ACES tone curve at exposures spanning the reference's luminance range, per-pixel maximum.

use atmoscope_model::colour::{delta_e2000, linear_srgb_to_lab, linear_srgb_to_xyz, srgb_decode};
use atmoscope_model::display::{EXPOSURE_SCALE, display, to_u8};
use atmoscope_model::scene::ToneMap;
use serde::Serialize;

/// The display transform under which display-referred metrics are computed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DisplaySetup {
    pub exposure_ev: f64,
    pub tone_map: ToneMap,
    /// Pixels per degree of visual angle for FLIP (67 = a 0.7 m viewing distance on a 24" 4K screen).
    pub pixels_per_degree: f64,
}

impl Default for DisplaySetup {
    fn default() -> Self {
        DisplaySetup {
            exposure_ev: 0.0,
            tone_map: ToneMap::Exponential,
            pixels_per_degree: 67.0,
        }
    }
}

/// Every metric of one comparison.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    pub rmse: f64,
    pub relative_rmse: f64,
    pub luminance_rmse_cd_m2: f64,
    pub luminance_relative_rmse: f64,
    /// Median over the pixels of test/reference luminance (pixels with a black reference left
    /// out; NaN if all are): above 1, most of the image is too bright. The median, so that the
    /// sun's few pixels and a noisy reference's outliers do not sway it.
    pub luminance_ratio: f64,
    pub delta_e2000_mean: f64,
    pub delta_e2000_p95: f64,
    pub ldr_flip_mean: f64,
    pub hdr_flip_mean: f64,
    pub display: DisplaySetup,
}

/// Per-pixel error maps, for writing as images.
pub struct ErrorMaps {
    pub delta_e2000: Vec<f64>,
    pub ldr_flip: Vec<f64>,
}

fn luminance_cd_m2(rgb: [f64; 3]) -> f64 {
    683.0 * linear_srgb_to_xyz(rgb).y
}

fn rmse(pairs: impl Iterator<Item = (f64, f64)>) -> (f64, f64) {
    let (mut se, mut sum, mut n) = (0.0, 0.0, 0usize);
    for (t, r) in pairs {
        se += (t - r) * (t - r);
        sum += r.abs();
        n += 1;
    }
    let rmse = (se / n.max(1) as f64).sqrt();
    let mean = sum / n.max(1) as f64;
    (rmse, if mean > 0.0 { rmse / mean } else { 0.0 })
}

/// The `p`-quantile (0–1) of `values`, nearest rank; 0 for none.
pub fn percentile(values: &[f64], p: f64) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    if v.is_empty() {
        return 0.0;
    }
    v[((p * (v.len() - 1) as f64).round() as usize).min(v.len() - 1)]
}

fn to_rgb8(image: &[[f64; 3]], exposure_ev: f64, tone_map: ToneMap) -> Vec<u8> {
    image
        .iter()
        .flat_map(|&c| display(c, exposure_ev, tone_map).map(to_u8))
        .collect()
}

#[cfg(not(target_arch = "wasm32"))]
fn ldr_flip(reference: &[u8], test: &[u8], width: u32, height: u32, ppd: f64) -> Vec<f64> {
    let r = nv_flip::FlipImageRgb8::with_data(width, height, reference);
    let t = nv_flip::FlipImageRgb8::with_data(width, height, test);
    nv_flip::flip(r, t, ppd as f32)
        .to_vec()
        .into_iter()
        .map(f64::from)
        .collect()
}

/// In the browser FLIP is not computed (its C++ library has no WebAssembly build): every
/// pixel's error, and so each mean of it, is NaN ("not computed").
#[cfg(target_arch = "wasm32")]
fn ldr_flip(reference: &[u8], _test: &[u8], _width: u32, _height: u32, _ppd: f64) -> Vec<f64> {
    vec![f64::NAN; reference.len() / 3]
}

fn delta_e2000_of_rgb8(test: &[u8], reference: &[u8]) -> Vec<f64> {
    let lab = |px: &[u8]| {
        linear_srgb_to_lab([px[0], px[1], px[2]].map(|v| srgb_decode(v as f64 / 255.0)))
    };
    test.chunks_exact(3)
        .zip(reference.chunks_exact(3))
        .map(|(t, r)| delta_e2000(lab(t), lab(r)))
        .collect()
}

/// Per-pixel CIEDE2000 between the display-referred images of `test` and `reference` (same
/// size): the cheap part of [`compare`], for interactive use.
pub fn delta_e2000_map(test: &[[f64; 3]], reference: &[[f64; 3]], setup: DisplaySetup) -> Vec<f64> {
    assert_eq!(test.len(), reference.len(), "images differ in size");
    delta_e2000_of_rgb8(
        &to_rgb8(test, setup.exposure_ev, setup.tone_map),
        &to_rgb8(reference, setup.exposure_ev, setup.tone_map),
    )
}

/// Compares `test` with `reference` (same size, `width` × `height`).
pub fn compare(
    test: &[[f64; 3]],
    reference: &[[f64; 3]],
    width: u32,
    height: u32,
    setup: DisplaySetup,
) -> (Comparison, ErrorMaps) {
    assert_eq!(test.len(), reference.len(), "images differ in size");
    let (rmse_rgb, rel_rgb) = rmse(
        test.iter()
            .zip(reference)
            .flat_map(|(t, r)| (0..3).map(move |c| (t[c], r[c]))),
    );
    let (rmse_l, rel_l) = rmse(
        test.iter()
            .zip(reference)
            .map(|(t, r)| (luminance_cd_m2(*t), luminance_cd_m2(*r))),
    );
    let ratios: Vec<f64> = test
        .iter()
        .zip(reference)
        .map(|(t, r)| (luminance_cd_m2(*t), luminance_cd_m2(*r)))
        .filter(|&(_, r)| r > 0.0)
        .map(|(t, r)| t / r)
        .collect();
    let luminance_ratio = if ratios.is_empty() {
        f64::NAN
    } else {
        percentile(&ratios, 0.5)
    };
    let t8 = to_rgb8(test, setup.exposure_ev, setup.tone_map);
    let r8 = to_rgb8(reference, setup.exposure_ev, setup.tone_map);
    let delta_e = delta_e2000_of_rgb8(&t8, &r8);
    let flip = ldr_flip(&r8, &t8, width, height, setup.pixels_per_degree);
    let hdr = hdr_flip(test, reference, width, height, setup.pixels_per_degree);
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    let comparison = Comparison {
        rmse: rmse_rgb,
        relative_rmse: rel_rgb,
        luminance_rmse_cd_m2: rmse_l,
        luminance_relative_rmse: rel_l,
        luminance_ratio,
        delta_e2000_mean: mean(&delta_e),
        delta_e2000_p95: percentile(&delta_e, 0.95),
        ldr_flip_mean: mean(&flip),
        hdr_flip_mean: mean(&hdr),
        display: setup,
    };
    (
        comparison,
        ErrorMaps {
            delta_e2000: delta_e,
            ldr_flip: flip,
        },
    )
}

/// HDR-FLIP: the reference's luminance range sets the exposures (from where its median maps to
/// mid-grey down to where its maximum is not clipped, Andersson et al. 2021 §4); LDR-FLIP under
/// ACES at each, and the per-pixel maximum.
fn hdr_flip(
    test: &[[f64; 3]],
    reference: &[[f64; 3]],
    width: u32,
    height: u32,
    ppd: f64,
) -> Vec<f64> {
    let y: Vec<f64> = reference
        .iter()
        .map(|&c| linear_srgb_to_xyz(c).y.max(0.0))
        .filter(|&v| v > 0.0)
        .collect();
    if y.is_empty() {
        return vec![0.0; test.len()];
    }
    let median = percentile(&y, 0.5);
    let max = percentile(&y, 1.0);
    // Exposure k·Y; tone-mapper input x = EXPOSURE_SCALE·2^ev·Y.
    let ev_for = |target_x: f64, y: f64| (target_x / (EXPOSURE_SCALE * y)).log2();
    let (start, stop) = (
        ev_for(0.85, max).min(ev_for(0.18, median)),
        ev_for(0.85, max).max(ev_for(0.18, median)),
    );
    let steps = ((stop - start).ceil() as usize).clamp(2, 12);
    let mut out = vec![0.0f64; test.len()];
    for k in 0..steps {
        let ev = start + (stop - start) * k as f64 / (steps - 1) as f64;
        let f = ldr_flip(
            &to_rgb8(reference, ev, ToneMap::Filmic),
            &to_rgb8(test, ev, ToneMap::Filmic),
            width,
            height,
            ppd,
        );
        for (o, v) in out.iter_mut().zip(f) {
            *o = o.max(v);
        }
    }
    out
}

/// Relative RMSE of luminance over the pixels where `keep` is true (same length as the
/// images): outside the sun's disk, say, whose few pixels of 10⁵-fold radiance would otherwise
/// be the whole error.
pub fn luminance_relative_rmse_where(
    test: &[[f64; 3]],
    reference: &[[f64; 3]],
    keep: &[bool],
) -> f64 {
    rmse(
        test.iter()
            .zip(reference)
            .zip(keep)
            .filter(|(_, k)| **k)
            .map(|((t, r), _)| (luminance_cd_m2(*t), luminance_cd_m2(*r))),
    )
    .1
}

/// Indices of the points on the Pareto front of `(cost, error)` pairs — those no other point
/// beats on one axis without losing on the other — in order of increasing cost. Lower is
/// better on both axes; a point equal to another on both is kept once (the first). Points
/// with a NaN coordinate are never on the front.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len())
        .filter(|&i| !points[i].0.is_nan() && !points[i].1.is_nan())
        .collect();
    // By cost, then by error: walking in this order, a point is on the front exactly when its
    // error is below every error seen so far.
    order.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for i in order {
        if points[i].1 < best {
            best = points[i].1;
            front.push(i);
        }
    }
    front
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gradient(w: u32, h: u32, scale: f64) -> Vec<[f64; 3]> {
        (0..w * h)
            .map(|i| [scale * (i % w) as f64, 5.0, scale * (i / w) as f64 + 1.0])
            .collect()
    }

    #[test]
    fn identical_images_have_zero_error() {
        let a = gradient(16, 8, 1.0);
        let (c, maps) = compare(&a, &a, 16, 8, DisplaySetup::default());
        assert_eq!(c.rmse, 0.0);
        assert_eq!(c.delta_e2000_mean, 0.0);
        assert!(c.ldr_flip_mean < 1e-6 && c.hdr_flip_mean < 1e-6);
        assert_eq!(maps.delta_e2000.len(), 128);
    }

    #[test]
    fn a_brighter_image_has_the_expected_relative_error_and_visible_differences() {
        let a = gradient(16, 8, 1.0);
        let b: Vec<[f64; 3]> = a.iter().map(|c| c.map(|v| v * 1.1)).collect();
        let (c, _) = compare(&b, &a, 16, 8, DisplaySetup::default());
        assert!((c.relative_rmse - 0.1).abs() < 0.03, "{}", c.relative_rmse);
        assert!((c.luminance_relative_rmse - 0.1).abs() < 0.03);
        assert!(
            (c.luminance_ratio - 1.1).abs() < 1e-9,
            "{}",
            c.luminance_ratio
        );
        assert!(
            c.delta_e2000_mean > 0.3 && c.ldr_flip_mean > 0.0 && c.hdr_flip_mean > 0.0,
            "{c:?}"
        );
    }

    #[test]
    fn the_delta_e_map_is_the_one_compare_reports() {
        let a = gradient(16, 8, 1.0);
        let b: Vec<[f64; 3]> = a.iter().map(|c| c.map(|v| v * 1.3)).collect();
        let (_, maps) = compare(&b, &a, 16, 8, DisplaySetup::default());
        let map = delta_e2000_map(&b, &a, DisplaySetup::default());
        assert_eq!(map, maps.delta_e2000);
        assert!(map.iter().any(|&d| d > 1.0));
    }

    #[test]
    fn the_pareto_front_of_a_hand_made_table() {
        // (ms, error): 0 and 2 are dominated by 1 and 3; 4 ties 3 on cost and loses on
        // error; 5 repeats 6 exactly and comes first; 7 has no error measured.
        let points = [
            (2.0, 5.0),
            (1.0, 4.0),
            (3.0, 3.0),
            (2.5, 2.0),
            (2.5, 2.5),
            (8.0, 0.5),
            (8.0, 0.5),
            (0.5, f64::NAN),
            (10.0, 0.6),
        ];
        assert_eq!(pareto_front(&points), vec![1, 3, 5]);
        assert_eq!(pareto_front(&[]), Vec::<usize>::new());
        assert_eq!(pareto_front(&[(1.0, 1.0)]), vec![0]);
    }

    #[test]
    fn pixels_left_out_do_not_count_in_the_relative_rmse() {
        let a = gradient(8, 4, 1.0);
        let mut b = a.clone();
        b[5] = [1e6; 3];
        let all = vec![true; a.len()];
        let mut keep = all.clone();
        keep[5] = false;
        assert!(luminance_relative_rmse_where(&b, &a, &all) > 100.0);
        assert_eq!(luminance_relative_rmse_where(&b, &a, &keep), 0.0);
        let (c, _) = compare(&b, &a, 8, 4, DisplaySetup::default());
        assert!(
            (c.luminance_relative_rmse - luminance_relative_rmse_where(&b, &a, &all)).abs() < 1e-12
        );
    }
}
