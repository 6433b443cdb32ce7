//! Guided scenes for teaching (the explorer's Learn menu and `atmoscope learn`): each sets a
//! scene, opens the tab that shows it and explains it in a few sentences whose numbers are
//! computed from the model for the scene on screen, so they follow the user's changes.
//!
//! Lessons are data, `presets/learn/*.ron`, embedded at build time. A lesson names a shipped
//! preset, fields to change in it (as `--set` does), the tab, a pixel for the Inspector, the
//! Scene panel section to try, and its text. Numbers in the text are placeholders:
//! `{tau_rayleigh:450}` is the vertical optical depth of air at 450 nm from the camera to space;
//! the full list is [`Quantity`]. Literal numbers in the text may only be wavelengths
//! ("450 nm"): anything measured comes from the model.

use crate::presets::load_shipped;
use crate::summary;
use crate::tab::Tab;
use atmoscope_model::{Atmosphere, Scene};
use serde::Deserialize;
use std::path::Path;
use thiserror::Error;

include!(concat!(env!("OUT_DIR"), "/lessons.rs"));

/// A section of the Scene panel, to highlight for the user to try.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
pub enum Section {
    Aerosols,
    Ozone,
    GroundAndAir,
    Sun,
    Camera,
    Rendering,
}

impl Section {
    /// The section's heading in the Scene panel.
    pub fn title(self) -> &'static str {
        match self {
            Section::Aerosols => "Aerosols",
            Section::Ozone => "Ozone",
            Section::GroundAndAir => "Ground and air",
            Section::Sun => "Sun",
            Section::Camera => "Camera",
            Section::Rendering => "Rendering and display",
        }
    }
}

/// A lesson as written in its file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Lesson {
    pub title: String,
    /// A shipped preset's file name, e.g. `clear-noon.ron`.
    pub preset: String,
    /// Fields to change in the preset: (dotted path, value), as `atmoscope render --set`.
    #[serde(default)]
    pub set: Vec<(String, String)>,
    pub tab: Tab,
    /// A point of the view (fractions of its width and height, 0–1) that the Inspector
    /// analyses; Sky, Fisheye and Luminance tabs only.
    #[serde(default)]
    pub inspect: Option<[f64; 2]>,
    /// The Scene panel section the user is invited to try.
    pub section: Section,
    /// One sentence: what to try there.
    pub try_this: String,
    /// The explanation, with `{quantity}` or `{quantity:wavelength_nm}` placeholders.
    pub text: String,
}

#[derive(Debug, Error)]
pub enum LessonError {
    #[error("{file}: {message}")]
    Parse { file: String, message: String },
    #[error("{file}: no shipped preset {preset}")]
    NoPreset { file: String, preset: String },
    #[error("{file}: {message}")]
    Scene { file: String, message: String },
    #[error("{file}: placeholder {{{placeholder}}}: {message}")]
    Placeholder {
        file: String,
        placeholder: String,
        message: String,
    },
    #[error("{file}: {message}")]
    Invalid { file: String, message: String },
}

/// What a placeholder can show, all computed by [`summary::compute`] for the current scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Quantity {
    /// Vertical optical depth from the camera to space of air, ozone, aerosol, or all (at λ).
    TauRayleigh,
    TauOzone,
    TauAerosol,
    TauTotal,
    /// Share of sunlight that reaches the camera directly, percent (at λ).
    SunPercent,
    /// Share of light that crosses a horizontal path from the camera out of the atmosphere,
    /// percent (at λ).
    HorizonPercent,
    /// The aerosol's single-scattering albedo and asymmetry parameter (at λ).
    AerosolSsa,
    AerosolG,
    /// How many times the vertical column's optical depth a horizontal ray from the camera
    /// out of the atmosphere meets (at λ).
    HorizonAirmass,
    /// Meteorological visibility at the camera (Koschmieder: the distance at which a black
    /// object's contrast falls to 2 %), km, at 550 nm; with everything, or with air alone.
    VisibilityKm,
    AirVisibilityKm,
    SunElevationDeg,
    AltitudeKm,
    OzoneDu,
    Aod550,
    /// The degree of polarisation of sunlight scattered once, 90° from the sun in its vertical
    /// plane (on the far side when the sun is up), percent (at λ); air alone's limit there,
    /// (1−ρ)/(1+ρ), percent (at λ); and what a polarising filter passes of that light turned
    /// across and along its electric vector, percent of the light without the filter (at λ).
    Polarisation90Percent,
    AirPolarisationPercent,
    PolariserAcrossPercent,
    PolariserAlongPercent,
}

impl Quantity {
    const NAMES: [(&'static str, Quantity, bool); 19] = [
        ("tau_rayleigh", Quantity::TauRayleigh, true),
        ("tau_ozone", Quantity::TauOzone, true),
        ("tau_aerosol", Quantity::TauAerosol, true),
        ("tau_total", Quantity::TauTotal, true),
        ("sun_percent", Quantity::SunPercent, true),
        ("horizon_percent", Quantity::HorizonPercent, true),
        ("aerosol_ssa", Quantity::AerosolSsa, true),
        ("aerosol_g", Quantity::AerosolG, true),
        ("horizon_airmass", Quantity::HorizonAirmass, true),
        ("visibility_km", Quantity::VisibilityKm, false),
        ("air_visibility_km", Quantity::AirVisibilityKm, false),
        ("sun_elevation_deg", Quantity::SunElevationDeg, false),
        ("altitude_km", Quantity::AltitudeKm, false),
        ("ozone_du", Quantity::OzoneDu, false),
        ("aod550", Quantity::Aod550, false),
        (
            "polarisation_90_percent",
            Quantity::Polarisation90Percent,
            true,
        ),
        (
            "air_polarisation_percent",
            Quantity::AirPolarisationPercent,
            true,
        ),
        (
            "polariser_across_percent",
            Quantity::PolariserAcrossPercent,
            true,
        ),
        (
            "polariser_along_percent",
            Quantity::PolariserAlongPercent,
            true,
        ),
    ];
}

/// A parsed placeholder: the quantity and, where it needs one, its wavelength.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Placeholder {
    quantity: Quantity,
    wavelength_nm: Option<f64>,
}

/// The contrast threshold of meteorological visibility (Koschmieder 1924; WMO).
const VISIBILITY_CONTRAST: f64 = 0.02;
/// The wavelength visibility is defined at, nm.
const VISIBILITY_NM: f64 = 550.0;

/// Wavelengths a placeholder may ask for, nm.
const WAVELENGTH_RANGE_NM: std::ops::RangeInclusive<f64> = 360.0..=830.0;

fn parse_placeholder(text: &str) -> Result<Placeholder, String> {
    let (name, wavelength) = match text.split_once(':') {
        Some((n, w)) => (n.trim(), Some(w.trim())),
        None => (text.trim(), None),
    };
    let Some(&(_, quantity, needs_wavelength)) =
        Quantity::NAMES.iter().find(|(n, _, _)| *n == name)
    else {
        let known: Vec<&str> = Quantity::NAMES.iter().map(|(n, _, _)| *n).collect();
        return Err(format!("unknown quantity; known: {}", known.join(", ")));
    };
    let wavelength_nm = match (needs_wavelength, wavelength) {
        (true, Some(w)) => {
            let w: f64 = w
                .parse()
                .map_err(|_| format!("`{w}` is not a wavelength in nm"))?;
            if !WAVELENGTH_RANGE_NM.contains(&w) {
                return Err(format!("{w} nm is outside 360–830 nm"));
            }
            Some(w)
        }
        (true, None) => return Err(format!("{name} needs a wavelength, e.g. {{{name}:550}}")),
        (false, Some(_)) => return Err(format!("{name} takes no wavelength")),
        (false, None) => None,
    };
    Ok(Placeholder {
        quantity,
        wavelength_nm,
    })
}

/// The text split into literal pieces and placeholders.
enum Piece<'a> {
    Text(&'a str),
    Value(Placeholder, &'a str),
}

fn pieces(text: &str) -> Result<Vec<Piece<'_>>, (String, String)> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(open) = rest.find('{') {
        out.push(Piece::Text(&rest[..open]));
        let after = &rest[open + 1..];
        let close = after
            .find('}')
            .ok_or_else(|| (after.to_string(), "no closing }".to_string()))?;
        let inner = &after[..close];
        let p = parse_placeholder(inner).map_err(|m| (inner.to_string(), m))?;
        out.push(Piece::Value(p, inner));
        rest = &after[close + 1..];
    }
    out.push(Piece::Text(rest));
    Ok(out)
}

/// A percentage; a share too small to read as a number says so.
fn format_percent(v: f64) -> String {
    if v < 0.01 {
        "less than 0.01".to_string()
    } else {
        format_number(v)
    }
}

/// A number with three significant digits, without trailing noise.
fn format_number(v: f64) -> String {
    let a = v.abs();
    if a >= 100.0 || a == 0.0 {
        format!("{v:.0}")
    } else if a >= 10.0 {
        format!("{v:.1}")
    } else if a >= 0.01 {
        let digits = 2 - a.log10().floor() as i32;
        format!("{v:.*}", digits.max(0) as usize)
    } else {
        format!("{v:.2e}")
    }
}

impl Lesson {
    /// Parses and checks a lesson: its preset exists and takes its changes, its tab can be
    /// inspected where it asks, and every placeholder names a known quantity.
    pub fn parse(file: &str, text: &str) -> Result<Lesson, LessonError> {
        let lesson: Lesson = ron::from_str(text).map_err(|e| LessonError::Parse {
            file: file.into(),
            message: e.to_string(),
        })?;
        lesson.scene(file)?;
        pieces(&lesson.text).map_err(|(placeholder, message)| LessonError::Placeholder {
            file: file.into(),
            placeholder,
            message,
        })?;
        if let Some(p) = lesson.inspect {
            if !matches!(
                lesson.tab,
                Tab::Sky | Tab::Fisheye | Tab::Luminance | Tab::Polarisation
            ) {
                return Err(LessonError::Invalid {
                    file: file.into(),
                    message: format!("the {} tab has no pixel to inspect", lesson.tab.label()),
                });
            }
            if !p.iter().all(|v| (0.0..=1.0).contains(v)) {
                return Err(LessonError::Invalid {
                    file: file.into(),
                    message: format!("inspect {p:?} must lie in 0–1"),
                });
            }
        }
        if lesson.title.trim().is_empty() || lesson.try_this.trim().is_empty() {
            return Err(LessonError::Invalid {
                file: file.into(),
                message: "a lesson needs a title and something to try".into(),
            });
        }
        Ok(lesson)
    }

    /// The lesson's scene: its preset with its changes, validated.
    pub fn scene(&self, file: &str) -> Result<Scene, LessonError> {
        let mut scene = match load_shipped(&self.preset) {
            Some(Ok(s)) => s,
            Some(Err(e)) => {
                return Err(LessonError::Scene {
                    file: file.into(),
                    message: e.to_string(),
                });
            }
            None => {
                return Err(LessonError::NoPreset {
                    file: file.into(),
                    preset: self.preset.clone(),
                });
            }
        };
        let scene_error = |message: String| LessonError::Scene {
            file: file.into(),
            message,
        };
        for (path, value) in &self.set {
            scene
                .set_path(path, value)
                .map_err(|e| scene_error(e.to_string()))?;
        }
        scene.validate().map_err(|errors| {
            scene_error(
                errors
                    .iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join("; "),
            )
        })?;
        Ok(scene)
    }

    /// The text with every placeholder replaced by its value for `scene`.
    pub fn text_for(&self, scene: &Scene) -> String {
        let Ok(pieces) = pieces(&self.text) else {
            // Checked by `parse`; a lesson that got here unchecked shows its raw text.
            return self.text.clone();
        };
        let mut wavelengths: Vec<f64> = pieces
            .iter()
            .filter_map(|p| match p {
                Piece::Value(v, _) => match v.quantity {
                    Quantity::VisibilityKm | Quantity::AirVisibilityKm => Some(VISIBILITY_NM),
                    _ => v.wavelength_nm,
                },
                Piece::Text(_) => None,
            })
            .collect();
        wavelengths.sort_by(f64::total_cmp);
        wavelengths.dedup();
        let info = summary::compute(scene, &wavelengths);
        let row = |w: f64| info.wavelengths.iter().find(|r| r.wavelength_nm == w);
        pieces
            .iter()
            .map(|p| match p {
                Piece::Text(t) => (*t).to_string(),
                Piece::Value(v, raw) => {
                    let visibility_km =
                        |extinction_per_m: f64| -VISIBILITY_CONTRAST.ln() / extinction_per_m / 1e3;
                    let at_550 = row(VISIBILITY_NM).map(|r| r.extinction_at_camera_per_m);
                    let percent = matches!(
                        v.quantity,
                        Quantity::SunPercent
                            | Quantity::HorizonPercent
                            | Quantity::Polarisation90Percent
                            | Quantity::AirPolarisationPercent
                            | Quantity::PolariserAcrossPercent
                            | Quantity::PolariserAlongPercent
                    );
                    let degree_90 = || v.wavelength_nm.map(|w| polarisation_90(scene, w));
                    let value = match (v.quantity, v.wavelength_nm.and_then(row)) {
                        (Quantity::VisibilityKm, _) => at_550.map(|e| visibility_km(e.total)),
                        (Quantity::AirVisibilityKm, _) => at_550.map(|e| visibility_km(e.rayleigh)),
                        (Quantity::HorizonAirmass, Some(r)) => {
                            Some(-r.horizontal_transmittance.ln() / r.optical_depth.total)
                        }
                        (Quantity::SunElevationDeg, _) => Some(info.sun_elevation_deg),
                        (Quantity::AltitudeKm, _) => Some(info.camera_altitude_m / 1e3),
                        (Quantity::OzoneDu, _) => Some(info.ozone_column_du),
                        (Quantity::Aod550, _) => Some(info.aod550),
                        (Quantity::TauRayleigh, Some(r)) => Some(r.optical_depth.rayleigh),
                        (Quantity::TauOzone, Some(r)) => Some(r.optical_depth.ozone),
                        (Quantity::TauAerosol, Some(r)) => Some(r.optical_depth.aerosol),
                        (Quantity::TauTotal, Some(r)) => Some(r.optical_depth.total),
                        (Quantity::SunPercent, Some(r)) => Some(100.0 * r.direct_transmittance),
                        (Quantity::HorizonPercent, Some(r)) => {
                            Some(100.0 * r.horizontal_transmittance)
                        }
                        (Quantity::AerosolSsa, Some(r)) => Some(r.aerosol_ssa),
                        (Quantity::AerosolG, Some(r)) => Some(r.aerosol_g),
                        (Quantity::Polarisation90Percent, Some(_)) => {
                            degree_90().map(|d| 100.0 * d)
                        }
                        (Quantity::AirPolarisationPercent, Some(_)) => v.wavelength_nm.map(|w| {
                            let rho = Atmosphere::for_scene(scene)
                                .optics(w)
                                .rayleigh_depolarisation;
                            100.0 * atmoscope_model::polarisation::rayleigh_degree(0.0, rho)
                        }),
                        (Quantity::PolariserAcrossPercent, Some(_)) => {
                            degree_90().map(|d| 50.0 * (1.0 - d))
                        }
                        (Quantity::PolariserAlongPercent, Some(_)) => {
                            degree_90().map(|d| 50.0 * (1.0 + d))
                        }
                        (_, None) => None,
                    };
                    match value {
                        Some(v) if percent => format_percent(v),
                        Some(v) => format_number(v),
                        None => format!("{{{raw}}}"),
                    }
                }
            })
            .collect()
    }
}

/// The degree of polarisation (0–1) of the sunlight scattered once that reaches the camera of
/// `scene` from 90° from the sun in the sun's vertical plane, at `wavelength_nm` (exact single
/// scattering, `methods::single_scattering::stokes`).
fn polarisation_90(scene: &Scene, wavelength_nm: f64) -> f64 {
    use atmoscope_model::geometry::{Ray, direction_from_angles};
    let atm = Atmosphere::for_scene(scene);
    let a = scene.sun.angles();
    let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
    let view = if a.elevation_deg >= 0.0 {
        direction_from_angles(90.0 - a.elevation_deg, a.azimuth_deg + 180.0)
    } else {
        direction_from_angles(90.0 + a.elevation_deg, a.azimuth_deg)
    };
    let origin = glam::DVec3::new(0.0, 0.0, atm.bottom_radius_m + scene.camera.altitude_m);
    atmoscope_model::methods::single_scattering::stokes(
        &atm,
        &Ray::new(origin, view),
        sun,
        wavelength_nm,
    )
    .degree_of_polarization()
}

/// Every shipped lesson, in file order: (file name, lesson or why it does not load).
pub fn shipped() -> Vec<(&'static str, Result<Lesson, LessonError>)> {
    LESSONS
        .iter()
        .map(|(name, text)| (*name, Lesson::parse(name, text)))
        .collect()
}

/// The shipped lesson of a file name, with or without `.ron`.
pub fn find(name: &str) -> Option<Result<Lesson, LessonError>> {
    let file = Path::new(name).with_extension("ron");
    LESSONS
        .iter()
        .find(|(n, _)| Path::new(n) == file)
        .map(|(n, text)| Lesson::parse(n, text))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Digit runs in the literal text that are not wavelengths ("450 nm").
    fn literal_numbers(text: &str) -> Vec<String> {
        let literal: String = match pieces(text) {
            Ok(p) => p
                .iter()
                .map(|p| match p {
                    Piece::Text(t) => *t,
                    Piece::Value(..) => " ",
                })
                .collect(),
            Err(_) => text.to_string(),
        };
        let mut found = Vec::new();
        let chars: Vec<char> = literal.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            if chars[i].is_ascii_digit() {
                let start = i;
                while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                    i += 1;
                }
                let tail: String = chars[i..].iter().take(3).collect();
                if tail != " nm" {
                    found.push(chars[start..i].iter().collect());
                }
            } else {
                i += 1;
            }
        }
        found
    }

    #[test]
    fn every_lesson_loads_and_every_number_in_its_text_is_computed() {
        let lessons = shipped();
        assert!(lessons.len() >= 6, "only {} lessons", lessons.len());
        for (file, lesson) in lessons {
            let lesson = lesson.unwrap_or_else(|e| panic!("{e}"));
            let scene = lesson.scene(file).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(
                literal_numbers(&lesson.text),
                Vec::<String>::new(),
                "{file}: numbers in the text must be placeholders"
            );
            let text = lesson.text_for(&scene);
            assert!(
                !text.contains('{'),
                "{file}: unresolved placeholder in {text}"
            );
            assert!(
                lesson.text.contains('{'),
                "{file}: a lesson shows at least one computed number"
            );
        }
    }

    #[test]
    fn placeholders_follow_the_scene() {
        let lesson = Lesson {
            title: "t".into(),
            preset: "clear-noon.ron".into(),
            set: vec![],
            tab: Tab::Sky,
            inspect: None,
            section: Section::Sun,
            try_this: "x".into(),
            text: "air {tau_rayleigh:450}, sun {sun_percent:450} %, at {sun_elevation_deg}°".into(),
        };
        let mut scene = lesson.scene("t").expect("scene");
        let high = lesson.text_for(&scene);
        scene
            .set_path("sun.Angles.elevation_deg", "5")
            .expect("set");
        let low = lesson.text_for(&scene);
        let info = summary::compute(&scene, &[450.0]);
        let expected = format!(
            "air {}, sun {} %, at 5.00°",
            format_number(info.wavelengths[0].optical_depth.rayleigh),
            format_number(100.0 * info.wavelengths[0].direct_transmittance)
        );
        assert_eq!(low, expected);
        assert_ne!(high, low);
    }

    #[test]
    fn bad_lessons_say_what_is_wrong() {
        let base = |text: &str, extra: &str| {
            format!(
                "(title: \"t\", preset: \"clear-noon.ron\", tab: Sky, section: Sun, try_this: \"x\", text: {text:?}{extra})"
            )
        };
        let err = |s: String| Lesson::parse("x.ron", &s).unwrap_err().to_string();
        assert!(err(base("{tau_air:450}", "")).contains("unknown quantity"));
        assert!(err(base("{tau_rayleigh}", "")).contains("needs a wavelength"));
        assert!(err(base("{tau_rayleigh:90}", "")).contains("outside"));
        assert!(err(base("{aod550", "")).contains("no closing"));
        assert!(err(base("ok", ", set: [(\"sun.nothing\", \"1\")]")).contains("nothing"));
        assert!(err(base("ok", "").replace("clear-noon", "missing")).contains("no shipped preset"));
        assert!(err(base("ok", ", inspect: Some((2.0, 0.5))")).contains("0–1"));
        assert!(
            err(base("ok", ", inspect: Some((0.5, 0.5))").replace("tab: Sky", "tab: Luts"))
                .contains("no pixel to inspect")
        );
    }

    #[test]
    fn numbers_keep_three_significant_digits() {
        assert_eq!(format_number(0.2371), "0.237");
        assert_eq!(format_number(4.5678), "4.57");
        assert_eq!(format_number(45.678), "45.7");
        assert_eq!(format_number(456.78), "457");
        assert_eq!(format_number(0.0012), "1.20e-3");
    }
}
