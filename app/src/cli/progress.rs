//! Progress of a long command over its steps: a bar on a terminal, and on a pipe one line per
//! step that the explorer's Bench tab (and a log) can read.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;

/// A progress bar on a terminal; elsewhere (a pipe: the explorer's Bench tab reads it) one
/// line per step, `progress DONE/TOTAL LABEL`.
pub(super) struct Progress {
    bar: Option<ProgressBar>,
    total: u64,
    done: std::cell::Cell<u64>,
}

impl Progress {
    pub(super) fn new(total: u64) -> Progress {
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = ProgressBar::new(total);
            bar.set_style(
                ProgressStyle::with_template(
                    "[{bar:30}] {pos}/{len} {msg} ({elapsed}, {eta} left)",
                )
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            bar
        });
        Progress {
            bar,
            total,
            done: std::cell::Cell::new(0),
        }
    }

    pub(super) fn step(&self, label: &str) {
        match &self.bar {
            Some(bar) => {
                bar.set_message(label.to_string());
                bar.inc(1);
            }
            None => {
                self.done.set(self.done.get() + 1);
                eprintln!("progress {}/{} {label}", self.done.get(), self.total);
            }
        }
    }

    pub(super) fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish();
        }
    }
}
