//! The Performance panel: for each engine drawn this frame, which passes ran and which were
//! skipped (dirty tracking), the time of each pass (GPU timestamps where the device has them,
//! else fenced CPU wall time) and the frame's wall time; plus the UI's own frame interval.

use super::gpu_view::GpuView;
use eframe::egui;

pub fn show(ui: &mut egui::Ui, views: &[(&str, &GpuView)], ui_frame_ms: f64, adapter: &str) {
    ui.horizontal(|ui| {
        ui.strong("Performance");
        ui.label(format!("UI frame interval {ui_frame_ms:.1} ms · {adapter}"))
            .on_hover_text("Time between the last two frames the window drew; the window draws only when something changed or work is in progress.");
    });
    // One grid per view: each may show another model, with passes of its own.
    for (i, (name, v)) in views.iter().enumerate() {
        let stats = v.stats();
        egui::Grid::new(("passes", i)).striped(true).show(ui, |ui| {
            ui.label("view");
            ui.label("model");
            for pass in &stats.passes {
                ui.label(*pass);
            }
            ui.label("frame (wall)");
            ui.label("this frame");
            ui.end_row();
            ui.label(*name);
            ui.label(atmoscope_model::methods::info(stats.method).label);
            for pass in &stats.passes {
                match stats.ms(pass) {
                    Some(ms) => ui.label(format!("{ms:.2} ms")),
                    None if stats.ran(pass) => ui.label("ran"),
                    None => ui.weak("skipped"),
                };
            }
            ui.label(format!("{:.1} ms", v.last_frame_ms))
                .on_hover_text("Wall time of the last frame that ran any pass, from submission until the GPU was idle.");
            let mut ran = format!("{} run, {} skipped", stats.run.len(), stats.skipped.len());
            if stats.sky_tile > 1 {
                // A view in motion on a software adapter: it sharpens in the first still frame.
                ran += &format!("; sky in {0}×{0} tiles", stats.sky_tile);
            }
            match stats.rebuild {
                Some(p) => ui.label(format!(
                    "{ran}; rebuilding tables {:.0} %",
                    100.0 * p.done as f64 / p.total.max(1) as f64
                ))
                .on_hover_text("A new atmosphere is being built a slice per frame; the view shows the last one until it is done."),
                None => ui.label(ran),
            }
            .on_hover_text(stats.timing_source.map_or("", |s| s.label()));
            ui.end_row();
        });
    }
}
