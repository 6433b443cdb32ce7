//! Sampled spectra: a function of wavelength known at increasing sample points.
//!
//! Between samples a spectrum is the straight line through its two neighbours (piecewise linear);
//! outside the sampled range it is zero, so a table never invents light or absorption where it has
//! no data. `bin_average` integrates that piecewise-linear function exactly, which is what a
//! renderer needs when one wavelength sample stands for a band.

use crate::ModelError;

/// A spectral function sampled at strictly increasing wavelengths (nm).
#[derive(Debug, Clone, PartialEq)]
pub struct Spectrum {
    wavelengths_nm: Vec<f64>,
    values: Vec<f64>,
    guide: Guide,
}

/// Where to start looking for a wavelength's neighbours: the sampled range cut into as many
/// equal cells as there are samples, each with the index of the first sample past its lower
/// edge. The path tracer samples spectra at every path's wavelengths, where a binary search of
/// the solar spectrum's thousands of samples is a noticeable cost; from the guide the search
/// is a step or two.
#[derive(Debug, Clone, PartialEq)]
struct Guide {
    cells_per_nm: f64,
    first: Vec<u32>,
}

impl Guide {
    fn new(w: &[f64]) -> Guide {
        let (lo, hi) = (w[0], w[w.len() - 1]);
        let cells = w.len();
        let cells_per_nm = if hi > lo {
            cells as f64 / (hi - lo)
        } else {
            0.0
        };
        let first = (0..cells)
            .map(|c| {
                let edge = lo + c as f64 / cells_per_nm.max(f64::MIN_POSITIVE);
                w.partition_point(|&x| x <= edge) as u32
            })
            .collect();
        Guide {
            cells_per_nm,
            first,
        }
    }

    /// The number of samples at or below `wavelength_nm` (inside the sampled range): what
    /// `partition_point(|x| x <= wavelength_nm)` gives.
    fn upper(&self, w: &[f64], wavelength_nm: f64) -> usize {
        let cell = ((wavelength_nm - w[0]) * self.cells_per_nm) as usize;
        let mut i = self.first[cell.min(self.first.len() - 1)] as usize;
        // The cell's edge is rounded: step either way to the exact place.
        while i < w.len() && w[i] <= wavelength_nm {
            i += 1;
        }
        while i > 0 && w[i - 1] > wavelength_nm {
            i -= 1;
        }
        i
    }
}

impl Spectrum {
    /// Builds a spectrum; wavelengths must be finite and strictly increasing, values finite.
    pub fn new(wavelengths_nm: Vec<f64>, values: Vec<f64>) -> Result<Spectrum, ModelError> {
        if wavelengths_nm.len() != values.len() || wavelengths_nm.is_empty() {
            return Err(ModelError::InvalidSpectrum(format!(
                "{} wavelengths for {} values",
                wavelengths_nm.len(),
                values.len()
            )));
        }
        if let Some(w) = wavelengths_nm.windows(2).find(|w| !(w[1] > w[0])) {
            return Err(ModelError::InvalidSpectrum(format!(
                "wavelengths must increase strictly, found {} then {} nm",
                w[0], w[1]
            )));
        }
        if wavelengths_nm.iter().chain(&values).any(|v| !v.is_finite()) {
            return Err(ModelError::InvalidSpectrum("non-finite sample".into()));
        }
        Ok(Spectrum::with_guide(wavelengths_nm, values))
    }

    fn with_guide(wavelengths_nm: Vec<f64>, values: Vec<f64>) -> Spectrum {
        Spectrum {
            guide: Guide::new(&wavelengths_nm),
            wavelengths_nm,
            values,
        }
    }

    /// A spectrum from two columns of an embedded table, which the tests prove valid.
    pub(crate) fn from_table(table: &crate::csv_table::Table, x: &str, y: &str) -> Spectrum {
        Spectrum::new(table.numbers(x), table.numbers(y))
            .expect("embedded table is a valid spectrum")
    }

    /// A spectrum equal to `f(λ)` at the given wavelengths.
    pub fn from_fn(wavelengths_nm: &[f64], f: impl Fn(f64) -> f64) -> Spectrum {
        let values = wavelengths_nm.iter().map(|&w| f(w)).collect();
        Spectrum::with_guide(wavelengths_nm.to_vec(), values)
    }

    pub fn wavelengths_nm(&self) -> &[f64] {
        &self.wavelengths_nm
    }

    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Sampled range, nm.
    pub fn range_nm(&self) -> (f64, f64) {
        (
            self.wavelengths_nm[0],
            *self
                .wavelengths_nm
                .last()
                .unwrap_or(&self.wavelengths_nm[0]),
        )
    }

    /// Value at `wavelength_nm` by linear interpolation; zero outside the sampled range.
    pub fn sample(&self, wavelength_nm: f64) -> f64 {
        let w = &self.wavelengths_nm;
        let (lo, hi) = self.range_nm();
        if !(wavelength_nm >= lo && wavelength_nm <= hi) {
            return 0.0;
        }
        let i = self
            .guide
            .upper(w, wavelength_nm)
            .clamp(1, w.len().max(2) - 1);
        if w.len() == 1 {
            return self.values[0];
        }
        let t = (wavelength_nm - w[i - 1]) / (w[i] - w[i - 1]);
        self.values[i - 1] + t * (self.values[i] - self.values[i - 1])
    }

    /// Value by linear interpolation of ln(value) against ln(λ): exact for power laws such as
    /// Rayleigh's λ⁻⁴, used where a coarse table samples a steep smooth curve. Zero outside.
    pub fn sample_log_log(&self, wavelength_nm: f64) -> f64 {
        let w = &self.wavelengths_nm;
        let (lo, hi) = self.range_nm();
        if !(wavelength_nm >= lo && wavelength_nm <= hi) || w.len() < 2 {
            return self.sample(wavelength_nm);
        }
        let i = self.guide.upper(w, wavelength_nm).clamp(1, w.len() - 1);
        let (y0, y1) = (self.values[i - 1], self.values[i]);
        if y0 <= 0.0 || y1 <= 0.0 {
            return self.sample(wavelength_nm);
        }
        let t = (wavelength_nm / w[i - 1]).ln() / (w[i] / w[i - 1]).ln();
        (y0.ln() + t * (y1.ln() - y0.ln())).exp()
    }

    /// Exact integral of the piecewise-linear spectrum over [a, b] nm (zero outside its range).
    pub fn integrate(&self, a_nm: f64, b_nm: f64) -> f64 {
        if b_nm < a_nm {
            return -self.integrate(b_nm, a_nm);
        }
        let (lo, hi) = self.range_nm();
        let (a, b) = (a_nm.max(lo), b_nm.min(hi));
        if b <= a {
            return 0.0;
        }
        let w = &self.wavelengths_nm;
        let mut sum = 0.0;
        let mut x0 = a;
        let mut y0 = self.sample(a);
        let start = w.partition_point(|&x| x <= a);
        for &x in w[start..].iter().take_while(|&&x| x < b) {
            let y = self.sample(x);
            sum += 0.5 * (y0 + y) * (x - x0);
            x0 = x;
            y0 = y;
        }
        sum + 0.5 * (y0 + self.sample(b)) * (b - x0)
    }

    /// Mean over the band [centre − width/2, centre + width/2] nm.
    pub fn bin_average(&self, centre_nm: f64, width_nm: f64) -> f64 {
        if width_nm <= 0.0 {
            return self.sample(centre_nm);
        }
        self.integrate(centre_nm - 0.5 * width_nm, centre_nm + 0.5 * width_nm) / width_nm
    }

    /// The spectrum resampled on `wavelengths_nm`: bin averages over each sample's band
    /// (bands meet halfway between neighbours) when `bin_average` is set, point samples otherwise.
    pub fn resample(&self, wavelengths_nm: &[f64], bin_average: bool) -> Spectrum {
        let values = wavelengths_nm
            .iter()
            .enumerate()
            .map(|(i, &w)| {
                if !bin_average || wavelengths_nm.len() < 2 {
                    return self.sample(w);
                }
                let left = if i == 0 {
                    w - 0.5 * (wavelengths_nm[1] - w)
                } else {
                    0.5 * (wavelengths_nm[i - 1] + w)
                };
                let n = wavelengths_nm.len();
                let right = if i + 1 == n {
                    w + 0.5 * (w - wavelengths_nm[n - 2])
                } else {
                    0.5 * (w + wavelengths_nm[i + 1])
                };
                self.integrate(left, right) / (right - left)
            })
            .collect();
        Spectrum::with_guide(wavelengths_nm.to_vec(), values)
    }
}

#[cfg(test)]
mod tests {
    /// The guide finds the neighbours a binary search finds, on even and uneven grids, at
    /// and between samples and at the ends.
    #[test]
    fn the_guide_finds_what_a_binary_search_finds() {
        let grids: [Vec<f64>; 4] = [
            (0..2000).map(|i| 300.0 + 0.5 * f64::from(i)).collect(),
            (0..50).map(|i| 380.0 + f64::from(i * i) * 0.17).collect(),
            vec![400.0, 400.001, 650.0, 650.5, 700.0],
            vec![550.0],
        ];
        for w in grids {
            let s = Spectrum::from_fn(&w, |x| x.sin());
            let (lo, hi) = s.range_nm();
            let probes = (0..=997)
                .map(|k| lo + (hi - lo) * f64::from(k) / 997.0)
                .chain(w.iter().copied());
            for x in probes {
                assert_eq!(
                    s.guide.upper(&w, x),
                    w.partition_point(|&v| v <= x),
                    "{x} nm"
                );
            }
        }
    }

    use super::*;

    fn ramp() -> Spectrum {
        Spectrum::new(vec![400.0, 500.0, 600.0], vec![1.0, 3.0, 2.0]).unwrap()
    }

    #[test]
    fn sample_interpolates_linearly_and_is_zero_outside() {
        let s = ramp();
        assert_eq!(s.sample(400.0), 1.0);
        assert_eq!(s.sample(450.0), 2.0);
        assert_eq!(s.sample(600.0), 2.0);
        assert_eq!(s.sample(550.0), 2.5);
        assert_eq!(s.sample(399.0), 0.0);
        assert_eq!(s.sample(601.0), 0.0);
        assert_eq!(s.sample(f64::NAN), 0.0);
    }

    #[test]
    fn integral_of_piecewise_linear_is_exact() {
        let s = ramp();
        // Two trapezoids: 100·(1+3)/2 + 100·(3+2)/2.
        assert!((s.integrate(0.0, 1000.0) - 450.0).abs() < 1e-12);
        assert!((s.integrate(450.0, 550.0) - (50.0 * 2.5 + 50.0 * 2.75)).abs() < 1e-12);
        assert!((s.bin_average(500.0, 100.0) - 2.625).abs() < 1e-12);
    }

    #[test]
    fn log_log_interpolation_is_exact_for_power_laws() {
        let grid = [400.0, 500.0, 600.0];
        let s = Spectrum::from_fn(&grid, |w| 1e12 * w.powf(-4.0));
        let w = 443.0_f64;
        assert!((s.sample_log_log(w) / (1e12 * w.powf(-4.0)) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn resample_bin_average_preserves_the_integral_of_a_line() {
        let s = Spectrum::new(vec![300.0, 900.0], vec![0.0, 6.0]).unwrap();
        let grid: Vec<f64> = (0..10).map(|i| 405.0 + 10.0 * i as f64).collect();
        let r = s.resample(&grid, true);
        for (w, v) in grid.iter().zip(r.values()) {
            assert!(
                (v - s.sample(*w)).abs() < 1e-12,
                "a line's bin average is its centre value"
            );
        }
    }

    #[test]
    fn invalid_spectra_are_rejected() {
        assert!(Spectrum::new(vec![500.0, 400.0], vec![1.0, 1.0]).is_err());
        assert!(Spectrum::new(vec![400.0], vec![1.0, 2.0]).is_err());
        assert!(Spectrum::new(vec![400.0, 500.0], vec![1.0, f64::NAN]).is_err());
    }
}
