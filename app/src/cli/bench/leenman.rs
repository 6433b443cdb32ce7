//! `atmoscope bench leenman`: Leenman's (2025) comparison replayed (`atmoscope_eval::leenman`):
//! his Earth in linear sRGB (RGB3), his twelve views and exposures, every model he compares
//! (his neural network excepted) and Atmoscope's others, against path-traced references with
//! his four scattering events; and the transmittance along each pixel's ray of his five
//! transmittance views, his flat homogeneous-shell depth and the transmittance table, against
//! his 128-step Riemann sum. The metrics are those of his appendices, on his scale of radiance
//! (exposure·6·L/E): A HDR-FLIP, B the image's mean squared difference per channel, C LDR-FLIP
//! and D the mean squared difference of the transmittance. Writes `leenman.csv` (`table, view,
//! model, value`, his spellings for his views and models, registry ids for the others) and
//! `leenman.md`, his published value beside ours in every cell he has.
//!
//! His "RMSE" is read as the mean of his per-pixel, per-channel squared-error image (his eq. 61
//! applied to one sample, then averaged): his Empty, a white image, scores 0.82 against skies
//! of about 0.1, and Hillaire 9·10⁻⁵ at ground-noon, below what a 4 096-path reference's own
//! noise allows for a root mean square.

use crate::cli::common::{PathTrace, gpu, outside_sun_disk, path_traced};
use anyhow::{Context, bail};
use atmoscope_eval::leenman::{self, LeenmanView, TRANSMITTANCE_VIEWS, VIEWS};
use atmoscope_eval::metrics::{DisplaySetup, compare};
use atmoscope_model::Atmosphere;
use atmoscope_model::camera::Camera;
use atmoscope_model::display::EXPOSURE_SCALE;
use atmoscope_model::geometry::altitude_along;
use atmoscope_model::methods::shared::Params;
use atmoscope_model::methods::shared::segments_sky::Segments;
use atmoscope_model::methods::shared::transmittance::{
    compute_transmittance_lut, transmittance_between,
};
use atmoscope_model::scene::{Method, Quality, ToneMap, WavelengthSet};
use atmoscope_model::wavelengths::to_linear_srgb;
use atmoscope_render::{Engine, View};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

/// His path tracer's scattering events.
const REFERENCE_MAX_ORDER: u32 = 4;
/// Steps of his transmittance reference (Riemann sum).
const TRANSMITTANCE_REFERENCE_STEPS: u32 = 128;
/// Spectral bins for the sun's colour seen by the spectral path tracer.
const SUN_COLOUR_BINS: u32 = 96;

#[derive(Args, Debug)]
pub struct LeenmanBench {
    /// Size WxH of every image (his are 1920x1080, far beyond a CPU path tracer here).
    #[arg(long, value_name = "WxH", value_parser = crate::args::parse_size, default_value = "160x90")]
    pub size: (u32, u32),
    /// Paths per pixel of the path-traced references (cached).
    #[arg(long, default_value_t = 1024, value_parser = clap::value_parser!(u64).range(1..=1_000_000))]
    pub spp: u64,
    /// Sky models, comma-separated registry ids, or `all` (default: his, then every other
    /// real-time model).
    #[arg(long, value_name = "IDS", value_parser = crate::args::parse_methods)]
    pub methods: Option<crate::args::MethodList>,
    /// His views, comma-separated (default: all twelve; the transmittance views always run).
    #[arg(long, value_delimiter = ',')]
    pub views: Vec<String>,
    /// Output folder (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

/// One cell of ours.
struct Cell {
    table: &'static str,
    view: String,
    model: String,
    /// None: the model refuses the view.
    value: Option<f64>,
}

/// The name a model goes by in the tables: his, where he compares it, else the registry id.
fn model_name(method: Method) -> String {
    leenman::his_name(method)
        .map_or_else(|| crate::args::method_id(method).to_string(), String::from)
}

/// The sun's irradiance in linear sRGB as the images of `set` see it (for the spectral path
/// tracer, a fine spectral set): the E of his exposure·6·L/E.
fn sun_rgb(atmosphere: &Atmosphere, set: WavelengthSet) -> [f64; 3] {
    let p = Params::new(atmosphere, set, Quality::Medium);
    let colours: Vec<_> = p.batches.iter().map(|b| b.colour.clone()).collect();
    let sun: Vec<_> = p.batches.iter().map(|b| b.solar_irradiance).collect();
    to_linear_srgb(&colours, &sun)
}

/// The image's mean over pixels and channels of the squared difference (his "RMSE").
fn mean_squared(test: &[[f64; 3]], reference: &[[f64; 3]]) -> f64 {
    let sum: f64 = test
        .iter()
        .zip(reference)
        .flat_map(|(t, r)| (0..3).map(move |c| (t[c] - r[c]).powi(2)))
        .sum();
    sum / (3 * test.len().max(1)) as f64
}

pub fn run(args: &LeenmanBench) -> anyhow::Result<ExitCode> {
    let views: Vec<&LeenmanView> = if args.views.is_empty() {
        VIEWS.iter().collect()
    } else {
        args.views
            .iter()
            .map(|n| {
                LeenmanView::find(n).with_context(|| {
                    let names: Vec<_> = VIEWS.iter().map(|v| v.name).collect();
                    format!("--views {n}: not one of his views ({})", names.join(", "))
                })
            })
            .collect::<anyhow::Result<_>>()?
    };
    let methods: Vec<Method> = args.methods.clone().map_or_else(
        || {
            let mut m: Vec<Method> = leenman::MODELS.iter().map(|m| m.1).collect();
            m.extend(
                atmoscope_model::methods::realtime()
                    .map(|i| i.method)
                    .filter(|x| leenman::his_name(*x).is_none()),
            );
            m
        },
        |m| m.0,
    );
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let (w, h) = args.size;
    let atmosphere = Atmosphere::for_scene(&leenman::scene());
    let sun_model = sun_rgb(&atmosphere, WavelengthSet::Rgb3);
    let sun_reference = sun_rgb(&atmosphere, WavelengthSet::SpectralN(SUN_COLOUR_BINS));
    let pt = PathTrace {
        spp: Some(args.spp),
        noise: None,
        max_order: Some(REFERENCE_MAX_ORDER),
        seed: 1,
        no_cache: false,
    };
    // He draws no sun disk (on his scale its radiance, 6 over 6.8·10⁻⁵ sr, would be the whole
    // error): the pixels it touches are left black in every image.
    let outside_sun: Vec<Vec<bool>> = views
        .iter()
        .map(|v| outside_sun_disk(&v.scene(), v.view().projection, w, h))
        .collect();
    let on_his_scale = |v: &LeenmanView, keep: &[bool], image: Vec<[f64; 3]>, sun: [f64; 3]| {
        image
            .into_iter()
            .zip(keep)
            .map(|(l, &k)| if k { v.to_his_scale(l, sun) } else { [0.0; 3] })
            .collect::<Vec<_>>()
    };
    let references: Vec<Vec<[f64; 3]>> = views
        .iter()
        .zip(&outside_sun)
        .map(|(v, keep)| {
            let rgb = path_traced(&v.scene(), v.view().projection, (w, h), &pt, v.name)?;
            Ok(on_his_scale(v, keep, rgb, sun_reference))
        })
        .collect::<anyhow::Result<_>>()?;
    let context = gpu()?;
    let bar = ProgressBar::new((methods.len() * views.len()) as u64);
    bar.set_style(
        ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_prefix("bench leenman");
    let mut cells = Vec::new();
    let mut failures = Vec::new();
    for &method in &methods {
        let info = atmoscope_model::methods::info(method);
        let mut engine = Engine::new(&context.device, &context.queue);
        for ((v, reference), keep) in views.iter().zip(&references).zip(&outside_sun) {
            bar.set_message(format!("{} {}", info.id, v.name));
            bar.inc(1);
            let mut scene = v.scene();
            scene.render.method = method;
            let name = model_name(method);
            let refused = info.cannot_draw(&scene).is_some();
            let image = if refused {
                None
            } else {
                let drawn = match engine.try_render(&scene, &View::new(v.view().projection, w, h)) {
                    Ok(_) => engine.read_radiance().map_err(anyhow::Error::from),
                    Err(e) => Err(anyhow::Error::from(e)),
                };
                match drawn {
                    Ok(px) => {
                        let rgb = px
                            .iter()
                            .map(|p| [p[0], p[1], p[2]].map(f64::from))
                            .collect();
                        Some(on_his_scale(v, keep, rgb, sun_model))
                    }
                    Err(e) => {
                        failures.push(format!("{} {}: {e:#}", info.id, v.name));
                        continue;
                    }
                }
            };
            let (flip, mse) = match &image {
                Some(img) => (
                    Some(
                        compare(img, reference, w, h, DisplaySetup::default())
                            .0
                            .hdr_flip_mean,
                    ),
                    Some(mean_squared(img, reference)),
                ),
                None => (None, None),
            };
            for (table, value) in [("A_FLIP", flip), ("B_RMSE", mse)] {
                cells.push(Cell {
                    table,
                    view: v.name.into(),
                    model: name.clone(),
                    value,
                });
            }
        }
    }
    bar.finish_and_clear();
    if !failures.is_empty() && cells.iter().all(|c| c.value.is_none()) {
        bail!("every case failed:\n{}", failures.join("\n"));
    }
    cells.extend(transmittance_cells((w, h))?);
    let csv = to_csv(&cells);
    let md = to_markdown(&cells, &views, (w, h), args.spp);
    crate::files::write_atomic(&args.out.join("leenman.csv"), csv.as_bytes())?;
    crate::files::write_atomic(&args.out.join("leenman.md"), md.as_bytes())?;
    print!("{md}");
    eprintln!("wrote leenman.csv and leenman.md to {}", args.out.display());
    if !failures.is_empty() {
        eprintln!("left out:\n{}", failures.join("\n"));
        return Ok(ExitCode::FAILURE);
    }
    Ok(ExitCode::SUCCESS)
}

/// Appendices C and D: per pixel of his five transmittance views, the transmittance along the
/// view ray through the atmosphere (to the ground or out), by his flat model's homogeneous
/// shell and by the transmittance table the table-based models share, against his 128-step
/// Riemann sum (midpoints) of the scene's medium.
fn transmittance_cells((w, h): (u32, u32)) -> anyhow::Result<Vec<Cell>> {
    let scene = leenman::scene();
    let p = Params::new(
        &Atmosphere::for_scene(&scene),
        WavelengthSet::Rgb3,
        scene.render.quality,
    );
    let slabs = Segments::new(&p, 1);
    let table = compute_transmittance_lut(&p);
    let (big_r, top) = (p.bottom_radius_m, p.top_radius_m);
    let rgb = |l: [f64; 4]| [l[0], l[1], l[2]];
    let mut cells = Vec::new();
    for (name, view_name) in TRANSMITTANCE_VIEWS {
        let v = LeenmanView::find(view_name)
            .with_context(|| format!("no view {view_name}"))?
            .view();
        let camera = Camera::new(&v.camera, big_r, v.projection);
        let (mut reference, mut flat, mut looked_up) = (Vec::new(), Vec::new(), Vec::new());
        for y in 0..h {
            for x in 0..w {
                let ray = camera.ray(f64::from(x) + 0.5, f64::from(y) + 0.5, w, h);
                let Some(ray) = ray else {
                    for img in [&mut reference, &mut flat, &mut looked_up] {
                        img.push([1.0; 3]);
                    }
                    continue;
                };
                let (r0, mu0) = ray.r_mu();
                let h0 = r0 - big_r;
                let Some((t_a, t_b)) = ray.atmosphere_segment(big_r, top) else {
                    for img in [&mut reference, &mut flat, &mut looked_up] {
                        img.push([1.0; 3]);
                    }
                    continue;
                };
                let n = TRANSMITTANCE_REFERENCE_STEPS;
                let dt = (t_b - t_a) / f64::from(n);
                let mut depth = [0.0; 4];
                for s in 0..n {
                    let t = t_a + (f64::from(s) + 0.5) * dt;
                    let e = p.medium(0, altitude_along(h0, mu0, t, big_r).0).extinction;
                    for l in 0..4 {
                        depth[l] += e[l] * dt;
                    }
                }
                reference.push(rgb(depth.map(|d| (-d).exp())));
                flat.push(rgb((-slabs.optical_depth_between(0, h0, mu0, t_a, t_b))
                    .exp()
                    .0));
                let (h_a, r_a) = altitude_along(h0, mu0, t_a, big_r);
                let mu_a = ((r0 * mu0 + t_a) / r_a).clamp(-1.0, 1.0);
                looked_up.push(rgb(transmittance_between(
                    &p,
                    &table,
                    0,
                    (h_a, mu_a),
                    t_b - t_a,
                )
                .0));
            }
        }
        // Transmittance shown as it is: a linear curve with exposure 1/EXPOSURE_SCALE.
        let setup = DisplaySetup {
            exposure_ev: (1.0 / EXPOSURE_SCALE).log2(),
            tone_map: ToneMap::Linear,
            ..DisplaySetup::default()
        };
        for (model, img) in [("Flat", &flat), ("transmittance table", &looked_up)] {
            let (c, _) = compare(img, &reference, w, h, setup);
            for (table, value) in [
                ("C_FLIP_T", c.ldr_flip_mean),
                ("D_RMSE_T", mean_squared(img, &reference)),
            ] {
                cells.push(Cell {
                    table,
                    view: name.into(),
                    model: model.into(),
                    value: Some(value),
                });
            }
        }
    }
    Ok(cells)
}

fn to_csv(cells: &[Cell]) -> String {
    let quote = |s: &str| {
        if s.contains([',', '"']) {
            format!("\"{}\"", s.replace('"', "\"\""))
        } else {
            s.to_string()
        }
    };
    let mut out = String::from("table,view,model,value\n");
    for c in cells {
        if let Some(v) = c.value {
            let _ = writeln!(out, "{},{},{},{v:e}", c.table, c.view, quote(&c.model));
        }
    }
    out
}

fn format_value(v: Option<f64>) -> String {
    match v {
        Some(v) if v != 0.0 && (v.abs() < 1e-3 || v.abs() >= 1e3) => format!("{v:.2e}"),
        Some(v) => format!("{v:.4}"),
        None => "refused".into(),
    }
}

/// His tables with ours: for his models "his / ours" per cell, then ours alone.
fn to_markdown(cells: &[Cell], views: &[&LeenmanView], (w, h): (u32, u32), spp: u64) -> String {
    let mut md = String::from("# Leenman (2025), appendices A–D, replayed\n\n");
    let _ = writeln!(
        md,
        "His Earth (Hillaire's, RGB3 here), his views, exposures and scale (exposure·6·L/E); \
         images {w}×{h} (his 1920×1080), references path-traced with {spp} paths per pixel \
         and {REFERENCE_MAX_ORDER} scattering events (his 4 096 and 4, RGB; ours spectral); \
         the sun's disk left out, as he draws none. B and D: the image's mean squared \
         difference per channel, as his values read. Each cell: his published value / ours; \
         his Empty is a white image, ours the planet without air.\n"
    );
    let get = |table: &str, view: &str, model: &str| {
        cells
            .iter()
            .find(|c| c.table == table && c.view == view && c.model == model)
            .map(|c| c.value)
    };
    let mut models: Vec<String> = Vec::new();
    for c in cells {
        if !models.contains(&c.model) {
            models.push(c.model.clone());
        }
    }
    for table in leenman::TABLES {
        let rows: Vec<String> = if table.ends_with("_T") {
            TRANSMITTANCE_VIEWS
                .iter()
                .map(|v| v.0.to_string())
                .collect()
        } else {
            views.iter().map(|v| v.name.to_string()).collect()
        };
        let present: Vec<&String> = models
            .iter()
            .filter(|m| rows.iter().any(|r| get(table, r, m).is_some()))
            .collect();
        let _ = writeln!(md, "## {table}\n");
        let _ = writeln!(
            md,
            "| view | {} |",
            present
                .iter()
                .map(|m| m.as_str())
                .collect::<Vec<_>>()
                .join(" | ")
        );
        let _ = writeln!(md, "| --- |{}", " ---: |".repeat(present.len()));
        for r in &rows {
            let row: Vec<String> = present
                .iter()
                .map(|m| {
                    let ours = get(table, r, m).map_or("—".to_string(), format_value);
                    match leenman::published_value(table, r, m) {
                        Some(his) => format!("{} / {ours}", format_value(Some(his))),
                        None => ours,
                    }
                })
                .collect();
            let _ = writeln!(md, "| {r} | {} |", row.join(" | "));
        }
        md.push('\n');
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mean_squared_difference_is_per_channel() {
        assert_eq!(
            mean_squared(&[[1.0, 0.0, 0.0]], &[[0.0, 0.0, 0.0]]),
            1.0 / 3.0
        );
    }
}
