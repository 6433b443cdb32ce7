//! Presets and exports from the window: native dialogs (rfd), and the writes themselves, which
//! run off the UI thread. In a browser, what is written is downloaded under a name chosen here,
//! and a preset to open comes from the browser's file picker (`web::pick_preset`). Exports: the active view as displayed (PNG), its linear radiance (EXR),
//! and an equirectangular panorama (EXR) rendered by an engine of its own on the window's device.

use super::gpu_view::Gpu;
use super::jobs::Progress;
use crate::images::{save_rgb8, write_exr};
use crate::timelapse;
use atmoscope_model::Scene;
use atmoscope_model::camera::Projection;
use atmoscope_render::View;
use std::path::{Path, PathBuf};

/// Pixels of an exported panorama (2:1, equirectangular).
pub const PANORAMA_SIZE: (u32, u32) = (2048, 1024);

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExportKind {
    /// The active view as displayed, 8-bit sRGB.
    Png,
    /// The active view's linear radiance (linear sRGB, W·m⁻²·sr⁻¹).
    Exr,
    /// A 360° × 180° panorama of linear radiance from the camera.
    PanoramaExr,
    /// A sunset (or the scene's day) as an animated PNG, its frames beside it.
    Timelapse,
}

impl ExportKind {
    pub fn extension(self) -> &'static str {
        match self {
            ExportKind::Png | ExportKind::Timelapse => "png",
            ExportKind::Exr | ExportKind::PanoramaExr => "exr",
        }
    }

    pub fn title(self) -> &'static str {
        match self {
            ExportKind::Png => "Export the view as PNG",
            ExportKind::Exr => "Export the view's radiance as EXR",
            ExportKind::PanoramaExr => "Export a panorama EXR",
            ExportKind::Timelapse => "Export a time-lapse (animated PNG)",
        }
    }
}

/// The preset file the user chose to open; in a browser it comes later, from
/// `web::take_picked`.
pub fn pick_preset_to_open(ctx: &eframe::egui::Context) -> Option<PathBuf> {
    #[cfg(target_arch = "wasm32")]
    {
        crate::web::pick_preset(ctx);
        None
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        let _ = ctx;
        rfd::FileDialog::new()
            .set_title("Open a preset")
            .add_filter("Atmoscope preset", &["ron"])
            .pick_file()
    }
}

pub fn pick_preset_to_save(scene: &Scene) -> Option<PathBuf> {
    let name: String = scene
        .name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect();
    save_dialog(
        "Save the scene as a preset",
        "Atmoscope preset",
        "ron",
        &format!("{name}.ron"),
    )
}

pub fn pick_export(kind: ExportKind) -> Option<PathBuf> {
    save_dialog(
        kind.title(),
        kind.extension(),
        kind.extension(),
        &format!("atmoscope.{}", kind.extension()),
    )
}

/// Where to save a file: the user's choice.
#[cfg(not(target_arch = "wasm32"))]
pub fn save_dialog(title: &str, filter: &str, extension: &str, name: &str) -> Option<PathBuf> {
    rfd::FileDialog::new()
        .set_title(title)
        .add_filter(filter, &[extension])
        .set_file_name(name)
        .save_file()
}

/// In a browser, the name of the download (the browser asks where, if it asks).
#[cfg(target_arch = "wasm32")]
pub fn save_dialog(_title: &str, _filter: &str, _extension: &str, name: &str) -> Option<PathBuf> {
    Some(PathBuf::from(name))
}

/// Writes RGBA8 rows as a PNG, dropping alpha, with `caption` burned in below (None: none).
pub fn write_display_png(
    path: &Path,
    rgba: &[u8],
    width: u32,
    height: u32,
    caption: Option<&str>,
) -> anyhow::Result<()> {
    let rgb = rgba
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    let (rgb, rows) = crate::images::with_caption(rgb, width, height, caption);
    save_rgb8(path, rgb, width, rows)
}

/// Writes linear radiance (RGBA f32 rows) as an EXR.
pub fn write_radiance_exr(
    path: &Path,
    rgba: &[[f32; 4]],
    width: u32,
    height: u32,
) -> anyhow::Result<()> {
    let rgb: Vec<[f64; 3]> = rgba
        .iter()
        .map(|p| [p[0], p[1], p[2]].map(f64::from))
        .collect();
    write_exr(path, &rgb, width, height)
}

/// Frames of the explorer's time-lapse, a second at 24 frames a second.
pub const TIMELAPSE_FRAMES: u32 = 48;
pub const TIMELAPSE_FPS: u16 = 24;
pub const TIMELAPSE_SIZE: (u32, u32) = (640, 360);

/// Renders a time-lapse of a sunset from the scene's sun (or of the scene's day, when the sun is
/// placed by date) with the view's projection: the animation at `path`, the frames in the
/// folder `<name>_frames` beside it. None when cancelled.
pub fn export_timelapse(
    gpu: &Gpu,
    scene: &Scene,
    projection: Projection,
    path: &Path,
    progress: &Progress,
) -> anyhow::Result<Option<String>> {
    let (w, h) = TIMELAPSE_SIZE;
    let stem = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("timelapse");
    let dir = path.with_file_name(format!("{stem}_frames"));
    let sweep = timelapse::Sweep::sunset_or_day(scene);
    let written = timelapse::render(
        &mut crate::engine_setup::engine_beside_a_window(&gpu.device, &gpu.queue),
        scene,
        sweep,
        TIMELAPSE_FRAMES,
        View::new(projection, w, h),
        TIMELAPSE_FPS,
        &dir,
        path,
        &|f| {
            progress.set(f);
            !progress.cancelled()
        },
    )?;
    Ok(written.map(|written| {
        format!(
            "wrote {} ({} frames, {w}×{h}; the frames are in {})",
            path.display(),
            written.frames.len(),
            dir.display()
        )
    }))
}

/// Renders and writes a panorama; None when cancelled.
pub fn export_panorama(
    gpu: &Gpu,
    scene: &Scene,
    path: &Path,
    progress: &Progress,
) -> anyhow::Result<Option<String>> {
    let (w, h) = PANORAMA_SIZE;
    // Beside the window: its build a slice at a time.
    let mut engine = crate::engine_setup::engine_beside_a_window(&gpu.device, &gpu.queue);
    progress.set(0.1);
    let view = View::new(Projection::Panorama, w, h);
    let cancelled = || progress.cancelled();
    if !crate::engine_setup::render_beside_a_window(&mut engine, scene, &view, &cancelled)? {
        return Ok(None);
    }
    engine.wait();
    progress.set(0.6);
    if progress.cancelled() {
        return Ok(None);
    }
    let radiance = engine.read_radiance()?;
    progress.set(0.8);
    write_radiance_exr(path, &radiance, w, h)?;
    progress.set(1.0);
    Ok(Some(format!("wrote {} ({w}×{h} panorama)", path.display())))
}
