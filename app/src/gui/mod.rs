//! The explorer window (eframe + egui on wgpu). Panels live one per module and return what they
//! want changed; the app applies it once per frame and repaints only when something changed.

mod scene_panel;
mod summary_panel;

use crate::cli::SceneArgs;
use crate::presets::load_shipped;
use atmoscope_model::Scene;
use eframe::egui;
use std::process::ExitCode;

/// Storage key of the last scene.
const SCENE_KEY: &str = "scene";

/// What a panel asks the app to do.
pub enum Command {
    /// Replace the scene (already validated by the panel's widgets' ranges).
    SetScene(Box<Scene>),
    /// Load a shipped preset by file name.
    LoadPreset(&'static str),
}

pub struct ExplorerApp {
    scene: Scene,
    summary: summary_panel::SummaryPanel,
    /// A message for the user (e.g. why a preset did not load), dismissible.
    message: Option<String>,
}

impl ExplorerApp {
    pub fn new(scene: Scene) -> ExplorerApp {
        ExplorerApp {
            scene,
            summary: summary_panel::SummaryPanel::default(),
            message: None,
        }
    }

    fn apply(&mut self, command: Command) {
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
        }
    }
}

impl eframe::App for ExplorerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let mut commands = Vec::new();
        egui::Panel::left("scene")
            .resizable(true)
            .default_size(330.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    commands.extend(scene_panel::show(ui, &self.scene));
                });
            });
        if let Some(message) = &self.message {
            let mut dismissed = false;
            egui::Panel::bottom("message").show(ui, |ui| {
                ui.horizontal(|ui| {
                    ui.colored_label(ui.visuals().error_fg_color, message);
                    dismissed = ui.button("Dismiss").clicked();
                });
            });
            if dismissed {
                self.message = None;
            }
        }
        egui::CentralPanel::default().show(ui, |ui| self.summary.show(ui, &self.scene));
        for c in commands {
            self.apply(c);
        }
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, SCENE_KEY, &self.scene);
    }
}

/// Opens the explorer. The scene comes from the command line when any scene option is given,
/// else from the last session, else the built-in default.
pub fn run(args: SceneArgs) -> anyhow::Result<ExitCode> {
    let from_args = args.preset.is_some() || std::env::args().len() > 1;
    let scene = if from_args { Some(args.scene()?) } else { None };
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_inner_size([1280.0, 800.0])
            .with_title("Atmoscope"),
        ..Default::default()
    };
    eframe::run_native(
        "Atmoscope",
        options,
        Box::new(move |cc| {
            let restored = cc
                .storage
                .and_then(|s| eframe::get_value::<Scene>(s, SCENE_KEY))
                .filter(|s| s.validate().is_ok());
            Ok(Box::new(ExplorerApp::new(
                scene.or(restored).unwrap_or_default(),
            )))
        }),
    )
    .map_err(|e| anyhow::anyhow!("cannot open the explorer window: {e}"))?;
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests;
