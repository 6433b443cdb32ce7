//! `atmoscope bench gui`: a scripted session of the explorer in its window, reporting per step
//! the UI frame intervals a user meets (the longest and the 99th percentile); or, with
//! `--script sky-frames`, the Sky view's frame time while the camera turns, which the web
//! explorer plays too (`web/tests`), to compare the browser with the native window. The script and
//! the report live here, apart from the GUI that plays it (`gui::scripted`), so that the
//! command line parses it and the tests check it without a window.

use crate::args::{method_id, parse_methods};
use crate::tab::Tab;
use atmoscope_model::methods;
use atmoscope_model::scene::Method;
use std::path::PathBuf;

#[derive(clap::Args, Debug, Clone)]
pub struct GuiBenchArgs {
    /// Models the explorer starts with, one fresh start each (registry ids, comma separated;
    /// `all`: every real-time model).
    #[arg(long, value_name = "IDS", default_value = "hillaire,bruneton,elek,nishita", value_parser = parse_methods)]
    pub models: crate::args::MethodList,
    /// The model of the steps after the starts (the tabs, the preset list, a preset loaded).
    #[arg(long, value_name = "ID", default_value = "bruneton", value_parser = crate::args::parse_method)]
    pub model: Method,
    /// Longest a step may take before the next one starts, s (1–3600).
    #[arg(long, value_name = "S", default_value_t = 180.0, value_parser = parse_step_timeout)]
    pub step_timeout_s: f64,
    /// What to play: `session` (starts, tabs, presets: the freezes a user meets) or
    /// `sky-frames` (the Sky view redrawn every frame as the camera turns: its frame time).
    #[arg(long, value_enum, default_value_t = Script::Session)]
    pub script: Script,
    /// Folder for gui.csv and gui.md.
    #[arg(long, value_name = "DIR", default_value = "target/bench-gui")]
    pub out: PathBuf,
}

/// A step's time limit: 1 to 3600 s.
fn parse_step_timeout(s: &str) -> Result<f64, String> {
    match crate::args::parse_positive(s)? {
        v if (1.0..=3600.0).contains(&v) => Ok(v),
        v => Err(format!("{v} s is outside 1 to 3600 s")),
    }
}

/// Which session `bench gui` plays.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Script {
    Session,
    SkyFrames,
}

/// Frames of the turning camera in the `sky-frames` script.
pub const TURN_FRAMES: u32 = 240;

/// What a step of the session does.
#[derive(Debug, Clone, PartialEq)]
pub enum Action {
    /// A fresh start of the explorer with this model: new engines, nothing built.
    Start(Method),
    /// A click on a tab.
    Open(Tab),
    /// The preset menu opened the first time: every shipped preset's thumbnail rendered.
    PresetList,
    /// A shipped preset loaded, drawn with this model.
    LoadPreset(&'static str, Method),
    /// The camera turned by a degree each frame for this many frames: every frame redraws
    /// the view and nothing else (no table depends on the heading).
    Turn(u32),
}

impl Action {
    pub fn label(&self) -> String {
        match self {
            Action::Start(m) => format!("start with {}", method_id(*m)),
            Action::Open(t) => format!("open the {} tab", t.label()),
            Action::PresetList => "open the preset list (thumbnails)".into(),
            Action::LoadPreset(name, m) => format!("load {name} with {}", method_id(*m)),
            Action::Turn(frames) => format!("turn the camera for {frames} frames"),
        }
    }
}

/// The preset the session loads: a low sun, for a sky unlike the default one.
pub const PRESET: &str = "civil-twilight.ron";

/// The steps `args` ask for: [`script`], or for `sky-frames` a fresh start with the model,
/// then the turning camera.
pub fn steps(args: &GuiBenchArgs) -> Vec<Action> {
    match args.script {
        Script::Session => script(&args.models.0, args.model),
        Script::SkyFrames => vec![Action::Start(args.model), Action::Turn(TURN_FRAMES)],
    }
}

/// The session: a fresh start with each of `models` (the real-time ones), then with `model`
/// every tab in turn and back to the Sky, the preset list, and a preset loaded.
pub fn script(models: &[Method], model: Method) -> Vec<Action> {
    let mut steps: Vec<Action> = models
        .iter()
        .filter(|m| methods::info(**m).is_realtime())
        .map(|&m| Action::Start(m))
        .collect();
    steps.push(Action::Start(model));
    steps.extend(
        Tab::ALL
            .iter()
            .filter(|&&t| t != Tab::Sky)
            .map(|&t| Action::Open(t)),
    );
    steps.push(Action::Open(Tab::Sky));
    steps.push(Action::PresetList);
    steps.push(Action::LoadPreset(PRESET, model));
    steps
}

/// What one step took: the UI frame intervals from its action until the window settled (no
/// view building or refining, no thumbnail job), ms.
#[derive(Debug, Clone, PartialEq)]
pub struct StepResult {
    pub label: String,
    pub intervals_ms: Vec<f64>,
    /// Whether the window settled before the step's time ran out.
    pub settled: bool,
}

impl StepResult {
    pub fn longest_ms(&self) -> f64 {
        self.intervals_ms.iter().copied().fold(0.0, f64::max)
    }

    /// The 99th percentile of the intervals (nearest rank), ms; 0 without frames.
    pub fn p99_ms(&self) -> f64 {
        let mut v = self.intervals_ms.clone();
        v.sort_by(f64::total_cmp);
        match v.len() {
            0 => 0.0,
            n => v[((0.99 * n as f64).ceil() as usize).clamp(1, n) - 1],
        }
    }

    /// The median interval (the upper middle one), ms; 0 without frames.
    pub fn median_ms(&self) -> f64 {
        let mut v = self.intervals_ms.clone();
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(0.0)
    }

    pub fn seconds(&self) -> f64 {
        self.intervals_ms.iter().sum::<f64>() / 1e3
    }
}

/// The results as CSV: one row per step.
pub fn to_csv(results: &[StepResult]) -> String {
    let mut s = String::from("step,frames,longest_ms,p99_ms,seconds,settled,median_ms\n");
    for r in results {
        s.push_str(&format!(
            "\"{}\",{},{:.1},{:.1},{:.2},{},{:.2}\n",
            r.label,
            r.intervals_ms.len(),
            r.longest_ms(),
            r.p99_ms(),
            r.seconds(),
            r.settled,
            r.median_ms()
        ));
    }
    s
}

/// The results as a Markdown table, headed by the adapter.
pub fn to_markdown(results: &[StepResult], adapter: &str) -> String {
    let mut s = format!(
        "# atmoscope bench gui\n\nAdapter: {adapter}\n\n| step | frames | longest UI frame interval (ms) | p99 (ms) | until settled (s) | median (ms) |\n| --- | ---: | ---: | ---: | ---: | ---: |\n"
    );
    for r in results {
        s.push_str(&format!(
            "| {} | {} | {:.0} | {:.0} | {:.1}{} | {:.1} |\n",
            r.label,
            r.intervals_ms.len(),
            r.longest_ms(),
            r.p99_ms(),
            r.seconds(),
            if r.settled { "" } else { " (timed out)" },
            r.median_ms()
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_script_starts_with_each_real_time_model_then_visits_every_tab() {
        let steps = script(&[Method::Hillaire, Method::PathTracer], Method::Bruneton);
        assert_eq!(
            steps[..2],
            [
                Action::Start(Method::Hillaire),
                Action::Start(Method::Bruneton)
            ]
        );
        for tab in Tab::ALL {
            assert!(steps.contains(&Action::Open(tab)), "{tab:?}");
        }
        assert_eq!(
            steps.last(),
            Some(&Action::LoadPreset(PRESET, Method::Bruneton))
        );
        assert!(crate::presets::load_shipped(PRESET).is_some_and(|r| r.is_ok()));
    }

    #[test]
    fn sky_frames_starts_fresh_then_turns_the_camera() {
        use clap::Parser;
        #[derive(clap::Parser)]
        struct Cli {
            #[command(flatten)]
            gui: GuiBenchArgs,
        }
        let args = Cli::try_parse_from(["x", "--script", "sky-frames", "--model", "hillaire"])
            .expect("parses")
            .gui;
        assert_eq!(
            steps(&args),
            [Action::Start(Method::Hillaire), Action::Turn(TURN_FRAMES)]
        );
        let session = Cli::try_parse_from(["x"]).expect("parses").gui;
        assert_eq!(steps(&session), script(&session.models.0, session.model));
    }

    #[test]
    fn the_report_gives_the_longest_and_the_99th_percentile() {
        let mut intervals: Vec<f64> = (1..=200).map(f64::from).collect();
        intervals.push(5000.0);
        let r = StepResult {
            label: "open the LUTs tab".into(),
            intervals_ms: intervals,
            settled: true,
        };
        assert_eq!(r.longest_ms(), 5000.0);
        // 201 frames: the 199th smallest; the median the 101st.
        assert_eq!(r.p99_ms(), 199.0);
        assert_eq!(r.median_ms(), 101.0);
        let csv = to_csv(std::slice::from_ref(&r));
        assert!(
            csv.lines()
                .nth(1)
                .is_some_and(|l| l.starts_with("\"open the LUTs tab\",201,5000.0,199.0,")),
            "{csv}"
        );
        let md = to_markdown(&[r], "llvmpipe");
        assert!(
            md.contains("| open the LUTs tab | 201 | 5000 | 199 |"),
            "{md}"
        );
        assert_eq!(
            StepResult {
                label: String::new(),
                intervals_ms: Vec::new(),
                settled: false
            }
            .p99_ms(),
            0.0
        );
    }
}
