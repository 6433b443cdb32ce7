//! The results of `atmoscope bench methods`, one row per model × wavelength set × quality ×
//! view: written to `results.csv` by the command, read back by the explorer's Bench tab (an
//! untrusted file: every line is checked), and summarised per configuration with the Pareto
//! front of frame time against error.

use atmoscope_eval::metrics::pareto_front;
use atmoscope_model::methods;

/// The columns of `results.csv`, in order.
pub const COLUMNS: [&str; 11] = [
    "method",
    "wavelengths",
    "quality",
    "view",
    "precompute_ms",
    "frame_ms",
    "table_bytes",
    "de2000_mean",
    "de2000_p95",
    "flip",
    "rel_rmse",
];

/// One model × wavelength set × quality on one view of the suite.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Registry id of the model.
    pub method: String,
    /// `rgb3`, `spectral4` or `spectralN`.
    pub wavelengths: String,
    /// `low`, `medium` or `high`.
    pub quality: String,
    pub view: String,
    /// The table passes of a full rebuild for the view's scene, ms.
    pub precompute_ms: f64,
    /// The passes of a frame with the camera turning (the sky pass, which draws the displayed
    /// image too), ms; None where the run timed no frame on this view (`--full` times frames
    /// on the quick views only).
    pub frame_ms: Option<f64>,
    /// GPU memory of the model's tables, bytes.
    pub table_bytes: u64,
    /// ΔE2000 against the path-traced reference, mean and 95th percentile over the pixels.
    pub de2000_mean: f64,
    pub de2000_p95: f64,
    /// HDR-FLIP, mean over the pixels.
    pub flip: f64,
    /// Relative RMSE of luminance outside the sun's disk.
    pub rel_rmse: f64,
}

/// Why `results.csv` could not be read.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum ResultsError {
    #[error("the file is empty")]
    Empty,
    #[error("line 1: expected the header {expected:?}")]
    Header { expected: String },
    #[error("line {line}: {message}")]
    Line { line: usize, message: String },
}

/// `rows` as CSV, header first.
pub fn to_csv(rows: &[Row]) -> String {
    let mut s = COLUMNS.join(",") + "\n";
    for r in rows {
        s += &format!(
            "{},{},{},{},{:.4},{},{},{:.4},{:.4},{:.5},{:.5}\n",
            r.method,
            r.wavelengths,
            r.quality,
            r.view,
            r.precompute_ms,
            r.frame_ms.map_or(String::new(), |ms| format!("{ms:.4}")),
            r.table_bytes,
            r.de2000_mean,
            r.de2000_p95,
            r.flip,
            r.rel_rmse
        );
    }
    s
}

/// Reads `results.csv`; names the first bad line and what is wrong with it.
pub fn parse_csv(text: &str) -> Result<Vec<Row>, ResultsError> {
    let mut lines = text.lines();
    let header = lines.next().ok_or(ResultsError::Empty)?;
    if header.trim() != COLUMNS.join(",") {
        return Err(ResultsError::Header {
            expected: COLUMNS.join(","),
        });
    }
    let mut rows = Vec::new();
    for (i, line) in lines.enumerate().filter(|(_, l)| !l.trim().is_empty()) {
        let bad = |message: String| ResultsError::Line {
            line: i + 2,
            message,
        };
        let f: Vec<&str> = line.trim().split(',').collect();
        if f.len() != COLUMNS.len() {
            return Err(bad(format!(
                "{} fields, expected {}",
                f.len(),
                COLUMNS.len()
            )));
        }
        let number = |k: usize| -> Result<f64, ResultsError> {
            match f[k].parse::<f64>() {
                Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
                _ => Err(bad(format!(
                    "{}: {:?} is not a finite number ≥ 0",
                    COLUMNS[k], f[k]
                ))),
            }
        };
        if let Some(k) = (0..4).find(|&k| f[k].is_empty()) {
            return Err(bad(format!("{} is empty", COLUMNS[k])));
        }
        rows.push(Row {
            method: f[0].into(),
            wavelengths: f[1].into(),
            quality: f[2].into(),
            view: f[3].into(),
            precompute_ms: number(4)?,
            frame_ms: match f[5] {
                "" => None,
                _ => Some(number(5)?),
            },
            table_bytes: f[6]
                .parse()
                .map_err(|_| bad(format!("table_bytes: {:?} is not a byte count", f[6])))?,
            de2000_mean: number(7)?,
            de2000_p95: number(8)?,
            flip: number(9)?,
            rel_rmse: number(10)?,
        });
    }
    Ok(rows)
}

/// One model × wavelength set × quality over the views it was measured on: means of every
/// figure (the largest table memory).
#[derive(Debug, Clone, PartialEq)]
pub struct Config {
    pub method: String,
    pub wavelengths: String,
    pub quality: String,
    pub views: usize,
    pub precompute_ms: f64,
    /// Mean over the views whose frames were timed; NaN where none was ([`Config::timed`]).
    pub frame_ms: f64,
    pub table_bytes: u64,
    pub de2000_mean: f64,
    pub de2000_p95: f64,
    pub flip: f64,
    pub rel_rmse: f64,
    /// On the Pareto front of frame time against mean ΔE2000 (a baseline never is, nor a
    /// configuration measured on fewer views than the most: a model that refuses some).
    pub on_front: bool,
}

impl Config {
    /// Whether any of the configuration's frames was timed (it has a place on a time axis).
    pub fn timed(&self) -> bool {
        self.frame_ms.is_finite()
    }

    /// `method/wavelengths/quality`, as the chart and the tables label it.
    pub fn name(&self) -> String {
        format!("{}/{}/{}", self.method, self.wavelengths, self.quality)
    }
}

/// The configurations in `rows`, in order of first appearance, with their Pareto front.
pub fn summarise(rows: &[Row]) -> Vec<Config> {
    let mut configs: Vec<(Config, Vec<&Row>)> = Vec::new();
    for r in rows {
        let same = |c: &Config| {
            c.method == r.method && c.wavelengths == r.wavelengths && c.quality == r.quality
        };
        match configs.iter_mut().find(|(c, _)| same(c)) {
            Some((_, group)) => group.push(r),
            None => configs.push((
                Config {
                    method: r.method.clone(),
                    wavelengths: r.wavelengths.clone(),
                    quality: r.quality.clone(),
                    views: 0,
                    precompute_ms: 0.0,
                    frame_ms: 0.0,
                    table_bytes: 0,
                    de2000_mean: 0.0,
                    de2000_p95: 0.0,
                    flip: 0.0,
                    rel_rmse: 0.0,
                    on_front: false,
                },
                vec![r],
            )),
        }
    }
    let mut out: Vec<Config> = configs
        .into_iter()
        .map(|(mut c, group)| {
            let n = group.len() as f64;
            let mean = |f: fn(&Row) -> f64| group.iter().map(|r| f(r)).sum::<f64>() / n;
            c.views = group.len();
            c.precompute_ms = mean(|r| r.precompute_ms);
            // Over the views whose frames were timed.
            let frames: Vec<f64> = group.iter().filter_map(|r| r.frame_ms).collect();
            c.frame_ms = if frames.is_empty() {
                f64::NAN
            } else {
                frames.iter().sum::<f64>() / frames.len() as f64
            };
            c.table_bytes = group.iter().map(|r| r.table_bytes).max().unwrap_or(0);
            c.de2000_mean = mean(|r| r.de2000_mean);
            c.de2000_p95 = mean(|r| r.de2000_p95);
            c.flip = mean(|r| r.flip);
            c.rel_rmse = mean(|r| r.rel_rmse);
            c
        })
        .collect();
    // A baseline (no atmosphere) is drawn for scale but is no choice for a sky: it never
    // stands on the front. Nor does a model that refused some views (Preetham off the
    // ground): its means cover easier views than the others' and would not compare. (A
    // configuration that failed on a view is left off the front for the same reason.)
    let most_views = out.iter().map(|c| c.views).max().unwrap_or(0);
    let candidates: Vec<usize> = (0..out.len())
        .filter(|&i| {
            out[i].views == most_views
                && out[i].timed()
                && !methods::by_id(&out[i].method).is_some_and(|m| m.baseline)
        })
        .collect();
    let points: Vec<(f64, f64)> = candidates
        .iter()
        .map(|&i| (out[i].frame_ms, out[i].de2000_mean))
        .collect();
    for k in pareto_front(&points) {
        out[candidates[k]].on_front = true;
    }
    out
}

/// The models of `configs`, each once, in order of first appearance (one legend entry and
/// one marker each, however the rows are ordered).
pub fn models_in_order(configs: &[Config]) -> Vec<&str> {
    let mut models: Vec<&str> = Vec::new();
    for c in configs {
        if !models.contains(&c.method.as_str()) {
            models.push(&c.method);
        }
    }
    models
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(method: &str, view: &str, frame_ms: f64, de: f64) -> Row {
        Row {
            method: method.into(),
            wavelengths: "rgb3".into(),
            quality: "medium".into(),
            view: view.into(),
            precompute_ms: 2.0,
            frame_ms: Some(frame_ms),
            table_bytes: 1024,
            de2000_mean: de,
            de2000_p95: 2.0 * de,
            flip: 0.1,
            rel_rmse: 0.05,
        }
    }

    #[test]
    fn results_read_back_as_written_and_bad_lines_are_named() {
        let untimed = Row {
            frame_ms: None,
            ..row("b", "v3", 0.0, 1.0)
        };
        let rows = vec![row("a", "v1", 1.5, 2.0), row("b", "v2", 0.25, 3.5), untimed];
        assert_eq!(parse_csv(&to_csv(&rows)), Ok(rows));
        let bad = to_csv(&[row("a", "v1", 1.0, 2.0)]).replace("1.0000,", "-1,");
        assert!(
            matches!(parse_csv(&bad), Err(ResultsError::Line { line: 2, ref message }) if message.starts_with("frame_ms")),
            "{:?}",
            parse_csv(&bad)
        );
        assert_eq!(
            parse_csv("method,view\n"),
            Err(ResultsError::Header {
                expected: COLUMNS.join(",")
            })
        );
        assert_eq!(parse_csv(""), Err(ResultsError::Empty));
        let short = COLUMNS.join(",") + "\na,b,c\n";
        assert!(matches!(
            parse_csv(&short),
            Err(ResultsError::Line { line: 2, .. })
        ));
    }

    #[test]
    fn configurations_average_their_views_and_mark_the_front() {
        let rows = vec![
            row("fast", "v1", 1.0, 4.0),
            row("fast", "v2", 3.0, 6.0),
            row("slow", "v1", 10.0, 1.0),
            row("bad", "v1", 20.0, 5.0),
            row("empty", "v1", 0.5, 30.0),
            row("empty", "v2", 0.5, 30.0),
            row("slow", "v2", 10.0, 1.0),
            row("bad", "v2", 20.0, 5.0),
            // Drawn on one view only (it refused the other): fastest and best, yet no pick.
            row("preetham", "v1", 0.2, 0.5),
        ];
        let c = summarise(&rows);
        assert_eq!(c.len(), 5);
        assert_eq!((c[0].views, c[0].frame_ms, c[0].de2000_mean), (2, 2.0, 5.0));
        // A view whose frame was not timed counts for the error, not for the frame time.
        let mut partly = rows.clone();
        partly[1].frame_ms = None;
        let c = summarise(&partly);
        assert_eq!((c[0].views, c[0].frame_ms, c[0].de2000_mean), (2, 1.0, 5.0));
        assert_eq!(c[0].name(), "fast/rgb3/medium");
        let front: Vec<bool> = c.iter().map(|c| c.on_front).collect();
        // The baseline is the fastest and on no front, nor the model that refused a view.
        assert_eq!(front, vec![true, true, false, false, false]);
        // A configuration with no frame timed has no frame time and stands on no front,
        // however good its error.
        let untimed = |view| Row {
            frame_ms: None,
            ..row("untimed", view, 0.0, 0.1)
        };
        let mut with_untimed = rows.clone();
        with_untimed.extend([untimed("v1"), untimed("v2")]);
        let c = summarise(&with_untimed);
        let u = c
            .iter()
            .find(|c| c.method == "untimed")
            .expect("summarised");
        assert!(!u.timed() && !u.on_front, "{u:?}");
        assert!(
            c.iter()
                .find(|c| c.method == "fast")
                .expect("fast")
                .on_front
        );
    }
}
