//! The Reference tab: the spectral path tracer (`model::reference`) rendering the current
//! perspective view progressively off the UI thread (in a browser, in bands of rows between
//! frames), with its samples per pixel and noise, next
//! to the real-time render at the same size and the CIEDE2000 map between them.

use super::gpu_view::{Gpu, GpuView};
use super::jobs::{Job, Step};
use atmoscope_eval::metrics::{DisplaySetup, delta_e2000_map};
use atmoscope_model::Scene;
use atmoscope_model::camera::Projection;
use atmoscope_model::display::{display_balanced, to_u8};
use atmoscope_model::methods::path_tracer::PathTracerSettings;
use atmoscope_model::reference::ReferenceRender;
use atmoscope_render::View;
use atmoscope_render::views::false_colour;
use eframe::egui::{self, Vec2};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

use super::state::{DELTA_E_SCALE_MAX, REFERENCE_SIZES, REFERENCE_SPP_RANGE, ReferenceSettings};

/// Paths per pixel added by each progressive pass.
const SPP_PER_PASS: u32 = 4;

/// The path tracer's state after a pass.
#[derive(Clone)]
pub struct Snapshot {
    pub rgb: Vec<[f64; 3]>,
    pub spp: u64,
    /// Mean relative standard error of pixel luminance.
    pub noise: f64,
}

struct Run {
    scene: Scene,
    /// Cleared while the tab is hidden: the worker waits instead of tracing.
    visible: Arc<AtomicBool>,
    settings: ReferenceSettings,
    job: Job<()>,
    latest: Arc<Mutex<Option<Snapshot>>>,
}

pub struct ReferenceTab {
    run: Option<Run>,
    realtime: GpuView,
    /// spp of the snapshot shown, and its images.
    shown: Option<u64>,
    /// The path-traced image shown and the paths per pixel it had.
    reference: Option<(u64, egui::TextureHandle)>,
    /// The ΔE2000 map of the real-time view against it.
    heat: Option<egui::TextureHandle>,
    pub delta_e_mean: Option<f64>,
    pub snapshot: Option<Snapshot>,
}

impl ReferenceTab {
    pub fn new(gpu: &Gpu) -> ReferenceTab {
        // Its tables are built in slices like every view's; it is compared with the path
        // tracer's only once they are the scene's (`update`).
        let realtime = GpuView::new(gpu);
        ReferenceTab {
            run: None,
            realtime,
            shown: None,
            reference: None,
            heat: None,
            delta_e_mean: None,
            snapshot: None,
        }
    }

    pub fn job(&self) -> Option<&Job<()>> {
        self.run.as_ref().map(|r| &r.job).filter(|j| j.is_running())
    }

    /// Paths per pixel the worker has reached (whether or not shown yet).
    pub fn latest_spp(&self) -> Option<u64> {
        let run = self.run.as_ref()?;
        run.latest.lock().ok()?.as_ref().map(|s| s.spp)
    }

    /// Pauses the path tracer while the tab is hidden and resumes it when shown.
    pub fn set_visible(&self, visible: bool) {
        if let Some(run) = &self.run {
            run.visible.store(visible, Ordering::Relaxed);
        }
    }

    pub fn realtime(&self) -> &GpuView {
        &self.realtime
    }

    /// Sets how the real-time view builds a new atmosphere (`GpuView::set_rebuild_slices`).
    pub fn set_rebuild_slices(&mut self, slice: Option<std::time::Duration>) {
        self.realtime.set_rebuild_slices(slice);
    }

    fn start(&mut self, ctx: &egui::Context, scene: &Scene, settings: ReferenceSettings) {
        if let Some(run) = &self.run {
            run.job.cancel();
        }
        let (w, h) = REFERENCE_SIZES[settings.size.min(REFERENCE_SIZES.len() - 1)];
        let latest = Arc::new(Mutex::new(None));
        let out = latest.clone();
        let s = scene.clone();
        let target = settings
            .target_spp
            .clamp(*REFERENCE_SPP_RANGE.start(), *REFERENCE_SPP_RANGE.end());
        let visible = Arc::new(AtomicBool::new(true));
        let shown = visible.clone();
        // The tracer goes through each pass in bands of rows: natively a band is the whole
        // image (a thread's loop); in a browser it is steered to half a frame's share of work.
        let mut render: Option<ReferenceRender> = None;
        let mut next_row = 0;
        let mut band_rows = if cfg!(target_arch = "wasm32") { 1 } else { h };
        let job = Job::spawn_steps(format!("path tracing {w}×{h}"), ctx, move |progress| {
            if progress.cancelled() {
                return Step::Done(());
            }
            // A hidden tab costs nothing: wait until it is shown again.
            if !shown.load(Ordering::Relaxed) {
                return Step::Wait;
            }
            let render = render.get_or_insert_with(|| {
                ReferenceRender::new(
                    &s,
                    Projection::Perspective,
                    w,
                    h,
                    1,
                    PathTracerSettings::default(),
                )
            });
            if next_row == 0 && render.samples_per_pixel() >= target {
                return Step::Done(());
            }
            let end = (next_row + band_rows).min(h);
            let started = web_time::Instant::now();
            if !render.run_rows(SPP_PER_PASS, next_row..end, progress.cancel_flag()) {
                return Step::Done(());
            }
            if cfg!(target_arch = "wasm32") {
                let per_row = started.elapsed().as_secs_f64() / f64::from(end - next_row);
                let aim = 0.5 * super::jobs::FRAME_BUDGET.as_secs_f64();
                band_rows = ((aim / per_row.max(1e-9)) as u32).clamp(1, h);
            }
            next_row = end % h;
            if next_row == 0 {
                let snapshot = Snapshot {
                    rgb: render.linear_srgb(),
                    spp: render.samples_per_pixel(),
                    noise: render.mean_relative_error(),
                };
                if let Ok(mut l) = out.lock() {
                    *l = Some(snapshot);
                }
                progress.set(render.samples_per_pixel() as f32 / target as f32);
            }
            Step::Again
        });
        self.run = Some(Run {
            scene: scene.clone(),
            visible,
            settings,
            job,
            latest,
        });
        self.shown = None;
        self.snapshot = None;
        self.delta_e_mean = None;
        // A map of the last scene's images would say nothing of this one's.
        self.heat = None;
    }

    pub fn show(&mut self, ui: &mut egui::Ui, scene: &Scene, settings: &mut ReferenceSettings) {
        ui.horizontal_wrapped(|ui| {
            egui::ComboBox::from_label("size")
                .selected_text(format!(
                    "{}×{}",
                    REFERENCE_SIZES[settings.size].0, REFERENCE_SIZES[settings.size].1
                ))
                .show_ui(ui, |ui| {
                    for (i, (w, h)) in REFERENCE_SIZES.iter().enumerate() {
                        ui.selectable_value(&mut settings.size, i, format!("{w}×{h}"));
                    }
                })
                .response
                .on_hover_text(
                    "Pixels of the reference: the path tracer's time grows with their number.",
                );
            ui.add(
                egui::Slider::new(&mut settings.target_spp, REFERENCE_SPP_RANGE)
                    .logarithmic(true)
                    .text("paths per pixel"),
            )
            .on_hover_text(
                "The render stops at this many paths per pixel; noise falls as 1/√paths.",
            );
            if ui.button("Restart").clicked() {
                self.run = None;
            }
        });
        let stale = self
            .run
            .as_ref()
            .is_none_or(|r| r.scene != *scene || r.settings != *settings);
        if stale {
            self.start(ui.ctx(), scene, *settings);
        }
        let (w, h) = REFERENCE_SIZES[settings.size.min(REFERENCE_SIZES.len() - 1)];
        self.realtime
            .render(scene, &View::new(Projection::Perspective, w, h));

        let latest = self
            .run
            .as_ref()
            .and_then(|r| r.latest.lock().ok().and_then(|l| l.clone()));
        if let Some(snapshot) = latest
            && (self.shown != Some(snapshot.spp) || self.heat.is_none())
        {
            self.update(ui.ctx(), scene, &snapshot, (w, h));
            self.snapshot = Some(snapshot);
        }
        if let Some(job) = self.job() {
            job.show(ui);
        }
        match (&self.snapshot, self.delta_e_mean) {
            (Some(s), Some(de)) => ui.label(format!(
                "{} paths per pixel · noise {:.2} % (mean relative standard error of luminance) · ΔE2000 real-time vs reference: mean {:.2}",
                s.spp,
                100.0 * s.noise,
                de
            )),
            _ => ui.label(
                self.realtime
                    .building(scene)
                    .unwrap_or("Waiting for the first pass…".into()),
            ),
        };
        let avail = ui.available_size();
        let each = Vec2::new(
            avail.x / 3.0 - 6.0,
            (avail.x / 3.0 - 6.0) * h as f32 / w as f32,
        )
        .min(Vec2::new(avail.x, avail.y - 20.0).max(Vec2::splat(16.0)));
        ui.horizontal(|ui| {
            let captions = ["path traced", "real time", "ΔE2000 (0–10)"];
            let ids = [
                self.reference.as_ref().map(|(_, t)| t.id()),
                self.realtime.texture(),
                self.heat.as_ref().map(egui::TextureHandle::id),
            ];
            for (caption, id) in captions.iter().zip(ids) {
                ui.vertical(|ui| {
                    ui.label(*caption);
                    if let Some(id) = id {
                        ui.add(egui::Image::new((id, each)));
                    }
                });
            }
        });
    }

    fn update(
        &mut self,
        ctx: &egui::Context,
        scene: &Scene,
        snapshot: &Snapshot,
        (w, h): (u32, u32),
    ) {
        let d = &scene.display;
        let balance = atmoscope_model::white_balance::matrix(scene);
        let image =
            |pixels: Vec<egui::Color32>| egui::ColorImage::new([w as usize, h as usize], pixels);
        let options = egui::TextureOptions::NEAREST;
        if self
            .reference
            .as_ref()
            .is_none_or(|(spp, _)| *spp != snapshot.spp)
        {
            let reference = image(
                snapshot
                    .rgb
                    .iter()
                    .map(|&c| {
                        let e = display_balanced(c, &balance, d.exposure_ev, d.tone_map).map(to_u8);
                        egui::Color32::from_rgb(e[0], e[1], e[2])
                    })
                    .collect(),
            );
            let texture = ctx.load_texture("reference", reference, options);
            self.reference = Some((snapshot.spp, texture));
        }
        // While the real-time view's tables are built in slices it shows the previous
        // atmosphere, or nothing: no comparison until it is the scene's.
        if self.realtime.engine().rebuilding() {
            return;
        }
        let Ok(realtime) = self.realtime.radiance() else {
            return;
        };
        if realtime.rgba.len() != snapshot.rgb.len() {
            return;
        }
        let map = delta_e2000_map(
            &realtime.rgb(),
            &snapshot.rgb,
            DisplaySetup {
                exposure_ev: d.exposure_ev,
                tone_map: d.tone_map,
                ..DisplaySetup::default()
            },
        );
        self.delta_e_mean = Some(map.iter().sum::<f64>() / map.len().max(1) as f64);
        let heat = image(
            map.iter()
                .map(|&de| {
                    let c = false_colour(de / DELTA_E_SCALE_MAX).map(|v| (v * 255.0) as u8);
                    egui::Color32::from_rgb(c[0], c[1], c[2])
                })
                .collect(),
        );
        self.heat = Some(ctx.load_texture("reference ΔE", heat, options));
        self.shown = Some(snapshot.spp);
    }
}

impl Drop for ReferenceTab {
    fn drop(&mut self) {
        if let Some(run) = &self.run {
            run.job.cancel();
        }
    }
}
