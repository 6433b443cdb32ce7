//! The explorer window (eframe + egui on wgpu). Panels live one per module and return what they
//! want changed; the app applies it once per frame. Only the active tab's views are drawn, each
//! engine skips passes whose inputs did not change, and the window repaints only on input or
//! while background work (path tracing, inspection, exports) is in progress.

pub mod bench_tab;
pub mod compare_tab;
pub mod engine_export_window;
pub mod exposure;
pub mod files;
pub mod gpu_view;
pub mod help;
pub mod inspector;
pub mod jobs;
pub mod lut_tab;
pub mod measured_tab;
pub mod performance_panel;
pub mod polarisation_overlay;
pub mod reference_tab;
pub mod scene_panel;
pub mod scripted;
pub mod sky_tab;
pub mod state;
pub mod summary_panel;
pub mod thumbnails;

use crate::lessons::{self, Lesson, LessonError};
use crate::presets::load_shipped;
#[cfg(not(target_arch = "wasm32"))]
use crate::scene_args::SceneArgs;
use atmoscope_model::Scene;
use compare_tab::CompareTab;
use eframe::egui;
use files::ExportKind;
use gpu_view::{Gpu, GpuView};
use inspector::{Inspector, Probe};
use jobs::Job;
use lut_tab::LutTab;
use reference_tab::ReferenceTab;
use state::angles_of;
pub use state::{Command, Layout, Tab};
use std::path::{Path, PathBuf};
#[cfg(not(target_arch = "wasm32"))]
use std::process::ExitCode;
use summary_panel::SummaryPanel;
use web_time::Instant;

/// Storage keys of the last scene and layout.
pub const SCENE_KEY: &str = "scene";
pub const LAYOUT_KEY: &str = "layout";

/// GPU state, present when eframe runs on wgpu.
pub struct Views {
    pub gpu: Gpu,
    pub main: GpuView,
    /// Created when their tab is first shown: each holds engines of its own.
    pub compare: Option<CompareTab>,
    pub reference: Option<ReferenceTab>,
}

impl Views {
    /// Sets how every view, and those created later, build a new atmosphere.
    pub fn set_rebuild_slices(&mut self, slice: Option<std::time::Duration>) {
        self.gpu.rebuild_slice = slice;
        self.main.set_rebuild_slices(slice);
        if let Some(c) = &mut self.compare {
            c.set_rebuild_slices(slice);
        }
        if let Some(r) = &mut self.reference {
            r.set_rebuild_slices(slice);
        }
    }

    /// Whether any view needs more frames of the same scene (`GpuView::settling`).
    pub fn settling(&self) -> bool {
        self.main.settling()
            || self.compare.as_ref().is_some_and(CompareTab::settling)
            || self
                .reference
                .as_ref()
                .is_some_and(|r| r.realtime().settling())
    }
}

/// The explorer: its state and the runtime that draws it. Panels change the state only through
/// the commands [`ExplorerApp::apply`] applies; the fields are public for the GUI tests
/// (`app/tests/gui.rs`) and the scripted session (`scripted`), which set up what a test or a
/// benchmark step needs.
pub struct ExplorerApp {
    pub scene: Scene,
    pub layout: Layout,
    pub views: Option<Views>,
    pub luts: LutTab,
    pub bench: bench_tab::BenchTab,
    pub inspector: Inspector,
    /// The per-wavelength summary shown under the Inspector.
    pub summary: SummaryPanel,
    /// A message for the user (why a preset did not load), dismissible.
    pub message: Option<String>,
    /// What the last finished export or save did.
    pub notice: Option<String>,
    pub exports: Vec<Job<anyhow::Result<Option<String>>>>,
    pub last_frame: Option<Instant>,
    pub ui_frame_ms: f64,
    /// The automatic exposure's last reading of the main view.
    pub meter: Option<exposure::Reading>,
    /// Print each frame's passes and times to stderr (ATMOSCOPE_FRAME_LOG=1).
    pub frame_log: bool,
    /// The Learn menu's lessons, parsed once (a broken one is listed with its error).
    pub lessons: Vec<(&'static str, Result<Lesson, LessonError>)>,
    /// The lesson on screen.
    pub lesson: Option<ActiveLesson>,
    /// The preset menu's pictures, and where they are cached.
    pub thumbnails: thumbnails::Thumbnails,
    pub thumbnail_dir: PathBuf,
    /// Exports of the main view asked for while its tables were being built, in order: they
    /// wait for them rather than building them whole in one frame.
    pub pending_exports: Vec<(ExportKind, PathBuf)>,
    /// A scripted session playing in the window (`atmoscope bench gui`); it saves nothing.
    pub session: Option<scripted::Session>,
    /// The panels whose contents came out wider than the panel in the last frame (they should
    /// wrap): read by the layout tests.
    pub overflowed: Vec<&'static str>,
    /// File → Export to engine.
    pub engine_export: engine_export_window::EngineExportWindow,
    /// The Measured tab: a measured sky beside the model's.
    pub measured: measured_tab::MeasuredTab,
}

/// A lesson the user started: its window stays until closed and its numbers follow the scene.
pub struct ActiveLesson {
    lesson: Lesson,
    /// The view point to inspect once the lesson's tab has drawn its view (fractions, 0–1).
    pending_inspect: Option<[f64; 2]>,
    /// The text for the scene it was computed for.
    text: Option<(Scene, String)>,
}

impl ExplorerApp {
    pub fn new(
        scene: Scene,
        layout: Layout,
        render_state: Option<&eframe::egui_wgpu::RenderState>,
    ) -> ExplorerApp {
        let views = render_state.map(|rs| {
            let gpu = Gpu::from_render_state(rs);
            Views {
                main: GpuView::new(&gpu),
                compare: None,
                reference: None,
                gpu,
            }
        });
        ExplorerApp {
            scene,
            layout,
            views,
            luts: LutTab::default(),
            bench: bench_tab::BenchTab::new(bench_tab::default_dir()).with_shipped_results(),
            inspector: Inspector::default(),
            summary: SummaryPanel::default(),
            message: None,
            notice: None,
            exports: Vec::new(),
            last_frame: None,
            ui_frame_ms: 0.0,
            meter: None,
            frame_log: if cfg!(target_arch = "wasm32") {
                crate::web_query("frame_log").is_some()
            } else {
                std::env::var_os("ATMOSCOPE_FRAME_LOG").is_some()
            },
            lessons: lessons::shipped(),
            lesson: None,
            thumbnails: thumbnails::Thumbnails::default(),
            thumbnail_dir: crate::cache::dir("thumbnails"),
            pending_exports: Vec::new(),
            session: None,
            overflowed: Vec::new(),
            engine_export: Default::default(),
            measured: measured_tab::MeasuredTab::new(),
        }
    }

    /// Sets how the views build a new atmosphere: in slices across frames (the default in a
    /// window), or at once (`None`: tests that step frames without waiting for the GPU).
    pub fn set_rebuild_slices(&mut self, slice: Option<std::time::Duration>) {
        if let Some(v) = &mut self.views {
            v.set_rebuild_slices(slice);
        }
    }

    fn load_file(&mut self, path: &Path) {
        match Scene::load(path) {
            Ok(scene) => {
                self.scene = scene;
                self.message = None;
                self.notice = Some(format!("loaded {}", path.display()));
            }
            Err(e) => self.message = Some(e.to_string()),
        }
    }

    /// Loads a preset from its contents (picked in a browser's file dialog, or dropped on
    /// the page), as [`Self::load_file`] does from a file.
    fn load_bytes(&mut self, name: &str, bytes: &[u8]) {
        use atmoscope_model::scene::MAX_PRESET_BYTES;
        let text = if bytes.len() as u64 > MAX_PRESET_BYTES {
            Err(format!(
                "{name}: {} bytes, more than a preset's {MAX_PRESET_BYTES}",
                bytes.len()
            ))
        } else {
            std::str::from_utf8(bytes).map_err(|e| format!("{name}: not UTF-8 text ({e})"))
        };
        match text.and_then(|t| Scene::from_ron(t, Path::new(name)).map_err(|e| e.to_string())) {
            Ok(scene) => {
                self.scene = scene;
                self.message = None;
                self.notice = Some(format!("loaded {name}"));
            }
            Err(e) => self.message = Some(e),
        }
    }

    /// Applies what a panel asked for: the one place the explorer's state changes on a user's
    /// behalf.
    pub fn apply(&mut self, ctx: &egui::Context, command: Command) {
        match command {
            Command::SetScene(scene) => match scene.validate() {
                Ok(()) => self.scene = *scene,
                Err(errors) => {
                    self.message = Some(
                        errors
                            .iter()
                            .map(ToString::to_string)
                            .collect::<Vec<_>>()
                            .join("\n"),
                    );
                }
            },
            Command::LoadPreset(name) => match load_shipped(name) {
                Some(Ok(scene)) => self.scene = scene,
                Some(Err(e)) => self.message = Some(e.to_string()),
                None => self.message = Some(format!("no shipped preset {name}")),
            },
            Command::LoadFile(path) => self.load_file(&path),
            Command::LoadBytes { name, bytes } => self.load_bytes(&name, &bytes),
            Command::SaveFile(path) => match save_preset(&self.scene, &path) {
                Ok(()) => self.notice = Some(format!("saved {}", path.display())),
                Err(e) => self.message = Some(e),
            },
            Command::CopyRon => {
                ctx.copy_text(self.scene.to_ron());
                self.notice = Some("copied the scene as RON".into());
            }
            Command::Export(kind, path) => self.export(ctx, kind, path),
            Command::Inspect { tab, x, y } => self.inspect(ctx, tab, x, y),
            Command::StartLesson(i) => self.start_lesson(i),
            // A browser page cannot wait for a GPU read-back, which the thumbnails' renders
            // need: its preset menu lists names only.
            Command::WantThumbnails if cfg!(target_arch = "wasm32") => {}
            Command::WantThumbnails => {
                if let Some(views) = &self.views {
                    self.thumbnails
                        .request(ctx, &views.gpu, self.thumbnail_dir.clone());
                }
            }
        }
    }

    /// Sets the lesson's scene, opens its tab (and the Inspector on its pixel once the view
    /// is drawn) and shows its text.
    fn start_lesson(&mut self, index: usize) {
        let Some((file, Ok(lesson))) = self.lessons.get(index) else {
            self.message = Some(match self.lessons.get(index) {
                Some((_, Err(e))) => e.to_string(),
                _ => format!("no lesson {index}"),
            });
            return;
        };
        match lesson.scene(file) {
            Ok(scene) => {
                self.scene = scene;
                self.layout.tab = lesson.tab;
                self.layout.full_view = false;
                self.layout.show_inspector |= lesson.inspect.is_some();
                self.inspector.clear();
                self.message = None;
                self.lesson = Some(ActiveLesson {
                    lesson: lesson.clone(),
                    pending_inspect: lesson.inspect,
                    text: None,
                });
            }
            Err(e) => self.message = Some(e.to_string()),
        }
    }

    /// Inspects the lesson's pixel once its tab's view exists.
    fn inspect_lesson_pixel(&mut self, ctx: &egui::Context) {
        let Some(active) = &mut self.lesson else {
            return;
        };
        let Some([fx, fy]) = active.pending_inspect else {
            return;
        };
        let tab = self.layout.tab;
        if tab != active.lesson.tab {
            active.pending_inspect = None;
            return;
        }
        let Some(view) = self.views.as_ref().and_then(|v| v.main.view()) else {
            return;
        };
        if view.projection != state::projection(tab) {
            return;
        }
        active.pending_inspect = None;
        let at = |f: f64, n: u32| ((f * f64::from(n)) as u32).min(n.saturating_sub(1));
        self.inspect(ctx, tab, at(fx, view.width), at(fy, view.height));
    }

    /// The lesson's window: its text with numbers for the scene on screen, and what to try.
    fn lesson_window(&mut self, ctx: &egui::Context) {
        let Some(active) = &mut self.lesson else {
            return;
        };
        // The numbers depend on the atmosphere, the sun and the camera, not on the display
        // (which a metered exposure changes frame by frame).
        let stale = active.text.as_ref().is_none_or(|(s, _)| {
            (&s.atmosphere, &s.sun, &s.camera)
                != (&self.scene.atmosphere, &self.scene.sun, &self.scene.camera)
        });
        if stale {
            let text = active.lesson.text_for(&self.scene);
            active.text = Some((self.scene.clone(), text));
        }
        let text = active.text.as_ref().map_or("", |(_, t)| t.as_str());
        let mut open = true;
        egui::Window::new(format!("Learn: {}", active.lesson.title))
            .open(&mut open)
            .default_width(380.0)
            .default_pos(ctx.content_rect().center_bottom() - egui::vec2(190.0, 260.0))
            .show(ctx, |ui| {
                ui.label(text);
                ui.add_space(6.0);
                ui.horizontal_wrapped(|ui| {
                    ui.strong(format!("Try ({}):", active.lesson.section.title()));
                    ui.label(&active.lesson.try_this);
                });
            });
        if !open {
            self.lesson = None;
        }
    }

    fn export(&mut self, ctx: &egui::Context, kind: ExportKind, path: PathBuf) {
        let Some(views) = &mut self.views else {
            self.message = Some("exports need the GPU renderer".into());
            return;
        };
        // The Sky, Fisheye or Luminance view last shown, brought up to date with the scene (it
        // may have changed while another tab was open).
        let view = views
            .main
            .view()
            .unwrap_or_else(|| sky_tab::view_for(Tab::Sky, &self.layout, [1280, 720]));
        if matches!(kind, ExportKind::Png | ExportKind::Exr) {
            // A new atmosphere of the view is built a slice per frame: the export waits for it
            // (`export_when_built`) instead of building it whole now.
            views.main.render(&self.scene, &view);
            if views.main.engine().rebuilding() {
                self.notice = Some(format!(
                    "{} waits for the tables to be built",
                    path.display()
                ));
                self.pending_exports.push((kind, path));
                return;
            }
        }
        views.main.render_complete(&self.scene, &view);
        let (w, h) = (view.width, view.height);
        let label = format!("exporting {}", path.display());
        // In a browser the image comes back from the GPU a frame later: the export waits.
        #[cfg(target_arch = "wasm32")]
        {
            let read = match kind {
                ExportKind::Png => views.main.display_rgba8().map(|_| ()),
                ExportKind::Exr => views.main.radiance().map(|_| ()),
                ExportKind::PanoramaExr | ExportKind::Timelapse => Ok(()),
            };
            if read.is_err_and(|e| e.is_pending()) {
                self.pending_exports.push((kind, path));
                ctx.request_repaint();
                return;
            }
        }
        let job = match kind {
            ExportKind::Png => match views.main.display_rgba8() {
                Ok(rgba) => {
                    let caption = self
                        .layout
                        .caption_exports
                        .then(|| crate::images::caption_text(&self.scene));
                    Job::spawn(label, ctx, move |_| {
                        files::write_display_png(&path, &rgba, w, h, caption.as_deref()).map(|()| {
                            Some(format!("wrote {} ({w}×{h}, as displayed)", path.display()))
                        })
                    })
                }
                Err(e) => return self.message = Some(e.to_string()),
            },
            ExportKind::Exr => match views.main.radiance() {
                Ok(r) => Job::spawn(label, ctx, move |_| {
                    files::write_radiance_exr(&path, &r.rgba, w, h).map(|()| {
                        Some(format!(
                            "wrote {} ({w}×{h}, linear radiance)",
                            path.display()
                        ))
                    })
                }),
                Err(e) => return self.message = Some(e.to_string()),
            },
            ExportKind::PanoramaExr => {
                let (gpu, scene) = (views.gpu.clone(), self.scene.clone());
                Job::spawn(label, ctx, move |p| {
                    files::export_panorama(&gpu, &scene, &path, p)
                })
            }
            ExportKind::Timelapse => {
                let (gpu, scene) = (views.gpu.clone(), self.scene.clone());
                Job::spawn(label, ctx, move |p| {
                    files::export_timelapse(&gpu, &scene, view.projection, &path, p)
                })
            }
        };
        self.exports.push(job);
    }

    fn inspect(&mut self, ctx: &egui::Context, tab: Tab, x: u32, y: u32) {
        let Some(views) = &mut self.views else { return };
        let Some(view) = views.main.view() else {
            return;
        };
        let Some(ray) = sky_tab::ray_at(&self.scene, &view, x, y) else {
            return;
        };
        // The Polarisation tab's radiance image holds Stokes vectors, not colours.
        let displayed = (tab != Tab::Polarisation)
            .then(|| views.main.radiance().ok().and_then(|r| r.at(x, y)))
            .flatten();
        let (elevation, azimuth) = angles_of(ray.direction);
        self.inspector.inspect(
            ctx,
            Probe {
                label: format!(
                    "{} pixel ({x}, {y}): elevation {elevation:.2}°, azimuth {azimuth:.2}°",
                    tab.label()
                ),
                scene: self.scene.clone(),
                ray,
                displayed,
            },
        );
        self.layout.show_inspector = true;
    }

    /// Takes the exports that waited for the main view's tables, once they are built; until
    /// then the view goes on building them, a slice per frame, whichever tab is open. A scene
    /// the view cannot draw drops them, saying why.
    fn export_when_built(&mut self, ctx: &egui::Context) {
        let Some(views) = &mut self.views else { return };
        if self.pending_exports.is_empty() {
            return;
        }
        if let Some(why) = gpu_view::notice(&self.scene).filter(|_| views.main.refused()) {
            self.message = Some(format!("exports not written: {why}"));
            self.pending_exports.clear();
            return;
        }
        if views.main.engine().rebuilding() {
            // The tabs that draw the main view build it themselves.
            let drawn = matches!(
                self.layout.tab,
                Tab::Sky | Tab::Fisheye | Tab::Luminance | Tab::Polarisation | Tab::Luts
            );
            if !drawn {
                let view = views
                    .main
                    .view()
                    .unwrap_or_else(|| sky_tab::view_for(Tab::Sky, &self.layout, [1280, 720]));
                views.main.render(&self.scene, &view);
            }
            ctx.request_repaint();
        } else {
            for (kind, path) in std::mem::take(&mut self.pending_exports) {
                self.export(ctx, kind, path);
            }
        }
    }

    /// Collects finished background work.
    fn poll_jobs(&mut self) {
        let mut i = 0;
        while i < self.exports.len() {
            match self.exports[i].take() {
                Some(result) => {
                    self.exports.remove(i);
                    match result {
                        Ok(Ok(Some(done))) => self.notice = Some(done),
                        Ok(Ok(None)) => self.notice = Some("export cancelled".into()),
                        Ok(Err(e)) => self.message = Some(format!("{e:#}")),
                        Err(e) => self.message = Some(e),
                    }
                }
                None => i += 1,
            }
        }
        if let Some(e) = self.inspector.poll() {
            self.message = Some(e);
        }
    }

    fn busy(&self) -> bool {
        let tracing = self.layout.tab == Tab::Reference
            && self
                .views
                .as_ref()
                .and_then(|v| v.reference.as_ref())
                .is_some_and(|r| r.job().is_some());
        !self.exports.is_empty()
            || self.inspector.job().is_some()
            || self.bench.running()
            || tracing
            || self.thumbnails.loading()
            || self.engine_export.running()
            || self.measured.busy()
    }

    fn shortcuts(&mut self, ctx: &egui::Context) -> Vec<Command> {
        use egui::{Key, KeyboardShortcut, Modifiers};
        let mut commands = Vec::new();
        let ctrl = |k| KeyboardShortcut::new(Modifiers::COMMAND, k);
        let ctrl_shift = |k| KeyboardShortcut::new(Modifiers::COMMAND | Modifiers::SHIFT, k);
        ctx.input_mut(|i| {
            if i.consume_shortcut(&ctrl_shift(Key::C)) {
                commands.push(Command::CopyRon);
            }
            if i.consume_shortcut(&ctrl_shift(Key::E))
                && let Some(p) = files::pick_export(ExportKind::Exr)
            {
                commands.push(Command::Export(ExportKind::Exr, p));
            }
            if i.consume_shortcut(&ctrl(Key::E))
                && let Some(p) = files::pick_export(ExportKind::Png)
            {
                commands.push(Command::Export(ExportKind::Png, p));
            }
            if i.consume_shortcut(&ctrl(Key::O))
                && let Some(p) = files::pick_preset_to_open(ctx)
            {
                commands.push(Command::LoadFile(p));
            }
            if i.consume_shortcut(&ctrl(Key::S))
                && let Some(p) = files::pick_preset_to_save(&self.scene)
            {
                commands.push(Command::SaveFile(p));
            }
        });
        // Plain keys only when no text field has the keyboard.
        if !ctx.egui_wants_keyboard_input() {
            ctx.input(|i| {
                for tab in Tab::ALL {
                    if i.key_pressed(tab.key()) && i.modifiers.is_none() {
                        self.layout.tab = tab;
                    }
                }
                if i.key_pressed(Key::S) && i.modifiers.is_none() {
                    self.layout.show_scene ^= true;
                }
                if i.key_pressed(Key::I) && i.modifiers.is_none() {
                    self.layout.show_inspector ^= true;
                }
                if i.key_pressed(Key::P) && i.modifiers.is_none() {
                    self.layout.show_performance ^= true;
                }
                if i.key_pressed(Key::F) && i.modifiers.is_none() {
                    self.layout.full_view ^= true;
                }
                if i.key_pressed(Key::Escape) {
                    self.layout.full_view = false;
                }
            });
        }
        for file in ctx.input(|i| i.raw.dropped_files.clone()) {
            // A browser reads a dropped file's contents later, as it does a picked one's.
            #[cfg(target_arch = "wasm32")]
            crate::web::read_dropped(ctx, file);
            #[cfg(not(target_arch = "wasm32"))]
            commands.push(Command::LoadFile(file.path().to_path_buf()));
        }
        #[cfg(target_arch = "wasm32")]
        if let Some((name, bytes)) = crate::web::take_picked() {
            commands.push(Command::LoadBytes { name, bytes });
        }
        commands
    }

    fn menu(&mut self, ui: &mut egui::Ui) -> Vec<Command> {
        let mut commands = Vec::new();
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if ui.button("Open preset…  (Ctrl+O)").clicked() {
                    commands.extend(files::pick_preset_to_open(ui.ctx()).map(Command::LoadFile));
                }
                if ui.button("Save preset…  (Ctrl+S)").clicked() {
                    commands.extend(files::pick_preset_to_save(&self.scene).map(Command::SaveFile));
                }
                if ui.button("Copy scene as RON  (Ctrl+Shift+C)").clicked() {
                    commands.push(Command::CopyRon);
                }
                ui.separator();
                for (kind, key) in [
                    (ExportKind::Png, "  (Ctrl+E)"),
                    (ExportKind::Exr, "  (Ctrl+Shift+E)"),
                    (ExportKind::PanoramaExr, ""),
                    (ExportKind::Timelapse, ""),
                ] {
                    // The panorama and the time-lapse render beside the window, waiting for
                    // the GPU, which a web page cannot do.
                    if cfg!(target_arch = "wasm32")
                        && matches!(kind, ExportKind::PanoramaExr | ExportKind::Timelapse)
                    {
                        continue;
                    }
                    if ui.button(format!("{}…{key}", kind.title())).clicked() {
                        commands.extend(files::pick_export(kind).map(|p| Command::Export(kind, p)));
                    }
                }
                if ui.button("Export to engine…").clicked() {
                    self.engine_export.open = true;
                }
                ui.checkbox(&mut self.layout.caption_exports, "Caption on PNG exports")
                    .on_hover_text(
                        "Burn the scene's name, the model, the wavelength set, the exposure, the sun's elevation and the camera's altitude under the exported view.",
                    );
            });
            ui.menu_button("View", |ui| {
                ui.checkbox(&mut self.layout.show_scene, "Scene panel  (S)");
                ui.checkbox(&mut self.layout.show_inspector, "Inspector  (I)");
                ui.checkbox(&mut self.layout.show_performance, "Performance  (P)");
                ui.checkbox(&mut self.layout.full_view, "Full view: hide the panels  (F)");
                for (label, scale, tip) in [
                    (
                        "render scale",
                        &mut self.layout.render_scale,
                        "Texels per screen pixel: a lower scale draws faster on a software renderer.",
                    ),
                    (
                        "while dragging",
                        &mut self.layout.drag_scale,
                        "Texels per screen pixel while the pointer drags; the view is redrawn at the render scale when the drag ends.",
                    ),
                ] {
                    ui.horizontal(|ui| {
                        ui.label(label);
                        for s in [0.25, 0.5, 1.0] {
                            ui.selectable_value(scale, s, format!("{:.0} %", s * 100.0));
                        }
                    })
                    .response
                    .on_hover_text(tip);
                }
            });
            ui.menu_button("Learn", |ui| {
                for (i, (file, lesson)) in self.lessons.iter().enumerate() {
                    match lesson {
                        Ok(l) => {
                            if ui.button(&l.title).clicked() {
                                commands.push(Command::StartLesson(i));
                            }
                        }
                        Err(e) => {
                            ui.add_enabled(false, egui::Button::new(*file))
                                .on_disabled_hover_text(e.to_string());
                        }
                    }
                }
            });
            ui.menu_button("Help", |ui| help::menu(ui, &mut self.layout));
            ui.separator();
            for tab in Tab::ALL {
                ui.selectable_value(&mut self.layout.tab, tab, tab.label())
                    .on_hover_text(tab.description());
            }
        });
        commands
    }

    fn centre(&mut self, ui: &mut egui::Ui) -> Vec<Command> {
        if self.layout.tab == Tab::Bench {
            return self.bench.show(ui, &self.scene);
        }
        if self.layout.tab == Tab::Measured {
            return self.measured.show(ui, &self.scene);
        }
        let Some(views) = &mut self.views else {
            ui.label("Atmoscope needs eframe's wgpu renderer to draw the views.");
            return Vec::new();
        };
        let tab = self.layout.tab;
        if let Some(r) = &views.reference {
            r.set_visible(tab == Tab::Reference);
        }
        match tab {
            Tab::Sky | Tab::Fisheye | Tab::Luminance | Tab::Polarisation => {
                sky_tab::show(ui, &self.scene, &mut views.main, tab, &mut self.layout)
            }
            Tab::Compare => {
                let gpu = &views.gpu;
                let compare = views.compare.get_or_insert_with(|| CompareTab::new(gpu));
                compare.show(ui, &self.scene, &mut self.layout);
                Vec::new()
            }
            Tab::Luts => {
                // The tables of the current scene: redraw the main view if the scene changed.
                let view = views
                    .main
                    .view()
                    .unwrap_or_else(|| sky_tab::view_for(Tab::Sky, &self.layout, [320, 180]));
                views.main.render(&self.scene, &view);
                self.luts
                    .show(ui, &self.scene, &views.main, &mut self.layout.luts);
                Vec::new()
            }
            Tab::Reference => {
                let gpu = &views.gpu;
                let reference = views
                    .reference
                    .get_or_insert_with(|| ReferenceTab::new(gpu));
                reference.show(ui, &self.scene, &mut self.layout.reference);
                Vec::new()
            }
            Tab::Bench | Tab::Measured => Vec::new(),
        }
    }

    /// Automatic exposure: reads the main view's histogram and moves the exposure towards
    /// the metered one (a frame at a time, asking for frames until it arrives).
    fn expose(&mut self, ctx: &egui::Context) {
        let d = &self.scene.display;
        let histogram = self.views.as_mut().and_then(|v| v.main.histogram());
        self.meter = match (d.auto_exposure, histogram) {
            (true, Some(h)) => exposure::Reading::new(h, d.compensation_ev),
            _ => None,
        };
        if let Some(m) = &self.meter {
            let dt = f64::from(ctx.input(|i| i.stable_dt)).min(0.1);
            let next = exposure::adapt(d.exposure_ev, m.target_ev, dt);
            if next != d.exposure_ev {
                self.scene.display.exposure_ev = next;
                ctx.request_repaint();
            }
        }
    }

    fn log_frame(&self) {
        let Some(views) = &self.views else { return };
        let s = views.main.stats();
        let passes: Vec<String> = s
            .run
            .iter()
            .map(|p| match s.timings_ms.iter().find(|(q, _)| q == p) {
                Some((_, ms)) => format!("{p} {ms:.1} ms"),
                None => p.to_string(),
            })
            .collect();
        let wall = if s.run.is_empty() {
            0.0
        } else {
            views.main.last_frame_ms
        };
        let rebuild = s.rebuild.map_or(String::new(), |p| {
            format!(", rebuilding {}/{}", p.done, p.total)
        });
        let line = format!(
            "frame: tab {:?}, view {:?}, passes run [{}], skipped {}, frame wall {wall:.1} ms, UI interval {:.1} ms{rebuild}",
            self.layout.tab,
            views.main.view().map(|v| (v.width, v.height)),
            passes.join(", "),
            s.skipped.len(),
            self.ui_frame_ms
        );
        // A web page has no standard error: its console instead (`?frame_log`).
        #[cfg(target_arch = "wasm32")]
        web_sys::console::log_1(&line.into());
        #[cfg(not(target_arch = "wasm32"))]
        eprintln!("{line}");
    }
}

impl eframe::App for ExplorerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        let now = Instant::now();
        if let Some(last) = self.last_frame {
            self.ui_frame_ms = (now - last).as_secs_f64() * 1e3;
        }
        self.last_frame = Some(now);
        if let Some(v) = &self.views {
            v.gpu.budget.new_frame();
        }
        if let Some(mut session) = self.session.take() {
            session.frame(self, &ctx);
            self.session = Some(session);
        }
        self.poll_jobs();
        self.thumbnails.poll(&ctx);
        if let Some(v) = &mut self.views {
            v.main.set_metering(self.scene.display.auto_exposure);
        }
        self.overflowed.clear();
        let mut commands = self.shortcuts(&ctx);
        egui::Panel::top("menu").show(ui, |ui| commands.extend(self.menu(ui)));
        let full = self.layout.full_view;
        let status = !full || self.message.is_some() || !self.exports.is_empty();
        if status {
            egui::Panel::bottom("status").show(ui, |ui| {
                let room = ui.max_rect();
                if let Some(message) = &self.message {
                    let mut dismissed = false;
                    ui.horizontal(|ui| {
                        ui.colored_label(ui.visuals().error_fg_color, message);
                        dismissed = ui.button("Dismiss").clicked();
                    });
                    if dismissed {
                        self.message = None;
                    }
                }
                for job in &self.exports {
                    job.show(ui);
                }
                if let Some(notice) = &self.notice {
                    ui.label(notice);
                }
                if self.layout.show_performance
                    && !full
                    && let Some(views) = &self.views
                {
                    let mut shown: Vec<(&str, &GpuView)> = Vec::new();
                    match self.layout.tab {
                        Tab::Compare => {
                            if let Some(c) = &views.compare {
                                for (name, v) in ["A", "B", "reference"].iter().zip(c.views()) {
                                    shown.push((name, v));
                                }
                            }
                        }
                        Tab::Reference => {
                            if let Some(r) = &views.reference {
                                shown.push(("real time", r.realtime()));
                            }
                        }
                        _ => shown.push(("view", &views.main)),
                    }
                    performance_panel::show(ui, &shown, self.ui_frame_ms, &views.gpu.adapter);
                }
                note_overflow(&mut self.overflowed, "status", room, ui);
            });
        }
        if self.layout.show_scene && !full {
            egui::Panel::left("scene")
                .resizable(true)
                .default_size(330.0)
                .show(ui, |ui| {
                    egui::ScrollArea::vertical().show(ui, |ui| {
                        let room = ui.max_rect();
                        commands.extend(scene_panel::show(
                            ui,
                            &self.scene,
                            self.meter.as_ref(),
                            self.lesson.as_ref().map(|l| l.lesson.section),
                            &self.thumbnails,
                        ));
                        note_overflow(&mut self.overflowed, "scene", room, ui);
                    });
                });
        }
        if self.layout.show_inspector && !full {
            egui::Panel::right("inspector")
                .resizable(true)
                .default_size(360.0)
                .show(ui, |ui| {
                    egui::ScrollArea::vertical().show(ui, |ui| {
                        let room = ui.max_rect();
                        self.inspector.show(ui, &self.scene);
                        egui::CollapsingHeader::new("Summary per wavelength")
                            .default_open(false)
                            .show(ui, |ui| self.summary.show(ui, &self.scene));
                        note_overflow(&mut self.overflowed, "inspector", room, ui);
                    });
                });
        }
        let centre = if full {
            egui::CentralPanel::default().frame(egui::Frame::NONE)
        } else {
            egui::CentralPanel::default()
        };
        centre.show(ui, |ui| {
            let room = ui.max_rect();
            commands.extend(self.centre(ui));
            note_overflow(&mut self.overflowed, "centre", room, ui);
        });
        self.lesson_window(&ctx);
        commands.extend(help::welcome(&ctx, &mut self.layout));
        if let Some(notice) = self.engine_export.show(&ctx, &self.scene) {
            self.notice = Some(notice);
        }
        for c in commands {
            self.apply(&ctx, c);
        }
        self.inspect_lesson_pixel(&ctx);
        self.export_when_built(&ctx);
        self.expose(&ctx);
        if let Some(fault) = self.views.as_mut().and_then(|v| v.main.take_fault()) {
            self.message = Some(fault);
        }
        if self.frame_log {
            self.log_frame();
        }
        if self.busy() {
            ctx.request_repaint_after(std::time::Duration::from_millis(250));
        }
        if self.views.as_ref().is_some_and(Views::settling) {
            // The next slice of the tables, or the full resolution, goes with the next frame.
            ctx.request_repaint();
        }
        #[cfg(target_arch = "wasm32")]
        if self.layout.tab == Tab::Sky
            && self
                .views
                .as_ref()
                .is_some_and(|v| v.main.view().is_some() && !v.main.settling())
        {
            crate::web::mark_first_frame();
        }
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        if self.session.is_some() {
            // A scripted session's scene is not the user's.
            return;
        }
        eframe::set_value(storage, SCENE_KEY, &self.scene);
        eframe::set_value(storage, LAYOUT_KEY, &self.layout);
    }
}

/// Saves `scene` as a preset at `path`; in a browser, downloads it under that name.
fn save_preset(scene: &Scene, path: &Path) -> Result<(), String> {
    #[cfg(target_arch = "wasm32")]
    return crate::files::write_atomic(path, (scene.to_ron() + "\n").as_bytes())
        .map_err(|e| format!("{e:#}"));
    #[cfg(not(target_arch = "wasm32"))]
    scene.save(path).map_err(|e| e.to_string())
}

/// Notes `panel` if what `ui` holds came out wider than `room`, the rect it was given (egui
/// widens a Ui's own rects to take what overflows them).
fn note_overflow(
    overflowed: &mut Vec<&'static str>,
    panel: &'static str,
    room: egui::Rect,
    ui: &egui::Ui,
) {
    if ui.min_rect().right() > room.right() + 0.5 {
        overflowed.push(panel);
    }
}

/// Opens the explorer. The scene comes from the command line when any scene option is given,
/// else from the last session, else the built-in default.
#[cfg(not(target_arch = "wasm32"))]
pub fn run(args: SceneArgs) -> anyhow::Result<ExitCode> {
    let from_args = args.preset.is_some() || std::env::args().len() > 1;
    let scene = if from_args { Some(args.scene()?) } else { None };
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_inner_size([1280.0, 800.0])
            .with_title("Atmoscope")
            .with_drag_and_drop(true),
        wgpu_options: wgpu_options(),
        ..Default::default()
    };
    eframe::run_native(
        "Atmoscope",
        options,
        Box::new(move |cc| {
            let (scene, layout) = restore(cc.storage, scene);
            Ok(Box::new(ExplorerApp::new(
                scene,
                layout,
                cc.wgpu_render_state.as_ref(),
            )))
        }),
    )
    .map_err(|e| anyhow::anyhow!("cannot open the explorer window: {e}"))?;
    Ok(ExitCode::SUCCESS)
}

/// The scene and layout to open with: `from_args` if given, else the last session's (a stored
/// scene that no longer validates is dropped, a stored layout is brought into range), else the
/// explorer's first scene (`presets::first_scene`) and the default layout.
pub fn restore(storage: Option<&dyn eframe::Storage>, from_args: Option<Scene>) -> (Scene, Layout) {
    let stored = storage
        .and_then(|s| eframe::get_value::<Scene>(s, SCENE_KEY))
        .filter(|s| s.validate().is_ok());
    let layout = storage
        .and_then(|s| eframe::get_value::<Layout>(s, LAYOUT_KEY))
        .unwrap_or_default()
        .validated();
    (
        from_args
            .or(stored)
            .unwrap_or_else(crate::presets::first_scene),
        layout,
    )
}

#[cfg(not(target_arch = "wasm32"))]
fn wgpu_options() -> eframe::egui_wgpu::WgpuConfiguration {
    let mut config = eframe::egui_wgpu::WgpuConfiguration::default();
    ask_for_what_the_engine_uses(&mut config.wgpu_setup);
    config
}

/// Asks the window's device for the engine's limits (`gpu::required_limits`) and for timestamp
/// queries where the adapter has them, so the Performance panel shows GPU time per pass (it
/// falls back to fenced wall time otherwise).
pub fn ask_for_what_the_engine_uses(setup: &mut eframe::egui_wgpu::WgpuSetup) {
    use eframe::egui_wgpu::{WgpuSetup, wgpu};
    if let WgpuSetup::CreateNew(create) = setup {
        let base = create.device_descriptor.clone();
        create.device_descriptor = std::sync::Arc::new(move |adapter: &wgpu::Adapter| {
            let mut d = base(adapter);
            d.required_features |= adapter.features() & atmoscope_render::gpu::optional_features();
            d.required_limits = atmoscope_render::gpu::required_limits(d.required_limits);
            d
        });
    }
}
