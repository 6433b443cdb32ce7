//! The explorer's state below the panels: the tabs, the layout (everything about the window
//! that is not the scene, restored on start) with each tab's settings, and the commands panels
//! return. Panels read this state and change the scene only through commands; no panel
//! imports another.

use super::files::ExportKind;
pub use crate::tab::Tab;
use atmoscope_model::Scene;
use atmoscope_model::camera::Projection;
use atmoscope_model::scene::{Method, WavelengthSet};
use eframe::egui;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// The range of render and drag scales, texels per screen pixel.
pub const SCALE_RANGE: std::ops::RangeInclusive<f32> = 0.25..=1.0;
/// The luminance map's range may lie anywhere in 10^-6 to 10^10 cd/m², at least a decade wide.
pub const LUMINANCE_LOG10_LIMITS: [f64; 2] = [-6.0, 10.0];
/// Image sizes the Reference tab offers.
pub const REFERENCE_SIZES: [(u32, u32); 3] = [(80, 45), (160, 90), (320, 180)];
/// The LUT tab's exposure range, EV.
pub const LUT_EXPOSURE_EV: std::ops::RangeInclusive<f64> = -10.0..=10.0;
/// Paths per pixel the Reference tab may stop at.
pub const REFERENCE_SPP_RANGE: std::ops::RangeInclusive<u64> = 16..=4096;

impl Layout {
    /// The layout with every field brought into its allowed range: a restored layout is
    /// untrusted (an older or hand-edited settings file), and a bad index must not panic a
    /// panel nor an absurd range hang one. What is out of range takes its default.
    pub fn validated(self) -> Layout {
        let d = Layout::default();
        let scale = |v: f32, default: f32| if SCALE_RANGE.contains(&v) { v } else { default };
        let [lo, hi] = self.luminance_log10_range;
        let [min, max] = LUMINANCE_LOG10_LIMITS;
        let luminance_ok = lo >= min && hi <= max && hi - lo >= 1.0;
        let realtime = |m: Method, default: Method| {
            if atmoscope_model::methods::info(m).is_realtime() {
                m
            } else {
                default
            }
        };
        let (c, dc) = (self.compare, d.compare);
        Layout {
            render_scale: scale(self.render_scale, d.render_scale),
            drag_scale: scale(self.drag_scale, d.drag_scale),
            luminance_log10_range: if luminance_ok {
                [lo, hi]
            } else {
                d.luminance_log10_range
            },
            compare: CompareSettings {
                a_method: realtime(c.a_method, dc.a_method),
                b_method: realtime(c.b_method, dc.b_method),
                reference_method: realtime(c.reference_method, dc.reference_method),
                a: if c.a.is_valid() { c.a } else { dc.a },
                b: if c.b.is_valid() { c.b } else { dc.b },
                reference: if c.reference.is_valid() {
                    c.reference
                } else {
                    dc.reference
                },
                split: if (0.0..=1.0).contains(&c.split) {
                    c.split
                } else {
                    dc.split
                },
                mode: c.mode,
            },
            luts: LutSettings {
                exposure_ev: if LUT_EXPOSURE_EV.contains(&self.luts.exposure_ev) {
                    self.luts.exposure_ev
                } else {
                    d.luts.exposure_ev
                },
                ..self.luts
            },
            reference: ReferenceSettings {
                size: self.reference.size.min(REFERENCE_SIZES.len() - 1),
                target_spp: self
                    .reference
                    .target_spp
                    .clamp(*REFERENCE_SPP_RANGE.start(), *REFERENCE_SPP_RANGE.end()),
            },
            ..self
        }
    }

    /// Texels per screen pixel for a view drawn now.
    pub fn scale(&self, ctx: &egui::Context) -> f32 {
        if ctx.input(|i| i.pointer.is_decidedly_dragging()) {
            self.render_scale.min(self.drag_scale)
        } else {
            self.render_scale
        }
    }
}

/// Everything about the window that is not the scene; restored on start.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Layout {
    pub tab: Tab,
    /// Texels per screen pixel of the views (0.25–1): lower is faster on a software renderer.
    pub render_scale: f32,
    /// Scale while the pointer drags (turning, moving the sun, dragging a slider), 0.25–1: the
    /// view follows the pointer at this resolution and is redrawn sharp when the drag ends.
    pub drag_scale: f32,
    /// Luminance map range, log10 cd/m².
    pub luminance_log10_range: [f64; 2],
    pub compare: CompareSettings,
    pub luts: LutSettings,
    pub reference: ReferenceSettings,
    /// The Scene panel on the left (S).
    pub show_scene: bool,
    /// The Inspector on the right (I); clicking a pixel opens it.
    pub show_inspector: bool,
    /// The Performance table under the view (P).
    pub show_performance: bool,
    /// Only the view (and the menu): for presenting, and for measuring a frame of a given size.
    pub full_view: bool,
    /// The welcome window was closed: it is shown on the first start only (Help → Welcome
    /// brings it back).
    pub welcomed: bool,
    /// Burn a caption (scene, model, wavelength set, exposure) under exported PNGs.
    pub caption_exports: bool,
}

impl Default for Layout {
    fn default() -> Self {
        Layout {
            tab: Tab::Sky,
            render_scale: 1.0,
            drag_scale: 0.5,
            luminance_log10_range: atmoscope_model::display::LUMINANCE_LOG10_RANGE,
            compare: CompareSettings::default(),
            luts: LutSettings::default(),
            reference: ReferenceSettings::default(),
            show_scene: true,
            show_inspector: false,
            show_performance: false,
            full_view: false,
            welcomed: false,
            caption_exports: false,
        }
    }
}

/// What a panel asks the app to do.
pub enum Command {
    /// Replace the scene (validated before it is applied).
    SetScene(Box<Scene>),
    /// Load a shipped preset by file name.
    LoadPreset(&'static str),
    /// Load a preset file; on any error the scene stays as it was.
    LoadFile(PathBuf),
    /// Load a preset from its contents (a browser's file picker or a file dropped on the page).
    LoadBytes {
        name: String,
        bytes: Vec<u8>,
    },
    SaveFile(PathBuf),
    CopyRon,
    Export(ExportKind, PathBuf),
    /// Analyse pixel (x, y) of the active view.
    Inspect {
        tab: Tab,
        x: u32,
        y: u32,
    },
    /// Start the Learn menu's lesson of this index.
    StartLesson(usize),
    /// The preset menu is open: load its thumbnails unless they are loaded or loading.
    WantThumbnails,
}

/// ΔE2000 at the top of the heat map's colour scale.
pub const DELTA_E_SCALE_MAX: f64 = 10.0;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
pub enum CompareMode {
    #[default]
    SideBySide,
    Split,
    DeltaE,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct CompareSettings {
    pub a_method: Method,
    pub a: WavelengthSet,
    pub b_method: Method,
    pub b: WavelengthSet,
    pub reference_method: Method,
    pub reference: WavelengthSet,
    pub mode: CompareMode,
    /// Where the split falls, 0–1 from the left.
    pub split: f32,
}

impl Default for CompareSettings {
    fn default() -> Self {
        CompareSettings {
            a_method: Method::Bruneton,
            a: WavelengthSet::Spectral4,
            b_method: Method::Hillaire,
            b: WavelengthSet::Spectral4,
            reference_method: Method::Hillaire,
            reference: WavelengthSet::SpectralN(32),
            mode: CompareMode::SideBySide,
            split: 0.5,
        }
    }
}

/// What the tab shows; persisted with the layout.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct LutSettings {
    /// Registry id of the table; the model's first table when the model has none of that id.
    pub table: String,
    /// None: colour; Some(i): wavelength i of the set alone.
    pub lane: Option<usize>,
    pub exposure_ev: f64,
    /// Scale so the brightest texel is white before the exposure.
    pub normalise: bool,
    /// Slice of a 3D table (clamped to its depth).
    pub slice: u32,
}

impl Default for LutSettings {
    fn default() -> Self {
        LutSettings {
            table: "transmittance".into(),
            lane: None,
            exposure_ev: 0.0,
            normalise: true,
            slice: 16,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ReferenceSettings {
    /// Index into the sizes offered.
    pub size: usize,
    /// Stop after this many paths per pixel (16–4096).
    pub target_spp: u64,
}

impl Default for ReferenceSettings {
    fn default() -> Self {
        ReferenceSettings {
            size: 1,
            target_spp: 256,
        }
    }
}

/// The projection a tab draws.
pub fn projection(tab: Tab) -> Projection {
    match tab {
        Tab::Fisheye | Tab::Polarisation => Projection::Fisheye,
        _ => Projection::Perspective,
    }
}

/// Direction of a ray as (elevation, azimuth) in degrees, for labels.
pub fn angles_of(d: DVec3) -> (f64, f64) {
    (
        d.z.clamp(-1.0, 1.0).asin().to_degrees(),
        d.x.atan2(d.y).to_degrees().rem_euclid(360.0),
    )
}
