//! The reader of measured-sky folders in the format of Kider et al. (2014) (`data/kider_2014/`
//! says what each file holds): per day `radiance_<date>.csv` and `scans_<date>.csv`, and where
//! present `pyranometer_<date>.csv` and an AERONET inversion file (`*.pfn`, [`super::aeronet`]).
//!
//! Everything read is untrusted: a folder reads whole or not at all, and a damaged file is
//! answered with its name, its line and what is wrong there.

use super::aeronet::{self, AeronetRecord};
use super::clock::Clock;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// What is wrong with a measured-sky folder: the file, the line (1-based) where known, and why.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{}: {message}", file.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
pub struct MeasuredError {
    pub file: PathBuf,
    pub line: Option<usize>,
    pub message: String,
}

impl MeasuredError {
    pub fn new(file: &Path, line: Option<usize>, message: impl Into<String>) -> MeasuredError {
        MeasuredError {
            file: file.to_path_buf(),
            line,
            message: message.into(),
        }
    }
}

/// One measured direction of a scan.
#[derive(Debug, Clone, PartialEq)]
pub struct Direction {
    /// The scanner's sample index (0 is the first, low in the north).
    pub sample: u32,
    /// Clockwise from north, degrees (0–360).
    pub azimuth_deg: f64,
    /// Above the horizon, degrees (0–90).
    pub elevation_deg: f64,
    /// Spectral radiance at the day's wavelengths, W·m⁻²·sr⁻¹·nm⁻¹.
    pub radiance: Vec<f64>,
}

/// One scan of the sky dome.
#[derive(Debug, Clone, PartialEq)]
pub struct Scan {
    /// The scan's nominal start on the local clock.
    pub time_local: Clock,
    /// The same instant in UTC.
    pub time_utc: Clock,
    pub directions: Vec<Direction>,
}

impl Scan {
    /// Offset of the local clock from UTC, hours (local − UTC), from the two clocks the file
    /// gives: −12 to +12 (the files carry no date per clock to tell +13 from −11).
    pub fn utc_offset_h(&self) -> f64 {
        let d = (self.time_local.seconds - self.time_utc.seconds) / 3600.0;
        // Days wrap: 01:00 local is 23:00 UTC the day before at +2 h.
        let d = (d + 12.0).rem_euclid(24.0) - 12.0;
        if d < -12.0 + 1e-9 { d + 24.0 } else { d }
    }
}

/// A pyranometer reading: global horizontal irradiance at a local time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GhiSample {
    pub time_local: Clock,
    /// W·m⁻², broadband.
    pub ghi_w_m2: f64,
}

/// The measurements of one day at one site.
#[derive(Debug, Clone, PartialEq)]
pub struct Day {
    /// As in the file names, `yyyy-mm-dd`.
    pub date: String,
    pub year: i32,
    pub month: u32,
    pub day: u32,
    /// The wavelengths of every direction's spectrum, nm, increasing.
    pub wavelengths_nm: Vec<f64>,
    pub scans: Vec<Scan>,
    /// Empty when the folder has no pyranometer file for the day.
    pub pyranometer: Vec<GhiSample>,
    /// The AERONET records of the day, in time order; empty without a `.pfn` file for it.
    pub aeronet: Vec<AeronetRecord>,
}

impl Day {
    /// The pyranometer's mean over a scan: the readings from its start to the next scan's
    /// start (at most `MAX_SCAN_MINUTES` later). None when there are none.
    pub fn ghi_during(&self, scan: usize) -> Option<f64> {
        let start = self.scans.get(scan)?.time_local.seconds;
        let next = self
            .scans
            .get(scan + 1)
            .map_or(f64::INFINITY, |s| s.time_local.seconds);
        let end = next.min(start + MAX_SCAN_MINUTES * 60.0);
        let v: Vec<f64> = self
            .pyranometer
            .iter()
            .filter(|s| s.time_local.seconds >= start && s.time_local.seconds < end)
            .map(|s| s.ghi_w_m2)
            .collect();
        (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
    }
}

/// The longest a scan is taken to last when matching pyranometer readings to it, minutes.
pub const MAX_SCAN_MINUTES: f64 = 15.0;

const RADIANCE_COLUMNS: [&str; 6] = [
    "date",
    "time_local_edt",
    "time_utc",
    "sample",
    "azimuth_deg",
    "elevation_deg",
];

/// Reads every day of a folder: one per `radiance_<date>.csv`, in date order.
pub fn read_folder(dir: &Path) -> Result<Vec<Day>, MeasuredError> {
    let entries = std::fs::read_dir(dir)
        .map_err(|e| MeasuredError::new(dir, None, format!("cannot read the folder: {e}")))?;
    let mut names = Vec::new();
    for entry in entries {
        let entry = entry.map_err(|e| MeasuredError::new(dir, None, e.to_string()))?;
        names.push(entry.file_name().to_string_lossy().into_owned());
    }
    names.sort();
    let dates: Vec<String> = names
        .iter()
        .filter_map(|n| n.strip_prefix("radiance_")?.strip_suffix(".csv"))
        .map(str::to_owned)
        .collect();
    if dates.is_empty() {
        return Err(MeasuredError::new(
            dir,
            None,
            "no radiance_<yyyy-mm-dd>.csv here: not a measured-sky folder",
        ));
    }
    let mut aeronet_records = Vec::new();
    for n in names.iter().filter(|n| n.ends_with(".pfn")) {
        aeronet_records.extend(aeronet::read(&dir.join(n))?);
    }
    dates
        .iter()
        .map(|date| read_day(dir, date, &aeronet_records))
        .collect()
}

fn read_day(dir: &Path, date: &str, aeronet: &[AeronetRecord]) -> Result<Day, MeasuredError> {
    let radiance_file = dir.join(format!("radiance_{date}.csv"));
    let (year, month, day) = parse_date(date).ok_or_else(|| {
        MeasuredError::new(&radiance_file, None, "the name's date is not yyyy-mm-dd")
    })?;
    let (wavelengths_nm, mut scans) = read_radiance(&radiance_file, date)?;
    let scans_file = dir.join(format!("scans_{date}.csv"));
    let listed = read_scan_list(&scans_file, date)?;
    for (local, _) in &listed {
        if !scans.contains_key(local) {
            return Err(MeasuredError::new(
                &scans_file,
                None,
                format!("scan {local} has no directions in radiance_{date}.csv"),
            ));
        }
    }
    if let Some(extra) = scans.keys().find(|k| !listed.iter().any(|(l, _)| l == *k)) {
        return Err(MeasuredError::new(
            &scans_file,
            None,
            format!("radiance_{date}.csv has scan {extra}, which this list lacks"),
        ));
    }
    let pyranometer_file = dir.join(format!("pyranometer_{date}.csv"));
    let pyranometer = if pyranometer_file.exists() {
        read_pyranometer(&pyranometer_file)?
    } else {
        Vec::new()
    };
    let mut aeronet: Vec<AeronetRecord> = aeronet
        .iter()
        .filter(|r| (r.year, r.month, r.day) == (year, month, day))
        .cloned()
        .collect();
    aeronet.sort_by(|a, b| a.time_utc.seconds.total_cmp(&b.time_utc.seconds));
    let mut scans: Vec<Scan> = std::mem::take(&mut scans).into_values().collect();
    scans.sort_by(|a, b| a.time_local.seconds.total_cmp(&b.time_local.seconds));
    Ok(Day {
        date: date.to_owned(),
        year,
        month,
        day,
        wavelengths_nm,
        scans,
        pyranometer,
        aeronet,
    })
}

fn parse_date(s: &str) -> Option<(i32, u32, u32)> {
    let mut it = s.split('-');
    let (y, m, d) = (it.next()?, it.next()?, it.next()?);
    if it.next().is_some() || y.len() != 4 || m.len() != 2 || d.len() != 2 {
        return None;
    }
    let (y, m, d) = (y.parse().ok()?, m.parse().ok()?, d.parse().ok()?);
    ((1900..=2100).contains(&y) && (1..=12).contains(&m) && (1..=31).contains(&d))
        .then_some((y, m, d))
}

/// Lines of a CSV file with their 1-based numbers, blank lines and `#` comments left out.
fn lines(file: &Path) -> Result<Vec<(usize, String)>, MeasuredError> {
    let text = std::fs::read_to_string(file)
        .map_err(|e| MeasuredError::new(file, None, format!("cannot read: {e}")))?;
    Ok(text
        .trim_start_matches('\u{feff}')
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim().to_owned()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'))
        .collect())
}

fn number(file: &Path, line: usize, column: &str, s: &str) -> Result<f64, MeasuredError> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| {
            MeasuredError::new(
                file,
                Some(line),
                format!("{column}: `{s}` is not a finite number"),
            )
        })
}

type Scans = BTreeMap<Clock, Scan>;

/// The cells of data row `line` of a file whose first column is the date: as many as the
/// header has, the first of them `date`.
fn dated_cells<'a>(
    file: &Path,
    line: usize,
    row: &'a str,
    columns: usize,
    date: &str,
) -> Result<Vec<&'a str>, MeasuredError> {
    let cells: Vec<&str> = row.split(',').map(str::trim).collect();
    if cells.len() != columns {
        return Err(MeasuredError::new(
            file,
            Some(line),
            format!("{} cells where the header has {columns}", cells.len()),
        ));
    }
    if cells[0] != date {
        return Err(MeasuredError::new(
            file,
            Some(line),
            format!("date `{}` in the file of {date}", cells[0]),
        ));
    }
    Ok(cells)
}

fn read_radiance(file: &Path, date: &str) -> Result<(Vec<f64>, Scans), MeasuredError> {
    let rows = lines(file)?;
    let Some(((header_line, header), body)) = rows.split_first() else {
        return Err(MeasuredError::new(file, None, "empty file"));
    };
    let columns: Vec<&str> = header.split(',').map(str::trim).collect();
    if columns.len() <= RADIANCE_COLUMNS.len() || columns[..6] != RADIANCE_COLUMNS {
        return Err(MeasuredError::new(
            file,
            Some(*header_line),
            format!(
                "the header must begin {} and go on with L<nm> columns",
                RADIANCE_COLUMNS.join(",")
            ),
        ));
    }
    let mut wavelengths_nm = Vec::new();
    for c in &columns[6..] {
        let w = c
            .strip_prefix('L')
            .and_then(|w| w.parse::<f64>().ok())
            .filter(|w| (200.0..=2500.0).contains(w))
            .ok_or_else(|| {
                MeasuredError::new(
                    file,
                    Some(*header_line),
                    format!("column `{c}` is not L<nm>, 200–2500 nm"),
                )
            })?;
        if wavelengths_nm.last().is_some_and(|&last| w <= last) {
            return Err(MeasuredError::new(
                file,
                Some(*header_line),
                "the wavelengths must increase",
            ));
        }
        wavelengths_nm.push(w);
    }
    let mut scans = Scans::new();
    for (n, row) in body {
        let cells = dated_cells(file, *n, row, columns.len(), date)?;
        let local = Clock::parse(cells[1])
            .map_err(|e| MeasuredError::new(file, Some(*n), format!("time_local_edt: {e}")))?;
        let utc = Clock::parse(cells[2])
            .map_err(|e| MeasuredError::new(file, Some(*n), format!("time_utc: {e}")))?;
        let sample = cells[3].parse::<u32>().map_err(|_| {
            MeasuredError::new(
                file,
                Some(*n),
                format!("sample: `{}` is not a whole number", cells[3]),
            )
        })?;
        let azimuth_deg = number(file, *n, "azimuth_deg", cells[4])?;
        let elevation_deg = number(file, *n, "elevation_deg", cells[5])?;
        if !(0.0..=360.0).contains(&azimuth_deg) || !(0.0..=90.0).contains(&elevation_deg) {
            return Err(MeasuredError::new(
                file,
                Some(*n),
                "azimuth must be 0–360° and elevation 0–90°",
            ));
        }
        let radiance = cells[6..]
            .iter()
            .zip(&columns[6..])
            .map(|(s, c)| number(file, *n, c, s))
            .collect::<Result<Vec<f64>, _>>()?;
        let scan = scans.entry(local).or_insert_with(|| Scan {
            time_local: local,
            time_utc: utc,
            directions: Vec::new(),
        });
        if scan.time_utc != utc {
            return Err(MeasuredError::new(
                file,
                Some(*n),
                "time_utc differs within the scan",
            ));
        }
        if scan.directions.iter().any(|d| d.sample == sample) {
            return Err(MeasuredError::new(
                file,
                Some(*n),
                format!("sample {sample} of scan {local} appears twice"),
            ));
        }
        scan.directions.push(Direction {
            sample,
            azimuth_deg,
            elevation_deg,
            radiance,
        });
    }
    if scans.is_empty() {
        return Err(MeasuredError::new(file, None, "no directions"));
    }
    Ok((wavelengths_nm, scans))
}

fn read_scan_list(file: &Path, date: &str) -> Result<Vec<(Clock, Clock)>, MeasuredError> {
    let rows = lines(file)?;
    let Some(((header_line, header), body)) = rows.split_first() else {
        return Err(MeasuredError::new(file, None, "empty file"));
    };
    let columns: Vec<&str> = header.split(',').map(str::trim).collect();
    if columns.len() < 3 || columns[..3] != RADIANCE_COLUMNS[..3] {
        return Err(MeasuredError::new(
            file,
            Some(*header_line),
            "the header must begin date,time_local_edt,time_utc",
        ));
    }
    body.iter()
        .map(|(n, row)| {
            let cells = dated_cells(file, *n, row, columns.len(), date)?;
            let local =
                Clock::parse(cells[1]).map_err(|e| MeasuredError::new(file, Some(*n), e))?;
            let utc = Clock::parse(cells[2]).map_err(|e| MeasuredError::new(file, Some(*n), e))?;
            Ok((local, utc))
        })
        .collect()
}

fn read_pyranometer(file: &Path) -> Result<Vec<GhiSample>, MeasuredError> {
    let rows = lines(file)?;
    let Some(((header_line, header), body)) = rows.split_first() else {
        return Err(MeasuredError::new(file, None, "empty file"));
    };
    if header.replace(' ', "") != "time_local_edt,global_horizontal_irradiance_w_m2" {
        return Err(MeasuredError::new(
            file,
            Some(*header_line),
            "the header must be time_local_edt,global_horizontal_irradiance_w_m2",
        ));
    }
    body.iter()
        .map(|(n, row)| {
            let (t, v) = row
                .split_once(',')
                .ok_or_else(|| MeasuredError::new(file, Some(*n), "two cells expected"))?;
            let time_local = Clock::parse(t).map_err(|e| MeasuredError::new(file, Some(*n), e))?;
            let ghi_w_m2 = number(file, *n, "global_horizontal_irradiance_w_m2", v)?;
            if !(0.0..=2000.0).contains(&ghi_w_m2) {
                return Err(MeasuredError::new(
                    file,
                    Some(*n),
                    format!("{ghi_w_m2} W/m² lies outside 0–2000"),
                ));
            }
            Ok(GhiSample {
                time_local,
                ghi_w_m2,
            })
        })
        .collect()
}
