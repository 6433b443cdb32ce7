//! The sun's azimuth from the symmetry of a measured sky. A clear sky over a uniform ground is
//! symmetric about the sun's vertical plane, so on every ring of equal elevation the radiance
//! at azimuth φ_s + δ equals that at φ_s − δ. The scanner's azimuth drifts during the day
//! (Kider et al. 2014; Bruneton 2017 estimates it the same way), so the axis of the measured
//! sky, not the theoretical sun, says where the sun stood in the instrument's frame.
//!
//! The estimate minimises, over the axis φ, the mean squared difference of ln L between each
//! direction and the ring's value at its mirror image 2φ − az (linear between the ring's
//! samples). The mirror of the axis φ is also the axis φ + 180°; the one nearer the theoretical
//! sun is the sun's.

/// A direction of a ring scan and the sky's brightness there (any positive measure: a
/// radiance, a luminance).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub azimuth_deg: f64,
    pub elevation_deg: f64,
    pub value: f64,
}

/// Rings with fewer samples than this are left out: they cannot say where their mirror lies.
pub const MIN_RING_SAMPLES: usize = 6;

/// The azimuth (degrees clockwise from north, 0–360) about which the samples are most
/// symmetric, on the side of `theory_deg`. None when no ring has enough positive samples.
pub fn sun_azimuth_deg(samples: &[Sample], theory_deg: f64) -> Option<f64> {
    let rings = rings(samples);
    if rings.is_empty() {
        return None;
    }
    let cost = |phi: f64| -> f64 {
        let (mut sum, mut n) = (0.0, 0usize);
        for ring in &rings {
            for &(az, ln_v) in ring {
                sum += (ln_v - ring_value(ring, 2.0 * phi - az)).powi(2);
                n += 1;
            }
        }
        sum / n as f64
    };
    // A coarse search over the half circle around the theoretical sun, then a golden-section
    // refinement around the best step.
    let step = 0.5;
    let best = (0..360)
        .map(|i| theory_deg - 90.0 + step * f64::from(i))
        .min_by(|a, b| cost(*a).total_cmp(&cost(*b)))?;
    let phi = golden_section(cost, best - step, best + step, 1e-4);
    Some(phi.rem_euclid(360.0))
}

/// Samples grouped by elevation (within 0.5°), as (azimuth, ln value) sorted by azimuth; the
/// zenith and rings too sparse to interpolate are left out.
fn rings(samples: &[Sample]) -> Vec<Vec<(f64, f64)>> {
    let mut rings: Vec<(f64, Vec<(f64, f64)>)> = Vec::new();
    for s in samples
        .iter()
        .filter(|s| s.value > 0.0 && s.value.is_finite() && s.elevation_deg < 89.0)
    {
        let point = (s.azimuth_deg.rem_euclid(360.0), s.value.ln());
        match rings
            .iter_mut()
            .find(|(e, _)| (e - s.elevation_deg).abs() < 0.5)
        {
            Some((_, r)) => r.push(point),
            None => rings.push((s.elevation_deg, vec![point])),
        }
    }
    rings
        .into_iter()
        .map(|(_, mut r)| {
            r.sort_by(|a, b| a.0.total_cmp(&b.0));
            r
        })
        .filter(|r| r.len() >= MIN_RING_SAMPLES)
        .collect()
}

/// The ring's ln value at `azimuth_deg`, linear between its neighbours around the circle.
fn ring_value(ring: &[(f64, f64)], azimuth_deg: f64) -> f64 {
    let a = azimuth_deg.rem_euclid(360.0);
    let upper = ring.iter().position(|p| p.0 >= a).unwrap_or(ring.len());
    let (lo, hi) = if upper == 0 || upper == ring.len() {
        // Between the last sample and the first, across north.
        let (last, first) = (ring[ring.len() - 1], ring[0]);
        ((last.0 - 360.0, last.1), first)
    } else {
        (ring[upper - 1], ring[upper])
    };
    let a = if a > hi.0 { a - 360.0 } else { a };
    let span = hi.0 - lo.0;
    if span <= 0.0 {
        return lo.1;
    }
    lo.1 + (a - lo.0) / span * (hi.1 - lo.1)
}

/// The minimum of a unimodal `f` on [a, b], to within `tol`.
pub fn golden_section(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64, tol: f64) -> f64 {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - r * (b - a), a + r * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    while (b - a).abs() > tol {
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - r * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + r * (b - a);
            fd = f(d);
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rings and azimuth counts of a Kider scan, sample 0 (north, lowest ring) left out.
    fn kider_directions() -> Vec<(f64, f64)> {
        let mut d = Vec::new();
        for (elevation, n) in [(12.1151, 32), (33.749, 24), (53.3665, 16), (71.9187, 8)] {
            for i in 0..n {
                d.push((360.0 - 360.0 * f64::from(i) / f64::from(n), elevation));
            }
        }
        d.retain(|&(az, el)| !(az == 360.0 && el < 13.0));
        d.push((0.0, 90.0));
        d
    }

    /// A sky symmetric about the sun at (`sun_az`, 40° elevation): brighter towards the sun and
    /// the horizon, with an aureole.
    fn sky(sun_az: f64) -> Vec<Sample> {
        let sun = glam::DVec3::new(
            40f64.to_radians().cos() * sun_az.to_radians().sin(),
            40f64.to_radians().cos() * sun_az.to_radians().cos(),
            40f64.to_radians().sin(),
        );
        kider_directions()
            .into_iter()
            .map(|(az, el)| {
                let (a, e) = (az.to_radians(), el.to_radians());
                let v = glam::DVec3::new(e.cos() * a.sin(), e.cos() * a.cos(), e.sin());
                let gamma = v.dot(sun).clamp(-1.0, 1.0).acos();
                let value = (1.0 + 4.0 * (-gamma / 0.4).exp() + gamma.cos().powi(2))
                    * (1.0 + 0.5 * (-e.sin() / 0.3).exp());
                Sample {
                    azimuth_deg: az,
                    elevation_deg: el,
                    value,
                }
            })
            .collect()
    }

    #[test]
    fn the_axis_of_a_symmetric_sky_is_found_to_a_tenth_of_a_degree() {
        for sun_az in [97.3, 123.4, 181.0, 250.2, 359.5] {
            // The theoretical sun 12° off, as the scanner's drift may leave it.
            let got = sun_azimuth_deg(&sky(sun_az), sun_az + 12.0).expect("rings");
            let off = (got - sun_az + 180.0).rem_euclid(360.0) - 180.0;
            assert!(off.abs() < 0.1, "sun at {sun_az}°: found {got}°");
        }
    }

    #[test]
    fn the_mirror_axis_is_not_taken_for_the_sun() {
        let got = sun_azimuth_deg(&sky(123.4), 150.0).expect("rings");
        assert!((got - 123.4).abs() < 0.1, "{got}");
        let got = sun_azimuth_deg(&sky(123.4), 303.4 + 60.0).expect("rings");
        assert!(
            (got - 303.4).abs() < 0.1,
            "the anti-solar axis when the theory says so: {got}"
        );
    }

    #[test]
    fn a_scan_without_rings_has_no_axis() {
        let only_zenith = [Sample {
            azimuth_deg: 0.0,
            elevation_deg: 90.0,
            value: 1.0,
        }];
        assert_eq!(sun_azimuth_deg(&only_zenith, 100.0), None);
    }
}
