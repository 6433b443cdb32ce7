//! The LUTs tab: every table of Hillaire (2020) as the GPU computed it for the current scene,
//! in colour (the batch lanes through the wavelength set's matrix) or one wavelength at a time,
//! with an exposure, the axes' physical meaning and a hover read-out of each texel's coordinates
//! through the same mappings the shaders use (`model::methods::hillaire`).

use super::gpu_view::GpuView;
use atmoscope_model::Scene;
use atmoscope_model::colour::srgb_encode;
use atmoscope_model::methods::hillaire::{
    self as h, AERIAL_PERSPECTIVE_SIZE, Params, aerial_perspective_slice_distance,
};
use atmoscope_model::wavelengths::{LANES, to_linear_srgb};
use atmoscope_render::Table;
use eframe::egui::{self, Sense, Vec2};
use serde::{Deserialize, Serialize};

/// What the tab shows; persisted with the layout.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct LutSettings {
    /// Index into `Table::ALL`.
    pub table: usize,
    /// None: colour; Some(i): wavelength i of the set alone.
    pub lane: Option<usize>,
    pub exposure_ev: f64,
    /// Scale so the brightest texel is white before the exposure.
    pub normalise: bool,
    /// Aerial-perspective slice, 0–31.
    pub slice: u32,
}

impl Default for LutSettings {
    fn default() -> Self {
        LutSettings {
            table: 0,
            lane: None,
            exposure_ev: 0.0,
            normalise: true,
            slice: AERIAL_PERSPECTIVE_SIZE[2] / 2,
        }
    }
}

/// Axis meanings of each table: (x, y).
fn axes(table: Table) -> (&'static str, &'static str) {
    match table {
        Table::Transmittance => (
            "x: view zenith cosine μ, from the horizon of each altitude (left) to straight up (right), Bruneton's mapping",
            "y: altitude h, ground (top row) to the top of the atmosphere (bottom row), √ spacing",
        ),
        Table::MultipleScattering => (
            "x: sun zenith cosine μ_s, −1 (left) to 1 (right)",
            "y: altitude h, ground (top row) to the top (bottom row)",
        ),
        Table::GroundIrradiance => (
            "x: sun zenith cosine μ_s, −1 (left) to 1 (right)",
            "one row",
        ),
        Table::SkyView => (
            "x: azimuth from the sun φ, 0 (left) to 180° (right), √ spacing",
            "y: view zenith θ, zenith (top) to the horizon (middle) to nadir (bottom), quadratic towards the horizon",
        ),
        Table::AerialPerspectiveInscattering | Table::AerialPerspectiveTransmittance => (
            "x: azimuth from the sun φ, 0 (left) to 180° (right)",
            "y: view zenith θ from the horizon (top) down to the nadir (bottom); slices: distance",
        ),
    }
}

/// Physical coordinates of texel (x, y) as text.
fn coordinates(table: Table, p: &Params, camera_h: f64, x: f64, y: f64, slice: u32) -> String {
    let deg = f64::to_degrees;
    match table {
        Table::Transmittance => {
            let (hh, mu) = h::transmittance_h_mu_from_texel(p, x, y);
            format!("h = {:.2} km, μ = {mu:.4}", hh / 1000.0)
        }
        Table::MultipleScattering => {
            let (hh, mu_s) = h::multiple_scattering_h_mu_s_from_texel(p, x, y);
            format!("h = {:.2} km, μ_s = {mu_s:.4}", hh / 1000.0)
        }
        Table::GroundIrradiance => {
            format!("μ_s = {:.4}", h::ground_irradiance_mu_s_from_texel(x))
        }
        Table::SkyView => {
            let (phi, theta) = h::sky_view_angles_from_texel(p, camera_h, x, y);
            format!("φ = {:.1}°, θ = {:.2}°", deg(phi), deg(theta))
        }
        Table::AerialPerspectiveInscattering | Table::AerialPerspectiveTransmittance => {
            let (phi, theta) = h::aerial_perspective_angles_from_texel(p, camera_h, x, y);
            format!(
                "φ = {:.1}°, θ = {:.2}°, distance ≤ {:.2} km",
                deg(phi),
                deg(theta),
                aerial_perspective_slice_distance(slice) / 1000.0
            )
        }
    }
}

fn is_transmittance(table: Table) -> bool {
    matches!(
        table,
        Table::Transmittance | Table::AerialPerspectiveTransmittance
    )
}

/// A table as shown: its image and linear colours, for one engine frame and settings.
struct Shown {
    generation: u64,
    settings: LutSettings,
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
            ui.label("The tables appear once a view has been drawn.");
            return;
        };
        let lanes = p.batches.len() * LANES;
        ui.horizontal(|ui| {
            egui::ComboBox::from_label("table")
                .selected_text(Table::ALL[s.table].name())
                .show_ui(ui, |ui| {
                    for (i, t) in Table::ALL.iter().enumerate() {
                        ui.selectable_value(&mut s.table, i, t.name());
                    }
                })
                .response
                .on_hover_text("Hillaire (2020): transmittance to the top of the atmosphere, multiple-scattering transfer Ψ, light on the ground, the sky seen from the camera, and in-scattering and transmittance along view rays (aerial perspective).");
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
            if s.lane.is_some_and(|l| l >= lanes) {
                s.lane = None;
            }
            ui.add(egui::Slider::new(&mut s.exposure_ev, -10.0..=10.0).suffix(" EV").text("exposure"))
                .on_hover_text("Brightness of the table's image: each EV doubles it.");
            ui.checkbox(&mut s.normalise, "normalise")
                .on_hover_text("Scale the brightest texel to white first, so tables of any unit are visible.");
        });
        let table = Table::ALL[s.table];
        let [w, hh, depth] = table.size();
        if depth > 1 {
            ui.add(egui::Slider::new(&mut s.slice, 0..=depth - 1).text("slice"))
                .on_hover_text(format!(
                    "Distance along the view ray: slice k ends at {:.0} km · ((k + 1)/{depth})².",
                    h::AERIAL_PERSPECTIVE_MAX_DISTANCE_M / 1000.0
                ));
        }
        let (x_axis, y_axis) = axes(table);
        ui.label(x_axis);
        ui.label(y_axis);

        let stale = self
            .cached
            .as_ref()
            .is_none_or(|c| c.generation != gpu.generation() || c.settings != *s);
        if stale {
            match gpu.engine().read_table(table) {
                Ok(data) => {
                    let (w, hh) = (w as usize, hh as usize);
                    let plane = w * hh * depth as usize;
                    let slice = s.slice.min(depth - 1) as usize;
                    let colours: Vec<[f64; 3]> = (0..w * hh)
                        .map(|i| {
                            let per_layer: Vec<[f64; LANES]> = (0..p.batches.len())
                                .map(|l| data[l * plane + slice * w * hh + i].map(f64::from))
                                .collect();
                            match s.lane {
                                Some(k) => [per_layer[k / LANES][k % LANES]; 3],
                                None => {
                                    let batches: Vec<_> =
                                        p.batches.iter().map(|b| b.colour.clone()).collect();
                                    let rgb = to_linear_srgb(&batches, &per_layer);
                                    if is_transmittance(table) {
                                        // Unitless: the colour of transmitted white light.
                                        let white = to_linear_srgb(
                                            &batches,
                                            &vec![[1.0; LANES]; batches.len()],
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
                        settings: *s,
                        texture,
                        colours,
                        size: [w, hh],
                    });
                    self.error = None;
                }
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
                    coordinates(
                        table,
                        p,
                        scene.camera.altitude_m,
                        x as f64,
                        y as f64,
                        s.slice
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
