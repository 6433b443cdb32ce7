//! The centre panel: the scene's name and description and its summary per wavelength (optical
//! depths, aerosol optics, direct sun transmittance), recomputed only when the scene changes.

use crate::summary::{self, Info};
use atmoscope_model::Scene;
use eframe::egui;

const WAVELENGTHS_NM: [f64; 10] = [
    380.0, 400.0, 450.0, 500.0, 550.0, 600.0, 650.0, 700.0, 750.0, 800.0,
];

#[derive(Default)]
pub struct SummaryPanel {
    cached: Option<(Scene, Info)>,
}

impl SummaryPanel {
    fn info(&mut self, scene: &Scene) -> &Info {
        let stale = self.cached.as_ref().is_none_or(|(s, _)| s != scene);
        if stale {
            self.cached = Some((scene.clone(), summary::compute(scene, &WAVELENGTHS_NM)));
        }
        &self.cached.as_ref().expect("just filled").1
    }

    /// The summary last drawn.
    pub fn shown(&self) -> Option<&Info> {
        self.cached.as_ref().map(|(_, info)| info)
    }

    pub fn show(&mut self, ui: &mut egui::Ui, scene: &Scene) {
        ui.heading(&scene.name);
        ui.label(&scene.description);
        ui.separator();
        let info = self.info(scene);
        ui.label(format!(
            "Sun: elevation {:.2}°, azimuth {:.2}°   ·   ozone column {:.1} DU   ·   aerosol {} (AOD at 550 nm {:.3})",
            info.sun_elevation_deg, info.sun_azimuth_deg, info.ozone_column_du, info.aerosol_type, info.aod550
        ));
        ui.add_space(6.0);
        ui.strong("Vertical optical depth from the camera to space, and direct sunlight reaching the camera");
        egui::Grid::new("summary")
            .striped(true)
            .num_columns(9)
            .show(ui, |ui| {
                for h in [
                    "λ (nm)",
                    "τ Rayleigh",
                    "τ ozone",
                    "τ aerosol",
                    "τ total",
                    "aerosol SSA",
                    "aerosol g",
                    "T sun",
                    "T horizontal",
                ] {
                    ui.strong(h);
                }
                ui.end_row();
                for r in &info.wavelengths {
                    let d = &r.optical_depth;
                    ui.label(format!("{:.0}", r.wavelength_nm));
                    for v in [d.rayleigh, d.ozone, d.aerosol, d.total] {
                        ui.monospace(format!("{v:.5}"));
                    }
                    ui.monospace(format!("{:.4}", r.aerosol_ssa));
                    ui.monospace(format!("{:.4}", r.aerosol_g));
                    ui.monospace(format!("{:.4}", r.direct_transmittance));
                    ui.monospace(format!("{:.4}", r.horizontal_transmittance));
                    ui.end_row();
                }
            });
        ui.add_space(6.0);
        ui.small(
            "τ is the optical depth: light crossing it is dimmed by e^−τ. SSA is the share of the aerosol's \
             extinction that is scattering rather than absorption; g is the mean cosine of its scattering angle. \
             T sun is zero when the sun is below the horizon or the camera is in the planet's shadow; \
             T horizontal is what a ray skimming the ground from the camera keeps.",
        );
    }
}
