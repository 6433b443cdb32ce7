//! The Help menu (every key and mouse gesture, from one table that the guide repeats) and the
//! welcome window shown on the first start.

use super::state::{Command, Layout};
use eframe::egui;

/// Every key and gesture of the window: (what to press or do, what it does). The guide's
/// "Shortcuts" table lists the same rows (a test compares them).
pub const SHORTCUTS: &[(&str, &str)] = &[
    (
        "1 – 9",
        "Sky, Fisheye, Luminance, Polarisation, Compare, LUTs, Reference, Bench, Measured",
    ),
    (
        "S / I / P",
        "show or hide the Scene panel / the Inspector / the Performance table",
    ),
    ("F", "full view: only the view and the menu (Esc leaves it)"),
    ("Ctrl+O / Ctrl+S", "open / save a preset"),
    ("Ctrl+Shift+C", "copy the scene as RON"),
    ("Ctrl+E / Ctrl+Shift+E", "export the view as PNG / EXR"),
    (
        "drag",
        "look around (Sky, Luminance); on the Fisheye and Polarisation domes, move the sun",
    ),
    ("Shift-drag", "move the sun (Sky, Luminance)"),
    ("wheel", "raise or lower the camera"),
    ("click", "inspect a pixel: what its light is made of"),
    ("drop a .ron file", "load it as the scene"),
    (
        "panel edges",
        "drag to resize the Scene panel and the Inspector",
    ),
];

/// The shortcuts as the guide's Markdown table.
pub fn shortcuts_markdown() -> String {
    let mut s = String::from("| shortcut | action |\n| --- | --- |\n");
    for (keys, action) in SHORTCUTS {
        s += &format!("| {keys} | {action} |\n");
    }
    s
}

/// The Help menu's contents.
pub fn menu(ui: &mut egui::Ui, layout: &mut Layout) {
    egui::Grid::new("shortcuts")
        .num_columns(2)
        .spacing([16.0, 4.0])
        .show(ui, |ui| {
            for (keys, action) in SHORTCUTS {
                ui.strong(*keys);
                ui.label(*action);
                ui.end_row();
            }
        });
    ui.separator();
    if ui.button("Welcome…").clicked() {
        layout.welcomed = false;
        ui.close();
    }
}

/// The welcome window, until it is closed once: three things to try, the Learn menu and
/// where presets are.
pub fn welcome(ctx: &egui::Context, layout: &mut Layout) -> Vec<Command> {
    let mut commands = Vec::new();
    if layout.welcomed {
        return commands;
    }
    let mut open = true;
    let mut start = false;
    egui::Window::new("Welcome to Atmoscope")
        .open(&mut open)
        .collapsible(false)
        .resizable(false)
        .default_width(420.0)
        .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
        .show(ctx, |ui| {
            ui.label(
                "A physically based sky, drawn live: change the air, the haze, the ozone, \
                 the ground and the sun, and see what the light does.",
            );
            ui.add_space(6.0);
            ui.strong("Three things to try");
            ui.label("1. Shift-drag on the view to lower the sun to the horizon and watch the sunset redden.");
            ui.horizontal_wrapped(|ui| {
                ui.label("2. Open a preset: the Earth's shadow, a sky from orbit…");
                if ui.button("Belt of Venus").clicked() {
                    commands.push(Command::LoadPreset("belt-of-venus.ron"));
                }
            });
            ui.label("3. Click the sky: the Inspector splits that pixel's light into its parts.");
            ui.add_space(6.0);
            ui.strong("Learn");
            ui.label("The Learn menu has short lessons (why the sky is blue, why sunsets redden, …), each with numbers computed for the scene on screen.");
            ui.add_space(6.0);
            ui.strong("Presets");
            ui.label("The shipped presets are in the Scene panel's \"Load a preset…\" menu. Open and save your own with the File menu's Open and Save (Ctrl+O, Ctrl+S), or drop a .ron file on the window.");
            ui.add_space(6.0);
            ui.label("Help lists every key and mouse gesture; this window is there too.");
            ui.add_space(6.0);
            start = ui.button("Start exploring").clicked();
        });
    if !open || start {
        layout.welcomed = true;
    }
    commands
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_guide_lists_every_shortcut_of_the_help_menu() {
        let guide = include_str!("../../../docs/guide.md");
        let table = shortcuts_markdown();
        assert!(
            guide.contains(&table),
            "docs/guide.md's Shortcuts table differs from the Help menu's; it should read:\n{table}"
        );
    }
}
