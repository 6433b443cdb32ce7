//! `atmoscope bench clear-sky`: Bruneton's (2016) evaluation of clear-sky models replayed on
//! this project's ground truth. Over the sky domes of the view suite (the camera on the
//! ground, the sun from 90° down to −12°), each real-time model against the path tracer: the
//! zenith luminance, the horizontal sky illuminance, the zenith's spectral radiance and a map
//! of the relative luminance error over the dome. Writes CSV, charts (`clear_sky_charts`) and a
//! summary that says which model is closest where.

use super::clear_sky_charts;
use crate::args::{method_id, parse_wavelengths, set_name};
use crate::cli::common::{gpu, suite_reference};
use crate::cli::sky_probe::{ProbeMethod, ProbeRequest, probe};
use atmoscope_model::camera::{Camera, Projection};
use atmoscope_model::colour::linear_srgb_to_xyz;
use atmoscope_model::constants::MAX_LUMINOUS_EFFICACY_LM_PER_W;
use atmoscope_model::geometry::direction_from_angles;
use atmoscope_model::methods::shared::{Params, viewpoint};
use atmoscope_model::methods::{self, SkyModel};
use atmoscope_model::scene::{Method, Quality, WavelengthSet};
use atmoscope_model::{Atmosphere, Scene, views};
use atmoscope_render::{Engine, View};
use clap::Args;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct ClearSkyBench {
    /// Directory of path-traced references named `<view>.exr` (default: the repository's
    /// tests/data/references, under the working directory or above the program).
    #[arg(long, value_name = "DIR")]
    pub refs: Option<PathBuf>,
    /// Where the CSV files, charts and summary go.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Sky models, comma-separated registry ids, or `all`.
    #[arg(long, value_name = "IDS", value_parser = crate::args::parse_methods, default_value = "all")]
    pub methods: crate::args::MethodList,
    /// The wavelength set the models render the domes with.
    #[arg(long, value_parser = parse_wavelengths, default_value = "spectral4")]
    pub set: WavelengthSet,
    /// Paths per wavelength of the path tracer's zenith spectrum.
    #[arg(long, default_value_t = 16_384, value_parser = clap::value_parser!(u64).range(2..))]
    pub spp: u64,
}

/// Wavelengths of the zenith spectrum, nm.
pub const SPECTRUM_NM: [f64; 21] = [
    380.0, 400.0, 420.0, 440.0, 460.0, 480.0, 500.0, 520.0, 540.0, 560.0, 580.0, 600.0, 620.0,
    640.0, 660.0, 680.0, 700.0, 720.0, 740.0, 760.0, 780.0,
];
/// Half-angle of the cap around the zenith whose mean is the zenith luminance, degrees.
pub const ZENITH_CAP_DEG: f64 = 8.0;
/// Rings (10° of zenith angle) and sectors (30° of azimuth from the sun, folded: the sky is
/// symmetric about the sun's vertical) of the coarse error maps in `error_maps.csv`.
pub const MAP_RING_DEG: f64 = 10.0;
pub const MAP_SECTOR_DEG: f64 = 30.0;

/// A dome's pixels: direction's zenith cosine, azimuth from the sun (0–180°), solid angle
/// (sr, times the share the fisheye shows) and whether the sun's disk leaves it alone.
pub struct Dome {
    pub cos_zenith: Vec<f64>,
    pub azimuth_deg: Vec<f64>,
    pub solid_angle: Vec<f64>,
    pub off_sun: Vec<bool>,
}

impl Dome {
    /// The pixels of a `w`×`h` fisheye of `scene` (camera looking up).
    pub fn new(scene: &Scene, w: u32, h: u32) -> Dome {
        let camera = Camera::new(
            &scene.camera,
            scene.atmosphere.planet_radius_km * 1000.0,
            Projection::Fisheye,
        );
        let a = scene.sun.angles();
        let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
        let off_sun = crate::cli::common::outside_sun_disk(scene, Projection::Fisheye, w, h);
        let mut d = Dome {
            cos_zenith: Vec::new(),
            azimuth_deg: Vec::new(),
            solid_angle: Vec::new(),
            off_sun,
        };
        for i in 0..w * h {
            let (x, y) = (f64::from(i % w) + 0.5, f64::from(i / w) + 0.5);
            match (camera.ray(x, y, w, h), camera.pixel_axes(x, y, w, h)) {
                (Some(ray), Some(axes)) => {
                    let up = ray.origin.normalize();
                    let mu = ray.direction.dot(up);
                    let horizontal = |v: glam::DVec3| (v - up * v.dot(up)).normalize_or_zero();
                    let cos_az = horizontal(ray.direction)
                        .dot(horizontal(sun))
                        .clamp(-1.0, 1.0);
                    d.cos_zenith.push(mu);
                    d.azimuth_deg.push(cos_az.acos().to_degrees());
                    d.solid_angle
                        .push(axes.solid_angle() * camera.pixel_coverage(i % w, i / w, w, h));
                }
                _ => {
                    d.cos_zenith.push(-1.0);
                    d.azimuth_deg.push(0.0);
                    d.solid_angle.push(0.0);
                }
            }
        }
        d
    }

    /// Whether pixel `i` is sky that the metrics count: above the horizon, off the sun.
    fn counts(&self, i: usize) -> bool {
        self.cos_zenith[i] > 0.0 && self.solid_angle[i] > 0.0 && self.off_sun[i]
    }
}

/// Luminance of a linear sRGB radiance (W·m⁻²·sr⁻¹ with Y = ∫ȳL dλ), cd/m².
pub fn luminance(rgb: [f64; 3]) -> f64 {
    linear_srgb_to_xyz(rgb).y * MAX_LUMINOUS_EFFICACY_LM_PER_W
}

/// What one image of a dome says: zenith luminance (cd/m²), horizontal sky illuminance (lx).
pub fn dome_figures(dome: &Dome, image: &[[f64; 3]]) -> (f64, f64) {
    let cap = ZENITH_CAP_DEG.to_radians().cos();
    let (mut zenith, mut zenith_w, mut illuminance) = (0.0, 0.0, 0.0);
    for (i, rgb) in image.iter().enumerate() {
        if !dome.counts(i) {
            continue;
        }
        let (y, w) = (luminance(*rgb), dome.solid_angle[i]);
        illuminance += y * dome.cos_zenith[i] * w;
        if dome.cos_zenith[i] >= cap {
            zenith += y * w;
            zenith_w += w;
        }
    }
    (zenith / zenith_w.max(f64::MIN_POSITIVE), illuminance)
}

/// Each pixel's relative luminance error of `image` against `reference` (NaN where the pixel
/// does not count or the reference is black).
pub fn relative_errors(dome: &Dome, image: &[[f64; 3]], reference: &[[f64; 3]]) -> Vec<f64> {
    (0..image.len())
        .map(|i| {
            let r = luminance(reference[i]);
            if dome.counts(i) && r > 0.0 {
                luminance(image[i]) / r - 1.0
            } else {
                f64::NAN
            }
        })
        .collect()
}

/// Solid-angle-weighted mean |e| and root mean square of the finite errors `e`.
pub fn error_summary(dome: &Dome, e: &[f64]) -> (f64, f64) {
    let (mut abs, mut sq, mut w) = (0.0, 0.0, 0.0);
    for (i, &v) in e.iter().enumerate() {
        if v.is_finite() {
            abs += v.abs() * dome.solid_angle[i];
            sq += v * v * dome.solid_angle[i];
            w += dome.solid_angle[i];
        }
    }
    if w > 0.0 {
        (abs / w, (sq / w).sqrt())
    } else {
        (f64::NAN, f64::NAN)
    }
}

/// One model (or the path tracer) at one sun elevation.
#[derive(Debug, Clone)]
pub struct Row {
    pub model: String,
    pub sun_elevation_deg: f64,
    /// None where the model refuses the view.
    pub figures: Option<Figures>,
}

#[derive(Debug, Clone)]
pub struct Figures {
    pub zenith_luminance_cd_m2: f64,
    pub illuminance_lx: f64,
    pub dome_mean_abs_error: f64,
    pub dome_rms_error: f64,
    /// Zenith spectral radiance at [`SPECTRUM_NM`], W·m⁻²·sr⁻¹·nm⁻¹.
    pub zenith_spectrum: Vec<f64>,
    /// Per-pixel relative luminance error against the path tracer.
    pub errors: Vec<f64>,
}

/// A model's CPU twin at the spectrum's wavelengths, moved from sun to sun where it can be.
struct Twin {
    method: Method,
    model: Option<Box<dyn SkyModel>>,
}

impl Twin {
    /// The zenith spectral radiance of the twin over `scene` (disk not included).
    fn zenith(&mut self, scene: &Scene) -> Vec<f64> {
        let atm = Atmosphere::for_scene(scene);
        let camera = Camera::new(&scene.camera, atm.bottom_radius_m, Projection::Perspective);
        let vp = viewpoint(scene, &camera);
        let info = methods::info(self.method);
        let moved = match self.model.as_mut() {
            Some(m) => !info.reads_viewpoint() || m.move_to(vp),
            None => false,
        };
        if !moved {
            let p = Params::at_wavelengths(&atm, &SPECTRUM_NM, scene.render.quality)
                .with_render(&scene.render);
            self.model = info.build.map(|build| build(&p, vp));
        }
        let Some(model) = self.model.as_ref() else {
            return vec![f64::NAN; SPECTRUM_NM.len()];
        };
        let a = scene.sun.angles();
        let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
        let up = camera.position.normalize();
        let at = (camera.position, scene.camera.altitude_m);
        (0..model.params().batches.len())
            .flat_map(|layer| model.radiance(layer, at, up, sun).0)
            .take(SPECTRUM_NM.len())
            .collect()
    }
}

pub fn run(args: &ClearSkyBench) -> anyhow::Result<ExitCode> {
    let started = std::time::Instant::now();
    let refs = crate::shipped::references(args.refs.as_deref())?;
    let context = gpu()?;
    let adapter = context.describe();
    let mut domes: Vec<&views::View> = views::suite()
        .iter()
        .filter(|v| v.projection == Projection::Fisheye && v.camera.altitude_m < 10.0)
        .collect();
    domes.sort_by(|a, b| {
        b.sun
            .angles()
            .elevation_deg
            .total_cmp(&a.sun.angles().elevation_deg)
    });
    let models = &args.methods.0;
    if let Some(m) = models.iter().find(|m| !methods::info(**m).is_realtime()) {
        anyhow::bail!(
            "--methods: {} is not a real-time model; the path tracer is the reference here ({})",
            method_id(*m),
            methods::realtime_ids()
        );
    }
    let mut engines: Vec<Engine> = models
        .iter()
        .map(|_| Engine::new(&context.device, &context.queue))
        .collect();
    let mut twins: Vec<Twin> = models
        .iter()
        .map(|&method| Twin {
            method,
            model: None,
        })
        .collect();
    let mut rows = Vec::new();
    let mut size: Option<(u32, u32)> = None;
    for v in &domes {
        let Some((reference, w, h)) = suite_reference(&refs, &v.name, false)? else {
            eprintln!("{}: no reference in {}, left out", v.name, refs.display());
            continue;
        };
        // The maps and the mosaic lay every dome on one grid.
        match size {
            None => size = Some((w, h)),
            Some(s) if s != (w, h) => anyhow::bail!(
                "{}: the reference is {w}×{h}, the others {}×{}: render every dome at one size",
                v.name,
                s.0,
                s.1
            ),
            Some(_) => {}
        }
        let scene: Scene = v.apply(&Scene::default());
        let elevation = scene.sun.angles().elevation_deg;
        let dome = Dome::new(&scene, w, h);
        let (pt_zenith, pt_illuminance) = dome_figures(&dome, &reference);
        let spectrum = probe(
            &scene,
            &ProbeRequest {
                view_zenith_deg: vec![0.0],
                view_azimuth_deg: vec![0.0],
                wavelengths_nm: SPECTRUM_NM.to_vec(),
                method: ProbeMethod::PathTracer,
                max_order: None,
                spp: args.spp,
                seed: 1,
                stokes: false,
            },
        );
        rows.push(Row {
            model: "path-tracer".into(),
            sun_elevation_deg: elevation,
            figures: Some(Figures {
                zenith_luminance_cd_m2: pt_zenith,
                illuminance_lx: pt_illuminance,
                dome_mean_abs_error: 0.0,
                dome_rms_error: 0.0,
                zenith_spectrum: spectrum.samples.iter().map(|s| s.radiance).collect(),
                errors: vec![0.0; reference.len()],
            }),
        });
        for ((&method, engine), twin) in models.iter().zip(engines.iter_mut()).zip(&mut twins) {
            let mut s = scene.clone();
            s.render.method = method;
            s.render.wavelengths = args.set;
            s.render.quality = Quality::Medium;
            let figures = if methods::info(method).cannot_draw(&s).is_some() {
                None
            } else {
                engine.try_render(&s, &View::new(Projection::Fisheye, w, h))?;
                let image: Vec<[f64; 3]> = engine
                    .read_radiance()?
                    .iter()
                    .map(|p| [p[0], p[1], p[2]].map(f64::from))
                    .collect();
                let (zenith, illuminance) = dome_figures(&dome, &image);
                let errors = relative_errors(&dome, &image, &reference);
                let (mean, rms) = error_summary(&dome, &errors);
                Some(Figures {
                    zenith_luminance_cd_m2: zenith,
                    illuminance_lx: illuminance,
                    dome_mean_abs_error: mean,
                    dome_rms_error: rms,
                    zenith_spectrum: twin.zenith(&s),
                    errors,
                })
            };
            rows.push(Row {
                model: method_id(method).into(),
                sun_elevation_deg: elevation,
                figures,
            });
        }
        eprintln!(
            "sun {elevation}° done ({:.0} s)",
            started.elapsed().as_secs_f64()
        );
    }
    if rows.is_empty() {
        anyhow::bail!("no sky-dome references found in {}", refs.display());
    }
    let (w, h) = size.unwrap_or((0, 0));
    std::fs::create_dir_all(&args.out)?;
    write_csv(&args.out, &rows, &domes, w, h)?;
    clear_sky_charts::write(&args.out, &rows, w, h)?;
    let header = format!(
        "Adapter: {adapter}. Domes of the view suite ({w}×{h} fisheyes from the ground, default scene) against the path-traced references in `{}`; the models at {} (medium quality); the zenith spectrum from each model's f64 twin and from the path tracer at {} paths per wavelength. Measured in {:.0} s.",
        refs.display(),
        set_name(args.set),
        args.spp,
        started.elapsed().as_secs_f64()
    );
    let summary = summary_markdown(&rows, &header);
    crate::files::write_atomic(&args.out.join("summary.md"), summary.as_bytes())?;
    println!("{summary}");
    Ok(ExitCode::SUCCESS)
}

/// `clear_sky.csv`, `zenith_spectra.csv` and `error_maps.csv`.
fn write_csv(
    out: &Path,
    rows: &[Row],
    domes: &[&views::View],
    w: u32,
    h: u32,
) -> anyhow::Result<()> {
    let mut figures = String::from(
        "model,sun_elevation_deg,zenith_luminance_cd_m2,horizontal_illuminance_lx,zenith_luminance_rel_error,illuminance_rel_error,dome_mean_abs_rel_error,dome_rms_rel_error\n",
    );
    let mut spectra = String::from("model,sun_elevation_deg,wavelength_nm,radiance_w_m2_sr_nm\n");
    let mut maps = String::from(
        "model,sun_elevation_deg,zenith_from_deg,zenith_to_deg,azimuth_from_sun_from_deg,azimuth_from_sun_to_deg,mean_rel_error\n",
    );
    for r in rows {
        let Some(f) = &r.figures else {
            writeln!(figures, "{},{},,,,,,", r.model, r.sun_elevation_deg)?;
            continue;
        };
        let truth = truth_of(rows, r.sun_elevation_deg);
        writeln!(
            figures,
            "{},{},{:.6e},{:.6e},{:.5},{:.5},{:.5},{:.5}",
            r.model,
            r.sun_elevation_deg,
            f.zenith_luminance_cd_m2,
            f.illuminance_lx,
            f.zenith_luminance_cd_m2 / truth.zenith_luminance_cd_m2 - 1.0,
            f.illuminance_lx / truth.illuminance_lx - 1.0,
            f.dome_mean_abs_error,
            f.dome_rms_error
        )?;
        for (l, v) in SPECTRUM_NM.iter().zip(&f.zenith_spectrum) {
            writeln!(spectra, "{},{},{l},{v:.6e}", r.model, r.sun_elevation_deg)?;
        }
        let view = domes
            .iter()
            .find(|v| v.sun.angles().elevation_deg == r.sun_elevation_deg);
        if let Some(view) = view {
            let dome = Dome::new(&view.apply(&Scene::default()), w, h);
            for (ring, sector, mean) in coarse_map(&dome, &f.errors) {
                writeln!(
                    maps,
                    "{},{},{},{},{},{},{mean:.5}",
                    r.model,
                    r.sun_elevation_deg,
                    ring * MAP_RING_DEG,
                    (ring + 1.0) * MAP_RING_DEG,
                    sector * MAP_SECTOR_DEG,
                    (sector + 1.0) * MAP_SECTOR_DEG
                )?;
            }
        }
    }
    crate::files::write_atomic(&out.join("clear_sky.csv"), figures.as_bytes())?;
    crate::files::write_atomic(&out.join("zenith_spectra.csv"), spectra.as_bytes())?;
    crate::files::write_atomic(&out.join("error_maps.csv"), maps.as_bytes())
}

/// The path tracer's figures at `elevation`.
pub fn truth_of(rows: &[Row], elevation: f64) -> &Figures {
    rows.iter()
        .find(|r| r.model == "path-tracer" && r.sun_elevation_deg == elevation)
        .and_then(|r| r.figures.as_ref())
        .expect("the path tracer's row comes first at each elevation")
}

/// The per-pixel errors averaged (by solid angle) over rings of zenith angle and sectors of
/// azimuth from the sun: (ring, sector, mean) for the cells with counted pixels.
pub fn coarse_map(dome: &Dome, errors: &[f64]) -> Vec<(f64, f64, f64)> {
    let rings = (90.0 / MAP_RING_DEG) as usize;
    let sectors = (180.0 / MAP_SECTOR_DEG) as usize;
    let mut sum = vec![(0.0, 0.0); rings * sectors];
    for (i, &e) in errors.iter().enumerate() {
        if !e.is_finite() {
            continue;
        }
        let z = dome.cos_zenith[i].clamp(-1.0, 1.0).acos().to_degrees();
        let ring = ((z / MAP_RING_DEG) as usize).min(rings - 1);
        let sector = ((dome.azimuth_deg[i] / MAP_SECTOR_DEG) as usize).min(sectors - 1);
        let cell = &mut sum[ring * sectors + sector];
        cell.0 += e * dome.solid_angle[i];
        cell.1 += dome.solid_angle[i];
    }
    sum.iter()
        .enumerate()
        .filter(|(_, c)| c.1 > 0.0)
        .map(|(k, c)| ((k / sectors) as f64, (k % sectors) as f64, c.0 / c.1))
        .collect()
}

/// Where the sun stands, in words, for the summary's groups.
fn period(elevation: f64) -> &'static str {
    if elevation >= 10.0 {
        "daylight (sun ≥ 10°)"
    } else if elevation >= 0.0 {
        "low sun (0–10°)"
    } else {
        "twilight (sun < 0°)"
    }
}

pub const PERIODS: [&str; 3] = [
    "daylight (sun ≥ 10°)",
    "low sun (0–10°)",
    "twilight (sun < 0°)",
];

/// The summary: per model and period the mean |relative error| of the zenith luminance, the
/// illuminance and over the dome; the closest model at each sun; what to use where.
pub fn summary_markdown(rows: &[Row], header: &str) -> String {
    let mut s = String::from("# Clear-sky models against the path tracer\n\n");
    let _ = writeln!(s, "{header}\n");
    s.push_str(
        "Mean |relative error| of the zenith luminance / the horizontal sky illuminance / the luminance over the dome (solid-angle weighted), per period of the day; `refused` where the model draws none of its views.\n\n",
    );
    s.push_str("| model |");
    for p in PERIODS {
        let _ = write!(s, " {p} |");
    }
    s.push_str("\n| --- |");
    for _ in PERIODS {
        s.push_str(" --- |");
    }
    s.push('\n');
    let names: Vec<&str> = {
        let mut n: Vec<&str> = Vec::new();
        for r in rows.iter().filter(|r| r.model != "path-tracer") {
            if !n.contains(&r.model.as_str()) {
                n.push(&r.model);
            }
        }
        n
    };
    let mut best: Vec<(&str, &str, f64)> = Vec::new();
    for name in &names {
        let _ = write!(s, "| {name} |");
        for p in PERIODS {
            let drawn: Vec<(&Figures, &Figures)> = rows
                .iter()
                .filter(|r| r.model == *name && period(r.sun_elevation_deg) == p)
                .filter_map(|r| {
                    r.figures
                        .as_ref()
                        .map(|f| (f, truth_of(rows, r.sun_elevation_deg)))
                })
                .collect();
            if drawn.is_empty() {
                s.push_str(" refused |");
                continue;
            }
            let n = drawn.len() as f64;
            let mean = |f: &dyn Fn(&Figures, &Figures) -> f64| {
                drawn.iter().map(|(m, t)| f(m, t)).sum::<f64>() / n
            };
            let zenith =
                mean(&|m, t| (m.zenith_luminance_cd_m2 / t.zenith_luminance_cd_m2 - 1.0).abs());
            let illuminance = mean(&|m, t| (m.illuminance_lx / t.illuminance_lx - 1.0).abs());
            let dome = mean(&|m, _| m.dome_mean_abs_error);
            let _ = write!(
                s,
                " {:.0} % / {:.0} % / {:.0} %{} |",
                100.0 * zenith,
                100.0 * illuminance,
                100.0 * dome,
                if drawn.len() < periods_count(rows, p) {
                    " (part)"
                } else {
                    ""
                }
            );
            if drawn.len() == periods_count(rows, p) {
                best.push((p, name, dome));
            }
        }
        s.push('\n');
    }
    s.push_str("\n## Closest to the path tracer\n\n| sun | closest over the dome | its mean \\|error\\| | closest zenith luminance | closest illuminance |\n| --- | --- | --- | --- | --- |\n");
    let mut elevations: Vec<f64> = rows.iter().map(|r| r.sun_elevation_deg).collect();
    elevations.dedup();
    for e in &elevations {
        let truth = truth_of(rows, *e);
        let at: Vec<(&str, &Figures)> = rows
            .iter()
            .filter(|r| r.model != "path-tracer" && r.sun_elevation_deg == *e)
            .filter_map(|r| r.figures.as_ref().map(|f| (r.model.as_str(), f)))
            .collect();
        let pick = |f: &dyn Fn(&Figures) -> f64| {
            at.iter()
                .min_by(|a, b| f(a.1).total_cmp(&f(b.1)))
                .map_or(("—", f64::NAN), |(n, fig)| (*n, f(fig)))
        };
        let (dome_name, dome_err) = pick(&|f| f.dome_mean_abs_error);
        let (z_name, _) =
            pick(&|f| (f.zenith_luminance_cd_m2 / truth.zenith_luminance_cd_m2 - 1.0).abs());
        let (i_name, _) = pick(&|f| (f.illuminance_lx / truth.illuminance_lx - 1.0).abs());
        let _ = writeln!(
            s,
            "| {e}° | {dome_name} | {:.1} % | {z_name} | {i_name} |",
            100.0 * dome_err
        );
    }
    s.push_str("\n## What to use where\n\n");
    for p in PERIODS {
        let mut ranked: Vec<&(&str, &str, f64)> = best.iter().filter(|b| b.0 == p).collect();
        ranked.sort_by(|a, b| a.2.total_cmp(&b.2));
        let top: Vec<String> = ranked
            .iter()
            .take(3)
            .map(|b| format!("{} ({:.0} %)", b.1, 100.0 * b.2))
            .collect();
        if !top.is_empty() {
            let _ = writeln!(
                s,
                "- {p}: closest over the dome (mean |relative error| of luminance): {}.",
                top.join(", ")
            );
        }
    }
    s.push_str("\nCharts: `zenith_luminance.svg`, `illuminance.svg`, `zenith_spectra.svg` (and PNG), `error_maps.png`; numbers: `clear_sky.csv`, `zenith_spectra.csv`, `error_maps.csv`.\n");
    s
}

/// Suns of period `p` the path tracer was measured at.
fn periods_count(rows: &[Row], p: &str) -> usize {
    rows.iter()
        .filter(|r| r.model == "path-tracer" && period(r.sun_elevation_deg) == p)
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A uniform sky of luminance L over the dome: the zenith's luminance is L and the
    /// horizontal illuminance πL (the fisheye's pixels' solid angles sum to the hemisphere's
    /// 2π, their cosines to π), within the 48 × 48 dome's rim; its errors against itself are 0.
    #[test]
    fn a_uniform_dome_gives_its_luminance_and_pi_times_it() {
        let view = views::find("fisheye-sun30").expect("a suite view");
        let mut scene = view.apply(&Scene::default());
        // The sun's disk lies outside what the metrics count; move it below the horizon so
        // every sky pixel counts.
        scene.sun = atmoscope_model::scene::SunSettings::Angles {
            elevation_deg: -30.0,
            azimuth_deg: 0.0,
        };
        let dome = Dome::new(&scene, 48, 48);
        let white = [1.0, 1.0, 1.0];
        let l = luminance(white);
        let image = vec![white; 48 * 48];
        let (zenith, illuminance) = dome_figures(&dome, &image);
        assert!((zenith / l - 1.0).abs() < 1e-9, "{zenith} vs {l}");
        let pi_l = std::f64::consts::PI * l;
        assert!(
            (illuminance / pi_l - 1.0).abs() < 0.02,
            "{illuminance} vs {pi_l}"
        );
        let sky: f64 = (0..image.len())
            .filter(|&i| dome.counts(i))
            .map(|i| dome.solid_angle[i])
            .sum();
        assert!(
            (sky / (2.0 * std::f64::consts::PI) - 1.0).abs() < 0.03,
            "{sky}"
        );
        let e = relative_errors(&dome, &image, &image);
        assert_eq!(error_summary(&dome, &e), (0.0, 0.0));
        let doubled: Vec<[f64; 3]> = image.iter().map(|p| p.map(|c| 2.0 * c)).collect();
        let e = relative_errors(&dome, &doubled, &image);
        let (mean, rms) = error_summary(&dome, &e);
        assert!((mean - 1.0).abs() < 1e-12 && (rms - 1.0).abs() < 1e-12);
        // Every coarse cell of a dome twice too bright is +100 %, and they cover the sky.
        let cells = coarse_map(&dome, &e);
        assert!(cells.len() >= 50, "{}", cells.len());
        assert!(cells.iter().all(|c| (c.2 - 1.0).abs() < 1e-12));
    }
}
