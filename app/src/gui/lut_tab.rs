//! The LUTs tab: every table of the model on screen as the GPU computed it for the current
//! scene, in colour (the batch lanes through the wavelength set's matrix) or one wavelength at a
//! time, with an exposure, the axes' physical meaning and a hover read-out of each texel's
//! coordinates — all from the table's declaration in the model registry
//! (`model::methods::MODELS`), so a new model's tables appear here with no change.

use super::gpu_view::GpuView;
use super::state::{LUT_EXPOSURE_EV, LutSettings};
use atmoscope_model::Scene;
use atmoscope_model::colour::srgb_encode;
use atmoscope_model::lanes::Lanes;
use atmoscope_model::methods::{self, shared::TableSpec};
use atmoscope_model::wavelengths::{LANES, to_linear_srgb};
use eframe::egui::{self, Sense, Vec2};

/// A table as shown: its image and linear colours, for one engine frame and settings.
struct Shown {
    generation: u64,
    settings: LutSettings,
    table: TableSpec,
    texture: egui::TextureHandle,
    colours: Vec<[f64; 3]>,
    size: [usize; 2],
}

#[derive(Default)]
pub struct LutTab {
    cached: Option<Shown>,
    error: Option<String>,
}

impl LutTab {
    pub fn show(&mut self, ui: &mut egui::Ui, scene: &Scene, gpu: &GpuView, s: &mut LutSettings) {
        let Some(p) = gpu.engine().params() else {
            ui.label(
                gpu.building(scene)
                    .unwrap_or("The tables appear once a view has been drawn.".into()),
            );
            return;
        };
        let model = methods::info(gpu.stats().method);
        let Some(&first) = model.tables.first() else {
            ui.label(format!("{} has no tables.", model.label));
            return;
        };
        let table = *model.table(&s.table).unwrap_or(&first);
        s.table = table.id.to_string();
        let lanes = p.batches.len() * LANES;
        // A lane of a larger set (an earlier scene, a restored layout) falls back to colour.
        if s.lane.is_some_and(|l| l >= lanes) {
            s.lane = None;
        }
        ui.horizontal_wrapped(|ui| {
            egui::ComboBox::from_label("table")
                .selected_text(table.label)
                .show_ui(ui, |ui| {
                    for t in model.tables {
                        ui.selectable_value(&mut s.table, t.id.to_string(), t.label)
                            .on_hover_text(t.invalidated_by.names().join(", "));
                    }
                })
                .response
                .on_hover_text(format!("The tables {} precomputes: {}", model.label, model.summary));
            let lane_text = |l: Option<usize>| match l {
                None => "colour".to_string(),
                Some(i) => format!(
                    "{:.0} nm",
                    p.batches[i / LANES].colour.wavelengths_nm[i % LANES]
                ),
            };
            egui::ComboBox::from_label("channel")
                .selected_text(lane_text(s.lane))
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut s.lane, None, lane_text(None));
                    for i in 0..lanes {
                        ui.selectable_value(&mut s.lane, Some(i), lane_text(Some(i)));
                    }
                })
                .response
                .on_hover_text("Colour combines every wavelength of the set with its matrix to sRGB; a single wavelength shows that band alone in grey.");
        });
        // A slider with its value and label is three widgets: on a row of its own, so that a
        // narrow panel never splits it.
        ui.horizontal_wrapped(|ui| {
            ui.add(
                egui::Slider::new(&mut s.exposure_ev, LUT_EXPOSURE_EV)
                    .suffix(" EV")
                    .text("exposure"),
            )
            .on_hover_text("Brightness of the table's image: each EV doubles it.");
            ui.checkbox(&mut s.normalise, "normalise").on_hover_text(
                "Scale the brightest texel to white first, so tables of any unit are visible.",
            );
        });
        let [w, hh, depth] = table.size;
        s.slice = s.slice.min(depth - 1);
        if depth > 1 {
            ui.add(egui::Slider::new(&mut s.slice, 0..=depth - 1).text("slice"))
                .on_hover_text(table.axes[2]);
        }
        for axis in table.axes.iter().filter(|a| !a.is_empty()) {
            ui.label(*axis);
        }

        let stale = self
            .cached
            .as_ref()
            .is_none_or(|c| c.generation != gpu.generation() || c.settings != *s);
        if stale {
            match gpu.engine().read_table(table.id) {
                Ok(data) => {
                    let (w, hh) = (w as usize, hh as usize);
                    let plane = w * hh * depth as usize;
                    let slice = s.slice.min(depth - 1) as usize;
                    let colours: Vec<[f64; 3]> = (0..w * hh)
                        .map(|i| {
                            let per_layer: Vec<Lanes> = (0..p.batches.len())
                                .map(|l| Lanes(data[l * plane + slice * w * hh + i].map(f64::from)))
                                .collect();
                            match s.lane {
                                Some(k) => [per_layer[k / LANES][k % LANES]; 3],
                                None => {
                                    let batches: Vec<_> =
                                        p.batches.iter().map(|b| b.colour.clone()).collect();
                                    let rgb = to_linear_srgb(&batches, &per_layer);
                                    if table.transmittance {
                                        // Unitless: the colour of transmitted white light.
                                        let white = to_linear_srgb(
                                            &batches,
                                            &vec![Lanes::ONE; batches.len()],
                                        );
                                        std::array::from_fn(|c| rgb[c] / white[c])
                                    } else {
                                        rgb
                                    }
                                }
                            }
                        })
                        .collect();
                    let peak = colours
                        .iter()
                        .flat_map(|c| c.iter().copied())
                        .fold(0.0f64, f64::max);
                    let scale = if s.normalise && peak > 0.0 {
                        1.0 / peak
                    } else {
                        1.0
                    } * 2f64.powf(s.exposure_ev);
                    let pixels = colours
                        .iter()
                        .map(|c| {
                            let e = c.map(|v| {
                                (srgb_encode((v * scale).clamp(0.0, 1.0)) * 255.0).round() as u8
                            });
                            egui::Color32::from_rgb(e[0], e[1], e[2])
                        })
                        .collect();
                    let texture = ui.ctx().load_texture(
                        "lut",
                        egui::ColorImage::new([w, hh], pixels),
                        egui::TextureOptions::NEAREST,
                    );
                    self.cached = Some(Shown {
                        generation: gpu.generation(),
                        settings: s.clone(),
                        table,
                        texture,
                        colours,
                        size: [w, hh],
                    });
                    self.error = None;
                }
                // A browser's read-back: the waker draws the next frame when it has come.
                Err(e) if e.is_pending() => {}
                Err(e) => self.error = Some(e.to_string()),
            }
        }
        if let Some(e) = &self.error {
            ui.colored_label(ui.visuals().error_fg_color, e);
        }
        let Some(Shown {
            texture,
            colours,
            size: [w, hh],
            table,
            ..
        }) = &self.cached
        else {
            return;
        };
        let avail = ui.available_size() - Vec2::new(0.0, 24.0);
        let aspect = *w as f32 / (*hh).max(1) as f32;
        let size = if *hh == 1 {
            Vec2::new(avail.x, 40.0)
        } else if avail.x / avail.y > aspect {
            Vec2::new(avail.y * aspect, avail.y)
        } else {
            Vec2::new(avail.x, avail.x / aspect)
        };
        let response = ui.add(egui::Image::new((texture.id(), size)).sense(Sense::hover()));
        let text = match response.hover_pos() {
            Some(pos) => {
                let f = (pos - response.rect.min) / response.rect.size();
                let (x, y) = (
                    ((f.x * *w as f32) as usize).min(w - 1),
                    ((f.y * *hh as f32) as usize).min(hh - 1),
                );
                let c = colours[y * w + x];
                format!(
                    "texel ({x}, {y}): {} · value ({:.4e}, {:.4e}, {:.4e})",
                    (table.describe_texel)(
                        p,
                        scene.camera.altitude_m,
                        [x as f64, y as f64, f64::from(s.slice)]
                    ),
                    c[0],
                    c[1],
                    c[2]
                )
            }
            None => format!(
                "{w} × {hh} texels × {} wavelengths; hover for coordinates",
                lanes
            ),
        };
        ui.label(text);
    }
}
