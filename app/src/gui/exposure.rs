//! Automatic exposure: the engine counts the view's luminance histogram (its meter pass), the
//! exposure that puts the histogram's log-average at mid-grey (plus the scene's compensation)
//! is the target, and the scene's exposure moves towards it over about half a second, as an
//! eye or a camera adapts. Also shows the histogram and the metered EV100.

use atmoscope_model::display::{Histogram, ev100, metered_exposure_ev};
use eframe::egui;
use egui_plot::{Bar, BarChart, Plot};
use std::sync::Arc;

/// Time constant of the adaptation, s.
const ADAPTATION_S: f64 = 0.4;

/// What the meter read from the view on screen.
#[derive(Debug, Clone)]
pub struct Reading {
    pub histogram: Arc<Histogram>,
    pub log_average_cd_m2: f64,
    pub ev100: f64,
    /// The exposure the view adapts to, EV.
    pub target_ev: f64,
}

impl Reading {
    pub fn new(histogram: Arc<Histogram>, compensation_ev: f64) -> Option<Reading> {
        let l = histogram.log_average_cd_m2()?;
        Some(Reading {
            histogram,
            log_average_cd_m2: l,
            ev100: ev100(l),
            target_ev: metered_exposure_ev(l, compensation_ev),
        })
    }
}

/// The exposure `dt_s` seconds after `current`, moving towards `target` (reached once within
/// a hundredth of a stop).
pub fn adapt(current: f64, target: f64, dt_s: f64) -> f64 {
    let next = current + (target - current) * (1.0 - (-dt_s.max(0.0) / ADAPTATION_S).exp());
    if (target - next).abs() < 0.01 {
        target
    } else {
        next
    }
}

/// The histogram as bars over log10 cd/m².
pub fn show_histogram(ui: &mut egui::Ui, h: &Histogram) {
    let total = h.counts.iter().sum::<u32>().max(1);
    let width = Histogram::bin_centre_log10(1) - Histogram::bin_centre_log10(0);
    let bars: Vec<Bar> = h
        .counts
        .iter()
        .enumerate()
        .filter(|(_, c)| **c > 0)
        .map(|(i, &c)| {
            Bar::new(
                Histogram::bin_centre_log10(i),
                f64::from(c) / f64::from(total),
            )
            .width(width)
        })
        .collect();
    Plot::new("luminance histogram")
        .height(70.0)
        .show_y(false)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .x_axis_label("log10 cd/m²")
        .show(ui, |plot| plot.bar_chart(BarChart::new("pixels", bars)));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Adapting moves part of the way each frame, never past the target, and arrives.
    #[test]
    fn exposure_adapts_smoothly_and_arrives() {
        let (mut ev, target) = (0.0, 6.0);
        let mut frames = 0;
        while ev != target {
            let next = adapt(ev, target, 1.0 / 60.0);
            assert!(next > ev && next <= target, "{ev} → {next}");
            ev = next;
            frames += 1;
        }
        // About 0.4 s · ln(600) ≈ 2.6 s at 60 frames a second.
        assert!((100..200).contains(&frames), "{frames} frames");
        assert_eq!(adapt(3.0, 3.0, 0.1), 3.0);
    }
}
