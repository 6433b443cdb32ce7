//! How close a modelled sky is to a measured one, in the terms of Bruneton (2017): the
//! |relative error| of spectral radiance over 360–720 nm, of luminance, the chromaticity
//! difference in CIE 1976 u′v′ and the zenith luminance; over the directions that count
//! ([`scored_directions`]).

use super::files::Scan;
use atmoscope_model::Spectrum;
use atmoscope_model::colour::{Xyz, spectrum_to_xyz};
use atmoscope_model::constants::MAX_LUMINOUS_EFFICACY_LM_PER_W;
use atmoscope_model::geometry::direction_from_angles;

/// The scored wavelength range, nm (Bruneton 2017).
pub const SCORED_NM: (f64, f64) = (360.0, 720.0);
/// Directions closer to the sun than this are not scored: the instrument's glare, and the
/// drift of its azimuth, make them unreliable. Degrees.
pub const SUN_EXCLUSION_DEG: f64 = 10.0;
/// The sample every scan reads wrong (north, lowest ring; Kider et al. 2014).
pub const BAD_SAMPLE: u32 = 0;

/// Indices of the directions of `scan` that are scored: all but the bad sample and those
/// within [`SUN_EXCLUSION_DEG`] of the sun at (zenith, azimuth) in the instrument's frame.
pub fn scored_directions(scan: &Scan, sun_zenith_deg: f64, sun_azimuth_deg: f64) -> Vec<usize> {
    let sun = direction_from_angles(90.0 - sun_zenith_deg, sun_azimuth_deg);
    scan.directions
        .iter()
        .enumerate()
        .filter(|(_, d)| d.sample != BAD_SAMPLE)
        .filter(|(_, d)| {
            let v = direction_from_angles(d.elevation_deg, d.azimuth_deg);
            v.dot(sun).clamp(-1.0, 1.0).acos().to_degrees() > SUN_EXCLUSION_DEG
        })
        .map(|(i, _)| i)
        .collect()
}

/// The two halves of a set of directions for a cross-validated fit: alternate directions in
/// scan order, so that both halves cover every ring. A fit reads `fit` alone and is scored on
/// `score` alone.
#[derive(Debug, Clone, PartialEq)]
pub struct Split {
    pub fit: Vec<usize>,
    pub score: Vec<usize>,
}

impl Split {
    pub fn alternate(directions: &[usize]) -> Split {
        let (fit, score) = directions
            .iter()
            .enumerate()
            .partition::<Vec<_>, _>(|(i, _)| i % 2 == 0);
        Split {
            fit: fit.into_iter().map(|(_, &d)| d).collect(),
            score: score.into_iter().map(|(_, &d)| d).collect(),
        }
    }
}

/// A spectrum sampled at increasing wavelengths.
pub fn spectrum(wavelengths_nm: &[f64], values: &[f64]) -> Option<Spectrum> {
    Spectrum::new(wavelengths_nm.to_vec(), values.to_vec()).ok()
}

/// Tristimulus values (CIE 1931) of a spectrum, W·m⁻²·sr⁻¹.
pub fn xyz(wavelengths_nm: &[f64], values: &[f64]) -> Option<Xyz> {
    spectrum(wavelengths_nm, values).map(|s| spectrum_to_xyz(&s))
}

/// Luminance, cd/m².
pub fn luminance(c: Xyz) -> f64 {
    MAX_LUMINOUS_EFFICACY_LM_PER_W * c.y
}

/// CIE 1976 u′v′ chromaticity; None for black.
pub fn uv(c: Xyz) -> Option<(f64, f64)> {
    let d = c.x + 15.0 * c.y + 3.0 * c.z;
    (d > 0.0).then(|| (4.0 * c.x / d, 9.0 * c.y / d))
}

/// The errors of one modelled sky against the measured one over some directions.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Errors {
    /// |modelled/measured − 1| of spectral radiance, per direction and scored wavelength where
    /// the measurement is positive.
    pub radiance: Vec<f64>,
    /// |relative error| of luminance, per direction.
    pub luminance: Vec<f64>,
    /// Distance in u′v′, per direction.
    pub chromaticity: Vec<f64>,
}

impl Errors {
    pub fn extend(&mut self, other: &Errors) {
        self.radiance.extend_from_slice(&other.radiance);
        self.luminance.extend_from_slice(&other.luminance);
        self.chromaticity.extend_from_slice(&other.chromaticity);
    }
}

/// Errors of `modelled` (spectra on `model_nm`) against `measured` (spectra on `measured_nm`),
/// direction by direction; the radiance at the model's wavelengths within [`SCORED_NM`] that
/// the measurement also holds.
pub fn compare(
    measured_nm: &[f64],
    measured: &[&[f64]],
    model_nm: &[f64],
    modelled: &[&[f64]],
) -> Errors {
    let mut e = Errors::default();
    for (m, l) in measured.iter().zip(modelled) {
        for (i, &w) in model_nm.iter().enumerate() {
            if !(SCORED_NM.0..=SCORED_NM.1).contains(&w) {
                continue;
            }
            let Some(j) = measured_nm.iter().position(|&x| (x - w).abs() < 1e-6) else {
                continue;
            };
            if m[j] > 0.0 {
                e.radiance.push((l[i] / m[j] - 1.0).abs());
            }
        }
        let (Some(cm), Some(cl)) = (xyz(measured_nm, m), xyz(model_nm, l)) else {
            continue;
        };
        if cm.y > 0.0 {
            e.luminance.push((cl.y / cm.y - 1.0).abs());
        }
        if let (Some(a), Some(b)) = (uv(cm), uv(cl)) {
            e.chromaticity
                .push(((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt());
        }
    }
    e
}

/// The `q`-quantile (0–1) of `v` by linear interpolation between order statistics; NaN of none.
pub fn quantile(v: &[f64], q: f64) -> f64 {
    let mut v: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let x = q.clamp(0.0, 1.0) * (v.len() - 1) as f64;
    let (i, f) = (x.floor() as usize, x.fract());
    if i + 1 < v.len() {
        v[i] + f * (v[i + 1] - v[i])
    } else {
        v[i]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_model_ten_percent_bright_is_ten_percent_off_with_the_same_colour() {
        let nm: Vec<f64> = (0..=96).map(|i| 350.0 + 5.0 * f64::from(i)).collect();
        let measured: Vec<f64> = nm.iter().map(|w| 0.1 * (500.0 / w).powi(4)).collect();
        let model_nm: Vec<f64> = (0..=47).map(|i| 360.0 + 10.0 * f64::from(i)).collect();
        let modelled: Vec<f64> = model_nm
            .iter()
            .map(|w| 1.1 * 0.1 * (500.0 / w).powi(4))
            .collect();
        let e = compare(&nm, &[&measured], &model_nm, &[&modelled]);
        // 360–720 nm at 10 nm: 37 wavelengths.
        assert_eq!(e.radiance.len(), 37);
        assert!(e.radiance.iter().all(|x| (x - 0.1).abs() < 1e-9));
        assert!((e.luminance[0] - 0.1).abs() < 2e-3, "{}", e.luminance[0]);
        assert!(e.chromaticity[0] < 1e-3, "{}", e.chromaticity[0]);
        // The control: a model redder than the measurement (its spectrum tilted by λ/500 nm)
        // is off in colour too.
        let redder: Vec<f64> = model_nm
            .iter()
            .zip(&modelled)
            .map(|(w, l)| l * w / 500.0)
            .collect();
        let e = compare(&nm, &[&measured], &model_nm, &[&redder]);
        assert!(e.chromaticity[0] > 0.01, "{}", e.chromaticity[0]);
    }

    #[test]
    fn the_halves_of_a_split_share_no_direction_and_cover_all() {
        let d: Vec<usize> = (1..81).filter(|i| i % 7 != 3).collect();
        let s = Split::alternate(&d);
        assert!(s.fit.iter().all(|i| !s.score.contains(i)));
        let mut all = [s.fit.clone(), s.score.clone()].concat();
        all.sort();
        assert_eq!(all, d);
        assert!(s.fit.len().abs_diff(s.score.len()) <= 1);
    }

    #[test]
    fn quantiles_interpolate_between_order_statistics() {
        assert_eq!(quantile(&[3.0, 1.0, 2.0], 0.5), 2.0);
        assert_eq!(quantile(&[1.0, 2.0, 3.0, 4.0], 0.5), 2.5);
        assert!(
            (quantile(&(0..=100).map(f64::from).collect::<Vec<_>>(), 0.95) - 95.0).abs() < 1e-12
        );
        assert!(quantile(&[], 0.5).is_nan());
    }
}
