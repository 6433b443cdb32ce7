//! Writing images: linear radiance as OpenEXR, display-referred previews and error maps as PNG.

use anyhow::Context;
use atmoscope_model::display::{display, to_u8};
use atmoscope_model::scene::ToneMap;
use image::{ImageBuffer, Rgb};
use std::path::Path;

/// Linear sRGB radiance (W·m⁻²·sr⁻¹) as 32-bit float EXR.
pub fn write_exr(path: &Path, rgb: &[[f64; 3]], width: u32, height: u32) -> anyhow::Result<()> {
    let data: Vec<f32> = rgb.iter().flat_map(|c| c.map(|v| v as f32)).collect();
    let img = ImageBuffer::<Rgb<f32>, _>::from_raw(width, height, data).context("image size")?;
    img.save(path)
        .with_context(|| format!("cannot write {}", path.display()))
}

/// Reads an EXR written by `write_exr` back as linear sRGB.
pub fn read_exr(path: &Path) -> anyhow::Result<(Vec<[f64; 3]>, u32, u32)> {
    let img = image::open(path)
        .with_context(|| format!("cannot read {}", path.display()))?
        .to_rgb32f();
    let (w, h) = img.dimensions();
    Ok((img.pixels().map(|p| p.0.map(f64::from)).collect(), w, h))
}

/// Display-referred PNG with the given exposure and tone map.
pub fn write_png(
    path: &Path,
    rgb: &[[f64; 3]],
    width: u32,
    height: u32,
    exposure_ev: f64,
    tone_map: ToneMap,
) -> anyhow::Result<()> {
    let data: Vec<u8> = rgb
        .iter()
        .flat_map(|&c| display(c, exposure_ev, tone_map).map(to_u8))
        .collect();
    save_rgb8(path, data, width, height)
}

/// A scalar error map as a PNG heat map (black → red → yellow → white over [0, max]).
pub fn write_heat_map(
    path: &Path,
    values: &[f64],
    width: u32,
    height: u32,
    max: f64,
) -> anyhow::Result<()> {
    let data: Vec<u8> = values
        .iter()
        .flat_map(|&v| {
            let t = (v / max).clamp(0.0, 1.0) * 3.0;
            [
                t.min(1.0),
                (t - 1.0).clamp(0.0, 1.0),
                (t - 2.0).clamp(0.0, 1.0),
            ]
            .map(to_u8)
        })
        .collect();
    save_rgb8(path, data, width, height)
}

/// Saves 8-bit RGB rows as an image file (format from the extension).
fn save_rgb8(path: &Path, data: Vec<u8>, width: u32, height: u32) -> anyhow::Result<()> {
    let img = ImageBuffer::<Rgb<u8>, _>::from_raw(width, height, data).context("image size")?;
    img.save(path)
        .with_context(|| format!("cannot write {}", path.display()))
}
