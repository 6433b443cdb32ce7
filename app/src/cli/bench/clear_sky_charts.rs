//! The charts of `atmoscope bench clear-sky`: zenith luminance and horizontal sky illuminance
//! against the sun's elevation, the zenith spectra at one sun, each model's line beside the path
//! tracer's (SVG and PNG); and the relative error maps of every model over every dome as one
//! mosaic (PNG).

use super::clear_sky::{Row, SPECTRUM_NM};
use crate::images::{PALETTE, chart_files};
use anyhow::anyhow;
use plotters::prelude::*;
use std::path::Path;

/// The sun's elevation of the zenith-spectra chart, degrees (the nearest dome's).
pub const SPECTRA_ELEVATION_DEG: f64 = 30.0;

/// Writes every chart into `out`.
pub fn write(out: &Path, rows: &[Row], w: u32, h: u32) -> anyhow::Result<()> {
    crate::images::register_font();
    let by_sun = |f: fn(&super::clear_sky::Figures) -> f64| {
        move |r: &Row| r.figures.as_ref().map(|x| (r.sun_elevation_deg, f(x)))
    };
    line_chart(
        out,
        "zenith_luminance",
        "Zenith luminance over the day",
        "sun elevation, degrees",
        "zenith luminance, cd/m² (log)",
        rows,
        &by_sun(|f| f.zenith_luminance_cd_m2),
    )?;
    line_chart(
        out,
        "illuminance",
        "Horizontal sky illuminance over the day (the sun's disk left out)",
        "sun elevation, degrees",
        "illuminance, lx (log)",
        rows,
        &by_sun(|f| f.illuminance_lx),
    )?;
    let elevations: Vec<f64> = rows.iter().map(|r| r.sun_elevation_deg).collect();
    let at = elevations
        .iter()
        .copied()
        .min_by(|a, b| {
            (a - SPECTRA_ELEVATION_DEG)
                .abs()
                .total_cmp(&(b - SPECTRA_ELEVATION_DEG).abs())
        })
        .unwrap_or(SPECTRA_ELEVATION_DEG);
    let spectra: Vec<Row> = rows
        .iter()
        .filter(|r| r.sun_elevation_deg == at)
        .cloned()
        .collect();
    let spectrum_points = |r: &Row| -> Vec<(f64, f64)> {
        r.figures.as_ref().map_or(Vec::new(), |f| {
            SPECTRUM_NM
                .iter()
                .copied()
                .zip(f.zenith_spectrum.iter().copied())
                .filter(|p| p.1 > 0.0 && p.1.is_finite())
                .collect()
        })
    };
    let title = format!("Zenith spectral radiance, sun {at}°");
    chart_files!(out, "zenith_spectra", (960, 640), |backend| lines(
        backend,
        &title,
        "wavelength, nm",
        "radiance, W/(m² sr nm) (log)",
        &spectra,
        &spectrum_points,
    ))?;
    error_mosaic(out, rows, w, h)
}

fn line_chart(
    out: &Path,
    stem: &str,
    title: &str,
    x: &str,
    y: &str,
    rows: &[Row],
    point: &dyn Fn(&Row) -> Option<(f64, f64)>,
) -> anyhow::Result<()> {
    // One line per model over the suns, in the order the rows name them.
    let series = |r: &Row| -> Vec<(f64, f64)> {
        let mut v: Vec<(f64, f64)> = rows
            .iter()
            .filter(|o| o.model == r.model)
            .filter_map(point)
            .filter(|p| p.1 > 0.0 && p.1.is_finite())
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        v
    };
    let mut firsts: Vec<Row> = Vec::new();
    for r in rows {
        if !firsts.iter().any(|f| f.model == r.model) {
            firsts.push(r.clone());
        }
    }
    chart_files!(out, stem, (960, 640), |backend| lines(
        backend, title, x, y, &firsts, &series
    ))
}

/// A chart of one line per row of `rows` (its points from `points`), the path tracer's black
/// and thick, on a log y axis.
fn lines<B: DrawingBackend>(
    backend: B,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    rows: &[Row],
    points: &dyn Fn(&Row) -> Vec<(f64, f64)>,
) -> anyhow::Result<()> {
    let err = |e: plotters::drawing::DrawingAreaErrorKind<B::ErrorType>| anyhow!("chart: {e}");
    let root = backend.into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let all: Vec<(f64, f64)> = rows.iter().flat_map(points).collect();
    let (x0, x1) = all
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    let (y0, y1) = all.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.1), b.max(p.1))
    });
    if !(x0.is_finite() && y0.is_finite() && y1 > 0.0) {
        return Ok(());
    }
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(
            x0..(x1 + 0.02 * (x1 - x0)),
            ((y0 / 1.5)..(y1 * 1.5)).log_scale(),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .label_style(("sans-serif", 14))
        .y_label_formatter(&|v| format!("{v:.3e}"))
        .draw()
        .map_err(err)?;
    for (i, r) in rows.iter().enumerate() {
        let pts = points(r);
        if pts.is_empty() {
            continue;
        }
        let truth = r.model == "path-tracer";
        let colour = if truth {
            BLACK
        } else {
            PALETTE[i % PALETTE.len()]
        };
        let style = colour.stroke_width(if truth { 3 } else { 1 });
        // Ten colours; past them the line's dashes and the marker tell the models apart (the
        // legend shows the marker).
        let group = if truth { 0 } else { (i / PALETTE.len()) % 3 };
        let series = match group {
            0 => chart.draw_series(LineSeries::new(pts.clone(), style)),
            1 => chart.draw_series(DashedLineSeries::new(pts.clone(), 6, 4, style)),
            _ => chart.draw_series(DashedLineSeries::new(pts.clone(), 2, 3, style)),
        }
        .map_err(err)?;
        let label = r.model.clone();
        match group {
            0 => {
                series
                    .label(label)
                    .legend(move |(x, y)| Circle::new((x + 9, y), 4, colour.filled()));
                chart
                    .draw_series(pts.iter().map(|p| Circle::new(*p, 3, colour.filled())))
                    .map_err(err)?;
            }
            1 => {
                series
                    .label(label)
                    .legend(move |(x, y)| TriangleMarker::new((x + 9, y), 5, colour.filled()));
                chart
                    .draw_series(
                        pts.iter()
                            .map(|p| TriangleMarker::new(*p, 4, colour.filled())),
                    )
                    .map_err(err)?;
            }
            _ => {
                series
                    .label(label)
                    .legend(move |(x, y)| Cross::new((x + 9, y), 4, colour.stroke_width(2)));
                chart
                    .draw_series(
                        pts.iter()
                            .map(|p| Cross::new(*p, 3, colour.stroke_width(2))),
                    )
                    .map_err(err)?;
            }
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .margin(4)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .label_font(("sans-serif", 12))
        .draw()
        .map_err(err)?;
    root.present().map_err(err)?;
    Ok(())
}

/// Colour of a relative error: blue where the model is too dark, red where too bright, white
/// where right, saturating at a factor of two (log₂ of the ratio ±1); grey where unmeasured.
pub fn error_colour(e: f64) -> RGBColor {
    if !e.is_finite() {
        return RGBColor(200, 200, 200);
    }
    let t = (1.0 + e).max(1e-6).log2().clamp(-1.0, 1.0);
    let fade = |c: f64| (255.0 * (1.0 - t.abs()) + c * t.abs()) as u8;
    if t < 0.0 {
        RGBColor(fade(33.0), fade(102.0), fade(172.0))
    } else {
        RGBColor(fade(178.0), fade(24.0), fade(43.0))
    }
}

/// `error_maps.png`: one row per model, one column per sun, each cell the dome's relative
/// luminance error against the path tracer.
fn error_mosaic(out: &Path, rows: &[Row], w: u32, h: u32) -> anyhow::Result<()> {
    let mut models: Vec<&str> = Vec::new();
    let mut suns: Vec<f64> = Vec::new();
    for r in rows.iter().filter(|r| r.model != "path-tracer") {
        if !models.contains(&r.model.as_str()) {
            models.push(&r.model);
        }
        if !suns.contains(&r.sun_elevation_deg) {
            suns.push(r.sun_elevation_deg);
        }
    }
    let scale = 2u32;
    let (cell_w, cell_h) = (w * scale + 8, h * scale + 8);
    let (left, top) = (170u32, 40u32);
    let size = (
        left + cell_w * suns.len() as u32 + 10,
        top + cell_h * models.len() as u32 + 40,
    );
    let mut rgb = vec![0u8; (size.0 * size.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        let err = |e: plotters::drawing::DrawingAreaErrorKind<_>| anyhow!("chart: {e:?}");
        root.fill(&WHITE).map_err(err)?;
        for (j, sun) in suns.iter().enumerate() {
            let x = (left + cell_w * j as u32) as i32;
            root.draw(&Text::new(
                format!("sun {sun}°"),
                (x + 4, 12),
                ("sans-serif", 14),
            ))
            .map_err(err)?;
        }
        for (i, model) in models.iter().enumerate() {
            let y = (top + cell_h * i as u32) as i32;
            root.draw(&Text::new(
                model.to_string(),
                (4, y + cell_h as i32 / 2 - 7),
                ("sans-serif", 14),
            ))
            .map_err(err)?;
            for (j, sun) in suns.iter().enumerate() {
                let x = (left + cell_w * j as u32) as i32;
                let Some(f) = rows
                    .iter()
                    .find(|r| r.model == *model && r.sun_elevation_deg == *sun)
                    .and_then(|r| r.figures.as_ref())
                else {
                    root.draw(&Text::new(
                        "refused",
                        (x + 10, y + cell_h as i32 / 2 - 7),
                        ("sans-serif", 12),
                    ))
                    .map_err(err)?;
                    continue;
                };
                for (k, e) in f.errors.iter().enumerate() {
                    let (px, py) = ((k as u32 % w) * scale, (k as u32 / w) * scale);
                    let c = error_colour(*e);
                    root.draw(&Rectangle::new(
                        [
                            (x + px as i32, y + py as i32),
                            (x + (px + scale) as i32, y + (py + scale) as i32),
                        ],
                        c.filled(),
                    ))
                    .map_err(err)?;
                }
            }
        }
        let legend_y = (size.1 - 24) as i32;
        for (k, e) in [-0.5, -0.25, 0.0, 0.33, 1.0].iter().enumerate() {
            let x = left as i32 + 130 * k as i32;
            root.draw(&Rectangle::new(
                [(x, legend_y), (x + 16, legend_y + 16)],
                error_colour(*e).filled(),
            ))
            .map_err(err)?;
            root.draw(&Text::new(
                format!("{:+.0} %", 100.0 * e),
                (x + 20, legend_y),
                ("sans-serif", 13),
            ))
            .map_err(err)?;
        }
        root.present().map_err(err)?;
    }
    crate::images::save_rgb8(&out.join("error_maps.png"), rgb, size.0, size.1)
}
