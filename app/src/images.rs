//! Writing images: linear radiance as OpenEXR, display-referred previews and error maps as PNG.

use anyhow::Context;
use atmoscope_model::Scene;
use atmoscope_model::colour::linear_srgb_to_xyz;
use atmoscope_model::display::{display_balanced, to_u8, to_u8_dithered};
use image::{ImageBuffer, Rgb};
use std::path::Path;

/// Linear sRGB radiance (W·m⁻²·sr⁻¹) as 32-bit float EXR.
pub fn write_exr(path: &Path, rgb: &[[f64; 3]], width: u32, height: u32) -> anyhow::Result<()> {
    write_exr_with_stokes(path, rgb, None, width, height)
}

/// [`write_exr`], with a photometric Stokes vector per pixel (I, Q, U, V; the path tracer's
/// vector mode) as four more channels of those names and an attribute saying their frame.
pub fn write_exr_with_stokes(
    path: &Path,
    rgb: &[[f64; 3]],
    stokes: Option<&[[f64; 4]]>,
    width: u32,
    height: u32,
) -> anyhow::Result<()> {
    use exr::prelude::{
        AnyChannel, AnyChannels, AttributeValue, Encoding, FlatSamples, Image, Layer,
        LayerAttributes, SmallVec, Text, Vec2, WritableImage,
    };
    let (w, h) = (width as usize, height as usize);
    anyhow::ensure!(rgb.len() == w * h, "image size");
    anyhow::ensure!(stokes.is_none_or(|s| s.len() == w * h), "Stokes image size");
    let channel = |name: &str, values: Vec<f32>| AnyChannel::new(name, FlatSamples::F32(values));
    let mut channels: SmallVec<[AnyChannel<FlatSamples>; 4]> = ["R", "G", "B"]
        .iter()
        .enumerate()
        .map(|(c, name)| channel(name, rgb.iter().map(|p| p[c] as f32).collect()))
        .collect();
    if let Some(stokes) = stokes {
        for (c, name) in ["I", "Q", "U", "V"].iter().enumerate() {
            channels.push(channel(name, stokes.iter().map(|s| s[c] as f32).collect()));
        }
    }
    let mut attributes = LayerAttributes::default();
    attributes.other.insert(
        Text::from(EXR_UNIT_ATTRIBUTE),
        AttributeValue::Text(Text::from(EXR_UNIT)),
    );
    if stokes.is_some() {
        attributes.other.insert(
            Text::from(EXR_STOKES_ATTRIBUTE),
            AttributeValue::Text(Text::from(EXR_STOKES)),
        );
    }
    let layer = Layer::new(
        Vec2(w, h),
        attributes,
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(channels),
    );
    let mut image = Image::from_layer(layer);
    // Linear sRGB: its primaries and D65 white, from the conversion the renderer uses.
    let xy = |c: [f64; 3]| {
        let v = linear_srgb_to_xyz(c);
        let sum = v.x + v.y + v.z;
        Vec2((v.x / sum) as f32, (v.y / sum) as f32)
    };
    image.attributes.chromaticities = Some(exr::meta::attribute::Chromaticities {
        red: xy([1.0, 0.0, 0.0]),
        green: xy([0.0, 1.0, 0.0]),
        blue: xy([0.0, 0.0, 1.0]),
        white: xy([1.0, 1.0, 1.0]),
    });
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .write()
        .to_buffered(&mut bytes)
        .with_context(|| format!("cannot encode {}", path.display()))?;
    crate::files::write_atomic(path, bytes.get_ref())
}

/// The EXR attribute saying what the I, Q, U, V channels are, and its text.
pub const EXR_STOKES_ATTRIBUTE: &str = "stokesFrame";
pub const EXR_STOKES: &str = "photometric Stokes vector (ybar-weighted like Y, W m^-2 sr^-1); Q > 0 vibrating along up in the picture, U > 0 at +45 deg from up towards view x up (right in perspective and panorama views, left in the fisheye)";

/// The EXR attribute naming the unit of the pixel values, and the unit.
pub const EXR_UNIT_ATTRIBUTE: &str = "radianceUnit";
pub const EXR_UNIT: &str = "W m^-2 sr^-1 (linear sRGB, Y = integral of ybar(lambda) L(lambda))";

/// Encodes `img` in memory and writes it atomically: a full disk or a cancelled export never
/// leaves a truncated image.
fn save_atomic(
    path: &Path,
    img: &image::DynamicImage,
    format: image::ImageFormat,
) -> anyhow::Result<()> {
    let mut bytes = std::io::Cursor::new(Vec::new());
    img.write_to(&mut bytes, format)
        .with_context(|| format!("cannot encode {}", path.display()))?;
    crate::files::write_atomic(path, bytes.get_ref())
}

/// Reads an EXR written by `write_exr` back as linear sRGB.
pub fn read_exr(path: &Path) -> anyhow::Result<(Vec<[f64; 3]>, u32, u32)> {
    let reader = image::ImageReader::open(path)
        .and_then(|r| r.with_guessed_format())
        .with_context(|| format!("cannot read {}", path.display()))?;
    match reader.format() {
        Some(image::ImageFormat::OpenExr) => {}
        other => anyhow::bail!(
            "{} is {}, not an OpenEXR file of linear radiance: a display-referred image cannot be \
             compared as radiance (write EXR with `atmoscope render --out FILE.exr` or `atmoscope reference`)",
            path.display(),
            other.map_or("of an unknown format".to_string(), |f| format!(
                "a {f:?} image"
            ))
        ),
    }
    let img = reader
        .decode()
        .with_context(|| format!("cannot read {}", path.display()))?
        .to_rgb32f();
    let (w, h) = img.dimensions();
    Ok((img.pixels().map(|p| p.0.map(f64::from)).collect(), w, h))
}

/// Display-referred PNG of `scene`'s display: white balance, exposure, tone map, dithering.
pub fn write_png(
    path: &Path,
    rgb: &[[f64; 3]],
    width: u32,
    height: u32,
    scene: &Scene,
) -> anyhow::Result<()> {
    let d = &scene.display;
    let balance = atmoscope_model::white_balance::matrix(scene);
    let data: Vec<u8> = rgb
        .iter()
        .enumerate()
        .flat_map(|(i, &c)| {
            let (x, y) = (i as u32 % width.max(1), i as u32 / width.max(1));
            display_balanced(c, &balance, d.exposure_ev, d.tone_map).map(|v| match d.dither {
                true => to_u8_dithered(v, x, y),
                false => to_u8(v),
            })
        })
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
pub fn save_rgb8(path: &Path, data: Vec<u8>, width: u32, height: u32) -> anyhow::Result<()> {
    let img = ImageBuffer::<Rgb<u8>, _>::from_raw(width, height, data).context("image size")?;
    save_atomic(path, &img.into(), image::ImageFormat::Png)
}

/// 3×5 pixel glyphs (rows top to bottom, 3 bits each, high bit left) for legend labels.
fn glyph(c: char) -> u16 {
    let rows: [u16; 5] = match c {
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [7, 1, 7, 4, 7],
        '3' => [7, 1, 7, 1, 7],
        '4' => [5, 5, 7, 1, 1],
        '5' => [7, 4, 7, 1, 7],
        '6' => [7, 4, 7, 5, 7],
        '7' => [7, 1, 2, 2, 2],
        '8' => [7, 5, 7, 5, 7],
        '9' => [7, 5, 7, 1, 7],
        '-' => [0, 0, 7, 0, 0],
        'e' => [0, 6, 7, 4, 3],
        'c' => [0, 3, 4, 4, 3],
        'd' => [1, 1, 7, 5, 7],
        'm' => [0, 6, 7, 5, 5],
        '/' => [1, 1, 2, 4, 4],
        '%' => [5, 1, 2, 4, 5],
        _ => [0; 5],
    };
    rows.iter().fold(0, |acc, r| (acc << 3) | r)
}

/// A legend strip for a luminance map `width` pixels wide: the false-colour bar from
/// 10^log10_min to 10^log10_max cd/m² with a label at every power of ten. Returns RGB8 rows and
/// their count.
pub fn legend_strip(width: u32, log10_min: f64, log10_max: f64) -> (Vec<u8>, u32) {
    let ticks: Vec<(f64, String)> = (log10_min.ceil() as i32..=log10_max.floor() as i32)
        .map(|k| {
            (
                (f64::from(k) - log10_min) / (log10_max - log10_min),
                format!("1e{k}"),
            )
        })
        .collect();
    false_colour_strip(width, &ticks, "cd/m2")
}

/// A legend strip for the polarisation map: the degree of polarisation from 0 to 100 %.
pub fn polarisation_strip(width: u32) -> (Vec<u8>, u32) {
    let ticks: Vec<(f64, String)> = [0, 25, 50, 75, 100]
        .map(|p| (f64::from(p) / 100.0, p.to_string()))
        .to_vec();
    false_colour_strip(width, &ticks, "%")
}

/// The false-colour bar `width` pixels wide with `ticks` (position 0–1, label) and `unit` at
/// the right. Returns RGB8 rows and their count.
fn false_colour_strip(width: u32, ticks: &[(f64, String)], unit: &str) -> (Vec<u8>, u32) {
    let scale = if width >= 320 { 2 } else { 1 };
    let (bar_top, bar_rows) = (4, 8);
    let text_top = bar_top + bar_rows + 3;
    let rows = text_top + 5 * scale + 4;
    let w = width as usize;
    let mut img = vec![0u8; w * rows * 3];
    let margin = (w / 40).max(2);
    let span = w.saturating_sub(2 * margin).max(1);
    for x in 0..span {
        let t = x as f64 / (span - 1).max(1) as f64;
        let c = atmoscope_render::views::false_colour(t).map(to_u8);
        for y in bar_top..bar_top + bar_rows {
            let i = (y * w + margin + x) * 3;
            img[i..i + 3].copy_from_slice(&c);
        }
    }
    let mut text = |label: &str, x0: usize| {
        for (k, ch) in label.chars().enumerate() {
            let g = glyph(ch);
            for gy in 0..5 {
                for gx in 0..3 {
                    if g >> (3 * (4 - gy) + (2 - gx)) & 1 == 1 {
                        for sy in 0..scale {
                            for sx in 0..scale {
                                let x = x0 + (k * 4 + gx) * scale + sx;
                                let y = text_top + gy * scale + sy;
                                if x < w {
                                    let i = (y * w + x) * 3;
                                    img[i..i + 3].copy_from_slice(&[230, 230, 230]);
                                }
                            }
                        }
                    }
                }
            }
        }
    };
    let unit_x = w.saturating_sub(margin + unit.len() * 4 * scale);
    text(unit, unit_x);
    for (t, label) in ticks {
        let x = (margin as f64 + t * (span - 1) as f64 - (label.len() * 2 * scale) as f64).max(0.0);
        // Labels that would run into the unit are left out.
        if x as usize + (label.len() * 4 + 2) * scale < unit_x {
            text(label, x as usize);
        }
    }
    (img, rows as u32)
}

/// Marker and line colours of the benchmarks' charts, dark enough to read on white.
pub const PALETTE: [plotters::style::RGBColor; 10] = [
    plotters::style::RGBColor(214, 39, 40),
    plotters::style::RGBColor(31, 119, 180),
    plotters::style::RGBColor(44, 160, 44),
    plotters::style::RGBColor(148, 103, 189),
    plotters::style::RGBColor(255, 127, 14),
    plotters::style::RGBColor(140, 86, 75),
    plotters::style::RGBColor(227, 119, 194),
    plotters::style::RGBColor(23, 190, 207),
    plotters::style::RGBColor(127, 127, 127),
    plotters::style::RGBColor(188, 189, 34),
];

/// Writes a chart as `<stem>.svg` and `<stem>.png` in folder `$out`, `$draw` drawing it on
/// each backend (a plotters `DrawingBackend`) at `$size`; evaluates to `anyhow::Result<()>`.
/// The subcommands' charts: native only.
#[cfg(not(target_arch = "wasm32"))]
macro_rules! chart_files {
    ($out:expr, $stem:expr, $size:expr, |$backend:ident| $draw:expr) => {{
        use plotters::prelude::{BitMapBackend, SVGBackend};
        let size: (u32, u32) = $size;
        (|| -> anyhow::Result<()> {
            let mut svg = String::new();
            {
                let $backend = SVGBackend::with_string(&mut svg, size);
                $draw?;
            }
            crate::files::write_atomic(&$out.join(format!("{}.svg", $stem)), svg.as_bytes())?;
            let mut rgb = vec![0u8; (size.0 * size.1 * 3) as usize];
            {
                let $backend = BitMapBackend::with_buffer(&mut rgb, size);
                $draw?;
            }
            crate::images::save_rgb8(&$out.join(format!("{}.png", $stem)), rgb, size.0, size.1)
        })()
    }};
}
#[cfg(not(target_arch = "wasm32"))]
pub(crate) use chart_files;

/// Registers the font egui ships as plotters' "sans-serif" (charts, captions), once, so that
/// text looks the same on every machine.
#[cfg(not(target_arch = "wasm32"))]
pub fn register_font() {
    use std::sync::Once;
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The font is compiled in; failing to parse it would be a build defect, and text
        // simply does not draw.
        let _ = plotters::style::register_font(
            "sans-serif",
            plotters::style::FontStyle::Normal,
            epaint_default_fonts::UBUNTU_LIGHT,
        );
    });
}

/// In a browser plotters draws text with the page's own fonts.
#[cfg(target_arch = "wasm32")]
pub fn register_font() {}

/// The caption of an exported view: the scene's name, the model, the wavelength set, the
/// exposure and tone map, the sun's elevation and the camera's altitude.
pub fn caption_text(scene: &Scene) -> String {
    let d = &scene.display;
    let exposure = if d.auto_exposure {
        format!(
            "auto exposure {:+.1} EV ({:+.2} EV)",
            d.compensation_ev, d.exposure_ev
        )
    } else {
        format!("exposure {:+.2} EV", d.exposure_ev)
    };
    let altitude_m = scene.camera.altitude_m;
    let altitude = if altitude_m >= 10_000.0 {
        format!("{:.0} km", altitude_m / 1000.0)
    } else {
        format!("{altitude_m:.0} m")
    };
    format!(
        "{} · {} · {} · {} · {} · sun {:.1}° · camera {altitude}",
        scene.name,
        atmoscope_model::methods::info(scene.render.method).label,
        scene.render.wavelengths.label(),
        exposure,
        d.tone_map.label(),
        scene.sun.angles().elevation_deg,
    )
}

/// A caption strip `width` pixels wide: `text` in light grey on a dark band, wrapped at word
/// boundaries to fit, its size following the width. Returns RGB8 rows and their count.
pub fn caption_strip(width: u32, text: &str) -> (Vec<u8>, u32) {
    use plotters::prelude::*;
    register_font();
    let size = (f64::from(width) / 64.0).clamp(10.0, 28.0);
    let font: FontDesc = ("sans-serif", size).into_font();
    let margin = (size * 0.6).ceil() as u32;
    let fits = |s: &str| {
        font.box_size(s)
            .map_or(s.chars().count() as f64 * size * 0.55, |(w, _)| {
                f64::from(w)
            })
            <= f64::from(width.saturating_sub(2 * margin))
    };
    let mut lines: Vec<String> = Vec::new();
    for word in text.split(' ') {
        match lines.last_mut() {
            Some(line) if fits(&format!("{line} {word}")) => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    let line_rows = (size * 1.3).ceil() as u32;
    let rows = 2 * margin + line_rows * lines.len() as u32;
    let mut buf = vec![24u8; (width * rows * 3) as usize];
    {
        let area = BitMapBackend::with_buffer(&mut buf, (width, rows)).into_drawing_area();
        let style = font.color(&RGBColor(225, 225, 225));
        for (i, line) in lines.iter().enumerate() {
            let y = margin + i as u32 * line_rows;
            // Text that cannot draw (no font) leaves the band plain.
            let _ = area.draw_text(line, &style, (margin as i32, y as i32));
        }
        let _ = area.present();
    }
    (buf, rows)
}

/// 8-bit RGB rows of a view, `width` × `height`, with `caption` burned in below it (None:
/// the view alone). Returns the rows and their count.
pub fn with_caption(
    rgb: Vec<u8>,
    width: u32,
    height: u32,
    caption: Option<&str>,
) -> (Vec<u8>, u32) {
    match caption {
        Some(text) => {
            let (strip, rows) = caption_strip(width, text);
            let mut out = rgb;
            out.extend(strip);
            (out, height + rows)
        }
        None => (rgb, height),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The caption names what made the image, draws visible text on its band, and wraps a
    /// caption too long for a narrow image onto more lines.
    #[test]
    fn a_caption_names_the_scene_and_draws_wrapped_text() {
        let scene = Scene::default();
        let text = caption_text(&scene);
        for part in ["Default", "Hillaire 2020", "Spectral4", "EV", "sun 30.0°"] {
            assert!(text.contains(part), "{text}");
        }
        let (wide, wide_rows) = caption_strip(1280, &text);
        assert_eq!(wide.len(), (1280 * wide_rows * 3) as usize);
        let lit = wide.iter().filter(|&&v| v > 120).count();
        assert!(lit > 100, "only {lit} bright subpixels: no text drawn");
        let (_, narrow_rows) = caption_strip(160, &text);
        assert!(narrow_rows > wide_rows, "{narrow_rows} vs {wide_rows}");
        let (rgb, rows) = with_caption(vec![0; 160 * 90 * 3], 160, 90, Some(&text));
        assert_eq!(
            (rows, rgb.len()),
            (90 + narrow_rows, (160 * rows * 3) as usize)
        );
        assert_eq!(with_caption(vec![0; 12], 2, 2, None).1, 2);
    }
}
