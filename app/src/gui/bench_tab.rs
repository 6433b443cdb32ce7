//! The Bench tab: the last `atmoscope bench methods` results as a scatter of frame time
//! against error (log–log, one marker per model, the Pareto front drawn; hover for the
//! figures, click a point or a row to render that model), and a button that runs
//! `bench methods --quick` in the background, as a child process of the same program, with
//! its progress and a Cancel button.

use super::jobs::Job;
use super::state::Command;
use crate::bench_results::{Config, Row, parse_csv, summarise};
use atmoscope_model::Scene;
use atmoscope_model::methods;
use eframe::egui;
use egui_plot::{HoverPosition, Legend, Line, MarkerShape, Plot, PlotPoints, Points};
use std::io::BufRead;
use std::path::{Path, PathBuf};
use std::process::{Command as Process, Stdio};
use std::sync::{Arc, Mutex};

/// Where the tab's own runs write and where it looks for results first.
pub fn default_dir() -> PathBuf {
    crate::cache::dir("bench")
}

/// Largest `results.csv` read, bytes: the whole registry at every set and quality is well
/// under a megabyte.
pub const MAX_RESULTS_BYTES: u64 = 64 << 20;

pub struct BenchTab {
    /// The folder whose `results.csv` the tab shows and its runs write.
    pub dir: PathBuf,
    /// The program a run starts and its arguments before `--out DIR` (by default this
    /// program's `bench methods --quick --refs …`).
    pub program: (PathBuf, Vec<String>),
    /// Results shown: rows and the file they came from, or why they could not be read.
    results: Option<Result<(Vec<Row>, PathBuf), String>>,
    /// Which view the chart shows: None for the mean over every view.
    view: Option<String>,
    run: Option<Job<Result<(), String>>>,
    /// Why the last run failed or was cancelled; the results shown stay (or are the run's
    /// own, when it wrote them before failing: cases it left out).
    run_error: Option<String>,
    /// When the last run started, to tell its results from older ones.
    run_started: Option<std::time::SystemTime>,
    /// Results to show while the tab has none of its own (the repository's `docs/bench`).
    fallback: Option<PathBuf>,
    /// The run's latest progress line (`progress N/M label`) and its last error lines.
    status: Arc<Mutex<Vec<String>>>,
}

impl BenchTab {
    pub fn new(dir: PathBuf) -> BenchTab {
        let exe = std::env::current_exe().unwrap_or_else(|_| PathBuf::from("atmoscope"));
        let mut args: Vec<String> = ["bench", "methods", "--quick"].map(String::from).into();
        if let Ok(refs) = crate::shipped::references(None) {
            args.extend(["--refs".into(), refs.to_string_lossy().into_owned()]);
        }
        BenchTab {
            dir,
            program: (exe, args),
            results: None,
            view: None,
            run: None,
            run_error: None,
            run_started: None,
            fallback: None,
            status: Arc::default(),
        }
    }

    /// The tab of the explorer: until it has results of its own it shows the repository's
    /// last committed quick run (`docs/bench/results.csv`), found beside the program.
    pub fn with_shipped_results(mut self) -> BenchTab {
        self.fallback = crate::shipped::near_program(Path::new(crate::shipped::BENCH_RESULTS))
            .filter(|p| p.is_file());
        // A web page has no files beside it: the results are built in.
        #[cfg(target_arch = "wasm32")]
        self.load_text(
            Path::new(crate::shipped::BENCH_RESULTS),
            include_str!("../../../docs/bench/results.csv"),
        );
        self
    }

    pub fn running(&self) -> bool {
        self.run.as_ref().is_some_and(Job::is_running)
    }

    /// Reads `results.csv` from `path` (a regular file of at most [`MAX_RESULTS_BYTES`]); a
    /// bad file is reported and shows nothing.
    pub fn load(&mut self, path: &Path) {
        match atmoscope_model::files::read_text_limited(path, MAX_RESULTS_BYTES) {
            Ok(text) => self.load_text(path, &text),
            Err(e) => {
                self.results = Some(Err(format!("{}: {e}", path.display())));
                self.view = None;
            }
        }
    }

    /// Shows the results in `text`, read from `path`.
    fn load_text(&mut self, path: &Path, text: &str) {
        self.results = Some(
            parse_csv(text)
                .map_err(|e| format!("{}: {e}", path.display()))
                .map(|rows| (rows, path.to_path_buf())),
        );
        self.view = None;
    }

    /// Starts a quick benchmark in the background, writing into [`BenchTab::dir`].
    fn start(&mut self, ctx: &egui::Context) {
        self.run_error = None;
        self.run_started = Some(std::time::SystemTime::now());
        let (program, mut args) = self.program.clone();
        args.extend(["--out".into(), self.dir.to_string_lossy().into_owned()]);
        let status = self.status.clone();
        if let Ok(mut s) = status.lock() {
            s.clear();
        }
        self.run = Some(Job::spawn("bench methods --quick", ctx, move |progress| {
            std::fs::create_dir_all(args.last().map_or(".", String::as_str))
                .map_err(|e| format!("cannot create the results folder: {e}"))?;
            let mut child = Process::new(&program)
                .args(&args)
                .stdin(Stdio::null())
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .map_err(|e| format!("cannot start {}: {e}", program.display()))?;
            let stderr = child.stderr.take();
            let lines = status.clone();
            let ctx = progress.clone();
            let reader = std::thread::spawn(move || {
                let Some(stderr) = stderr else { return };
                for line in std::io::BufReader::new(stderr)
                    .lines()
                    .map_while(Result::ok)
                {
                    if let Some((done, total)) = parse_progress(&line) {
                        ctx.set(done as f32 / total.max(1) as f32);
                    }
                    if let Ok(mut l) = lines.lock() {
                        l.push(line);
                        let excess = l.len().saturating_sub(8);
                        l.drain(..excess);
                    }
                }
            });
            let exit = loop {
                if progress.cancelled() {
                    // Killing a finished child fails harmlessly.
                    let _ = child.kill();
                }
                match child.try_wait() {
                    Ok(Some(exit)) => break exit,
                    Ok(None) => std::thread::sleep(std::time::Duration::from_millis(50)),
                    Err(e) => {
                        let _ = child.kill();
                        let _ = child.wait();
                        return Err(format!("lost the benchmark: {e}"));
                    }
                }
            };
            // The reader ends when the pipe closes; a grandchild holding it open must not
            // hold the job, so give it a second to take the last lines and then leave it.
            for _ in 0..100 {
                if reader.is_finished() {
                    break;
                }
                std::thread::sleep(std::time::Duration::from_millis(10));
            }
            if progress.cancelled() {
                Err("cancelled".into())
            } else if exit.success() {
                Ok(())
            } else {
                let tail = status.lock().map(|l| l.join("\n")).unwrap_or_default();
                Err(format!("the benchmark failed ({exit}):\n{tail}"))
            }
        }));
    }

    /// Collects a finished run: loads its results, or shows why it failed.
    fn poll(&mut self) {
        let Some(result) = self.run.as_mut().and_then(Job::take) else {
            return;
        };
        self.run = None;
        match result.and_then(|r| r) {
            Ok(()) => {
                self.run_error = None;
                self.load(&self.dir.join("results.csv"));
            }
            Err(e) => {
                let path = self.dir.join("results.csv");
                let written_by_this_run = std::fs::metadata(&path)
                    .and_then(|m| m.modified())
                    .is_ok_and(|t| self.run_started.is_some_and(|s| t >= s));
                if written_by_this_run {
                    self.load(&path);
                }
                self.run_error = Some(e);
            }
        }
    }

    pub fn show(&mut self, ui: &mut egui::Ui, scene: &Scene) -> Vec<Command> {
        self.poll();
        if self.results.is_none() && self.run.is_none() {
            let own = self.dir.join("results.csv");
            if let Some(path) = Some(own)
                .filter(|p| p.is_file())
                .or_else(|| self.fallback.clone())
            {
                self.load(&path);
            }
        }
        let mut commands = Vec::new();
        ui.horizontal_wrapped(|ui| {
            match &self.run {
                Some(job) => {
                    job.show(ui);
                    if let Some(line) = self.status.lock().ok().and_then(|l| l.last().cloned()) {
                        ui.label(line);
                    }
                    ui.ctx()
                        .request_repaint_after(std::time::Duration::from_millis(200));
                }
                // A web page cannot start the benchmark's program.
                None if cfg!(target_arch = "wasm32") => {
                    ui.label("In the browser this tab shows the shipped results: `atmoscope bench methods` runs in the desktop app.");
                }
                None => {
                    if ui
                        .button("Run quick benchmark")
                        .on_hover_text("atmoscope bench methods --quick: every model with RGB3 and Spectral4 on six views, against the path-traced references (about four minutes on two CPU cores without a GPU)")
                        .clicked()
                    {
                        self.start(ui.ctx());
                    }
                }
            }
            #[cfg(not(target_arch = "wasm32"))]
            if ui.button("Open results…").clicked()
                && let Some(p) = rfd::FileDialog::new()
                    .add_filter("bench results", &["csv"])
                    .pick_file()
            {
                self.load(&p);
            }
        });
        if let Some(e) = &self.run_error {
            ui.colored_label(ui.visuals().error_fg_color, e);
        }
        let (rows, path) = match &self.results {
            None => {
                ui.label(format!(
                    "No results yet: run the quick benchmark, open a results.csv, or run `atmoscope bench methods --quick --out {}`.",
                    self.dir.display()
                ));
                return commands;
            }
            Some(Err(e)) => {
                ui.colored_label(ui.visuals().error_fg_color, e);
                return commands;
            }
            Some(Ok((rows, path))) => (rows, path),
        };
        let mut views: Vec<&str> = rows.iter().map(|r| r.view.as_str()).collect();
        views.sort();
        views.dedup();
        ui.horizontal_wrapped(|ui| {
            ui.label(format!("{} ({} rows)", path.display(), rows.len()));
            egui::ComboBox::from_label("view")
                .selected_text(self.view.as_deref().unwrap_or("mean of every view"))
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut self.view, None, "mean of every view");
                    for v in &views {
                        ui.selectable_value(&mut self.view, Some(v.to_string()), *v);
                    }
                });
        });
        let shown: Vec<Row> = rows
            .iter()
            .filter(|r| self.view.as_ref().is_none_or(|v| *v == r.view))
            .cloned()
            .collect();
        let mut configs = summarise(&shown);
        if self.view.is_some() {
            // A view whose frames were not timed (`--full` times the quick views) takes its
            // configuration's frame time over the views that were: a property of the model,
            // set and quality more than of the view.
            let all = summarise(&rows);
            for c in configs.iter_mut().filter(|c| !c.timed()) {
                if let Some(a) = all.iter().find(|a| a.name() == c.name()) {
                    c.frame_ms = a.frame_ms;
                }
            }
        }
        let clicked = chart(ui, &configs, self.view.as_deref());
        commands.extend(clicked.and_then(|i| render_command(scene, &configs[i])));
        commands.extend(table(ui, &configs).and_then(|i| render_command(scene, &configs[i])));
        commands
    }
}

/// Closing the explorer (or replacing the tab) ends a run: the worker kills its child at its
/// next check, within 50 ms, so no benchmark outlives the window.
impl Drop for BenchTab {
    fn drop(&mut self) {
        if let Some(job) = &self.run {
            job.cancel();
            for _ in 0..40 {
                if !job.is_running() {
                    break;
                }
                std::thread::sleep(std::time::Duration::from_millis(25));
            }
        }
    }
}

/// `progress DONE/TOTAL …` as the command prints it on a pipe.
fn parse_progress(line: &str) -> Option<(u64, u64)> {
    let (done, total) = line
        .strip_prefix("progress ")?
        .split_whitespace()
        .next()?
        .split_once('/')?;
    Some((done.parse().ok()?, total.parse().ok()?))
}

/// The scene with the configuration's model, wavelength set and quality; None when the row
/// names a model or set this build does not know (a results file from elsewhere).
fn render_command(scene: &Scene, c: &Config) -> Option<Command> {
    let mut s = scene.clone();
    s.render.method = methods::by_id(&c.method)
        .filter(|m| m.is_realtime())?
        .method;
    s.render.wavelengths = crate::args::parse_wavelengths(&c.wavelengths).ok()?;
    s.render.quality = crate::args::parse_quality(&c.quality).ok()?;
    Some(Command::SetScene(Box::new(s)))
}

/// egui_plot's shape for a chart marker, and whether it is filled.
fn marker_shape(marker: crate::chart_style::Marker) -> (MarkerShape, bool) {
    use crate::chart_style::Marker;
    match marker {
        Marker::Circle => (MarkerShape::Circle, true),
        Marker::Ring => (MarkerShape::Circle, false),
        Marker::Triangle => (MarkerShape::Up, true),
        Marker::OpenTriangle => (MarkerShape::Up, false),
        Marker::Square => (MarkerShape::Square, true),
        Marker::OpenSquare => (MarkerShape::Square, false),
        Marker::Cross => (MarkerShape::Cross, true),
    }
}

/// A model's marker as drawn on the chart, for the table's key.
fn marker_icon(ui: &mut egui::Ui, style: crate::chart_style::Style) {
    use crate::chart_style::Marker;
    let (rect, _) = ui.allocate_exact_size(egui::vec2(12.0, 12.0), egui::Sense::hover());
    let [r, g, b] = style.colour;
    let colour = egui::Color32::from_rgb(r, g, b);
    let (c, h) = (rect.center(), 5.0);
    let stroke = egui::Stroke::new(1.5, colour);
    let painter = ui.painter();
    let triangle = vec![
        c + egui::vec2(0.0, -h),
        c + egui::vec2(h, h),
        c + egui::vec2(-h, h),
    ];
    let square = egui::Rect::from_center_size(c, egui::vec2(2.0 * h - 1.0, 2.0 * h - 1.0));
    let shape = match style.marker {
        Marker::Circle => egui::Shape::circle_filled(c, h, colour),
        Marker::Ring => egui::Shape::circle_stroke(c, h - 0.5, stroke),
        Marker::Triangle => egui::Shape::convex_polygon(triangle, colour, egui::Stroke::NONE),
        Marker::OpenTriangle => egui::Shape::closed_line(triangle, stroke),
        Marker::Square => egui::Shape::rect_filled(square, 0.0, colour),
        Marker::OpenSquare => {
            egui::Shape::rect_stroke(square, 0.0, stroke, egui::StrokeKind::Inside)
        }
        Marker::Cross => egui::Shape::Vec(vec![
            egui::Shape::line_segment([c + egui::vec2(-h, -h), c + egui::vec2(h, h)], stroke),
            egui::Shape::line_segment([c + egui::vec2(-h, h), c + egui::vec2(h, -h)], stroke),
        ]),
    };
    painter.add(shape);
}

/// The scatter, log–log (axes in log10, labelled in ms and ΔE); returns the index of a
/// clicked configuration.
fn chart(ui: &mut egui::Ui, configs: &[Config], view: Option<&str>) -> Option<usize> {
    let log = |c: &Config| {
        [
            c.frame_ms.max(1e-6).log10(),
            c.de2000_mean.max(1e-6).log10(),
        ]
    };
    let models = crate::bench_results::models_in_order(configs);
    let describe = configs.to_vec();
    let view_name = view.unwrap_or("mean of every view").to_string();
    // Room around the points, more towards the legend's corner.
    let span = |f: fn(&Config) -> f64| {
        configs
            .iter()
            .filter(|c| c.timed())
            .map(|c| f(c).max(1e-6).log10())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            })
    };
    let (x, y) = (span(|c| c.frame_ms), span(|c| c.de2000_mean));
    let response = Plot::new("bench-scatter")
        .height((ui.available_height() * 0.6).max(200.0))
        .legend(Legend::default())
        .include_x(x.0 - 0.05)
        .include_x(x.1 + 0.15)
        .include_y(y.0 - 0.05)
        .include_y(y.1 + 0.2)
        .x_axis_label("frame time, ms (log)")
        .y_axis_label("mean ΔE2000 against the path tracer (log)")
        .x_grid_spacer(log_grid)
        .y_grid_spacer(log_grid)
        .x_axis_formatter(|m, _| log_label(m.value))
        .y_axis_formatter(|m, _| log_label(m.value))
        .label_formatter(move |pos| {
            // Near a point: its configuration's figures; elsewhere nothing.
            let HoverPosition::NearDataPoint { position: p, .. } = pos else {
                return None;
            };
            nearest(&describe, [p.x, p.y]).map(|(i, _)| {
                let c = &describe[i];
                format!(
                    "{}\n{view_name}\nframe {:.2} ms, precompute {:.0} ms, tables {:.2} MiB\nΔE2000 {:.2} (p95 {:.2}), FLIP {:.3}, rel. RMSE {:.3}",
                    c.name(),
                    c.frame_ms,
                    c.precompute_ms,
                    c.table_bytes as f64 / 1048576.0,
                    c.de2000_mean,
                    c.de2000_p95,
                    c.flip,
                    c.rel_rmse
                )
            })
        })
        .show(ui, |p| {
            for (i, model) in models.iter().enumerate() {
                // Only what has a frame time has a place on the chart (the table lists all).
                let points: Vec<[f64; 2]> = configs
                    .iter()
                    .filter(|c| c.method == *model && c.timed())
                    .map(log)
                    .collect();
                // The family's colour, the model's marker within it (`chart_style`); the
                // legend names the families (the table's markers name the models).
                let style = crate::chart_style::style(model, i);
                let [r, g, b] = style.colour;
                let (shape, filled) = marker_shape(style.marker);
                let legend = atmoscope_model::methods::by_id(model)
                    .map_or(*model, |m| m.family.label());
                p.points(
                    Points::new(legend, PlotPoints::from(points))
                        .color(egui::Color32::from_rgb(r, g, b))
                        .shape(shape)
                        .filled(filled)
                        .radius(5.0),
                );
            }
            let mut front: Vec<[f64; 2]> = configs.iter().filter(|c| c.on_front).map(log).collect();
            front.sort_by(|a, b| a[0].total_cmp(&b[0]));
            let mut steps = Vec::new();
            for (i, q) in front.iter().enumerate() {
                steps.push(*q);
                if let Some(n) = front.get(i + 1) {
                    steps.push([n[0], q[1]]);
                }
            }
            // No band aggregation: the staircase has vertical steps.
            p.line(
                Line::new("Pareto front", PlotPoints::from(steps))
                    .allow_band(false)
                    .width(2.0),
            );
            (p.response().clicked())
                .then(|| p.pointer_coordinate())
                .flatten()
        });
    let at = response.inner?;
    nearest(configs, [at.x, at.y])
        .filter(|(_, d)| *d < 0.05)
        .map(|(i, _)| i)
}

/// Grid lines of a log10 axis at 1 to 9 times the powers of ten, decades strongest.
fn log_grid(input: egui_plot::GridInput) -> Vec<egui_plot::GridMark> {
    let (lo, hi) = input.bounds;
    if !(lo.is_finite() && hi.is_finite()) || hi - lo > 12.0 {
        return Vec::new();
    }
    (lo.floor() as i32..=hi.ceil() as i32)
        .flat_map(|d| {
            (1..10).map(move |m| egui_plot::GridMark {
                value: f64::from(d) + f64::from(m).log10(),
                step_size: match m {
                    1 => 1.0,
                    2 | 5 => 0.3,
                    _ => 0.1,
                },
            })
        })
        .filter(|g| g.value >= lo && g.value <= hi)
        .collect()
}

/// The label of a log10 grid line: its value at 1, 2 and 5 times a power of ten, else none.
fn log_label(v: f64) -> String {
    let value = 10f64.powf(v);
    let leading = value / 10f64.powf(v.floor());
    if [1.0, 2.0, 5.0].iter().any(|m| (leading - m).abs() < 1e-6) {
        format!("{}", (value * 1e6).round() / 1e6)
    } else {
        String::new()
    }
}

/// The configuration nearest to a point of the log–log chart (of those on it), and its
/// distance in decades.
fn nearest(configs: &[Config], at: [f64; 2]) -> Option<(usize, f64)> {
    configs
        .iter()
        .enumerate()
        .filter(|(_, c)| c.timed())
        .map(|(i, c)| {
            let (x, y) = (
                c.frame_ms.max(1e-6).log10(),
                c.de2000_mean.max(1e-6).log10(),
            );
            (i, ((x - at[0]).powi(2) + (y - at[1]).powi(2)).sqrt())
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// The configurations as a table, fastest first, each named on a button that renders it.
fn table(ui: &mut egui::Ui, configs: &[Config]) -> Option<usize> {
    let mut order: Vec<usize> = (0..configs.len()).collect();
    order.sort_by(|&a, &b| configs[a].frame_ms.total_cmp(&configs[b].frame_ms));
    let mut clicked = None;
    // Scroll bars beside the table, not floating over its last row (where they took the
    // clicks meant for its button).
    ui.spacing_mut().scroll = egui::style::ScrollStyle::solid();
    egui::ScrollArea::both().show(ui, |ui| {
        egui::Grid::new("bench-table").striped(true).show(ui, |ui| {
            for h in [
                "", "model / set / quality (click to render)", "", "frame ms", "precompute ms", "tables MiB",
                "ΔE2000", "p95", "FLIP", "rel. RMSE",
            ] {
                ui.strong(h);
            }
            ui.end_row();
            let models = crate::bench_results::models_in_order(configs);
            for i in order {
                let c = &configs[i];
                let index = models.iter().position(|m| *m == c.method).unwrap_or(0);
                marker_icon(ui, crate::chart_style::style(&c.method, index));
                if ui
                    .button(c.name())
                    .on_hover_text("render the views with this model, wavelength set and quality")
                    .clicked()
                {
                    clicked = Some(i);
                }
                ui.label(if c.on_front { "front" } else { "" })
                    .on_hover_text("on the Pareto front: nothing measured is both faster and closer to the path tracer");
                for v in [
                    if c.timed() {
                        format!("{:.2}", c.frame_ms)
                    } else {
                        "—".into()
                    },
                    format!("{:.0}", c.precompute_ms),
                    format!("{:.2}", c.table_bytes as f64 / 1048576.0),
                    format!("{:.2}", c.de2000_mean),
                    format!("{:.2}", c.de2000_p95),
                    format!("{:.3}", c.flip),
                    format!("{:.3}", c.rel_rmse),
                ] {
                    ui.label(v);
                }
                ui.end_row();
            }
        });
    });
    clicked
}
