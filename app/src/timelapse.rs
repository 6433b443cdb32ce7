//! Time-lapse: a sweep of the sun rendered frame by frame by the GPU engine, written as a
//! numbered PNG sequence and one animated PNG (APNG, which browsers and most viewers play).
//! The sweep moves the sun's elevation from one angle to another (its azimuth kept), or runs
//! through the hours of the scene's day when the sun is placed by date, time and place. A
//! scene with automatic exposure is metered frame by frame, as a time-lapse camera does.

use crate::files::write_atomic;
use anyhow::Context;
use atmoscope_model::Scene;
use atmoscope_model::scene::SunSettings;
use atmoscope_render::{Engine, View};
use std::path::{Path, PathBuf};

/// What moves from the first frame to the last.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sweep {
    /// The sun's elevation, degrees (−90 to 90), its azimuth kept.
    Elevation { from_deg: f64, to_deg: f64 },
    /// The local clock time of the scene's date and place, hours (0 to 24).
    Hours { from_h: f64, to_h: f64 },
}

/// Frames of a time-lapse, at most.
pub const MAX_FRAMES: u32 = 1000;

impl Sweep {
    /// A sunset from the scene's sun (or 10°, if lower) to 8° below the horizon, or the
    /// scene's day from 4 h to 22 h: what the explorer exports.
    pub fn sunset_or_day(scene: &Scene) -> Sweep {
        match scene.sun {
            SunSettings::Date { .. } => Sweep::Hours {
                from_h: 4.0,
                to_h: 22.0,
            },
            SunSettings::Angles { elevation_deg, .. } => Sweep::Elevation {
                from_deg: elevation_deg.max(10.0),
                to_deg: -8.0,
            },
        }
    }

    /// The scene of frame `i` of `n` (the ends included).
    pub fn scene(&self, base: &Scene, i: u32, n: u32) -> anyhow::Result<Scene> {
        let t = if n > 1 {
            f64::from(i) / f64::from(n - 1)
        } else {
            0.0
        };
        let mut scene = base.clone();
        match (*self, &mut scene.sun) {
            (Sweep::Elevation { from_deg, to_deg }, _) => {
                let azimuth_deg = base.sun.angles().azimuth_deg;
                scene.sun = SunSettings::Angles {
                    elevation_deg: from_deg + (to_deg - from_deg) * t,
                    azimuth_deg,
                };
            }
            (Sweep::Hours { from_h, to_h }, SunSettings::Date { time, .. }) => {
                time.hour = (from_h + (to_h - from_h) * t).clamp(0.0, 24.0 - 1e-9);
            }
            (Sweep::Hours { .. }, SunSettings::Angles { .. }) => anyhow::bail!(
                "a sweep through the hours needs the sun placed by date, time and place \
                 (sun: Date(...) in the preset); sweep its elevation instead"
            ),
        }
        scene.validate().map_err(|e| {
            let e: Vec<String> = e.iter().map(ToString::to_string).collect();
            anyhow::anyhow!("frame {i}: {}", e.join("; "))
        })?;
        Ok(scene)
    }

    /// Checks the sweep's numbers.
    pub fn validate(&self) -> anyhow::Result<()> {
        match *self {
            Sweep::Elevation { from_deg, to_deg } => anyhow::ensure!(
                [from_deg, to_deg]
                    .iter()
                    .all(|e| (-90.0..=90.0).contains(e)),
                "elevations {from_deg},{to_deg}: each must be from -90 to 90°"
            ),
            Sweep::Hours { from_h, to_h } => anyhow::ensure!(
                [from_h, to_h].iter().all(|h| (0.0..=24.0).contains(h)),
                "hours {from_h},{to_h}: each must be from 0 to 24"
            ),
        }
        Ok(())
    }
}

/// What a time-lapse wrote.
#[derive(Debug)]
pub struct Written {
    pub frames: Vec<PathBuf>,
    pub animation: PathBuf,
}

/// Renders `frames` frames of `sweep` over `base` with `engine` and writes
/// `<dir>/frame_NNNN.png` and the animation `animation` (APNG at `fps` frames a second,
/// looping). `progress` gets the fraction done after each frame and returns false to stop:
/// then None, and the animation is not written. An engine that builds in slices works beside
/// a window (`engine_setup::engine_beside_a_window`): it builds a slice at a time and leaves
/// the window a frame's time between its frames.
#[allow(clippy::too_many_arguments)]
pub fn render(
    engine: &mut Engine,
    base: &Scene,
    sweep: Sweep,
    frames: u32,
    view: View,
    fps: u16,
    dir: &Path,
    animation: &Path,
    progress: &dyn Fn(f32) -> bool,
) -> anyhow::Result<Option<Written>> {
    sweep.validate()?;
    anyhow::ensure!(
        (1..=MAX_FRAMES).contains(&frames),
        "{frames} frames: from 1 to {MAX_FRAMES}"
    );
    anyhow::ensure!(
        (1..=120).contains(&fps),
        "{fps} frames a second: from 1 to 120"
    );
    // A model that refuses some frame (Preetham once the sun sets) fails here, before any
    // frame is written, rather than halfway through.
    for i in 0..frames {
        let scene = sweep.scene(base, i, frames)?;
        if let Some(why) = atmoscope_model::methods::info(scene.render.method).cannot_draw(&scene) {
            anyhow::bail!(
                "frame {} of {frames}: {why}; choose another model or a sweep inside its domain",
                i + 1
            );
        }
    }
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let beside_a_window = engine.rebuild_slices().is_some();
    let mut images = Vec::new();
    let mut written = Vec::new();
    for i in 0..frames {
        let scene = sweep.scene(base, i, frames)?;
        let done = i as f32 / frames as f32;
        let drawn =
            crate::engine_setup::render_still_beside_a_window(engine, &scene, &view, &|| {
                !progress(done)
            })?;
        if drawn.is_none() {
            return Ok(None);
        }
        if beside_a_window {
            std::thread::sleep(crate::engine_setup::BESIDE_A_WINDOW_PAUSE);
        }
        let rgba = engine.read_display()?;
        let path = dir.join(format!("frame_{i:04}.png"));
        write_atomic(&path, &encode_png(&[&rgba], view.width, view.height, fps)?)?;
        written.push(path);
        images.push(rgba);
        if !progress((i + 1) as f32 / frames as f32) {
            return Ok(None);
        }
    }
    let frames: Vec<&[u8]> = images.iter().map(Vec::as_slice).collect();
    write_atomic(
        animation,
        &encode_png(&frames, view.width, view.height, fps)?,
    )?;
    Ok(Some(Written {
        frames: written,
        animation: animation.to_path_buf(),
    }))
}

/// RGBA8 frames as a PNG: one frame a still image, several an APNG that loops.
fn encode_png(frames: &[&[u8]], width: u32, height: u32, fps: u16) -> anyhow::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, width, height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        if frames.len() > 1 {
            encoder.set_animated(frames.len() as u32, 0)?;
            encoder.set_frame_delay(1, fps)?;
        }
        let mut writer = encoder.write_header()?;
        for frame in frames {
            writer.write_image_data(frame)?;
        }
        writer.finish()?;
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An elevation sweep runs from its first angle to its last with the azimuth kept; a day
    /// sweep needs a sun placed by date and runs the clock; the numbers are checked.
    #[test]
    fn sweeps_place_the_sun_frame_by_frame() {
        let base = Scene::default();
        let sweep = Sweep::Elevation {
            from_deg: 12.0,
            to_deg: -6.0,
        };
        let first = sweep.scene(&base, 0, 10).expect("frame").sun.angles();
        let last = sweep.scene(&base, 9, 10).expect("frame").sun.angles();
        assert!(
            (first.elevation_deg - 12.0).abs() < 1e-9 && (last.elevation_deg + 6.0).abs() < 1e-9
        );
        assert_eq!(first.azimuth_deg, base.sun.angles().azimuth_deg);
        let day = Sweep::Hours {
            from_h: 4.0,
            to_h: 22.0,
        };
        assert!(
            day.scene(&base, 0, 3).is_err(),
            "the default sun is by angles"
        );
        assert_eq!(
            Sweep::sunset_or_day(&base),
            Sweep::Elevation {
                from_deg: 30.0,
                to_deg: -8.0
            }
        );
        let mut dated = base.clone();
        dated.sun = SunSettings::Date {
            time: atmoscope_model::sun_position::DateTime {
                year: 2026,
                month: 6,
                day: 21,
                hour: 12.0,
                utc_offset_h: 1.0,
            },
            latitude_deg: 47.4,
            longitude_deg: 8.5,
        };
        let noon = day
            .scene(&dated, 1, 3)
            .expect("noon")
            .sun
            .angles()
            .elevation_deg;
        let dawn = day
            .scene(&dated, 0, 3)
            .expect("dawn")
            .sun
            .angles()
            .elevation_deg;
        assert!(noon > 60.0 && dawn < 0.0, "{dawn} {noon}");
        assert!(
            Sweep::Elevation {
                from_deg: 95.0,
                to_deg: 0.0
            }
            .validate()
            .is_err()
        );
    }

    /// Several frames make an animated PNG that decodes with every frame.
    #[test]
    fn frames_encode_as_a_looping_apng() {
        let (w, h) = (4, 3);
        let frames: Vec<Vec<u8>> = (0..5u8)
            .map(|i| vec![i * 40; (w * h * 4) as usize])
            .collect();
        let refs: Vec<&[u8]> = frames.iter().map(Vec::as_slice).collect();
        let bytes = encode_png(&refs, w, h, 12).expect("encode");
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let reader = decoder.read_info().expect("decode");
        let control = reader.info().animation_control().expect("an APNG");
        assert_eq!((control.num_frames, control.num_plays), (5, 0));
    }
}
