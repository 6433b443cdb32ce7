//! File → Export to engine: the scene's atmosphere as bevy's, Unreal's or Blender's parameters
//! (`engine_export`), to copy or save, and how close each engine can come to the scene's full
//! physics, measured over the view suite in the background.

use super::jobs::{Job, Step};
use crate::engine_export::{Target, ViewError, fidelity, mean_delta_e};
use atmoscope_model::Scene;
use atmoscope_model::scene::{AtmosphereSettings, Quality, SunSettings, ToneMap};
use atmoscope_model::views::View;
use eframe::egui;
use std::sync::atomic::{AtomicUsize, Ordering};

/// What a snippet depends on: the atmosphere, the scene's name, and for Blender the sun and
/// the camera's altitude it writes too.
type TextKey = (
    Target,
    AtmosphereSettings,
    String,
    Option<(SunSettings, f64)>,
);

/// What a measurement depends on: the atmosphere, and the tone map and quality it is drawn
/// with (the views bring their own sun and camera).
type MeasureKey = (Target, AtmosphereSettings, ToneMap, Quality);

fn text_key(target: Target, scene: &Scene) -> TextKey {
    let blender = (target == Target::Blender).then_some((scene.sun, scene.camera.altitude_m));
    (
        target,
        scene.atmosphere.clone(),
        scene.name.clone(),
        blender,
    )
}

fn measure_key(target: Target, scene: &Scene) -> MeasureKey {
    (
        target,
        scene.atmosphere.clone(),
        scene.display.tone_map,
        scene.render.quality,
    )
}

enum Measure {
    Running(Job<Result<Vec<ViewError>, String>>),
    Done(Result<Vec<ViewError>, String>),
}

pub struct EngineExportWindow {
    pub open: bool,
    pub target: Target,
    /// The views a measurement draws: the suite's (the GUI tests take fewer).
    pub views: Vec<View>,
    /// The snippet, for the key it was written for.
    text: Option<(TextKey, String)>,
    /// The measurement of a key, running or done.
    measure: Option<(MeasureKey, Measure)>,
}

impl Default for EngineExportWindow {
    fn default() -> Self {
        EngineExportWindow {
            open: false,
            target: Target::Bevy,
            views: atmoscope_model::views::suite().to_vec(),
            text: None,
            measure: None,
        }
    }
}

impl EngineExportWindow {
    /// Whether a measurement runs (the window repaints for its progress).
    pub fn running(&self) -> bool {
        matches!(&self.measure, Some((_, Measure::Running(_))))
    }

    /// The measured errors of the current snippet, once done.
    pub fn errors(&self) -> Option<&[ViewError]> {
        match &self.measure {
            Some((_, Measure::Done(Ok(e)))) => Some(e),
            _ => None,
        }
    }

    /// Draws the window while open; returns a notice for the status bar (what was copied or
    /// saved, or why saving failed).
    pub fn show(&mut self, ctx: &egui::Context, scene: &Scene) -> Option<String> {
        if !self.open {
            return None;
        }
        let k = text_key(self.target, scene);
        if self.text.as_ref().is_none_or(|(t, _)| *t != k) {
            self.text = Some((k.clone(), self.target.write(scene)));
        }
        if let Some((_, Measure::Running(job))) = &mut self.measure
            && let Some(result) = job.take()
        {
            let done = result.and_then(|r| r);
            if let Some((mk, _)) = self.measure.take() {
                self.measure = Some((mk, Measure::Done(done)));
            }
        }
        // The first look at a snippet measures it; a changed scene waits for the button.
        if self.measure.is_none() {
            self.start(ctx, scene);
        }
        let mut notice = None;
        let mut open = self.open;
        let text = self
            .text
            .as_ref()
            .map_or("", |(_, t)| t.as_str())
            .to_owned();
        egui::Window::new("Export to engine")
            .open(&mut open)
            .default_width(560.0)
            .default_height(520.0)
            .show(ctx, |ui| {
                ui.horizontal_wrapped(|ui| {
                    for t in Target::ALL {
                        if ui
                            .selectable_value(&mut self.target, t, t.label())
                            .changed()
                        {
                            self.stop();
                        }
                    }
                });
                ui.label(
                    "The scene's atmosphere fitted to the engine's parameters: air and aerosol as \
                     exponentials, ozone as a tent (bevy, Unreal) or Blender's own Earth scaled by \
                     densities, each keeping the scene's vertical optical depths.",
                );
                ui.horizontal(|ui| {
                    if ui.button("Copy").clicked() {
                        ctx.copy_text(text.clone());
                        notice = Some(format!("copied the {} parameters", self.target.label()));
                    }
                    if ui.button("Save…").clicked()
                        && let Some(path) = super::files::save_dialog(
                            "Save the engine's parameters",
                            self.target.label(),
                            self.target.extension(),
                            &format!("atmosphere.{}", self.target.extension()),
                        )
                    {
                        notice = Some(match crate::files::write_atomic(&path, text.as_bytes()) {
                            Ok(()) => format!("wrote {}", path.display()),
                            Err(e) => format!("{e:#}"),
                        });
                    }
                });
                self.show_measure(ui, ctx, scene);
                egui::ScrollArea::vertical()
                    .max_height(320.0)
                    .show(ui, |ui| {
                        ui.add(
                            egui::TextEdit::multiline(&mut text.as_str())
                                .code_editor()
                                .desired_width(f32::INFINITY),
                        );
                    });
            });
        self.open = open;
        notice
    }

    /// Drops the measurement, cancelling it if it runs.
    fn stop(&mut self) {
        if let Some((_, Measure::Running(job))) = &self.measure {
            job.cancel();
        }
        self.measure = None;
    }

    fn start(&mut self, ctx: &egui::Context, scene: &Scene) {
        let k = measure_key(self.target, scene);
        let (target, scene, views) = (self.target, scene.clone(), self.views.clone());
        let exported = target
            .read(&target.write(&scene))
            .map_err(|e| format!("{e:#}"));
        // Natively the views are drawn in parallel in one step; in a browser, which has one
        // thread, a view a step, so that the page stays live and Cancel works.
        let chunk = if cfg!(target_arch = "wasm32") {
            1
        } else {
            views.len().max(1)
        };
        let (mut next, mut errors) = (0, Vec::new());
        let job = Job::spawn_steps(
            format!("measuring the {} parameters", target.label()),
            ctx,
            move |p| {
                let exported = match &exported {
                    Ok(e) => e,
                    Err(e) => return Step::Done(Err(e.clone())),
                };
                let end = (next + chunk).min(views.len());
                let done = AtomicUsize::new(next);
                let go_on = |_: &str| {
                    let n = done.fetch_add(1, Ordering::Relaxed) + 1;
                    p.set(n as f32 / views.len() as f32);
                    !p.cancelled()
                };
                errors.extend(fidelity(&scene, exported, &views[next..end], &go_on));
                next = end;
                if p.cancelled() {
                    Step::Done(Err("measurement cancelled".into()))
                } else if next < views.len() {
                    Step::Again
                } else {
                    Step::Done(Ok(std::mem::take(&mut errors)))
                }
            },
        );
        self.measure = Some((k, Measure::Running(job)));
    }

    fn show_measure(&mut self, ui: &mut egui::Ui, ctx: &egui::Context, scene: &Scene) {
        let current = self
            .measure
            .as_ref()
            .is_some_and(|(k, _)| *k == measure_key(self.target, scene));
        match &self.measure {
            Some((_, Measure::Running(job))) => {
                if job.show(ui) {
                    job.cancel();
                }
            }
            Some((_, Measure::Done(Ok(errors)))) => {
                let (engine, colours) = mean_delta_e(errors);
                if !current {
                    ui.label("For the scene as it was when measured:");
                }
                ui.label(format!(
                    "ΔE2000 against the scene's full physics over {} views: {engine:.2} \
                     with these parameters, {colours:.2} from the engine's colours alone \
                     (both drawn by Hillaire's model).",
                    errors.len()
                ));
                egui::CollapsingHeader::new("per view").show(ui, |ui| {
                    egui::Grid::new("engine-fidelity")
                        .striped(true)
                        .show(ui, |ui| {
                            for h in ["view", "parameters", "p95", "colours alone"] {
                                ui.strong(h);
                            }
                            ui.end_row();
                            for e in errors {
                                ui.label(&e.view);
                                ui.label(format!("{:.2}", e.delta_e2000_mean));
                                ui.label(format!("{:.2}", e.delta_e2000_p95));
                                ui.label(format!("{:.2}", e.colours_delta_e2000_mean));
                                ui.end_row();
                            }
                        });
                });
            }
            Some((_, Measure::Done(Err(e)))) => {
                ui.colored_label(ui.visuals().error_fg_color, e);
            }
            None => {}
        }
        if !current && !self.running() && ui.button("Measure again").clicked() {
            self.start(ctx, scene);
        }
    }
}
