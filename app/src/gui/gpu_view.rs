//! One engine drawing into an egui texture: the Sky, Fisheye, Luminance, Compare and Reference
//! tabs each own one. The engine's dirty tracking means an unchanged view runs no GPU pass; the
//! egui texture is rebound only when a frame actually drew something.

use atmoscope_model::Scene;
use atmoscope_model::display::Histogram;
use atmoscope_render::{Engine, EngineError, FrameStats, View};
use eframe::egui;
use eframe::egui_wgpu::{self, wgpu};
use std::sync::Arc;
use std::time::Duration;
use web_time::Instant;

/// The device egui renders with, shared by every engine of the window.
#[derive(Clone)]
pub struct Gpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub renderer: Arc<egui::mutex::RwLock<egui_wgpu::Renderer>>,
    pub adapter: String,
    /// A CPU implementation (lavapipe): its timestamps are taken at recording, so per-pass
    /// times come from fenced wall time instead.
    pub software: bool,
    /// How the views' engines build a new atmosphere (`Engine::set_rebuild_slices`): in
    /// slices across frames in the window, at once where frames are stepped without waiting
    /// for the GPU (the UI tests).
    pub rebuild_slice: Option<Duration>,
    /// The window's one slice of a rebuild per frame, which its views share.
    pub budget: FrameBudget,
}

/// The window's budget of rebuild slices for one frame: the first view that builds in a frame
/// takes it, and the views drawn after it hold their builds where they are
/// (`Engine::hold_rebuild`), so that two engines building at once do not double the frame.
/// The window frees it at the start of each frame ([`FrameBudget::new_frame`]).
#[derive(Clone, Default)]
pub struct FrameBudget(Arc<std::sync::atomic::AtomicBool>);

impl FrameBudget {
    /// A new frame: no view has built in it yet.
    pub fn new_frame(&self) {
        self.0.store(false, std::sync::atomic::Ordering::Relaxed);
    }

    fn taken(&self) -> bool {
        self.0.load(std::sync::atomic::Ordering::Relaxed)
    }

    fn take(&self) {
        self.0.store(true, std::sync::atomic::Ordering::Relaxed);
    }
}

impl Gpu {
    pub fn from_render_state(rs: &egui_wgpu::RenderState) -> Gpu {
        let info = rs.adapter.get_info();
        Gpu {
            device: rs.device.clone(),
            queue: rs.queue.clone(),
            renderer: rs.renderer.clone(),
            adapter: format!("{} ({:?}, {:?})", info.name, info.backend, info.device_type),
            software: info.device_type == wgpu::DeviceType::Cpu,
            // In a browser the GPU works in a process of its own: a whole build never stalls
            // the page, while slices would be paced by frames the compositor may make slow.
            rebuild_slice: (!cfg!(target_arch = "wasm32"))
                .then_some(crate::engine_setup::REBUILD_SLICE),
            budget: FrameBudget::default(),
        }
    }
}

/// Linear radiance of a rendered frame, read back once and kept while the frame stands.
pub struct Radiance {
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<[f32; 4]>,
}

impl Radiance {
    pub fn at(&self, x: u32, y: u32) -> Option<[f64; 3]> {
        (x < self.width && y < self.height).then(|| {
            let p = self.rgba[(y * self.width + x) as usize];
            [p[0], p[1], p[2]].map(f64::from)
        })
    }

    pub fn rgb(&self) -> Vec<[f64; 3]> {
        self.rgba
            .iter()
            .map(|p| [p[0], p[1], p[2]].map(f64::from))
            .collect()
    }
}

pub struct GpuView {
    engine: Engine,
    gpu: Gpu,
    texture: Option<egui::TextureId>,
    view: Option<View>,
    /// Counts frames that drew something; keys the caches of read-backs.
    generation: u64,
    radiance: Option<(u64, Arc<Radiance>)>,
    histogram: Option<(u64, Arc<Histogram>)>,
    /// Wall time of the last frame that ran a pass, from `render` until the GPU was idle, ms.
    pub last_frame_ms: f64,
    /// The last frame's GPU fault, until the app shows it.
    fault: Option<String>,
    /// Whether the scene's model refused the last frame (or is offline): the view then shows
    /// nothing rather than an earlier frame, and `notice` says why.
    refused: bool,
}

impl GpuView {
    pub fn new(gpu: &Gpu) -> GpuView {
        let setup = crate::engine_setup::EngineSetup {
            rebuild_slice: gpu.rebuild_slice,
            cpu_timing: gpu.software,
            ..crate::engine_setup::EngineSetup::explorer(&gpu.device)
        };
        let engine = setup.engine(&gpu.device, &gpu.queue);
        GpuView {
            engine,
            gpu: gpu.clone(),
            texture: None,
            view: None,
            generation: 0,
            radiance: None,
            histogram: None,
            last_frame_ms: 0.0,
            fault: None,
            refused: false,
        }
    }

    /// Renders `view` of `scene` if anything changed; returns what the frame ran. A rebuild in
    /// slices goes on only while no view before it in the window's frame took the frame's
    /// slice ([`FrameBudget`]); one that goes on takes it.
    pub fn render(&mut self, scene: &Scene, view: &View) -> &FrameStats {
        let start = Instant::now();
        let held = self.gpu.budget.taken();
        self.engine.hold_rebuild(held);
        let result = self
            .engine
            .try_render(scene, view)
            .map(|stats| !stats.run.is_empty() || stats.rebuild_done);
        self.engine.hold_rebuild(false);
        // A frame that failed left the last frame's stats: it built nothing.
        let built = result.is_ok()
            && (self.engine.stats().rebuild.is_some() || self.engine.stats().rebuild_done);
        if built && !held {
            self.gpu.budget.take();
        }
        self.refused = matches!(result, Err(EngineError::CannotDraw(_)));
        let drew = match result {
            Ok(drew) => drew,
            // A path-tracer scene or a refused view draws nothing here (`notice` says why); a
            // GPU fault is shown to the user.
            Err(EngineError::CannotDraw(_)) => false,
            Err(e) => {
                self.fault = Some(e.to_string());
                false
            }
        };
        if drew {
            self.last_frame_ms = start.elapsed().as_secs_f64() * 1e3;
            self.generation += 1;
            self.view = Some(*view);
            self.bind_texture();
        }
        self.engine.stats()
    }

    fn bind_texture(&mut self) {
        let Some(display) = self.engine.display_view() else {
            return;
        };
        let mut renderer = self.gpu.renderer.write();
        match self.texture {
            Some(id) => renderer.update_egui_texture_from_wgpu_texture(
                &self.gpu.device,
                &display,
                wgpu::FilterMode::Linear,
                id,
            ),
            None => {
                self.texture = Some(renderer.register_native_texture(
                    &self.gpu.device,
                    &display,
                    wgpu::FilterMode::Linear,
                ))
            }
        }
    }

    /// Renders like `render`, but finishes a rebuild under way in this frame and draws every
    /// pixel (for exports, which must show the scene as it is now, exactly).
    pub fn render_complete(&mut self, scene: &Scene, view: &View) -> &FrameStats {
        self.engine.set_rebuild_slices(None);
        self.render(scene, view);
        if self.engine.settling() {
            // The frame was drawn in tiles: the still frame after it draws every pixel.
            self.render(scene, view);
        }
        self.engine.set_rebuild_slices(self.gpu.rebuild_slice);
        self.engine.stats()
    }

    /// Sets how this view builds a new atmosphere (see [`Gpu::rebuild_slice`]).
    pub fn set_rebuild_slices(&mut self, slice: Option<Duration>) {
        self.gpu.rebuild_slice = slice;
        self.engine.set_rebuild_slices(slice);
    }

    /// Whether the view needs more frames of the same scene: a rebuild in slices, the full
    /// resolution of a frame drawn in tiles, or a moving sky being built in slices
    /// (`Engine::settling`).
    pub fn settling(&self) -> bool {
        self.engine.settling()
    }

    /// While a new atmosphere is built in slices: what is being built for `scene` and how far
    /// it has come, for the view to say so (over the last image, or in its place before the
    /// first).
    pub fn building(&self, scene: &Scene) -> Option<String> {
        let p = self.engine.stats().rebuild?;
        let share = p.done as f64 / p.total.max(1) as f64;
        let model = atmoscope_model::methods::info(scene.render.method);
        Some(format!(
            "Building {}'s tables… {:.0} %",
            model.label,
            100.0 * share.clamp(0.0, 1.0)
        ))
    }

    /// The last GPU fault not yet shown, if any.
    pub fn take_fault(&mut self) -> Option<String> {
        self.fault.take()
    }

    /// The frame on screen; None before the first or while the model refuses the view.
    pub fn texture(&self) -> Option<egui::TextureId> {
        self.texture.filter(|_| !self.refused)
    }

    /// The view last drawn.
    pub fn view(&self) -> Option<View> {
        self.view
    }

    pub fn stats(&self) -> &FrameStats {
        self.engine.stats()
    }

    pub fn engine(&self) -> &Engine {
        &self.engine
    }

    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The linear radiance of the frame on screen (read back at most once per frame drawn).
    pub fn radiance(&mut self) -> Result<Arc<Radiance>, EngineError> {
        if self.refused {
            return Err(EngineError::NotRendered);
        }
        if let Some((g, r)) = &self.radiance
            && *g == self.generation
        {
            return Ok(r.clone());
        }
        let view = self.view.ok_or(EngineError::NotRendered)?;
        let r = Arc::new(Radiance {
            width: view.width,
            height: view.height,
            rgba: self.engine.read_radiance()?,
        });
        self.radiance = Some((self.generation, r.clone()));
        Ok(r)
    }

    /// Counts the view's luminance histogram in every frame that redraws it.
    pub fn set_metering(&mut self, on: bool) {
        self.engine.set_metering(on);
    }

    /// The luminance histogram of the frame on screen, while metering (read back at most
    /// once per frame drawn).
    pub fn histogram(&mut self) -> Option<Arc<Histogram>> {
        if self.refused {
            return None;
        }
        if let Some((g, h)) = &self.histogram
            && *g == self.generation
        {
            return Some(h.clone());
        }
        let h = Arc::new(self.engine.histogram().ok()?);
        self.histogram = Some((self.generation, h.clone()));
        Some(h)
    }

    /// The frame as displayed, RGBA8.
    pub fn display_rgba8(&self) -> Result<Vec<u8>, EngineError> {
        if self.refused {
            return Err(EngineError::NotRendered);
        }
        self.engine.read_display()
    }

    /// Whether the scene's model refused the last frame (or is offline).
    pub fn refused(&self) -> bool {
        self.refused
    }
}

impl Drop for GpuView {
    fn drop(&mut self) {
        if let Some(id) = self.texture {
            self.gpu.renderer.write().free_texture(&id);
        }
    }
}

/// Why the scene's model cannot draw this view, or why the view lies outside the model's
/// domain; None when all is well.
pub fn notice(scene: &Scene) -> Option<String> {
    let model = atmoscope_model::methods::info(scene.render.method);
    if !model.is_realtime() {
        return Some(format!(
            "{} is offline: the Reference tab renders it; choose a real-time model under Method to draw here.",
            model.label
        ));
    }
    if let Some(why) = model.cannot_draw(scene) {
        return Some(format!(
            "{why}. Bring the camera down or the sun up, or choose another model under Method."
        ));
    }
    model
        .domain
        .excludes_scene(scene)
        .map(|why| format!("Outside {}'s domain — {why}", model.label))
}

/// Marks a view drawn in `rect` with its [`notice`], if any, in the view itself.
pub fn mark(ui: &egui::Ui, rect: egui::Rect, scene: &Scene) {
    let Some(text) = notice(scene) else { return };
    let painter = ui.painter_at(rect);
    let galley = painter.layout(
        text,
        egui::FontId::proportional(13.0),
        egui::Color32::from_rgb(255, 220, 120),
        (rect.width() - 16.0).max(40.0),
    );
    let at = rect.left_top() + egui::vec2(8.0, 8.0);
    painter.rect_filled(
        egui::Rect::from_min_size(at, galley.size()).expand(4.0),
        4.0,
        egui::Color32::from_black_alpha(180),
    );
    painter.galley(at, galley, egui::Color32::WHITE);
}

/// Says over the top left of the view in `rect` that its tables are being built
/// ([`GpuView::building`]): a label floating above the image, below a [`mark`] if any.
pub fn building_over(ui: &egui::Ui, rect: egui::Rect, text: String) {
    egui::Area::new(ui.scope_id().with("building"))
        .fixed_pos(rect.left_top() + egui::vec2(8.0, 36.0))
        // Above the panels, below menus and pop-ups.
        .order(egui::Order::Middle)
        .interactable(false)
        .show(ui.ctx(), |ui| {
            egui::Frame::new()
                .fill(egui::Color32::from_black_alpha(180))
                .corner_radius(4.0)
                .inner_margin(4.0)
                .show(ui, |ui| {
                    ui.colored_label(egui::Color32::WHITE, text);
                });
        });
}

/// Pixel size of a view filling `points` of screen at `scale` (1 = one texel per pixel).
pub fn pixels(ctx: &egui::Context, points: egui::Vec2, scale: f32) -> [u32; 2] {
    let px = points * ctx.pixels_per_point() * scale;
    [px.x, px.y].map(|v| (v.round() as u32).clamp(16, 4096))
}
