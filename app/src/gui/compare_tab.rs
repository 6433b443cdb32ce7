//! The Compare tab: the current view rendered by two (model, wavelength set) pairs (default
//! Bruneton | Hillaire at Spectral4), side by side or split, with the per-pixel CIEDE2000
//! map between them and the mean ΔE of each against a dense spectral reference (default
//! Hillaire at Spectral32). The models come from the registry; the path tracer is compared in
//! the Reference tab.

use super::gpu_view::{Gpu, GpuView, mark, notice, pixels};
use super::state::{CompareMode, DELTA_E_SCALE_MAX, Layout, Tab, projection};
use atmoscope_eval::metrics::{DisplaySetup, delta_e2000_map, percentile};
use atmoscope_model::Scene;
use atmoscope_model::methods;
use atmoscope_model::scene::{Method, WavelengthSet};
use atmoscope_render::View;
use atmoscope_render::views::false_colour;
use eframe::egui::{self, Sense, Vec2};

/// ΔE2000 figures of one comparison.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Figures {
    pub a_vs_b_mean: f64,
    pub a_vs_b_p95: f64,
    pub a_vs_reference_mean: f64,
    pub b_vs_reference_mean: f64,
}

pub struct CompareTab {
    views: [GpuView; 3],
    /// Generations of the three views the figures were computed from.
    computed: Option<[u64; 3]>,
    pub figures: Option<Figures>,
    heat_map: Option<egui::TextureHandle>,
}

/// A model and a wavelength set, chosen side by side.
fn choice(ui: &mut egui::Ui, label: &str, method: &mut Method, set: &mut WavelengthSet, tip: &str) {
    if !methods::info(*method).is_realtime() {
        *method = Method::default();
    }
    egui::ComboBox::from_id_salt((label, "model"))
        .selected_text(methods::info(*method).label)
        .show_ui(ui, |ui| {
            for m in methods::realtime() {
                ui.selectable_value(method, m.method, m.label)
                    .on_hover_text(m.summary);
            }
        })
        .response
        .on_hover_text(tip);
    set_choice(ui, label, set, tip);
}

fn pair_label(method: Method, set: WavelengthSet) -> String {
    format!("{} {}", methods::info(method).label, set.label())
}

fn set_choice(ui: &mut egui::Ui, label: &str, set: &mut WavelengthSet, tip: &str) {
    egui::ComboBox::from_label(label)
        .selected_text(set.label())
        .show_ui(ui, |ui| {
            for s in [
                WavelengthSet::Rgb3,
                WavelengthSet::Spectral4,
                WavelengthSet::SpectralN(8),
                WavelengthSet::SpectralN(16),
                WavelengthSet::SpectralN(32),
            ] {
                ui.selectable_value(set, s, s.label());
            }
        })
        .response
        .on_hover_text(tip);
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

impl CompareTab {
    pub fn set_rebuild_slices(&mut self, slice: Option<std::time::Duration>) {
        for v in &mut self.views {
            v.set_rebuild_slices(slice);
        }
    }

    /// Whether any of the three views needs more frames of the same scene.
    pub fn settling(&self) -> bool {
        self.views.iter().any(GpuView::settling)
    }

    pub fn new(gpu: &Gpu) -> CompareTab {
        CompareTab {
            views: std::array::from_fn(|_| GpuView::new(gpu)),
            computed: None,
            figures: None,
            heat_map: None,
        }
    }

    /// The views, for the Performance panel.
    pub fn views(&self) -> &[GpuView; 3] {
        &self.views
    }

    pub fn show(&mut self, ui: &mut egui::Ui, scene: &Scene, layout: &mut Layout) {
        let c = &mut layout.compare;
        ui.horizontal_wrapped(|ui| {
            choice(ui, "A", &mut c.a_method, &mut c.a, "Model and wavelengths of the left image.");
            choice(ui, "B", &mut c.b_method, &mut c.b, "Model and wavelengths of the right image.");
            choice(
                ui,
                "reference",
                &mut c.reference_method,
                &mut c.reference,
                "A dense spectral render both are measured against (colour from many bands integrated against the CIE 1931 observer).",
            );
            ui.separator();
            ui.selectable_value(&mut c.mode, CompareMode::SideBySide, "side by side")
                .on_hover_text("A on the left, B on the right, each at half the width.");
            ui.selectable_value(&mut c.mode, CompareMode::Split, "split")
                .on_hover_text("One image, A left of a divider you drag and B right of it: differences show at the seam.");
            ui.selectable_value(&mut c.mode, CompareMode::DeltaE, "ΔE map")
                .on_hover_text("Where A and B differ, per pixel, in CIEDE2000 units.");
        });
        let c = *c;
        let avail = ui.available_size() - Vec2::new(0.0, 40.0);
        let each = match c.mode {
            CompareMode::SideBySide => Vec2::new(avail.x * 0.5 - 4.0, avail.y),
            _ => avail,
        }
        .max(Vec2::splat(16.0));
        let size = pixels(ui.ctx(), each, layout.scale(ui.ctx()));
        let view = View::new(projection(Tab::Sky), size[0], size[1]);
        let pairs = [
            (c.a_method, c.a),
            (c.b_method, c.b),
            (c.reference_method, c.reference),
        ];
        // Three engines, one budget (`FrameBudget`): they build their tables one at a time.
        for (v, (method, set)) in self.views.iter_mut().zip(pairs) {
            let mut s = scene.clone();
            s.render.method = method;
            s.render.wavelengths = set;
            v.render(&s, &view);
        }
        self.update_figures(ui.ctx(), scene);

        if let Some(f) = &self.figures {
            ui.label(format!(
                "ΔE2000 {} vs {}: mean {:.2}, 95th percentile {:.2}   ·   vs {}: A {:.2}, B {:.2}",
                pair_label(c.a_method, c.a),
                pair_label(c.b_method, c.b),
                f.a_vs_b_mean,
                f.a_vs_b_p95,
                pair_label(c.reference_method, c.reference),
                f.a_vs_reference_mean,
                f.b_vs_reference_mean,
            ))
            .on_hover_text("CIEDE2000 between the displayed images (scene exposure and tone map): about 1 is a just-noticeable difference, above 5 is plainly visible.");
        }
        let textures = [self.views[0].texture(), self.views[1].texture()];
        let [Some(ta), Some(tb)] = textures else {
            // A side the model refuses (or not drawn yet): say why.
            for (texture, (method, _)) in textures.iter().zip(pairs) {
                let mut s = scene.clone();
                s.render.method = method;
                if let (None, Some(why)) = (texture, notice(&s)) {
                    ui.label(why);
                }
            }
            for (view, (method, _)) in self.views.iter().zip(pairs) {
                let mut s = scene.clone();
                s.render.method = method;
                if let Some(building) = view.building(&s) {
                    ui.label(building);
                }
            }
            return;
        };
        match c.mode {
            CompareMode::SideBySide => {
                ui.horizontal(|ui| {
                    for (texture, (method, set)) in [(ta, pairs[0]), (tb, pairs[1])] {
                        let response = ui
                            .add(egui::Image::new((texture, each)))
                            .on_hover_text(pair_label(method, set));
                        let mut s = scene.clone();
                        s.render.method = method;
                        mark(ui, response.rect, &s);
                    }
                });
            }
            CompareMode::Split => {
                let response = ui.add(egui::Image::new((tb, each)).sense(Sense::drag()));
                let rect = response.rect;
                let x = rect.left() + layout.compare.split * rect.width();
                let left = egui::Rect::from_min_max(rect.min, egui::pos2(x, rect.bottom()));
                ui.painter().image(
                    ta,
                    left,
                    egui::Rect::from_min_max(
                        egui::pos2(0.0, 0.0),
                        egui::pos2(layout.compare.split, 1.0),
                    ),
                    egui::Color32::WHITE,
                );
                ui.painter().vline(
                    x,
                    rect.y_range(),
                    egui::Stroke::new(2.0, egui::Color32::WHITE),
                );
                if let Some(pos) = response.interact_pointer_pos()
                    && response.dragged()
                {
                    layout.compare.split = ((pos.x - rect.left()) / rect.width()).clamp(0.0, 1.0);
                }
                response.on_hover_text("A on the left, B on the right; drag to move the split.");
            }
            CompareMode::DeltaE => {
                if let Some(map) = &self.heat_map {
                    ui.add(egui::Image::new((map.id(), each)))
                        .on_hover_text(format!("ΔE2000 of A vs B per pixel, false colour from 0 to {DELTA_E_SCALE_MAX}."));
                }
            }
        }
    }

    fn update_figures(&mut self, ctx: &egui::Context, scene: &Scene) {
        // A side the model refuses has no image: no figures rather than stale ones.
        if self.views.iter().any(|v| v.refused()) {
            self.figures = None;
            self.heat_map = None;
            self.computed = None;
            return;
        }
        let generations = [0, 1, 2].map(|i| self.views[i].generation());
        if self.computed == Some(generations) {
            return;
        }
        let images: Result<Vec<_>, _> = self.views.iter_mut().map(|v| v.radiance()).collect();
        let Ok(images) = images else { return };
        let rgb: Vec<Vec<[f64; 3]>> = images.iter().map(|r| r.rgb()).collect();
        let setup = DisplaySetup {
            exposure_ev: scene.display.exposure_ev,
            tone_map: scene.display.tone_map,
            ..DisplaySetup::default()
        };
        let ab = delta_e2000_map(&rgb[0], &rgb[1], setup);
        self.figures = Some(Figures {
            a_vs_b_mean: mean(&ab),
            a_vs_b_p95: percentile(&ab, 0.95),
            a_vs_reference_mean: mean(&delta_e2000_map(&rgb[0], &rgb[2], setup)),
            b_vs_reference_mean: mean(&delta_e2000_map(&rgb[1], &rgb[2], setup)),
        });
        let (w, h) = (images[0].width as usize, images[0].height as usize);
        let pixels: Vec<egui::Color32> = ab
            .iter()
            .map(|&d| {
                let c = false_colour(d / DELTA_E_SCALE_MAX).map(|v| (v * 255.0) as u8);
                egui::Color32::from_rgb(c[0], c[1], c[2])
            })
            .collect();
        let image = egui::ColorImage::new([w, h], pixels);
        self.heat_map = Some(ctx.load_texture("ΔE map", image, egui::TextureOptions::LINEAR));
        self.computed = Some(generations);
    }
}
