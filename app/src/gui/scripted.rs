//! The explorer playing a scripted session (`atmoscope bench gui`, `crate::gui_bench`): each
//! step's action, then frames until the window settles, every UI frame interval recorded;
//! at the end the report is written and the window closes.

use super::{Command, ExplorerApp, GpuView, Views};
use crate::gui_bench::{Action, GuiBenchArgs, StepResult, steps, to_csv, to_markdown};
use atmoscope_model::Scene;
use eframe::egui;
use web_time::Instant;

/// Frames a step records at least, so that a step whose action starts work a frame later
/// (a tab's first engine) is not taken as settled before it begins.
const MIN_FRAMES: usize = 5;

/// A session under way.
pub struct Session {
    steps: Vec<Action>,
    step: usize,
    /// When the step's action was taken; None until it is.
    started: Option<Instant>,
    last_frame: Option<Instant>,
    results: Vec<StepResult>,
    timeout_s: f64,
    /// Where the report goes (a web page reports on itself instead).
    #[cfg_attr(target_arch = "wasm32", allow(dead_code))]
    out: std::path::PathBuf,
    /// Whether the report was written, once the session is over (read after the window
    /// closes).
    outcome: Outcome,
    over: bool,
}

/// The end of a session, handed out of the window.
type Outcome = std::sync::Arc<std::sync::Mutex<Option<anyhow::Result<()>>>>;

impl Session {
    pub fn new(args: &GuiBenchArgs, outcome: Outcome) -> Session {
        Session {
            steps: steps(args),
            step: 0,
            started: None,
            last_frame: None,
            results: Vec::new(),
            timeout_s: args.step_timeout_s,
            out: args.out.clone(),
            outcome,
            over: false,
        }
    }

    /// Plays one frame of the session: records the interval since the last frame, takes the
    /// next step's action once the last step has settled, and closes the window at the end.
    pub fn frame(&mut self, app: &mut ExplorerApp, ctx: &egui::Context) {
        let now = Instant::now();
        let interval = self.last_frame.map(|t| (now - t).as_secs_f64() * 1e3);
        self.last_frame = Some(now);
        // A web page stays open after the session: it then draws only when asked.
        if self.over {
            return;
        }
        ctx.request_repaint();
        let Some(action) = self.steps.get(self.step).cloned() else {
            self.finish(app, ctx);
            return;
        };
        match self.started {
            None => {
                take(app, ctx, &action);
                self.started = Some(now);
                self.results.push(StepResult {
                    label: action.label(),
                    intervals_ms: Vec::new(),
                    settled: false,
                });
                eprintln!("bench gui: {}", action.label());
            }
            Some(started) => {
                let Some(result) = self.results.last_mut() else {
                    return;
                };
                result.intervals_ms.extend(interval);
                if let Action::Turn(frames) = action {
                    // One degree a frame; the step ends after its frames, whatever they took.
                    let camera = &mut app.scene.camera;
                    camera.heading_deg = (camera.heading_deg + 1.0).rem_euclid(360.0);
                    if result.intervals_ms.len() >= frames as usize {
                        result.settled = true;
                        self.step += 1;
                        self.started = None;
                    }
                    return;
                }
                let settled = result.intervals_ms.len() >= MIN_FRAMES
                    && !app.views.as_ref().is_some_and(Views::settling)
                    && !app.thumbnails.loading();
                let timed_out = (now - started).as_secs_f64() > self.timeout_s;
                if settled || timed_out {
                    result.settled = settled;
                    self.step += 1;
                    self.started = None;
                }
            }
        }
    }

    /// Writes the report, prints it and closes the window.
    fn finish(&mut self, app: &ExplorerApp, ctx: &egui::Context) {
        let adapter = app
            .views
            .as_ref()
            .map_or_else(|| "no GPU".to_string(), |v| v.gpu.adapter.clone());
        let md = to_markdown(&self.results, &adapter);
        let csv = to_csv(&self.results);
        print!("{md}");
        // A web page reports on itself, for the browser test to read (`web/tests`).
        #[cfg(target_arch = "wasm32")]
        let written = {
            crate::web::report_bench(&md, &csv);
            Ok(())
        };
        #[cfg(not(target_arch = "wasm32"))]
        let written = std::fs::create_dir_all(&self.out)
            .map_err(anyhow::Error::from)
            .and_then(|()| crate::files::write_atomic(&self.out.join("gui.csv"), csv.as_bytes()))
            .and_then(|()| crate::files::write_atomic(&self.out.join("gui.md"), md.as_bytes()));
        #[cfg(not(target_arch = "wasm32"))]
        if written.is_ok() {
            eprintln!("bench gui: wrote {}", self.out.display());
        }
        // The thumbnails were rendered into a folder of the session's own.
        #[cfg(not(target_arch = "wasm32"))]
        let _ = std::fs::remove_dir_all(&app.thumbnail_dir);
        if let Ok(mut slot) = self.outcome.lock() {
            *slot = Some(written);
        }
        self.over = true;
        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
    }
}

/// Takes a step's action as a user's clicks would.
fn take(app: &mut ExplorerApp, ctx: &egui::Context, action: &Action) {
    match *action {
        Action::Start(method) => {
            // A fresh start: new engines, nothing built, the default scene with this model.
            if let Some(views) = &mut app.views {
                let gpu = views.gpu.clone();
                *views = Views {
                    main: GpuView::new(&gpu),
                    compare: None,
                    reference: None,
                    gpu,
                };
            }
            let mut scene = Scene::default();
            scene.render.method = method;
            app.scene = scene;
            app.layout.tab = crate::tab::Tab::Sky;
            app.layout.compare.a_method = method;
        }
        Action::Open(tab) => app.layout.tab = tab,
        Action::PresetList => app.apply(ctx, Command::WantThumbnails),
        Action::LoadPreset(name, method) => {
            app.apply(ctx, Command::LoadPreset(name));
            app.scene.render.method = method;
        }
        // The frames turn the camera (`Session::frame`).
        Action::Turn(_) => {}
    }
}

/// Runs the session in the explorer's window; fails when the report could not be written or
/// the window closed before the end.
#[cfg(not(target_arch = "wasm32"))]
pub fn run(args: GuiBenchArgs) -> anyhow::Result<std::process::ExitCode> {
    let outcome: Outcome = std::sync::Arc::new(std::sync::Mutex::new(None));
    let shared = outcome.clone();
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_inner_size([1280.0, 800.0])
            .with_title("Atmoscope (bench gui)"),
        wgpu_options: super::wgpu_options(),
        // The session starts from the defaults, not from the user's last layout.
        persist_window: false,
        ..Default::default()
    };
    eframe::run_native(
        "Atmoscope bench gui",
        options,
        Box::new(move |cc| {
            let mut app = ExplorerApp::new(
                Scene::default(),
                super::Layout::default(),
                cc.wgpu_render_state.as_ref(),
            );
            // Thumbnails rendered, not read from the user's cache: the first opening is the
            // one measured.
            app.thumbnail_dir = std::env::temp_dir().join(format!(
                "atmoscope-bench-gui-thumbnails-{}",
                std::process::id()
            ));
            app.session = Some(Session::new(&args, shared));
            Ok(Box::new(app))
        }),
    )
    .map_err(|e| anyhow::anyhow!("cannot open the explorer window: {e}"))?;
    let result = outcome
        .lock()
        .map_err(|_| anyhow::anyhow!("the session's report was lost"))?
        .take();
    match result {
        Some(Ok(())) => Ok(std::process::ExitCode::SUCCESS),
        Some(Err(e)) => Err(e),
        None => anyhow::bail!("the window closed before the session ended"),
    }
}
