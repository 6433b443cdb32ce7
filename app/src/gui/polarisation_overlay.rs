//! What the Polarisation tab draws over its dome: the electric vector's direction as a line per
//! cell (longer where the light is more polarised), the neutral points found in the view
//! (`model::polarisation::neutral_points`), the degree's false-colour legend and a read-out
//! under the pointer. All from the view's radiance image, which in the Polarisation mode holds
//! the Stokes vector (I_Y, Q_Y, U_Y) referred to up in the picture.

use super::gpu_view::{GpuView, Radiance};
use super::sky_tab::{camera, false_colour_bar};
use atmoscope_model::Scene;
use atmoscope_model::camera::Projection;
use atmoscope_model::geometry::direction_from_angles;
use atmoscope_model::polarisation::neutral_points::{self, Kind, NeutralPoint};
use atmoscope_render::View;
use eframe::egui::{self, Color32, Pos2, Stroke, Vec2};
use std::sync::Arc;

/// Height of the legend and read-out under the dome, points.
pub const LEGEND_HEIGHT: f32 = 96.0;
/// Spacing of the electric vector's lines, points.
const LINE_SPACING: f32 = 22.0;
/// A degree of polarisation at or above which a line spans its whole cell.
const FULL_LINE_DEGREE: f64 = 0.8;

/// The degree (0–1) and angle (radians from up in the picture towards view × up) of a Stokes
/// vector (I, Q, U).
fn degree_and_angle(s: [f64; 3]) -> (f64, f64) {
    let degree = if s[0] > 0.0 {
        (s[1].hypot(s[2]) / s[0]).min(1.0)
    } else {
        0.0
    };
    (degree, 0.5 * s[2].atan2(s[1]))
}

/// The screen direction (y down) of an electric vector at `angle` from up in the picture: the
/// frame's second axis, view × up, points right in a perspective picture and left in the dome,
/// which shows the sky as from above.
fn screen_direction(angle: f64, projection: Projection) -> Vec2 {
    let across = if projection == Projection::Fisheye {
        -1.0
    } else {
        1.0
    };
    Vec2::new((across * angle.sin()) as f32, -(angle.cos()) as f32)
}

/// The neutral points of the image, computed once per drawn view.
fn neutral_points_of(
    ctx: &egui::Context,
    generation: u64,
    radiance: &Radiance,
    scene: &Scene,
    view: &View,
) -> Arc<Vec<NeutralPoint>> {
    let id = egui::Id::unique("polarisation neutral points");
    if let Some((g, points)) = ctx.data(|d| d.get_temp::<(u64, Arc<Vec<NeutralPoint>>)>(id))
        && g == generation
    {
        return points;
    }
    let cam = camera(scene, view.projection);
    let a = scene.sun.angles();
    let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
    let qu: Vec<Option<[f64; 2]>> = radiance
        .rgba
        .iter()
        .map(|p| (p[0] > 0.0 && p[3] > 0.0).then_some([f64::from(p[1]), f64::from(p[2])]))
        .collect();
    let points = Arc::new(neutral_points::find(
        &qu,
        radiance.width as usize,
        radiance.height as usize,
        |x, y| {
            cam.ray(x, y, radiance.width, radiance.height)
                .map(|r| r.direction)
        },
        sun,
        cam.position.normalize(),
    ));
    ctx.data_mut(|d| d.insert_temp(id, (generation, points.clone())));
    points
}

/// The lines, the neutral points, the legend and the read-out of the pixel under the pointer.
pub fn show(
    ui: &mut egui::Ui,
    rect: egui::Rect,
    scene: &Scene,
    view: &View,
    gpu: &mut GpuView,
    hovered: Option<(u32, u32)>,
) {
    let generation = gpu.generation();
    let Ok(radiance) = gpu.radiance() else {
        return;
    };
    let to_pixel = |pos: Pos2| {
        let f = (pos - rect.min) / rect.size();
        (
            (f.x * radiance.width as f32) as u32,
            (f.y * radiance.height as f32) as u32,
        )
    };
    let painter = ui.painter_at(rect);
    let columns = (rect.width() / LINE_SPACING).floor() as i32;
    let rows = (rect.height() / LINE_SPACING).floor() as i32;
    for j in 0..rows {
        for i in 0..columns {
            let centre = rect.min
                + Vec2::new(
                    (i as f32 + 0.5) * rect.width() / columns as f32,
                    (j as f32 + 0.5) * rect.height() / rows as f32,
                );
            let (x, y) = to_pixel(centre);
            let Some(s) = radiance.at(x, y).filter(|s| s[0] > 0.0) else {
                continue;
            };
            let (degree, angle) = degree_and_angle(s);
            let half = 0.45 * LINE_SPACING * (degree / FULL_LINE_DEGREE).min(1.0) as f32;
            if half < 1.0 {
                continue;
            }
            let d = screen_direction(angle, view.projection) * half;
            painter.line_segment(
                [centre - d, centre + d],
                Stroke::new(3.0, Color32::from_black_alpha(160)),
            );
            painter.line_segment([centre - d, centre + d], Stroke::new(1.2, Color32::WHITE));
        }
    }
    let points = neutral_points_of(ui.ctx(), generation, &radiance, scene, view);
    let scale = rect.size() / Vec2::new(radiance.width as f32, radiance.height as f32);
    for p in points.iter() {
        let at = rect.min + Vec2::new(p.x as f32, p.y as f32) * scale;
        painter.circle_stroke(at, 7.0, Stroke::new(2.0, Color32::BLACK));
        painter.circle_stroke(at, 7.0, Stroke::new(1.0, Color32::YELLOW));
        painter.text(
            at + Vec2::new(10.0, -10.0),
            egui::Align2::LEFT_BOTTOM,
            p.kind.label(),
            egui::FontId::proportional(13.0),
            Color32::YELLOW,
        );
    }
    legend(
        ui,
        hovered.and_then(|(x, y)| radiance.at(x, y)),
        &points,
        scene,
        view,
    );
}

fn legend(
    ui: &mut egui::Ui,
    hovered: Option<[f64; 3]>,
    points: &[NeutralPoint],
    scene: &Scene,
    view: &View,
) {
    let (bar, _) =
        ui.allocate_exact_size(Vec2::new(ui.available_width(), 14.0), egui::Sense::hover());
    let bar = bar.shrink2(Vec2::new(20.0, 0.0));
    false_colour_bar(ui.painter(), bar);
    for percent in [0, 25, 50, 75, 100] {
        ui.painter().text(
            Pos2::new(
                bar.left() + percent as f32 / 100.0 * bar.width(),
                bar.bottom() + 1.0,
            ),
            egui::Align2::CENTER_TOP,
            format!("{percent} %"),
            egui::FontId::proportional(11.0),
            ui.visuals().text_color(),
        );
    }
    ui.add_space(14.0);
    ui.horizontal_wrapped(|ui| {
        ui.label("degree of polarisation; lines: the electric vector, longer where more polarised")
            .on_hover_text("The share of the light (weighted by the eye's response) that is linearly polarised: single scattering along the view through the model's own transmittance, with a correction for the light scattered more than once, fitted to the vector path tracer. Aerosols add unpolarised light here; the path tracer's vector mode (probe --stokes, reference --stokes) gives a Mie aerosol's own polarisation.");
        ui.separator();
        match hovered.filter(|s| s[0] > 0.0) {
            Some(s) => {
                let (degree, angle) = degree_and_angle(s);
                let side = if view.projection == Projection::Fisheye { "left" } else { "right" };
                ui.label(format!(
                    "under the pointer: {:.1} %, {:.1}° from up towards {side}",
                    100.0 * degree,
                    angle.to_degrees()
                ))
            }
            None => ui.label("hover the dome to read the polarisation"),
        };
    });
    ui.horizontal_wrapped(|ui| {
        if points.is_empty() {
            let why = if scene.sun.angles().elevation_deg > 25.0 {
                "no neutral point in view (with the sun high, Arago's lies below the horizon and Babinet's and Brewster's close to the sun)"
            } else {
                "no neutral point in view (a model of single scattering alone has none: its zeros are the sun and the antisolar point)"
            };
            ui.label(why);
        }
        for p in points {
            let from = match p.kind {
                Kind::Arago | Kind::BelowAntisun => {
                    format!("{:.1}° from the antisolar point", 180.0 - p.from_sun_deg)
                }
                Kind::Babinet | Kind::Brewster => format!("{:.1}° from the sun", p.from_sun_deg),
            };
            ui.label(format!("{}: elevation {:.1}°, {from}", p.kind.label(), p.elevation_deg));
            ui.separator();
        }
    });
}
