//! `atmoscope render`: one view of a scene rendered headless by the real-time engine, written as
//! a display-referred PNG (a luminance map gets a legend strip) or as linear EXR radiance.

use crate::args::{parse_range, parse_wavelengths};
use crate::cli::common::{ViewArg, gpu};
use crate::images::{legend_strip, save_rgb8, write_exr};
use crate::scene_args::SceneArgs;
use anyhow::{Context, bail};
use atmoscope_model::camera::Projection;
use atmoscope_model::scene::{Method, WavelengthSet};
use atmoscope_model::views;
use atmoscope_render::{DisplayMode, Engine, View};
use clap::Args;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// A named view of the suite (`atmoscope reference --list-views`), applied on the scene.
    #[arg(long, value_name = "NAME")]
    pub view: Option<String>,
    /// Sky model, a real-time model's registry id (default: the scene's; an unknown id is
    /// answered with the list).
    #[arg(long, value_name = "ID", value_parser = crate::args::parse_method)]
    pub method: Option<Method>,
    /// Wavelength set: rgb3, spectral4 or spectralN (N a multiple of 4, 4–128, e.g. spectral32).
    #[arg(long, value_name = "SET", value_parser = parse_wavelengths)]
    pub wavelengths: Option<WavelengthSet>,
    /// Projection, or `luminance` for a false-colour luminance map of the sky dome.
    #[arg(long, value_enum)]
    pub projection: Option<ViewArg>,
    /// Image size WxH (default: the view's size, or 1280x720).
    #[arg(long, value_name = "WxH", value_parser = crate::args::parse_size)]
    pub size: Option<(u32, u32)>,
    /// Luminance map range as log10 of cd/m²: MIN,MAX.
    #[arg(long, value_name = "MIN,MAX", value_parser = parse_range, allow_hyphen_values = true)]
    pub luminance_range: Option<(f64, f64)>,
    /// Burn a caption under a PNG: the scene's name, the model, the wavelength set, the
    /// exposure and tone map, the sun's elevation and the camera's altitude.
    #[arg(long)]
    pub caption: bool,
    /// Output file: .png (as displayed) or .exr (linear radiance, W·m⁻²·sr⁻¹ as linear sRGB).
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Png,
    Exr,
}

fn format_of(path: &Path) -> anyhow::Result<Format> {
    match path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .as_deref()
    {
        Some("png") => Ok(Format::Png),
        Some("exr") => Ok(Format::Exr),
        _ => bail!(
            "--out {}: the file name must end in .png (as displayed) or .exr (linear radiance)",
            path.display()
        ),
    }
}

pub fn run(args: &RenderArgs) -> anyhow::Result<ExitCode> {
    let format = format_of(&args.out)?;
    if args.caption && matches!(format, Format::Exr) {
        bail!(
            "--caption burns text into a PNG; {} is an EXR of linear radiance, which keeps no text",
            args.out.display()
        );
    }
    crate::files::check_writable(&args.out)?;
    let mut scene = args.scene.scene()?;
    let mut projection = Projection::Perspective;
    let mut size = (1280, 720);
    if let Some(name) = &args.view {
        let v = views::find(name).with_context(|| {
            format!("--view {name}: no such view (see `atmoscope reference --list-views`)")
        })?;
        scene = v.apply(&scene);
        projection = v.projection;
        size = v.size;
    }
    if let Some(set) = args.wavelengths {
        scene.render.wavelengths = set;
    }
    if let Some(m) = args.method {
        scene.render.method = m;
    }
    if let Err(e) = crate::args::parse_method(crate::args::method_id(scene.render.method)) {
        bail!("the scene's method: {e}");
    }
    let mut mode = DisplayMode::Colour;
    if let Some(p) = args.projection {
        (projection, mode) = p.projection_and_mode();
    }
    if let (Some((log10_min, log10_max)), DisplayMode::Luminance { .. }) =
        (args.luminance_range, mode)
    {
        mode = DisplayMode::Luminance {
            log10_min,
            log10_max,
        };
    }
    if mode == DisplayMode::Polarisation && format == Format::Exr {
        bail!(
            "--projection polarisation draws the degree of polarisation as a PNG; the Stokes vectors as EXR channels come from `atmoscope reference --stokes`"
        );
    }
    let (width, height) = args.size.unwrap_or(size);
    let gpu = gpu()?;
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    let view = View {
        projection,
        mode,
        width,
        height,
    };
    let (shown, metered) = engine.render_still(&scene, &view)?;
    if let Some(l) = metered {
        eprintln!(
            "metered: {l:.3} cd/m² log-average, EV100 {:.1}, exposure {:+.2} EV",
            atmoscope_model::display::ev100(l),
            shown.display.exposure_ev
        );
    }
    match format {
        Format::Exr => {
            let rgb: Vec<[f64; 3]> = engine
                .read_radiance()?
                .iter()
                .map(|p| [p[0], p[1], p[2]].map(f64::from))
                .collect();
            write_exr(&args.out, &rgb, width, height)?;
        }
        Format::Png => {
            let mut rgb: Vec<u8> = engine
                .read_display()?
                .chunks_exact(4)
                .flat_map(|p| [p[0], p[1], p[2]])
                .collect();
            let mut rows = height;
            if let DisplayMode::Luminance {
                log10_min,
                log10_max,
            } = mode
            {
                let (strip, strip_rows) = legend_strip(width, log10_min, log10_max);
                rgb.extend(strip);
                rows += strip_rows;
            }
            if mode == DisplayMode::Polarisation {
                let (strip, strip_rows) = crate::images::polarisation_strip(width);
                rgb.extend(strip);
                rows += strip_rows;
            }
            let caption = args.caption.then(|| crate::images::caption_text(&shown));
            let (rgb, rows) = crate::images::with_caption(rgb, width, rows, caption.as_deref());
            save_rgb8(&args.out, rgb, width, rows)?;
        }
    }
    eprintln!(
        "wrote {} ({width}x{height}, {:?}, {:?}) on {}",
        args.out.display(),
        scene.render.wavelengths,
        projection,
        gpu.describe()
    );
    Ok(ExitCode::SUCCESS)
}
