//! AERONET almucantar inversion files (`.pfn`, "Phase Functions – Total Mode", Version 2): the
//! aerosol optical depth at 440 nm, the Ångström exponent 440–870 nm and the phase function at
//! 442 and 674 nm, each record at a UTC time; and their value at another time of the same day.
//!
//! The file has three lines of description, a header line beginning `Date(dd-mm-yyyy)` and one
//! record per line, dates written `dd:mm:yyyy`.

use super::clock::Clock;
use super::files::MeasuredError;
use std::path::Path;

/// One inversion.
#[derive(Debug, Clone, PartialEq)]
pub struct AeronetRecord {
    pub year: i32,
    pub month: u32,
    pub day: u32,
    pub time_utc: Clock,
    /// Aerosol optical depth at 440 nm, as measured (0–5).
    pub tau440: f64,
    /// Ångström exponent between 440 and 870 nm (−1–4).
    pub angstrom: f64,
    /// Asymmetry parameter g of the retrieved phase function at 442 and 674 nm, where the file
    /// has a phase function at both.
    pub asymmetry_g: Option<(f64, f64)>,
}

impl AeronetRecord {
    /// Aerosol optical depth at 550 nm by the Ångström law from 440 nm.
    pub fn aod550(&self) -> f64 {
        self.tau440 * (550.0_f64 / 440.0).powf(-self.angstrom)
    }

    /// The asymmetry parameter at 550 nm, interpolated between 442 and 674 nm in ln λ.
    pub fn asymmetry_g550(&self) -> Option<f64> {
        self.asymmetry_g.map(|(g442, g674)| {
            let t = (550.0_f64 / 442.0).ln() / (674.0_f64 / 442.0).ln();
            g442 + t * (g674 - g442)
        })
    }
}

/// The aerosol at a time between (or beyond) the records: linear in time between the two that
/// bracket it, the nearest record's outside them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AerosolAt {
    pub aod550: f64,
    pub angstrom: f64,
    pub asymmetry_g550: Option<f64>,
    /// Hours from the time asked for to the nearest record.
    pub hours_to_record: f64,
}

/// The aerosol of `records` (one day, in time order, not empty) at `time_utc`.
pub fn at(records: &[AeronetRecord], time_utc: Clock) -> Option<AerosolAt> {
    let first = records.first()?;
    let t = time_utc.seconds;
    let nearest = records
        .iter()
        .map(|r| (r.time_utc.seconds - t).abs())
        .fold(f64::INFINITY, f64::min)
        / 3600.0;
    let upper = records.iter().position(|r| r.time_utc.seconds >= t);
    let (a, b, w) = match upper {
        None => (records.last()?, records.last()?, 0.0),
        Some(0) => (first, first, 0.0),
        Some(i) => {
            let (a, b) = (&records[i - 1], &records[i]);
            let span = b.time_utc.seconds - a.time_utc.seconds;
            let w = if span > 0.0 {
                (t - a.time_utc.seconds) / span
            } else {
                0.0
            };
            (a, b, w)
        }
    };
    let mix = |x: f64, y: f64| x + w * (y - x);
    Some(AerosolAt {
        aod550: mix(a.aod550(), b.aod550()),
        angstrom: mix(a.angstrom, b.angstrom),
        asymmetry_g550: match (a.asymmetry_g550(), b.asymmetry_g550()) {
            (Some(x), Some(y)) => Some(mix(x, y)),
            _ => None,
        },
        hours_to_record: nearest,
    })
}

/// Reads every record of an inversion file.
pub fn read(file: &Path) -> Result<Vec<AeronetRecord>, MeasuredError> {
    let text = std::fs::read_to_string(file)
        .map_err(|e| MeasuredError::new(file, None, format!("cannot read: {e}")))?;
    let lines: Vec<&str> = text.lines().collect();
    let Some(header_at) = lines.iter().position(|l| l.starts_with("Date(dd-mm-yyyy)")) else {
        return Err(MeasuredError::new(
            file,
            None,
            "no header line beginning Date(dd-mm-yyyy): not an AERONET inversion file",
        ));
    };
    let columns: Vec<&str> = lines[header_at].split(',').map(str::trim).collect();
    let find = |name: &str| {
        columns.iter().position(|c| *c == name).ok_or_else(|| {
            MeasuredError::new(file, Some(header_at + 1), format!("no column `{name}`"))
        })
    };
    let (time_col, tau_col, alpha_col) = (
        find("Time(hh:mm:ss)")?,
        find("tau440(measured)")?,
        find("alpha440-870")?,
    );
    // The phase function's columns: `<angle>[442nm]` and `<angle>[674nm]`.
    let phase_columns = |band: &str| -> Vec<(usize, f64)> {
        columns
            .iter()
            .enumerate()
            .filter_map(|(i, c)| Some((i, c.strip_suffix(band)?.parse::<f64>().ok()?)))
            .collect()
    };
    let (p442, p674) = (phase_columns("[442nm]"), phase_columns("[674nm]"));
    let mut records = Vec::new();
    for (i, line) in lines.iter().enumerate().skip(header_at + 1) {
        let n = i + 1;
        if line.trim().is_empty() {
            continue;
        }
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        if cells.len() < columns.len() {
            return Err(MeasuredError::new(
                file,
                Some(n),
                format!(
                    "{} cells where the header has {}",
                    cells.len(),
                    columns.len()
                ),
            ));
        }
        let (day, month, year) = parse_date(cells[0]).ok_or_else(|| {
            MeasuredError::new(
                file,
                Some(n),
                format!("date `{}` is not dd:mm:yyyy", cells[0]),
            )
        })?;
        let time_utc =
            Clock::parse(cells[time_col]).map_err(|e| MeasuredError::new(file, Some(n), e))?;
        let value = |col: usize, name: &str, range: std::ops::RangeInclusive<f64>| {
            cells[col]
                .parse::<f64>()
                .ok()
                .filter(|v| range.contains(v))
                .ok_or_else(|| {
                    MeasuredError::new(
                        file,
                        Some(n),
                        format!("{name}: `{}` is not a number in {range:?}", cells[col]),
                    )
                })
        };
        let tau440 = value(tau_col, "tau440(measured)", 0.0..=5.0)?;
        let angstrom = value(alpha_col, "alpha440-870", -1.0..=4.0)?;
        let g = |cols: &[(usize, f64)]| -> Option<f64> {
            let points: Vec<(f64, f64)> = cols
                .iter()
                .map(|&(c, angle)| {
                    Some((
                        angle,
                        cells[c]
                            .parse::<f64>()
                            .ok()
                            .filter(|v| v.is_finite() && *v >= 0.0)?,
                    ))
                })
                .collect::<Option<_>>()?;
            asymmetry(&points)
        };
        let asymmetry_g = g(&p442).zip(g(&p674));
        records.push(AeronetRecord {
            year,
            month,
            day,
            time_utc,
            tau440,
            angstrom,
            asymmetry_g,
        });
    }
    Ok(records)
}

fn parse_date(s: &str) -> Option<(u32, u32, i32)> {
    let mut it = s.split([':', '-']);
    let (d, m, y) = (
        it.next()?.parse().ok()?,
        it.next()?.parse().ok()?,
        it.next()?.parse().ok()?,
    );
    (it.next().is_none()
        && (1..=31).contains(&d)
        && (1..=12).contains(&m)
        && (1900..=2100).contains(&y))
    .then_some((d, m, y))
}

/// The asymmetry parameter ⟨cos θ⟩ of a phase function tabulated at scattering angles
/// (degrees, increasing, spanning 0–180°), by the trapezoid rule in θ with weight sin θ.
/// None when the table does not span the sphere or integrates to nothing.
pub fn asymmetry(points: &[(f64, f64)]) -> Option<f64> {
    let (first, last) = (points.first()?, points.last()?);
    if first.0 > 1.0 || last.0 < 179.0 || points.windows(2).any(|w| w[1].0 <= w[0].0) {
        return None;
    }
    let (mut norm, mut moment) = (0.0, 0.0);
    for w in points.windows(2) {
        let (t0, t1) = (w[0].0.to_radians(), w[1].0.to_radians());
        let f = |t: f64, p: f64| (p * t.sin(), p * t.sin() * t.cos());
        let (a0, b0) = f(t0, w[0].1);
        let (a1, b1) = f(t1, w[1].1);
        norm += 0.5 * (a0 + a1) * (t1 - t0);
        moment += 0.5 * (b0 + b1) * (t1 - t0);
    }
    (norm > 0.0).then(|| moment / norm)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_asymmetry_of_henyey_greenstein_is_its_g() {
        for g in [0.0, 0.5, 0.7] {
            let hg =
                |t: f64| (1.0 - g * g) / (1.0 + g * g - 2.0 * g * t.to_radians().cos()).powf(1.5);
            let points: Vec<(f64, f64)> = (0..=720)
                .map(|i| f64::from(i) * 0.25)
                .map(|t| (t, hg(t)))
                .collect();
            let got = asymmetry(&points).expect("spans the sphere");
            assert!((got - g).abs() < 2e-3, "g {g}: {got}");
        }
    }

    #[test]
    fn the_aerosol_between_two_records_is_interpolated_in_time_and_held_outside() {
        let record = |h: u32, tau440: f64| AeronetRecord {
            year: 2013,
            month: 5,
            day: 27,
            time_utc: Clock {
                seconds: f64::from(h * 3600),
            },
            tau440,
            angstrom: 1.0,
            asymmetry_g: None,
        };
        let records = [record(10, 0.1), record(12, 0.3)];
        let mid = at(
            &records,
            Clock {
                seconds: 11.0 * 3600.0,
            },
        )
        .expect("records");
        assert!((mid.aod550 - 0.2 * 440.0 / 550.0).abs() < 1e-12);
        assert!((mid.hours_to_record - 1.0).abs() < 1e-12);
        let late = at(
            &records,
            Clock {
                seconds: 15.0 * 3600.0,
            },
        )
        .expect("records");
        assert!((late.aod550 - 0.3 * 440.0 / 550.0).abs() < 1e-12);
        assert!((late.hours_to_record - 3.0).abs() < 1e-12);
    }
}
