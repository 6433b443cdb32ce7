//! Wavelength sets: which wavelengths a real-time method renders and how their radiances become
//! linear sRGB. Every set is split into batches of four lanes (one `vec4` on the GPU).
//!
//! - RGB3: 680/550/440 nm read directly as R, G, B (the common shortcut; wrong in hue).
//! - Spectral4: García Liñán (2023)'s method, four wavelengths with a 3×4 matrix to linear sRGB,
//!   with the wavelengths chosen and the matrix fitted by this project against SpectralN renders
//!   (`atmoscope fit-wavelengths`, stored in `data/spectral4_fitted.csv`); the published
//!   630/560/490/430 nm and matrix (`data/garcia_linan_2023_constants.csv`) are kept for
//!   comparison.
//! - SpectralN: N equal bands over 360–830 nm; each lane is weighted by the CIE 1931 functions
//!   integrated over its band, then XYZ → linear sRGB.
//!
//! Linear sRGB here is in the units of `colour::xyz_to_linear_srgb` applied to spectral radiance:
//! Y = ∫ȳL dλ in W·m⁻²·sr⁻¹, so all three sets are directly comparable.

use crate::colour::{Xyz, cie1931, xyz_to_linear_srgb};
use crate::constants::{VISIBLE_MAX_NM, VISIBLE_MIN_NM};
use crate::csv_table::{Table, tables};
use crate::scene::WavelengthSet;

/// Lanes per batch (one `vec4<f32>` on the GPU).
pub const LANES: usize = 4;

/// Band over which RGB3 and Spectral4 average the solar spectrum at each of their wavelengths,
/// nm: a point sample can land on a Fraunhofer line (430 nm, Spectral4's blue, lies 22 % below
/// its 10 nm mean), which would tint the whole sky.
pub const POINT_SET_SOLAR_BAND_NM: f64 = 10.0;

/// RGB3's wavelengths, nm (R, G, B).
pub const RGB3_NM: [f64; 3] = [680.0, 550.0, 440.0];

/// Four wavelengths and the weights that turn their spectral radiances into linear sRGB.
#[derive(Debug, Clone, PartialEq)]
pub struct WavelengthBatch {
    /// Lane wavelengths, nm (a padding lane repeats a real wavelength with zero weight).
    pub wavelengths_nm: [f64; LANES],
    /// Band over which each lane averages the solar spectrum, nm: the band each lane stands
    /// for in the spectral sets, [`POINT_SET_SOLAR_BAND_NM`] for RGB3 and Spectral4; `None` for
    /// a monochromatic probe.
    pub bandwidth_nm: Option<f64>,
    /// Rows R, G, B: linear sRGB = Σ_lane to_srgb[row][lane] · L_lane, with L in
    /// W·m⁻²·sr⁻¹·nm⁻¹.
    pub to_srgb: [[f64; LANES]; 3],
}

/// ∫ȳ dλ over the visible range, nm: the weight that gives RGB3 the luminance scale of the
/// spectral sets (a flat spectrum of 1 maps to R = G = B with Y = ∫ȳ dλ).
pub fn y_bar_integral_nm() -> f64 {
    let y = &cie1931().y;
    y.bin_average(
        0.5 * (VISIBLE_MIN_NM + VISIBLE_MAX_NM),
        VISIBLE_MAX_NM - VISIBLE_MIN_NM,
    ) * (VISIBLE_MAX_NM - VISIBLE_MIN_NM)
}

/// The published Spectral4 wavelengths (nm) and 3×4 matrix (rows R, G, B).
pub fn garcia_linan_spectral4() -> ([f64; LANES], [[f64; LANES]; 3]) {
    let t = tables::garcia_linan_constants();
    let names = t.text("name");
    let indices = t.text("index");
    let values = t.numbers("value");
    let mut wavelengths = [0.0; LANES];
    let mut matrix = [[0.0; LANES]; 3];
    for ((name, index), value) in names.iter().zip(&indices).zip(&values) {
        match *name {
            "wavelength" => {
                let lane: usize = index.parse().expect("embedded table: lane index");
                wavelengths[lane] = *value;
            }
            "M_srgb_from_samples" => {
                // "col{lane}_row{channel}": column j holds the weights of sample j.
                let rest = index.strip_prefix("col").expect("embedded table: col");
                let (col, row) = rest.split_once("_row").expect("embedded table: row");
                let (col, row): (usize, usize) = (
                    col.parse().expect("embedded table: column"),
                    row.parse().expect("embedded table: row"),
                );
                matrix[row][col] = *value;
            }
            _ => {}
        }
    }
    (wavelengths, matrix)
}

/// The project's Spectral4: its four wavelengths (nm, longest first) and its 3×4 matrix (rows
/// R, G, B), from `atmoscope fit-wavelengths` (`data/spectral4_fitted.csv`).
pub fn spectral4_fitted() -> ([f64; LANES], [[f64; LANES]; 3]) {
    spectral4_from(tables::spectral4_fitted())
}

/// Spectral4's wavelengths and matrix from a table in the form `fit-wavelengths` writes
/// (columns quantity, lane, value; quantities wavelength_nm, R, G, B); a lane the table leaves
/// out is NaN. Panics on another quantity, as on any malformed embedded table.
pub fn spectral4_from(t: &Table) -> ([f64; LANES], [[f64; LANES]; 3]) {
    let mut wavelengths = [f64::NAN; LANES];
    let mut matrix = [[f64::NAN; LANES]; 3];
    for ((quantity, lane), value) in t
        .text("quantity")
        .iter()
        .zip(t.numbers("lane"))
        .zip(t.numbers("value"))
    {
        let lane = lane as usize;
        match *quantity {
            "wavelength_nm" => wavelengths[lane] = value,
            "R" => matrix[0][lane] = value,
            "G" => matrix[1][lane] = value,
            "B" => matrix[2][lane] = value,
            other => panic!("embedded table spectral4_fitted: unknown quantity {other}"),
        }
    }
    (wavelengths, matrix)
}

/// The 3×4 matrix M minimising Σ w·|M·l − c|² over samples (lanes l, target linear sRGB c)
/// with w = 1/Y(c)², so that errors count relative to each sample's luminance; None when the
/// samples do not determine it.
pub fn fit_matrix(samples: &[([f64; LANES], [f64; 3])]) -> Option<[[f64; LANES]; 3]> {
    let mut a = [[0.0; LANES]; LANES];
    let mut b = [[0.0; LANES]; 3];
    for (l, c) in samples {
        let y = crate::colour::linear_srgb_to_xyz(*c).y;
        if !(y > 0.0) {
            continue;
        }
        let w = 1.0 / (y * y);
        for i in 0..LANES {
            for j in 0..LANES {
                a[i][j] += w * l[i] * l[j];
            }
            for row in 0..3 {
                b[row][i] += w * l[i] * c[row];
            }
        }
    }
    let mut m = [[0.0; LANES]; 3];
    for row in 0..3 {
        m[row] = solve4(a, b[row])?;
    }
    Some(m)
}

/// Solves the 4×4 system a·x = b by Gaussian elimination with partial pivoting.
fn solve4(mut a: [[f64; LANES]; LANES], mut b: [f64; LANES]) -> Option<[f64; LANES]> {
    for col in 0..LANES {
        let pivot = (col..LANES).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col].abs() < 1e-300 {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for r in col + 1..LANES {
            let f = a[r][col] / a[col][col];
            for k in col..LANES {
                a[r][k] -= f * a[col][k];
            }
            b[r] -= f * b[col];
        }
    }
    let mut x = [0.0; LANES];
    for r in (0..LANES).rev() {
        let sum: f64 = (r + 1..LANES).map(|k| a[r][k] * x[k]).sum();
        x[r] = (b[r] - sum) / a[r][r];
    }
    Some(x)
}

/// Batches of any wavelengths (nm, 360–830), four per batch, the last padded by repeating its
/// last wavelength, with no colour matrix: for probing or fitting at given wavelengths. Each lane
/// averages the solar spectrum over `bandwidth_nm` (None: a point sample).
pub fn batches_at(wavelengths_nm: &[f64], bandwidth_nm: Option<f64>) -> Vec<WavelengthBatch> {
    wavelengths_nm
        .chunks(LANES)
        .map(|c| WavelengthBatch {
            wavelengths_nm: std::array::from_fn(|i| c[i.min(c.len() - 1)]),
            bandwidth_nm,
            to_srgb: [[0.0; LANES]; 3],
        })
        .collect()
}

/// The batches of a wavelength set, in rendering order.
pub fn batches(set: WavelengthSet) -> Vec<WavelengthBatch> {
    match set {
        WavelengthSet::Rgb3 => {
            let w = y_bar_integral_nm();
            vec![WavelengthBatch {
                wavelengths_nm: [RGB3_NM[0], RGB3_NM[1], RGB3_NM[2], RGB3_NM[1]],
                bandwidth_nm: Some(POINT_SET_SOLAR_BAND_NM),
                to_srgb: [[w, 0.0, 0.0, 0.0], [0.0, w, 0.0, 0.0], [0.0, 0.0, w, 0.0]],
            }]
        }
        WavelengthSet::Spectral4 => {
            let (wavelengths_nm, to_srgb) = spectral4_fitted();
            vec![WavelengthBatch {
                wavelengths_nm,
                bandwidth_nm: Some(POINT_SET_SOLAR_BAND_NM),
                to_srgb,
            }]
        }
        WavelengthSet::SpectralN(n) => spectral_n(n.max(LANES as u32) as usize),
    }
}

fn spectral_n(n: usize) -> Vec<WavelengthBatch> {
    let n = n.div_ceil(LANES) * LANES;
    let width = (VISIBLE_MAX_NM - VISIBLE_MIN_NM) / n as f64;
    let cmf = cie1931();
    (0..n / LANES)
        .map(|b| {
            let mut wavelengths_nm = [0.0; LANES];
            let mut to_srgb = [[0.0; LANES]; 3];
            for lane in 0..LANES {
                let centre = VISIBLE_MIN_NM + (b * LANES + lane) as f64 * width + 0.5 * width;
                wavelengths_nm[lane] = centre;
                let xyz = Xyz {
                    x: cmf.x.bin_average(centre, width) * width,
                    y: cmf.y.bin_average(centre, width) * width,
                    z: cmf.z.bin_average(centre, width) * width,
                };
                let rgb = xyz_to_linear_srgb(xyz);
                for row in 0..3 {
                    to_srgb[row][lane] = rgb[row];
                }
            }
            WavelengthBatch {
                wavelengths_nm,
                bandwidth_nm: Some(width),
                to_srgb,
            }
        })
        .collect()
}

/// Linear sRGB from per-batch lane radiances (W·m⁻²·sr⁻¹·nm⁻¹).
pub fn to_linear_srgb(batches: &[WavelengthBatch], radiance: &[crate::lanes::Lanes]) -> [f64; 3] {
    let mut rgb = [0.0; 3];
    for (batch, l) in batches.iter().zip(radiance) {
        for row in 0..3 {
            for lane in 0..LANES {
                rgb[row] += batch.to_srgb[row][lane] * l[lane];
            }
        }
    }
    rgb
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::colour::{linear_srgb_to_xyz, spectrum_to_xyz};
    use crate::lanes::Lanes;
    use crate::spectrum::Spectrum;

    #[test]
    fn the_published_spectral4_matrix_is_read_column_major() {
        let (w, m) = garcia_linan_spectral4();
        assert_eq!(w, [630.0, 560.0, 490.0, 430.0]);
        assert!((m[0][0] - 137.6723892).abs() < 1e-9);
        assert!((m[2][3] - 117.4758528).abs() < 1e-9);
        assert!((m[1][2] - 34.31665471).abs() < 1e-9);
    }

    /// The shipped Spectral4 is read whole (every lane's wavelength and every weight), its
    /// wavelengths are visible and longest first as the set's lanes are named, and what it makes
    /// of sky-like spectra is their colour: lanes read into the wrong slots, or a matrix fitted
    /// at other wavelengths than those shipped beside it, would not be.
    #[test]
    fn the_shipped_spectral4_renders_sky_spectra_in_their_colour() {
        let (w, m) = spectral4_fitted();
        assert!(
            w.iter().chain(m.iter().flatten()).all(|v| v.is_finite()),
            "{w:?} {m:?}"
        );
        assert!(w.windows(2).all(|p| p[0] > p[1]), "{w:?}");
        assert!(
            w.iter()
                .all(|l| (VISIBLE_MIN_NM..=VISIBLE_MAX_NM).contains(l))
        );
        let b = batches(WavelengthSet::Spectral4);
        assert_eq!((b[0].wavelengths_nm, b[0].to_srgb), (w, m));
        // Sunlight blued as a clear or hazy sky does, (550/λ)ⁿ, and the sun's own colour: each
        // within 5 % of the exact colour's green. The bound is wide enough for a matrix fitted at
        // the shipped wavelengths and too narrow for one fitted at others or for swapped lanes.
        let sun = crate::solar_spectrum::SolarSpectrum::AstmG173;
        let grid: Vec<f64> = (360..=830).map(f64::from).collect();
        for n in [4.0, 2.0, 1.0, 0.0] {
            let tint = |l: f64| (550.0 / l).powf(n);
            let values = grid.iter().map(|&l| sun.spectrum().sample(l) * tint(l));
            let spectrum = Spectrum::new(grid.clone(), values.collect()).unwrap();
            let exact = xyz_to_linear_srgb(spectrum_to_xyz(&spectrum));
            let lanes = w.map(|l| sun.irradiance(l, POINT_SET_SOLAR_BAND_NM) * tint(l));
            let rgb = to_linear_srgb(&b, &[Lanes(lanes)]);
            for c in 0..3 {
                assert!(
                    (rgb[c] - exact[c]).abs() < 0.05 * exact[1],
                    "(550/λ)^{n}, channel {c}: {rgb:?} vs {exact:?}"
                );
            }
        }
    }

    #[test]
    fn fitting_recovers_a_known_matrix() {
        let truth = [
            [120.0, 30.0, -35.0, 8.0],
            [-9.0, 95.0, 30.0, -10.0],
            [-2.0, -12.0, 30.0, 110.0],
        ];
        let samples: Vec<([f64; 4], [f64; 3])> = (0..50)
            .map(|i| {
                let x = i as f64 * 0.37;
                let l = [
                    1.0 + x.sin().abs(),
                    1.2 + x.cos().abs(),
                    1.5 + (2.0 * x).sin(),
                    2.0 + (3.0 * x).cos(),
                ];
                let c = std::array::from_fn(|r| (0..4).map(|k| truth[r][k] * l[k]).sum());
                (l, c)
            })
            .collect();
        let m = fit_matrix(&samples).unwrap();
        for r in 0..3 {
            for k in 0..4 {
                assert!((m[r][k] - truth[r][k]).abs() < 1e-6, "{m:?}");
            }
        }
        assert!(fit_matrix(&[]).is_none());
    }

    #[test]
    fn spectral_n_integrates_a_smooth_spectrum_like_the_cie_functions() {
        // A smooth sky-like spectrum: the band sums must match the 1 nm integration.
        let w: Vec<f64> = (360..=830).map(f64::from).collect();
        let v: Vec<f64> = w.iter().map(|l| (450.0 / l).powi(4)).collect();
        let spectrum = Spectrum::new(w, v).unwrap();
        let exact = xyz_to_linear_srgb(spectrum_to_xyz(&spectrum));
        for n in [32, 64] {
            let b = batches(WavelengthSet::SpectralN(n));
            assert_eq!(b.len(), n as usize / 4);
            let lanes: Vec<Lanes> = b
                .iter()
                .map(|b| Lanes(b.wavelengths_nm.map(|l| spectrum.sample(l))))
                .collect();
            let rgb = to_linear_srgb(&b, &lanes);
            for c in 0..3 {
                assert!(
                    (rgb[c] - exact[c]).abs() < 0.01 * exact[1],
                    "N = {n}, channel {c}: {} vs {}",
                    rgb[c],
                    exact[c]
                );
            }
        }
    }

    #[test]
    fn rgb3_maps_a_flat_spectrum_to_the_spectral_luminance() {
        let b = batches(WavelengthSet::Rgb3);
        let rgb = to_linear_srgb(&b, &[Lanes::ONE]);
        let y = linear_srgb_to_xyz(rgb).y;
        assert!((y - y_bar_integral_nm()).abs() < 1e-6 * y);
        assert!(
            (y_bar_integral_nm() - 106.86).abs() < 0.1,
            "{}",
            y_bar_integral_nm()
        );
    }
}
