//! The Sky, Fisheye, Luminance and Polarisation tabs: the real-time view with its controls.
//! Drag to look around, the wheel changes altitude, Shift-drag (any drag on a dome) puts the sun
//! under the pointer, a click inspects the pixel. The luminance map adds a legend and a hover
//! read-out; the polarisation dome its legend, the electric vector's lines and the neutral
//! points (`polarisation_overlay`).

use super::gpu_view::{GpuView, building_over, mark, notice, pixels};
use super::polarisation_overlay;
use super::state::{Command, LUMINANCE_LOG10_LIMITS, Layout, Tab, angles_of, projection};
use atmoscope_model::Scene;
use atmoscope_model::camera::{Camera, Projection};
use atmoscope_model::constants::MAX_LUMINOUS_EFFICACY_LM_PER_W;
use atmoscope_model::geometry::Ray;
use atmoscope_model::scene::{MAX_CAMERA_ALTITUDE_M, SunSettings};
use atmoscope_render::{DisplayMode, View};
use eframe::egui::{self, Color32, Pos2, Sense, Stroke, Vec2};

const LEGEND_HEIGHT: f32 = 72.0;
/// Relative altitude change per point of wheel scroll.
const ALTITUDE_PER_SCROLL: f64 = 0.01;
/// Lowest altitude the wheel goes to, m (the slider reaches 0).
const MIN_WHEEL_ALTITUDE_M: f64 = 1.0;

/// The view a tab shows in `points` of screen.
pub fn view_for(tab: Tab, layout: &Layout, size: [u32; 2]) -> View {
    let mut view = View::new(projection(tab), size[0], size[1]);
    if tab == Tab::Luminance {
        view.mode = DisplayMode::Luminance {
            log10_min: layout.luminance_log10_range[0],
            log10_max: layout.luminance_log10_range[1],
        };
    }
    if tab == Tab::Polarisation {
        view.mode = DisplayMode::Polarisation;
    }
    view
}

/// The camera a view of `scene` uses.
pub fn camera(scene: &Scene, projection: Projection) -> Camera {
    Camera::new(
        &scene.camera,
        scene.atmosphere.planet_radius_km * 1000.0,
        projection,
    )
}

/// The ray through the centre of pixel (x, y) of `view`.
pub fn ray_at(scene: &Scene, view: &View, x: u32, y: u32) -> Option<Ray> {
    camera(scene, view.projection).ray(
        f64::from(x) + 0.5,
        f64::from(y) + 0.5,
        view.width,
        view.height,
    )
}

pub fn show(
    ui: &mut egui::Ui,
    scene: &Scene,
    gpu: &mut GpuView,
    tab: Tab,
    layout: &mut Layout,
) -> Vec<Command> {
    let mut commands = Vec::new();
    let mut avail = ui.available_size();
    if tab == Tab::Luminance {
        avail.y -= LEGEND_HEIGHT;
    }
    if tab == Tab::Polarisation {
        avail.y -= polarisation_overlay::LEGEND_HEIGHT;
    }
    let dome = projection(tab) == Projection::Fisheye;
    let points = if dome {
        Vec2::splat(avail.x.min(avail.y))
    } else {
        avail
    }
    .max(Vec2::splat(16.0));
    let view = view_for(
        tab,
        layout,
        pixels(ui.ctx(), points, layout.scale(ui.ctx())),
    );
    gpu.render(scene, &view);
    let response = match gpu.texture() {
        Some(texture) => ui.add(egui::Image::new((texture, points)).sense(Sense::click_and_drag())),
        None if gpu.refused() => {
            // The model refuses this view: the reason, over an empty view that still takes the
            // wheel and the drags that brought it here, so that they can undo it.
            ui.label(notice(scene).unwrap_or_default());
            let (_, response) = ui.allocate_exact_size(
                egui::vec2(points.x, ui.available_height().min(points.y)),
                Sense::click_and_drag(),
            );
            response
        }
        None => {
            let why = notice(scene).or_else(|| gpu.building(scene));
            ui.label(why.unwrap_or("The view has not been drawn yet.".into()));
            return commands;
        }
    };
    let response = response.on_hover_text(match tab {
        Tab::Fisheye | Tab::Polarisation => {
            "Drag to move the sun over the dome · click a pixel to inspect it"
        }
        _ => "Drag to look around · wheel: altitude · Shift-drag: move the sun · click: inspect",
    });
    let rect = response.rect;
    if !gpu.refused() {
        mark(ui, rect, scene);
    }
    if let Some(building) = gpu.building(scene) {
        building_over(ui, rect, building);
    }
    let pixel_at = |pos: Pos2| -> Option<(u32, u32)> {
        let f = (pos - rect.min) / rect.size();
        ((0.0..1.0).contains(&f.x) && (0.0..1.0).contains(&f.y)).then_some({
            (
                (f.x * view.width as f32) as u32,
                (f.y * view.height as f32) as u32,
            )
        })
    };

    let mut s = scene.clone();
    let move_sun = dome || ui.input(|i| i.modifiers.shift);
    if response.dragged() {
        if move_sun {
            let ray = response
                .interact_pointer_pos()
                .and_then(pixel_at)
                .and_then(|(x, y)| ray_at(scene, &view, x, y));
            if let Some(ray) = ray {
                let (elevation_deg, azimuth_deg) = angles_of(ray.direction);
                s.sun = SunSettings::Angles {
                    elevation_deg,
                    azimuth_deg,
                };
            }
        } else {
            // Grab the sky: it follows the pointer.
            let deg_per_point = scene.camera.fov_deg / f64::from(points.y);
            let delta = response.drag_delta();
            let c = &mut s.camera;
            c.heading_deg = (c.heading_deg - f64::from(delta.x) * deg_per_point).rem_euclid(360.0);
            c.pitch_deg = (c.pitch_deg + f64::from(delta.y) * deg_per_point).clamp(-90.0, 90.0);
        }
    }
    if response.hovered() {
        let scroll = f64::from(ui.input(|i| i.smooth_scroll_delta.y));
        if scroll != 0.0 {
            let c = &mut s.camera;
            c.altitude_m = (c.altitude_m.max(MIN_WHEEL_ALTITUDE_M)
                * (-scroll * ALTITUDE_PER_SCROLL).exp())
            .clamp(MIN_WHEEL_ALTITUDE_M, MAX_CAMERA_ALTITUDE_M);
        }
    }
    if response.clicked()
        && let Some((x, y)) = response.interact_pointer_pos().and_then(pixel_at)
    {
        commands.push(Command::Inspect { tab, x, y });
    }
    if s != *scene {
        commands.push(Command::SetScene(Box::new(s)));
    }

    if dome {
        compass(ui.painter(), rect, scene.camera.heading_deg);
    }
    if tab == Tab::Polarisation {
        let hovered = response.hover_pos().and_then(pixel_at);
        polarisation_overlay::show(ui, rect, scene, &view, gpu, hovered);
    }
    if tab == Tab::Luminance {
        let hovered = response.hover_pos().and_then(pixel_at);
        let read_out = hovered.and_then(|(x, y)| {
            let r = gpu.radiance().ok()?;
            let rgb = r.at(x, y)?;
            Some(
                MAX_LUMINOUS_EFFICACY_LM_PER_W * atmoscope_model::colour::linear_srgb_to_xyz(rgb).y,
            )
        });
        legend(ui, layout, read_out);
    }
    commands
}

/// N, E, S, W on the fisheye's horizon circle (the heading is at the top).
fn compass(painter: &egui::Painter, rect: egui::Rect, heading_deg: f64) {
    let centre = rect.center();
    let radius = rect.width().min(rect.height()) * 0.5;
    painter.circle_stroke(
        centre,
        radius,
        Stroke::new(1.0, Color32::from_white_alpha(90)),
    );
    for (label, azimuth) in [("N", 0.0), ("E", 90.0), ("S", 180.0), ("W", 270.0)] {
        let a = ((azimuth - heading_deg) as f32).to_radians();
        let pos = centre + Vec2::new(a.sin(), -a.cos()) * (radius - 12.0);
        painter.text(
            pos,
            egui::Align2::CENTER_CENTER,
            label,
            egui::FontId::proportional(14.0),
            Color32::WHITE,
        );
    }
}

/// The false-colour scale from its low end on the left to its high end on the right.
pub fn false_colour_bar(painter: &egui::Painter, rect: egui::Rect) {
    let n = 64;
    for i in 0..n {
        let t0 = i as f32 / n as f32;
        let c = atmoscope_render::views::false_colour(
            (f64::from(t0) + 0.5 / f64::from(n)).clamp(0.0, 1.0),
        );
        let x0 = rect.left() + t0 * rect.width();
        let x1 = rect.left() + (i + 1) as f32 / n as f32 * rect.width();
        painter.rect_filled(
            egui::Rect::from_min_max(Pos2::new(x0, rect.top()), Pos2::new(x1, rect.bottom())),
            0.0,
            Color32::from_rgb(
                (c[0] * 255.0) as u8,
                (c[1] * 255.0) as u8,
                (c[2] * 255.0) as u8,
            ),
        );
    }
}

/// The false-colour scale with a tick per decade, the range controls and the hover read-out.
fn legend(ui: &mut egui::Ui, layout: &mut Layout, read_out: Option<f64>) {
    let [lo, hi] = layout.luminance_log10_range;
    let (rect, _) = ui.allocate_exact_size(Vec2::new(ui.available_width(), 14.0), Sense::hover());
    // Room at both ends for the first and last tick labels.
    let rect = rect.shrink2(Vec2::new(20.0, 0.0));
    false_colour_bar(ui.painter(), rect);
    ui.horizontal(|ui| {
        for k in (lo.ceil() as i32)..=(hi.floor() as i32) {
            let t = ((f64::from(k) - lo) / (hi - lo)) as f32;
            ui.painter().text(
                Pos2::new(rect.left() + t * rect.width(), rect.bottom() + 1.0),
                egui::Align2::CENTER_TOP,
                format!("10^{k}"),
                egui::FontId::proportional(11.0),
                ui.visuals().text_color(),
            );
        }
    });
    ui.add_space(14.0);
    ui.horizontal_wrapped(|ui| {
        ui.label("cd/m², log scale from 10^");
        let [mut lo, mut hi] = layout.luminance_log10_range;
        ui.add(egui::DragValue::new(&mut lo).range(LUMINANCE_LOG10_LIMITS[0]..=hi - 1.0).speed(0.1))
            .on_hover_text("Lowest luminance shown, as a power of ten (deep twilight ≈ 10^-2, night < 10^-3).");
        ui.label("to 10^");
        ui.add(egui::DragValue::new(&mut hi).range(lo + 1.0..=LUMINANCE_LOG10_LIMITS[1]).speed(0.1))
            .on_hover_text("Highest luminance shown, as a power of ten (a bright sky ≈ 10^4, the sun's disk ≈ 10^9).");
        layout.luminance_log10_range = [lo, hi];
        ui.separator();
        match read_out {
            Some(l) => ui.label(format!("under the pointer: {l:.4e} cd/m²")),
            None => ui.label("hover the map to read the luminance"),
        };
    });
}
