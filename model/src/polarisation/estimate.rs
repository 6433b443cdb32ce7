//! Means of Monte Carlo Stokes vectors with standard errors, for the degree and angle of
//! polarisation too (the delta method on the sample covariance of I, Q, U, V).

use super::Stokes;

/// Running sums of Stokes vector samples.
#[derive(Debug, Clone, Copy, Default)]
pub struct StokesMean {
    n: u64,
    sum: [f64; 4],
    /// Σ sₐ·s_b.
    products: [[f64; 4]; 4],
}

/// A mean Stokes vector and the standard errors of what it gives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StokesEstimate {
    pub mean: Stokes,
    /// Standard errors of I, Q, U, V.
    pub std_error: [f64; 4],
    /// Standard error of the degree of polarisation (0–1).
    pub degree_std_error: f64,
    /// Standard error of the angle of polarisation, degrees.
    pub angle_std_error_deg: f64,
}

impl StokesMean {
    pub fn add(&mut self, s: Stokes) {
        let s = s.to_array();
        self.n += 1;
        for a in 0..4 {
            self.sum[a] += s[a];
            for b in 0..4 {
                self.products[a][b] += s[a] * s[b];
            }
        }
    }

    /// The mean and its standard errors (infinite with fewer than two samples).
    pub fn estimate(&self) -> StokesEstimate {
        let n = self.n as f64;
        let m = self.sum.map(|s| s / n.max(1.0));
        // Covariance of the mean.
        let cov = |a: usize, b: usize| {
            if self.n < 2 {
                f64::INFINITY
            } else {
                (self.products[a][b] / n - m[a] * m[b]) / (n - 1.0)
            }
        };
        let mean = Stokes {
            i: m[0],
            q: m[1],
            u: m[2],
            v: m[3],
        };
        let quadratic = |g: [f64; 4]| {
            let mut v = 0.0;
            for a in 0..4 {
                for b in 0..4 {
                    if g[a] != 0.0 && g[b] != 0.0 {
                        v += g[a] * g[b] * cov(a, b);
                    }
                }
            }
            v.max(0.0).sqrt()
        };
        let polarised = (m[1] * m[1] + m[2] * m[2] + m[3] * m[3]).sqrt();
        let degree_std_error = if m[0] > 0.0 && polarised > 0.0 {
            let p = polarised / m[0];
            quadratic([
                -p / m[0],
                m[1] / (m[0] * polarised),
                m[2] / (m[0] * polarised),
                m[3] / (m[0] * polarised),
            ])
        } else {
            0.0
        };
        let linear2 = m[1] * m[1] + m[2] * m[2];
        let angle_std_error_deg = if linear2 > 0.0 {
            quadratic([0.0, -0.5 * m[2] / linear2, 0.5 * m[1] / linear2, 0.0]).to_degrees()
        } else {
            f64::INFINITY
        };
        StokesEstimate {
            mean,
            std_error: std::array::from_fn(|a| cov(a, a).max(0.0).sqrt()),
            degree_std_error,
            angle_std_error_deg,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Over many independent means of samples of known spread, the standard errors reported
    /// for I and Q, and the delta method's for the degree and the angle, match the spread of
    /// the means themselves.
    #[test]
    fn standard_errors_match_the_spread_of_repeated_means() {
        let mut state = 12345u64;
        let mut uniform = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let (runs, per_run) = (400, 200);
        let (mut degrees, mut angles, mut reported) = (Vec::new(), Vec::new(), Vec::new());
        let (mut means_i, mut means_q, mut reported_iq) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..runs {
            let mut m = StokesMean::default();
            for _ in 0..per_run {
                let i = 1.0 + uniform();
                m.add(Stokes {
                    i,
                    q: -0.5 * i + 0.2 * (uniform() - 0.5),
                    u: 0.2 * i * (uniform() - 0.5),
                    v: 0.0,
                });
            }
            let e = m.estimate();
            degrees.push(e.mean.degree_of_polarization());
            angles.push(e.mean.angle_of_polarization_deg().rem_euclid(180.0));
            reported.push((e.degree_std_error, e.angle_std_error_deg));
            means_i.push(e.mean.i);
            means_q.push(e.mean.q);
            reported_iq.push((e.std_error[0], e.std_error[1]));
        }
        let spread = |v: &[f64]| {
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt()
        };
        let mean_reported =
            |f: fn(&(f64, f64)) -> f64| reported.iter().map(f).sum::<f64>() / reported.len() as f64;
        let (sd_degree, sd_angle) = (spread(&degrees), spread(&angles));
        let (se_degree, se_angle) = (mean_reported(|r| r.0), mean_reported(|r| r.1));
        let (sd_i, sd_q) = (spread(&means_i), spread(&means_q));
        let mean_of = |f: fn(&(f64, f64)) -> f64| {
            reported_iq.iter().map(f).sum::<f64>() / reported_iq.len() as f64
        };
        let (se_i, se_q) = (mean_of(|r| r.0), mean_of(|r| r.1));
        assert!((se_i / sd_i - 1.0).abs() < 0.15, "I: {se_i} vs {sd_i}");
        assert!((se_q / sd_q - 1.0).abs() < 0.15, "Q: {se_q} vs {sd_q}");
        assert!(
            (se_degree / sd_degree - 1.0).abs() < 0.15,
            "{se_degree} vs {sd_degree}"
        );
        assert!(
            (se_angle / sd_angle - 1.0).abs() < 0.15,
            "{se_angle} vs {sd_angle}"
        );
    }
}
