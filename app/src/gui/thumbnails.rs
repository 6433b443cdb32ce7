//! Thumbnails of the shipped presets for the preset menu: each rendered by the engine with the
//! preset's own settings (metered where it asks), off the UI thread, and cached on disk under a
//! key of the preset's text and the fingerprint of the model's and the engine's sources, so
//! later sessions of the same build read them back.

use super::gpu_view::Gpu;
use super::jobs::{Job, Progress};
use crate::presets::{SHIPPED, load_shipped};
use atmoscope_model::camera::Projection;
use atmoscope_render::{Engine, View};
use eframe::egui;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Thumbnail size, pixels (16:9).
pub const SIZE: [u32; 2] = [96, 54];

/// One preset's thumbnail: RGBA8 rows of [`SIZE`].
pub type Rgba = Vec<u8>;

/// The cache file of a preset's thumbnail.
fn cache_file(dir: &Path, ron: &str) -> PathBuf {
    let key = format!(
        "{}|{}x{}|{ron}",
        env!("ATMOSCOPE_ENGINE_SOURCES"),
        SIZE[0],
        SIZE[1]
    );
    dir.join(format!("{:016x}.png", crate::cache::key(key.as_bytes())))
}

/// A cached thumbnail, if the file reads back whole at the right size.
fn read_cached(path: &Path) -> Option<Rgba> {
    let img = image::open(path).ok()?.to_rgba8();
    (img.dimensions() == (SIZE[0], SIZE[1])).then(|| img.into_raw())
}

/// Every shipped preset's thumbnail, from the cache in `dir` or rendered (and then cached; a
/// cache that cannot be written only costs the next session a render). Presets that do not
/// load are left out. Returns `None` when cancelled.
pub fn load_or_render(
    gpu: &Gpu,
    dir: &Path,
    progress: &Progress,
) -> anyhow::Result<Option<Vec<(&'static str, Rgba)>>> {
    let mut engine: Option<Engine> = None;
    let view = View::new(Projection::Perspective, SIZE[0], SIZE[1]);
    let mut out = Vec::new();
    for (i, (name, ron)) in SHIPPED.iter().enumerate() {
        if progress.cancelled() {
            return Ok(None);
        }
        progress.set(i as f32 / SHIPPED.len() as f32);
        let file = cache_file(dir, ron);
        if let Some(rgba) = read_cached(&file) {
            out.push((*name, rgba));
            continue;
        }
        let Some(Ok(scene)) = load_shipped(name) else {
            continue;
        };
        // In slices, a pause between them: the window's frames share the GPU's queue and
        // would otherwise wait behind a whole build of each preset's tables.
        let engine = engine.get_or_insert_with(|| {
            crate::engine_setup::engine_beside_a_window(&gpu.device, &gpu.queue)
        });
        let cancelled = || progress.cancelled();
        if crate::engine_setup::render_still_beside_a_window(engine, &scene, &view, &cancelled)?
            .is_none()
        {
            return Ok(None);
        }
        let rgba = engine.read_display()?;
        let rgb: Vec<u8> = rgba
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        if let Err(e) = std::fs::create_dir_all(dir)
            .map_err(anyhow::Error::from)
            .and_then(|()| crate::images::save_rgb8(&file, rgb, SIZE[0], SIZE[1]))
        {
            eprintln!("thumbnail cache: {e:#}");
        }
        out.push((*name, rgba));
    }
    progress.set(1.0);
    Ok(Some(out))
}

/// The preset menu's thumbnails: loaded once, on first need, in the background.
#[derive(Default)]
pub struct Thumbnails {
    job: Option<Job<anyhow::Result<Option<Vec<(&'static str, Rgba)>>>>>,
    textures: HashMap<&'static str, egui::TextureHandle>,
    /// Why they could not be made, shown in the menu.
    pub error: Option<String>,
}

impl Thumbnails {
    /// Starts loading them unless that has begun.
    pub fn request(&mut self, ctx: &egui::Context, gpu: &Gpu, dir: PathBuf) {
        if self.job.is_some() || !self.textures.is_empty() || self.error.is_some() {
            return;
        }
        let gpu = gpu.clone();
        self.job = Some(Job::spawn("preset thumbnails", ctx, move |p| {
            load_or_render(&gpu, &dir, p)
        }));
    }

    /// Turns finished thumbnails into textures.
    pub fn poll(&mut self, ctx: &egui::Context) {
        let Some(job) = &mut self.job else { return };
        let Some(result) = job.take() else { return };
        self.job = None;
        match result {
            Ok(Ok(Some(images))) => {
                for (name, rgba) in images {
                    let image = egui::ColorImage::from_rgba_unmultiplied(
                        [SIZE[0] as usize, SIZE[1] as usize],
                        &rgba,
                    );
                    let texture = ctx.load_texture(
                        format!("thumbnail {name}"),
                        image,
                        egui::TextureOptions::LINEAR,
                    );
                    self.textures.insert(name, texture);
                }
            }
            Ok(Ok(None)) => {}
            Ok(Err(e)) => self.error = Some(format!("{e:#}")),
            Err(e) => self.error = Some(e),
        }
    }

    pub fn loading(&self) -> bool {
        self.job.is_some()
    }

    /// A preset's thumbnail, once loaded.
    pub fn get(&self, name: &str) -> Option<&egui::TextureHandle> {
        self.textures.get(name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cache_entries_are_named_after_the_preset_text_and_checked_on_read() {
        let dir = tempfile::tempdir().expect("temp dir");
        let a = cache_file(dir.path(), "(name: \"a\")");
        assert_ne!(a, cache_file(dir.path(), "(name: \"b\")"));
        assert_eq!(a, cache_file(dir.path(), "(name: \"a\")"));
        // Cut short, not an image, or of another size: not a thumbnail.
        std::fs::write(&a, b"\x89PNG\r\n").expect("write");
        assert!(read_cached(&a).is_none());
        crate::images::save_rgb8(&a, vec![0; 4 * 4 * 3], 4, 4).expect("write");
        assert!(read_cached(&a).is_none());
        crate::images::save_rgb8(
            &a,
            vec![7; (SIZE[0] * SIZE[1] * 3) as usize],
            SIZE[0],
            SIZE[1],
        )
        .expect("write");
        let rgba = read_cached(&a).expect("a whole thumbnail");
        assert_eq!(&rgba[..4], &[7, 7, 7, 255]);
    }
}
