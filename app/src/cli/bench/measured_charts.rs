//! The charts of `atmoscope bench measured`: the day's zenith luminance and global irradiance,
//! measured against each model; measured and modelled spectra in four directions of one scan;
//! and per model the dome of its luminance errors in three scans (SVG and PNG).

use crate::images::{PALETTE, chart_files};
use anyhow::anyhow;
use atmoscope_eval::measured::files::Day;
use atmoscope_eval::measured::run::{ScanResult, Settings};
use atmoscope_eval::measured::score;
use plotters::prelude::*;
use std::path::Path;

/// A line of a chart: its label and points; the measurement black and thick, the path tracer
/// grey and thick.
struct Series {
    label: String,
    points: Vec<(f64, f64)>,
}

pub fn write(
    out: &Path,
    days: &[Day],
    results: &[(usize, ScanResult)],
    settings: &Settings,
) -> anyhow::Result<()> {
    crate::images::register_font();
    let ids: Vec<&str> = results.first().map_or(Vec::new(), |(_, r)| {
        r.sources.iter().map(|s| s.id).collect()
    });
    let hour = |d: usize, r: &ScanResult| days[d].scans[r.scan].time_local.hours();
    let over_day = |measured: &dyn Fn(&ScanResult) -> Option<f64>,
                    modelled: &dyn Fn(&ScanResult, &str) -> Option<f64>| {
        let mut v = vec![Series {
            label: "measured".into(),
            points: results
                .iter()
                .filter_map(|(d, r)| Some((hour(*d, r), measured(r)?)))
                .collect(),
        }];
        for id in &ids {
            v.push(Series {
                label: (*id).into(),
                points: results
                    .iter()
                    .filter_map(|(d, r)| Some((hour(*d, r), modelled(r, id)?)))
                    .collect(),
            });
        }
        v
    };
    let source = |r: &ScanResult, id: &str| r.sources.iter().find(|s| s.id == id).cloned();
    let zenith = over_day(&|r| r.zenith_luminance_measured, &|r, id| {
        source(r, id)?.zenith_luminance
    });
    chart_files!(out, "day_zenith_luminance", (960, 640), |backend| lines(
        backend,
        "Zenith luminance over the day",
        "local time, hours",
        "cd/m²",
        &zenith
    ))?;
    let ghi = over_day(&|r| r.ghi_measured_w_m2, &|r, id| source(r, id)?.ghi_w_m2);
    chart_files!(out, "day_global_irradiance", (960, 640), |backend| lines(
        backend,
        "Global horizontal irradiance over the day",
        "local time, hours",
        "W/m²",
        &ghi
    ))?;
    if let Some((d, r)) = results.get(results.len() / 2) {
        spectra(out, &days[*d], r, settings)?;
    }
    let picked: Vec<&(usize, ScanResult)> = match results.len() {
        0 => Vec::new(),
        n => {
            let mut v = vec![&results[0], &results[n / 2], &results[n - 1]];
            v.dedup_by(|a, b| a.1.scan == b.1.scan && a.0 == b.0);
            v
        }
    };
    for id in &ids {
        let stem = format!("dome_{id}");
        chart_files!(
            out,
            &stem,
            (300 * picked.len().max(1) as u32, 340),
            |backend| domes(backend, days, &picked, id, settings)
        )?;
    }
    Ok(())
}

/// Four directions of one scan: the highest scored (the zenith), and on the two lowest rings the
/// scored directions nearest to the sun's azimuth, across it and away from it.
fn spectra(out: &Path, day: &Day, r: &ScanResult, settings: &Settings) -> anyhow::Result<()> {
    let scan = &day.scans[r.scan];
    let nearest = |elevation: f64, from_sun: f64| -> Option<usize> {
        r.scored
            .iter()
            .enumerate()
            .filter(|(_, i)| (scan.directions[**i].elevation_deg - elevation).abs() < 1.0)
            .min_by(|(_, a), (_, b)| {
                let off = |i: usize| {
                    let az = scan.directions[i].azimuth_deg - r.sun_azimuth_deg - from_sun;
                    ((az + 180.0).rem_euclid(360.0) - 180.0).abs()
                };
                off(**a).total_cmp(&off(**b))
            })
            .map(|(k, _)| k)
    };
    // The scan's rings, lowest first, whatever its instrument's elevations.
    let mut rings: Vec<f64> = r
        .scored
        .iter()
        .map(|&i| scan.directions[i].elevation_deg)
        .collect();
    rings.sort_by(f64::total_cmp);
    rings.dedup_by(|a, b| (*a - *b).abs() < 1.0);
    let (lowest, second) = (
        rings.first().copied().unwrap_or(0.0),
        rings.get(1).copied().unwrap_or(0.0),
    );
    let picks = [
        nearest(rings.last().copied().unwrap_or(90.0), 0.0),
        nearest(second, 0.0),
        nearest(second, 90.0),
        nearest(lowest, 180.0),
    ];
    for (n, k) in picks.into_iter().flatten().enumerate() {
        let dir = &scan.directions[r.scored[k]];
        let mut series = vec![Series {
            label: "measured".into(),
            points: day
                .wavelengths_nm
                .iter()
                .copied()
                .zip(dir.radiance.iter().copied())
                .filter(|(w, l)| (360.0..=830.0).contains(w) && *l > 0.0)
                .collect(),
        }];
        for s in r.sources.iter().filter(|s| s.refused.is_none()) {
            series.push(Series {
                label: s.id.into(),
                points: settings
                    .model_nm
                    .iter()
                    .copied()
                    .zip(s.radiance[k].iter().copied())
                    .filter(|p| p.1 > 0.0)
                    .collect(),
            });
        }
        let title = format!(
            "{} {}: azimuth {:.0}° ({:+.0}° from the sun), elevation {:.1}°",
            day.date,
            scan.time_local,
            dir.azimuth_deg,
            (dir.azimuth_deg - r.sun_azimuth_deg + 180.0).rem_euclid(360.0) - 180.0,
            dir.elevation_deg
        );
        let stem = format!("spectra_{}", n + 1);
        chart_files!(out, &stem, (960, 640), |backend| lines(
            backend,
            &title,
            "wavelength, nm",
            "W/(m² sr nm)",
            &series
        ))?;
    }
    Ok(())
}

fn lines<B: DrawingBackend>(
    backend: B,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[Series],
) -> anyhow::Result<()> {
    let err = |e: plotters::drawing::DrawingAreaErrorKind<B::ErrorType>| anyhow!("chart: {e}");
    let root = backend.into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    let (x0, x1) = all
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    let (y0, y1) = all
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.1), b.max(p.1))
        });
    if !(x0.is_finite() && y0.is_finite() && x1 > x0) {
        return Ok(());
    }
    let pad = 0.05 * (y1 - y0).max(y1.abs() * 0.05);
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 18))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(72)
        .build_cartesian_2d(x0..x1, (y0 - pad)..(y1 + pad))
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(err)?;
    for (i, s) in series.iter().enumerate() {
        let (colour, width) = match s.label.as_str() {
            "measured" => (BLACK, 3),
            "path-tracer" => (RGBColor(120, 120, 120), 3),
            _ => (PALETTE[i % PALETTE.len()], 1),
        };
        let style = colour.stroke_width(width);
        let drawn = if i / PALETTE.len() % 2 == 1 {
            chart
                .draw_series(DashedLineSeries::new(s.points.clone(), 6, 4, style))
                .map_err(err)?
        } else {
            chart
                .draw_series(LineSeries::new(s.points.clone(), style))
                .map_err(err)?
        };
        drawn
            .label(s.label.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], style));
        if s.label == "measured" {
            chart
                .draw_series(s.points.iter().map(|p| Circle::new(*p, 3, colour.filled())))
                .map_err(err)?;
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 11))
        .draw()
        .map_err(err)?;
    Ok(())
}

/// Relative luminance error at which the dome's colours saturate.
const DOME_RANGE: f64 = 0.5;

/// A diverging colour for a relative error: blue where the model is too dark, red too bright.
fn error_colour(e: f64) -> RGBColor {
    let t = (e / DOME_RANGE).clamp(-1.0, 1.0);
    let mix = |a: f64, b: f64, t: f64| (a + (b - a) * t).round() as u8;
    if t < 0.0 {
        RGBColor(
            mix(255.0, 33.0, -t),
            mix(255.0, 102.0, -t),
            mix(255.0, 172.0, -t),
        )
    } else {
        RGBColor(
            mix(255.0, 178.0, t),
            mix(255.0, 24.0, t),
            mix(255.0, 43.0, t),
        )
    }
}

/// The scored directions of a few scans on fisheyes (zenith in the middle, north up, east
/// right), each coloured by the model's relative luminance error; the sun a yellow disk.
fn domes<B: DrawingBackend>(
    backend: B,
    days: &[Day],
    scans: &[&(usize, ScanResult)],
    id: &str,
    settings: &Settings,
) -> anyhow::Result<()> {
    let err = |e: plotters::drawing::DrawingAreaErrorKind<B::ErrorType>| anyhow!("chart: {e}");
    let root = backend.into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let (w, _) = root.dim_in_pixel();
    let panels = root.split_evenly((1, scans.len().max(1)));
    let _ = w;
    for (panel, (d, r)) in panels.iter().zip(scans) {
        let day = &days[*d];
        let scan = &day.scans[r.scan];
        let (pw, ph) = panel.dim_in_pixel();
        let (cx, cy, radius) = (
            pw as i32 / 2,
            ph as i32 / 2 + 10,
            (pw.min(ph) as i32) / 2 - 24,
        );
        let at = |azimuth_deg: f64, elevation_deg: f64| {
            let rr = f64::from(radius) * (90.0 - elevation_deg) / 90.0;
            let a = azimuth_deg.to_radians();
            (
                cx + (rr * a.sin()).round() as i32,
                cy - (rr * a.cos()).round() as i32,
            )
        };
        panel
            .draw(&Circle::new(
                (cx, cy),
                radius,
                ShapeStyle::from(&BLACK).stroke_width(1),
            ))
            .map_err(err)?;
        panel
            .draw(&Text::new(
                format!("{id} {} {}", day.date, scan.time_local),
                (8, 4),
                ("sans-serif", 14),
            ))
            .map_err(err)?;
        let Some(s) = r.sources.iter().find(|s| s.id == id) else {
            continue;
        };
        if let Some(why) = &s.refused {
            panel
                .draw(&Text::new(
                    format!("refused: {why}"),
                    (8, 24),
                    ("sans-serif", 10),
                ))
                .map_err(err)?;
            continue;
        }
        let lum = atmoscope_eval::measured::run::measured_luminance(day, scan);
        for (k, &i) in r.scored.iter().enumerate() {
            let dir = &scan.directions[i];
            let l =
                score::xyz(&settings.model_nm, &s.radiance[k]).map_or(f64::NAN, score::luminance);
            let e = l / lum[i] - 1.0;
            if !e.is_finite() {
                continue;
            }
            let p = at(dir.azimuth_deg, dir.elevation_deg);
            panel
                .draw(&Circle::new(p, 8, error_colour(e).filled()))
                .map_err(err)?;
            panel
                .draw(&Circle::new(
                    p,
                    8,
                    ShapeStyle::from(&RGBColor(90, 90, 90)).stroke_width(1),
                ))
                .map_err(err)?;
        }
        let sun = at(r.sun_azimuth_deg, 90.0 - r.sun_zenith_deg);
        panel
            .draw(&Circle::new(sun, 6, RGBColor(240, 200, 0).filled()))
            .map_err(err)?;
    }
    root.draw(&Text::new(
        format!(
            "luminance error: blue −{:.0} % … red +{:.0} %",
            100.0 * DOME_RANGE,
            100.0 * DOME_RANGE
        ),
        (8, 322),
        ("sans-serif", 12),
    ))
    .map_err(err)?;
    Ok(())
}
