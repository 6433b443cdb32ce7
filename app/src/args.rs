//! Parsers of the values a user writes on the command line or in a preset field: numbers,
//! sizes, model ids, wavelength sets and qualities. Each error names what was expected.

use atmoscope_model::scene::{Method, Quality, WavelengthSet};

/// Refuses wavelengths outside the visible range the model's tables cover.
pub fn check_wavelengths(wavelengths_nm: &[f64]) -> anyhow::Result<()> {
    use atmoscope_model::constants::{VISIBLE_MAX_NM, VISIBLE_MIN_NM};
    match wavelengths_nm
        .iter()
        .find(|w| !(**w >= VISIBLE_MIN_NM && **w <= VISIBLE_MAX_NM))
    {
        Some(w) => anyhow::bail!(
            "--wavelengths-nm: {w} nm is outside {VISIBLE_MIN_NM} to {VISIBLE_MAX_NM} nm"
        ),
        None => Ok(()),
    }
}

/// A finite number (NaN and infinities are refused: they would pass every later comparison).
pub fn parse_finite(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(v) => Err(format!("{v} is not a finite number")),
        Err(e) => Err(format!("`{s}` is not a number: {e}")),
    }
}

/// A finite number above zero.
pub fn parse_positive(s: &str) -> Result<f64, String> {
    match parse_finite(s)? {
        v if v > 0.0 => Ok(v),
        v => Err(format!("{v} must be above 0")),
    }
}

/// A real-time model by its registry id (`--method`).
pub fn parse_method(id: &str) -> Result<Method, String> {
    use atmoscope_model::methods;
    match methods::by_id(id) {
        Some(m) if m.is_realtime() => Ok(m.method),
        Some(m) => Err(format!(
            "{} is the offline ground truth: use `atmoscope reference` for it (real-time models: {})",
            m.id,
            methods::realtime_ids()
        )),
        None => Err(format!(
            "no model `{id}` (real-time models: {})",
            methods::realtime_ids()
        )),
    }
}

/// Real-time models named on the command line (`--methods`).
#[derive(Debug, Clone, PartialEq)]
pub struct MethodList(pub Vec<Method>);

/// A comma-separated list of real-time models, or `all` (`--methods`).
pub fn parse_methods(list: &str) -> Result<MethodList, String> {
    if list == "all" {
        return Ok(MethodList(
            atmoscope_model::methods::realtime()
                .map(|m| m.method)
                .collect(),
        ));
    }
    list.split(',')
        .map(|id| parse_method(id.trim()))
        .collect::<Result<_, _>>()
        .map(MethodList)
}

/// The registry id of a method, for tables and file names.
pub fn method_id(method: Method) -> &'static str {
    atmoscope_model::methods::info(method).id
}

/// An image size `WxH`, each side 1 to 8192 pixels.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or("expected WxH, e.g. 320x180")?;
    let w: u32 = w.parse().map_err(|_| format!("bad width {w:?}"))?;
    let h: u32 = h.parse().map_err(|_| format!("bad height {h:?}"))?;
    if w == 0 || h == 0 || w > 8192 || h > 8192 {
        return Err("width and height must be 1 to 8192".into());
    }
    Ok((w, h))
}

/// Parses rgb3 | spectral4 | spectralN.
pub fn parse_wavelengths(s: &str) -> Result<WavelengthSet, String> {
    let lower = s.to_ascii_lowercase();
    match lower.as_str() {
        "rgb3" => Ok(WavelengthSet::Rgb3),
        "spectral4" => Ok(WavelengthSet::Spectral4),
        _ => {
            let n: u32 = lower
                .strip_prefix("spectral")
                .and_then(|n| n.parse().ok())
                .ok_or_else(|| format!("{s:?}: expected rgb3, spectral4 or spectralN"))?;
            if !n.is_multiple_of(4) || !(4..=128).contains(&n) {
                return Err(format!(
                    "spectral{n}: N must be a multiple of 4 from 4 to 128"
                ));
            }
            Ok(WavelengthSet::SpectralN(n))
        }
    }
}

/// A luminance range `MIN,MAX` as log10 of cd/m², −10 ≤ MIN < MAX ≤ 12.
pub fn parse_range(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s.split_once(',').ok_or("expected MIN,MAX, e.g. -2,5")?;
    let a: f64 = a.trim().parse().map_err(|_| format!("bad minimum {a:?}"))?;
    let b: f64 = b.trim().parse().map_err(|_| format!("bad maximum {b:?}"))?;
    if !(a < b) || a < -10.0 || b > 12.0 {
        return Err("need -10 ≤ MIN < MAX ≤ 12 (log10 cd/m²)".into());
    }
    Ok((a, b))
}

/// The name of a wavelength set as `--wavelengths` takes it (rgb3, spectral4, spectralN).
pub fn set_name(s: WavelengthSet) -> String {
    match s {
        WavelengthSet::Rgb3 => "rgb3".into(),
        WavelengthSet::Spectral4 => "spectral4".into(),
        WavelengthSet::SpectralN(n) => format!("spectral{n}"),
    }
}

/// A quality as `--qualities` takes it: low, medium or high.
pub fn parse_quality(s: &str) -> Result<Quality, String> {
    match s.to_ascii_lowercase().as_str() {
        "low" => Ok(Quality::Low),
        "medium" => Ok(Quality::Medium),
        "high" => Ok(Quality::High),
        _ => Err(format!("{s:?}: expected low, medium or high")),
    }
}

/// The name `parse_quality` reads back.
pub fn quality_name(q: Quality) -> &'static str {
    match q {
        Quality::Low => "low",
        Quality::Medium => "medium",
        Quality::High => "high",
    }
}
