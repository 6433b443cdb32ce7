//! The Measured tab: a real sky beside the model's. Pick a day and a scan of measured sky
//! radiance (Kider et al. 2014 ships; any folder in its format opens); the tab builds the
//! scan's scene (its time, place and aerosol, `atmoscope_eval::measured`) and draws, on the
//! same dome and exposure, the measured sky interpolated between its directions and the
//! model's sky with every measured direction coloured by the model's luminance error. Click a
//! direction for its measured spectrum against the model's and the path tracer's. "Use this
//! scan's scene" hands the scene to the other tabs.
//!
//! The model is the scene's (Scene panel → Rendering); its CPU twin and the path tracer run in
//! the background, as `atmoscope bench measured` runs them.

use super::jobs::Job;
use super::state::Command;
use atmoscope_eval::measured::files::{self, Day};
use atmoscope_eval::measured::run::{self, ScanResult, Settings};
use atmoscope_eval::measured::score;
use atmoscope_eval::measured::sky::{self, Site, Source, View};
use atmoscope_model::Scene;
use atmoscope_model::colour::{srgb_encode, xyz_to_linear_srgb};
use atmoscope_model::methods;
use atmoscope_model::scene::Method;
use eframe::egui;
use egui_plot::{Legend, Line, Plot, PlotPoints};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The shipped day's folder, relative to the repository.
pub const SHIPPED: &str = "eval/data/kider_2014";
/// Directions across the dome's diameter in the drawn skies.
pub const DOME_CELLS: u32 = 48;
/// Paths per direction and batch of four wavelengths of the tab's path tracer.
pub const TAB_SPP: u64 = 128;

/// What the tab computed for one (scan, model).
pub struct Evaluation {
    pub day: usize,
    pub scan: usize,
    pub method: Method,
    pub result: ScanResult,
    /// The model's sky over the dome's cells (linear sRGB, W·m⁻²·sr⁻¹), row-major, None
    /// outside the dome.
    pub model_dome: Vec<Option<[f64; 3]>>,
    /// The measured sky interpolated over the same cells.
    pub measured_dome: Vec<Option<[f64; 3]>>,
    /// The luminance of each measured direction, cd/m².
    pub measured_luminance: Vec<f64>,
}

pub struct MeasuredTab {
    pub folder: PathBuf,
    days: Option<Result<Arc<Vec<Day>>, String>>,
    pub day: usize,
    pub scan: usize,
    job: Option<Job<Result<Evaluation, String>>>,
    pub evaluation: Option<Evaluation>,
    error: Option<String>,
    /// Index into the evaluation's scored directions.
    pub selected: Option<usize>,
    /// Where the model's dome was last drawn (clicks land on it).
    pub model_dome_rect: Option<egui::Rect>,
}

impl MeasuredTab {
    /// The tab over the shipped day (found under the working directory or beside the
    /// program, else where this crate was built).
    pub fn new() -> MeasuredTab {
        let folder = crate::shipped::near_program(Path::new(SHIPPED))
            .filter(|p| p.is_dir())
            .unwrap_or_else(atmoscope_eval::measured::shipped_folder);
        MeasuredTab::with_folder(folder)
    }

    pub fn with_folder(folder: PathBuf) -> MeasuredTab {
        MeasuredTab {
            folder,
            days: None,
            day: 0,
            scan: 0,
            job: None,
            evaluation: None,
            error: None,
            selected: None,
            model_dome_rect: None,
        }
    }

    /// Whether background work is under way.
    pub fn busy(&self) -> bool {
        self.job.as_ref().is_some_and(Job::is_running)
    }

    fn days(&mut self) -> Result<Arc<Vec<Day>>, String> {
        let folder = self.folder.clone();
        self.days
            .get_or_insert_with(|| {
                files::read_folder(&folder)
                    .map(Arc::new)
                    .map_err(|e| e.to_string())
            })
            .clone()
    }

    /// Opens another folder of measured days; what was shown stays if it does not read.
    pub fn open(&mut self, folder: PathBuf) {
        match files::read_folder(&folder) {
            Ok(days) => {
                self.folder = folder;
                self.days = Some(Ok(Arc::new(days)));
                (self.day, self.scan) = (0, 0);
                self.forget();
            }
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    fn forget(&mut self) {
        self.evaluation = None;
        self.job = None;
        self.selected = None;
    }

    /// The scene of the chosen scan for the other tabs: its sun, air, ozone, ground and
    /// aerosol; the model, wavelengths and display stay the user's.
    pub fn scan_scene(&mut self, current: &Scene) -> Option<Scene> {
        let (d, s) = (self.day, self.scan);
        let days = self.days().ok()?;
        let day = days.get(d)?;
        let scan = day.scans.get(s)?;
        let source = run::default_source(day);
        let aerosol = match source {
            atmoscope_eval::measured::retrieve::AerosolSource::Aeronet => {
                atmoscope_eval::measured::retrieve::from_aeronet(day, scan).ok()
            }
            _ => atmoscope_eval::measured::retrieve::from_pyranometer(day, s, &Site::CORNELL).ok(),
        }
        .map(|r| r.aerosol)
        .unwrap_or_default();
        let mut scene = sky::scene(day, scan, &Site::CORNELL, &aerosol);
        scene.render = current.render.clone();
        scene.display = current.display.clone();
        scene.camera.fov_deg = current.camera.fov_deg;
        Some(scene)
    }

    pub fn show(&mut self, ui: &mut egui::Ui, scene: &Scene) -> Vec<Command> {
        let mut commands = Vec::new();
        let days = match self.days() {
            Ok(d) => d,
            Err(e) => {
                ui.label(format!("No measured skies: {e}"));
                self.open_button(ui);
                return commands;
            }
        };
        ui.horizontal_wrapped(|ui| {
            let mut changed = false;
            egui::ComboBox::from_label("Day")
                .selected_text(days.get(self.day).map_or("–".into(), |d| d.date.clone()))
                .show_ui(ui, |ui| {
                    for (i, d) in days.iter().enumerate() {
                        changed |= ui.selectable_value(&mut self.day, i, &d.date).changed();
                    }
                });
            let scans = days.get(self.day).map_or(&[][..], |d| &d.scans[..]);
            egui::ComboBox::from_label("Scan")
                .selected_text(
                    scans
                        .get(self.scan)
                        .map_or("–".into(), |s| s.time_local.to_string()),
                )
                .show_ui(ui, |ui| {
                    for (i, s) in scans.iter().enumerate() {
                        changed |= ui
                            .selectable_value(&mut self.scan, i, s.time_local.to_string())
                            .changed();
                    }
                });
            if changed {
                self.scan = self.scan.min(scans.len().saturating_sub(1));
                self.forget();
            }
            self.open_button(ui);
            if ui
                .button("Use this scan's scene")
                .on_hover_text(
                    "Sets the scene to the scan's date, time, place and aerosol, for every tab",
                )
                .clicked()
                && let Some(s) = self.scan_scene(scene)
            {
                commands.push(Command::SetScene(Box::new(s)));
            }
        });
        if let Some(e) = &self.error {
            ui.colored_label(ui.visuals().error_fg_color, e);
        }
        let method = scene.render.method;
        self.poll();
        let stale = self
            .evaluation
            .as_ref()
            .is_none_or(|e| (e.day, e.scan, e.method) != (self.day, self.scan, method));
        if stale && self.job.is_none() {
            self.start(ui.ctx(), &days, method);
        }
        if let Some(job) = &self.job {
            ui.label(format!("{} …", job.label));
            if job.show(ui) {
                job.cancel();
            }
        }
        if let Some(e) = &self.evaluation {
            self.draw(ui, &days[e.day], method);
        }
        commands
    }

    fn open_button(&mut self, ui: &mut egui::Ui) {
        #[cfg(not(target_arch = "wasm32"))]
        if ui
            .button("Open folder…")
            .on_hover_text("A folder of measured days in the Kider et al. (2014) format")
            .clicked()
            && let Some(folder) = rfd::FileDialog::new().pick_folder()
        {
            self.open(folder);
        }
        #[cfg(target_arch = "wasm32")]
        let _ = ui;
    }

    fn poll(&mut self) {
        let Some(job) = &mut self.job else { return };
        match job.take() {
            None => {}
            Some(Ok(Ok(e))) => {
                self.evaluation = Some(e);
                self.error = None;
                self.job = None;
            }
            Some(Ok(Err(e)) | Err(e)) => {
                self.error = Some(e);
                self.job = None;
            }
        }
    }

    fn start(&mut self, ctx: &egui::Context, days: &[Day], method: Method) {
        let (d, s) = (self.day, self.scan);
        let Some(day) = days.get(d).cloned() else {
            return;
        };
        if s >= day.scans.len() {
            return;
        }
        self.selected = None;
        let label = format!(
            "{} {} with {}",
            day.date,
            day.scans[s].time_local,
            methods::info(method).label
        );
        self.job = Some(Job::spawn(label, ctx, move |_| {
            evaluate(&day, d, s, method)
        }));
    }

    fn draw(&mut self, ui: &mut egui::Ui, day: &Day, method: Method) {
        let Some(e) = &self.evaluation else { return };
        let r = &e.result;
        let scan = &day.scans[r.scan];
        let id = methods::info(method).id;
        let of = |id: &str| r.sources.iter().find(|s| s.id == id);
        let median = |id: &str| of(id).map(|s| score::quantile(&s.errors.radiance, 0.5));
        let a = &r.retrieved.aerosol;
        ui.label(format!(
            "Sun {:.1}° from the zenith, azimuth {:.1}° from the sky's symmetry ({:.1}° by the clock). Aerosol: AOD {:.3} at 550 nm, Ångström {:.2} ({}).",
            r.sun_zenith_deg, r.sun_azimuth_deg, r.sun_azimuth_theory_deg, a.aod550, a.angstrom, r.retrieved.note
        ));
        match of(id).and_then(|s| s.refused.clone()) {
            Some(why) => {
                ui.label(why);
            }
            None => {
                ui.label(format!(
                    "Median |error| of spectral radiance, 360–720 nm, {} directions: {} {:.1} %, path tracer {:.1} %.",
                    r.scored.len(),
                    methods::info(method).label,
                    100.0 * median(id).unwrap_or(f64::NAN),
                    100.0 * median("path-tracer").unwrap_or(f64::NAN),
                ));
            }
        }
        let lum = &e.measured_luminance;
        let exposure = exposure(lum);
        let errors: Vec<Option<f64>> = match of(id) {
            Some(s) if s.refused.is_none() => s
                .radiance
                .iter()
                .zip(&r.scored)
                .map(|(l, &i)| {
                    score::xyz(&run::default_model_nm(), l)
                        .map(|c| score::luminance(c) / lum[i] - 1.0)
                })
                .collect(),
            _ => vec![None; r.scored.len()],
        };
        let size = (ui.available_width() / 2.0 - 12.0).clamp(120.0, 420.0);
        let mut clicked = None;
        let mut dome_rect = None;
        ui.horizontal(|ui| {
            ui.vertical(|ui| {
                ui.label("Measured, interpolated between its directions");
                let (rect, _) =
                    ui.allocate_exact_size(egui::vec2(size, size), egui::Sense::hover());
                paint_dome(ui.painter(), rect, &e.measured_dome, exposure);
            });
            ui.vertical(|ui| {
                ui.label(format!(
                    "{}, and its luminance error at each measured direction",
                    methods::info(method).label
                ));
                let (rect, response) =
                    ui.allocate_exact_size(egui::vec2(size, size), egui::Sense::click());
                dome_rect = Some(rect);
                paint_dome(ui.painter(), rect, &e.model_dome, exposure);
                for (k, &i) in r.scored.iter().enumerate() {
                    let d = &scan.directions[i];
                    let p = dome_point(rect, d.azimuth_deg, d.elevation_deg);
                    let fill = errors[k].map_or(egui::Color32::GRAY, error_colour);
                    ui.painter().circle(
                        p,
                        5.0,
                        fill,
                        egui::Stroke::new(1.0, egui::Color32::DARK_GRAY),
                    );
                    if self.selected == Some(k) {
                        ui.painter().circle_stroke(
                            p,
                            8.0,
                            egui::Stroke::new(2.0, egui::Color32::YELLOW),
                        );
                    }
                }
                let sun = dome_point(rect, r.sun_azimuth_deg, 90.0 - r.sun_zenith_deg);
                ui.painter()
                    .circle_filled(sun, 6.0, egui::Color32::from_rgb(250, 210, 0));
                if response.clicked()
                    && let Some(pos) = response.interact_pointer_pos()
                {
                    clicked = r
                        .scored
                        .iter()
                        .enumerate()
                        .map(|(k, &i)| {
                            let d = &scan.directions[i];
                            (
                                k,
                                dome_point(rect, d.azimuth_deg, d.elevation_deg).distance(pos),
                            )
                        })
                        .filter(|(_, dist)| *dist < 14.0)
                        .min_by(|a, b| a.1.total_cmp(&b.1))
                        .map(|(k, _)| k);
                }
            });
        });
        ui.label("Blue: the model is too dark there; red: too bright (±50 % at full colour). Click a direction for its spectra.");
        self.model_dome_rect = dome_rect;
        if clicked.is_some() {
            self.selected = clicked;
        }
        if let Some(k) = self.selected {
            let d = &scan.directions[r.scored[k]];
            ui.label(format!(
                "Sample {}: azimuth {:.1}°, elevation {:.1}°",
                d.sample, d.azimuth_deg, d.elevation_deg
            ));
            let model_nm = run::default_model_nm();
            let line = |nm: &[f64], l: &[f64], name: &str| {
                Line::new(
                    name.to_owned(),
                    PlotPoints::from_iter(
                        nm.iter()
                            .zip(l)
                            .filter(|(w, _)| **w >= 360.0)
                            .map(|(w, l)| [*w, *l]),
                    ),
                )
            };
            Plot::new("measured_spectra")
                .legend(Legend::default())
                .height(220.0)
                .x_axis_label("wavelength, nm")
                .y_axis_label("W/(m² sr nm)")
                .show(ui, |plot| {
                    plot.line(line(&day.wavelengths_nm, &d.radiance, "measured"));
                    for s in r.sources.iter().filter(|s| s.refused.is_none()) {
                        plot.line(line(&model_nm, &s.radiance[k], s.id));
                    }
                });
        }
    }
}

impl Default for MeasuredTab {
    fn default() -> Self {
        MeasuredTab::new()
    }
}

/// The scan held against `method` and the path tracer, and the model's dome.
fn evaluate(day: &Day, d: usize, s: usize, method: Method) -> Result<Evaluation, String> {
    let mut sources = vec![Source::PathTracer {
        spp: TAB_SPP,
        seed: 1,
    }];
    if methods::info(method).is_realtime() {
        sources.insert(0, Source::Model(method));
    }
    let settings = Settings {
        site: Site::CORNELL,
        aerosol: None,
        sources: sources.clone(),
        model_nm: run::default_model_nm(),
        fit_spp: 64,
        irradiance_strata: 6,
    };
    let result = run::evaluate(day, s, &settings).map_err(|e| e.to_string())?;
    let scene = sky::scene(
        day,
        &day.scans[s],
        &settings.site,
        &result.retrieved.aerosol,
    );
    let (views, cells) = dome_views(result.sun_azimuth_deg);
    let sky = sky::Sky::new(&scene, sources[0], &settings.model_nm).map_err(|e| e.to_string())?;
    let radiance = sky.radiance(&views);
    let mut model_dome = vec![None; (DOME_CELLS * DOME_CELLS) as usize];
    for (cell, l) in cells.into_iter().zip(radiance) {
        model_dome[cell] = score::xyz(&settings.model_nm, &l).map(xyz_to_linear_srgb);
    }
    let scan = &day.scans[s];
    let colours: Vec<[f64; 3]> = scan
        .directions
        .iter()
        .map(|d| score::xyz(&day.wavelengths_nm, &d.radiance).map_or([0.0; 3], xyz_to_linear_srgb))
        .collect();
    Ok(Evaluation {
        day: d,
        scan: s,
        method,
        result,
        model_dome,
        measured_dome: interpolated_dome(scan, &colours),
        measured_luminance: run::measured_luminance(day, scan),
    })
}

/// The view through the centre of each cell of the dome inside its circle (north up, east
/// right), with the cell's index.
fn dome_views(sun_azimuth_deg: f64) -> (Vec<View>, Vec<usize>) {
    let n = DOME_CELLS;
    let mut views = Vec::new();
    let mut cells = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let x = (f64::from(i) + 0.5) / f64::from(n) * 2.0 - 1.0;
            let y = 1.0 - (f64::from(j) + 0.5) / f64::from(n) * 2.0;
            let r = (x * x + y * y).sqrt();
            if r > 1.0 {
                continue;
            }
            let azimuth = x.atan2(y).to_degrees();
            views.push(View {
                zenith_deg: 90.0 * r,
                azimuth_from_sun_deg: azimuth - sun_azimuth_deg,
            });
            cells.push((j * n + i) as usize);
        }
    }
    (views, cells)
}

/// The measured colour over the dome's cells: inverse-square-distance weights of the scan's
/// directions (sample 0 left out) on the sphere.
fn interpolated_dome(
    scan: &atmoscope_eval::measured::files::Scan,
    colours: &[[f64; 3]],
) -> Vec<Option<[f64; 3]>> {
    let unit = |az: f64, el: f64| atmoscope_model::geometry::direction_from_angles(el, az);
    let points: Vec<(glam::DVec3, [f64; 3])> = scan
        .directions
        .iter()
        .zip(colours)
        .filter(|(d, _)| d.sample != score::BAD_SAMPLE)
        .map(|(d, c)| (unit(d.azimuth_deg, d.elevation_deg), *c))
        .collect();
    let (views, cells) = dome_views(0.0);
    let mut out = vec![None; (DOME_CELLS * DOME_CELLS) as usize];
    for (v, cell) in views.iter().zip(cells) {
        let dir = unit(v.azimuth_from_sun_deg, 90.0 - v.zenith_deg);
        let (mut sum, mut weight) = ([0.0; 3], 0.0);
        for (p, c) in &points {
            let w = 1.0 / (1.0 - dir.dot(*p) + 1e-4).powi(2);
            (0..3).for_each(|k| sum[k] += w * c[k]);
            weight += w;
        }
        out[cell] = Some(sum.map(|s| s / weight));
    }
    out
}

/// The factor that brings the scan's median luminance to mid-grey after the tone map.
fn exposure(luminance_cd_m2: &[f64]) -> f64 {
    let median = score::quantile(luminance_cd_m2, 0.5);
    if median > 0.0 {
        0.6 * 683.0 / median
    } else {
        1.0
    }
}

fn paint_dome(
    painter: &egui::Painter,
    rect: egui::Rect,
    cells: &[Option<[f64; 3]>],
    exposure: f64,
) {
    let n = DOME_CELLS as usize;
    let cell = rect.width() / n as f32;
    painter.circle_filled(rect.center(), rect.width() / 2.0, egui::Color32::BLACK);
    for (i, c) in cells.iter().enumerate() {
        let Some(rgb) = c else { continue };
        let [r, g, b] =
            rgb.map(|x| (255.0 * srgb_encode(1.0 - (-exposure * x.max(0.0)).exp())).round() as u8);
        let min = rect.min + egui::vec2((i % n) as f32 * cell, (i / n) as f32 * cell);
        painter.rect_filled(
            egui::Rect::from_min_size(min, egui::vec2(cell + 0.5, cell + 0.5)),
            0.0,
            egui::Color32::from_rgb(r, g, b),
        );
    }
}

/// A direction's point on a dome drawn in `rect` (zenith in the centre, north up, east right).
pub fn dome_point(rect: egui::Rect, azimuth_deg: f64, elevation_deg: f64) -> egui::Pos2 {
    let r = f64::from(rect.width() / 2.0) * (90.0 - elevation_deg) / 90.0;
    let a = azimuth_deg.to_radians();
    rect.center() + egui::vec2((r * a.sin()) as f32, (-r * a.cos()) as f32)
}

/// Blue where the model is too dark, red where too bright, white where right (±50 % full).
fn error_colour(e: f64) -> egui::Color32 {
    let t = (e / 0.5).clamp(-1.0, 1.0) as f32;
    let mix = |a: f32, b: f32, t: f32| (a + (b - a) * t).round() as u8;
    if t < 0.0 {
        egui::Color32::from_rgb(
            mix(255.0, 33.0, -t),
            mix(255.0, 102.0, -t),
            mix(255.0, 172.0, -t),
        )
    } else {
        egui::Color32::from_rgb(
            mix(255.0, 178.0, t),
            mix(255.0, 24.0, t),
            mix(255.0, 43.0, t),
        )
    }
}
