//! The explorer's centre tabs. They live apart from the GUI because the Learn menu's lessons
//! (read from files, also by `atmoscope learn`) name the tab that shows their sight.

use eframe::egui;
use serde::{Deserialize, Serialize};

/// The centre tabs, with their shortcut keys 1–9.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
pub enum Tab {
    #[default]
    Sky,
    Fisheye,
    Luminance,
    Polarisation,
    Compare,
    Luts,
    Reference,
    Bench,
    Measured,
}

impl Tab {
    pub const ALL: [Tab; 9] = [
        Tab::Sky,
        Tab::Fisheye,
        Tab::Luminance,
        Tab::Polarisation,
        Tab::Compare,
        Tab::Luts,
        Tab::Reference,
        Tab::Bench,
        Tab::Measured,
    ];

    pub fn label(self) -> &'static str {
        match self {
            Tab::Sky => "Sky",
            Tab::Fisheye => "Fisheye",
            Tab::Luminance => "Luminance",
            Tab::Polarisation => "Polarisation",
            Tab::Compare => "Compare",
            Tab::Luts => "LUTs",
            Tab::Reference => "Reference",
            Tab::Bench => "Bench",
            Tab::Measured => "Measured",
        }
    }

    pub fn description(self) -> &'static str {
        match self {
            Tab::Sky => "The view from the camera, drawn live by the scene's sky model.",
            Tab::Fisheye => {
                "The whole sky dome from the camera, zenith in the centre, horizon on the circle."
            }
            Tab::Luminance => {
                "Brightness as the eye weighs it (cd/m²), in false colour on a log scale."
            }
            Tab::Polarisation => {
                "The sky dome's degree of polarisation in false colour, the direction of its electric vector as lines, and the neutral points."
            }
            Tab::Compare => {
                "The same view by two models or wavelength sets, and how much their colours differ (ΔE2000)."
            }
            Tab::Luts => "The lookup tables the sky model precomputes, and what their axes mean.",
            Tab::Reference => {
                "A spectral path tracer's ground truth of the view, next to the real-time render."
            }
            Tab::Bench => {
                "Every model's frame time against its error from the path tracer, from `atmoscope bench methods`; click a point to render that model."
            }
            Tab::Measured => {
                "A measured sky (spectroradiometer scans) beside the model's, each measured direction coloured by the model's error; click one for its spectra."
            }
        }
    }

    pub fn key(self) -> egui::Key {
        const KEYS: [egui::Key; 9] = [
            egui::Key::Num1,
            egui::Key::Num2,
            egui::Key::Num3,
            egui::Key::Num4,
            egui::Key::Num5,
            egui::Key::Num6,
            egui::Key::Num7,
            egui::Key::Num8,
            egui::Key::Num9,
        ];
        KEYS[Tab::ALL.iter().position(|&t| t == self).unwrap_or(0)]
    }
}
