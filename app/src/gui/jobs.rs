//! Long work off the UI thread (path tracing, inspection, exports): a thread with a progress
//! fraction and a cancel flag the UI can read and set, and a result the UI collects when done.
//! The worker asks for a repaint when it moves on, so an idle window wakes only for progress.
//!
//! A browser page has no threads (WebAssembly threads need headers a static host cannot be
//! relied on to send), so there a job runs on the UI thread between frames: work given as
//! steps ([`Job::spawn_steps`]) runs steps in each frame until [`FRAME_BUDGET`] has passed (a
//! step begun before then finishes) and the page stays live; work given whole ([`Job::spawn`])
//! runs in one go in the frame after it was asked for.

use eframe::egui;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};

/// What a step of a job says: run another, nothing to do for now (the tab is hidden), or done.
pub enum Step<T> {
    Again,
    Wait,
    Done(T),
}

/// How long a step waits before it is asked again after [`Step::Wait`].
const WAIT: std::time::Duration = std::time::Duration::from_millis(50);

/// In the browser: the share of a frame given to jobs' steps.
pub const FRAME_BUDGET: std::time::Duration = std::time::Duration::from_millis(25);

/// What a worker sees: where to report progress and whether it was asked to stop.
#[derive(Clone)]
pub struct Progress {
    fraction: Arc<AtomicU32>,
    cancel: Arc<AtomicBool>,
    ctx: egui::Context,
}

impl Progress {
    /// Reports how far the work is, 0–1, and wakes the UI to show it.
    pub fn set(&self, fraction: f32) {
        self.fraction
            .store(fraction.clamp(0.0, 1.0).to_bits(), Ordering::Relaxed);
        self.ctx.request_repaint();
    }

    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    /// The cancel flag itself, for model code that polls one.
    pub fn cancel_flag(&self) -> &AtomicBool {
        &self.cancel
    }
}

/// One piece of background work producing a `T`.
pub struct Job<T> {
    pub label: String,
    progress: Progress,
    runner: Runner<T>,
}

type StepFn<T> = Box<dyn FnMut(&Progress) -> Step<T> + Send>;

impl<T: Send + 'static> Job<T> {
    /// Work done in one go (in the browser, in the frame after this one).
    pub fn spawn(
        label: impl Into<String>,
        ctx: &egui::Context,
        work: impl FnOnce(&Progress) -> T + Send + 'static,
    ) -> Job<T> {
        let mut work = Some(work);
        Job::spawn_steps(label, ctx, move |p| match work.take() {
            Some(work) => Step::Done(work(p)),
            None => Step::Wait,
        })
    }

    /// Work done in steps, each short enough to share a browser frame with the UI; natively
    /// a thread runs them one after another.
    pub fn spawn_steps(
        label: impl Into<String>,
        ctx: &egui::Context,
        step: impl FnMut(&Progress) -> Step<T> + Send + 'static,
    ) -> Job<T> {
        let progress = Progress {
            fraction: Arc::new(AtomicU32::new(0)),
            cancel: Arc::new(AtomicBool::new(false)),
            ctx: ctx.clone(),
        };
        let runner = Runner::start(Box::new(step), &progress);
        Job {
            label: label.into(),
            progress,
            runner,
        }
    }

    pub fn fraction(&self) -> f32 {
        f32::from_bits(self.progress.fraction.load(Ordering::Relaxed))
    }

    /// Asks the worker to stop; it returns what it has at its next check.
    pub fn cancel(&self) {
        self.progress.cancel.store(true, Ordering::Relaxed);
    }

    pub fn cancelled(&self) -> bool {
        self.progress.cancelled()
    }

    pub fn is_running(&self) -> bool {
        self.runner.is_running(&self.progress)
    }

    /// The result once the worker has finished (None while it runs or after it was taken).
    /// A worker that panicked yields an error message.
    pub fn take(&mut self) -> Option<Result<T, String>> {
        if self.is_running() {
            return None;
        }
        self.runner.take(&self.label)
    }

    /// Draws the job's progress bar and Cancel button; true when Cancel was clicked.
    pub fn show(&self, ui: &mut egui::Ui) -> bool {
        let mut clicked = false;
        ui.horizontal(|ui| {
            ui.add(
                egui::ProgressBar::new(self.fraction())
                    .desired_width(160.0)
                    .show_percentage(),
            );
            ui.label(&self.label);
            if self.cancelled() {
                ui.label("(cancelling…)");
            } else if ui.button("Cancel").clicked() {
                self.cancel();
                clicked = true;
            }
        });
        clicked
    }
}

/// Waits for `job` (tests and shutdown).
#[cfg(not(target_arch = "wasm32"))]
pub fn wait<T: Send + 'static>(job: &Job<T>) {
    while job.is_running() {
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
}

/// Natively: a thread running the steps.
#[cfg(not(target_arch = "wasm32"))]
struct Runner<T>(Option<std::thread::JoinHandle<T>>);

#[cfg(not(target_arch = "wasm32"))]
impl<T: Send + 'static> Runner<T> {
    fn start(mut step: StepFn<T>, progress: &Progress) -> Runner<T> {
        let p = progress.clone();
        Runner(Some(std::thread::spawn(move || {
            let result = loop {
                match step(&p) {
                    Step::Again => {}
                    Step::Wait => std::thread::sleep(WAIT),
                    Step::Done(t) => break t,
                }
            };
            p.ctx.request_repaint();
            result
        })))
    }

    fn is_running(&self, _: &Progress) -> bool {
        self.0.as_ref().is_some_and(|h| !h.is_finished())
    }

    fn take(&mut self, label: &str) -> Option<Result<T, String>> {
        self.0.take().map(|h| {
            h.join()
                .map_err(|_| format!("{label} stopped unexpectedly"))
        })
    }
}

/// In the browser: the steps, run by whoever asks after the job in a frame, at most once a
/// frame and for at most [`FRAME_BUDGET`]; a step that panics ends the page, as any panic
/// does there.
#[cfg(target_arch = "wasm32")]
struct Runner<T> {
    step: std::cell::RefCell<Option<StepFn<T>>>,
    result: std::cell::RefCell<Option<T>>,
    /// The frame whose share was last run; None before the first, which is the frame after
    /// the job was asked for.
    ran_in: std::cell::Cell<Option<u64>>,
}

#[cfg(target_arch = "wasm32")]
impl<T: Send + 'static> Runner<T> {
    fn start(step: StepFn<T>, progress: &Progress) -> Runner<T> {
        progress.ctx.request_repaint();
        Runner {
            step: std::cell::RefCell::new(Some(step)),
            result: std::cell::RefCell::new(None),
            ran_in: std::cell::Cell::new(Some(progress.ctx.cumulative_frame_nr())),
        }
    }

    fn is_running(&self, progress: &Progress) -> bool {
        let frame = progress.ctx.cumulative_frame_nr();
        if self.ran_in.get() != Some(frame) {
            self.ran_in.set(Some(frame));
            self.run_share(progress);
        }
        self.step.borrow().is_some()
    }

    fn run_share(&self, progress: &Progress) {
        let mut slot = self.step.borrow_mut();
        let Some(step) = slot.as_mut() else { return };
        let started = web_time::Instant::now();
        loop {
            match step(progress) {
                Step::Again if started.elapsed() < FRAME_BUDGET => {}
                Step::Again => return progress.ctx.request_repaint(),
                Step::Wait => return progress.ctx.request_repaint_after(WAIT),
                Step::Done(t) => {
                    *self.result.borrow_mut() = Some(t);
                    *slot = None;
                    return progress.ctx.request_repaint();
                }
            }
        }
    }

    fn take(&mut self, _: &str) -> Option<Result<T, String>> {
        self.result.get_mut().take().map(Ok)
    }
}
