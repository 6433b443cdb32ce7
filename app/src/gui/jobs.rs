//! Long work off the UI thread (path tracing, inspection, exports): a thread with a progress
//! fraction and a cancel flag the UI can read and set, and a result the UI collects when done.
//! The worker asks for a repaint when it moves on, so an idle window wakes only for progress.

use eframe::egui;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::thread::JoinHandle;

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
    handle: Option<JoinHandle<T>>,
}

impl<T: Send + 'static> Job<T> {
    pub fn spawn(
        label: impl Into<String>,
        ctx: &egui::Context,
        work: impl FnOnce(&Progress) -> T + Send + 'static,
    ) -> Job<T> {
        let progress = Progress {
            fraction: Arc::new(AtomicU32::new(0)),
            cancel: Arc::new(AtomicBool::new(false)),
            ctx: ctx.clone(),
        };
        let p = progress.clone();
        let handle = std::thread::spawn(move || {
            let result = work(&p);
            p.ctx.request_repaint();
            result
        });
        Job {
            label: label.into(),
            progress,
            handle: Some(handle),
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
        self.handle.as_ref().is_some_and(|h| !h.is_finished())
    }

    /// The result once the worker has finished (None while it runs or after it was taken).
    /// A worker that panicked yields an error message.
    pub fn take(&mut self) -> Option<Result<T, String>> {
        if self.is_running() {
            return None;
        }
        self.handle.take().map(|h| {
            h.join()
                .map_err(|_| format!("{} stopped unexpectedly", self.label))
        })
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
pub fn wait<T: Send + 'static>(job: &Job<T>) {
    while job.is_running() {
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
}
