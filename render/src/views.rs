//! Views: what a frame shows and how (projection, size, display mode), plus the CPU twin of
//! the luminance map's false-colour scale so a legend drawn on the CPU matches the shader.

use crate::uniforms::DisplayMode;
use atmoscope_model::camera::Projection;

/// Colour stops of the luminance map, display sRGB from low to high (a turbo-like ramp:
/// dark blue, blue, cyan, green, yellow, orange, red, dark red).
pub const FALSE_COLOUR_STOPS: [[f64; 3]; 9] = [
    [0.19, 0.07, 0.23],
    [0.27, 0.35, 0.80],
    [0.16, 0.64, 0.98],
    [0.10, 0.87, 0.76],
    [0.44, 0.99, 0.37],
    [0.80, 0.93, 0.20],
    [0.99, 0.67, 0.17],
    [0.89, 0.29, 0.05],
    [0.48, 0.02, 0.01],
];

/// Display sRGB of position `t` ∈ [0, 1] on the false-colour scale (twin of views/tone.wgsl).
pub fn false_colour(t: f64) -> [f64; 3] {
    let n = FALSE_COLOUR_STOPS.len();
    let x = t.clamp(0.0, 1.0) * (n - 1) as f64;
    let i = (x.floor() as usize).min(n - 2);
    let f = x - i as f64;
    let (a, b) = (FALSE_COLOUR_STOPS[i], FALSE_COLOUR_STOPS[i + 1]);
    std::array::from_fn(|k| a[k] + (b[k] - a[k]) * f)
}

/// Pixels on a side of the tiles a view in motion computes at the corners and interpolates
/// inside (`Engine::set_sky_tile`), by adapter; the full resolution follows in the first still
/// frame. On a CPU adapter (lavapipe) 4 × 4 tiles, a sixteenth of the per-pixel work, made the
/// sky pass 2.3–10× faster (1280×720). On a GPU (an H200) they made it 0.7–1.26× as fast: a
/// sixteenth of the invocations no longer fill the chip, and the exact tiles' second dispatch
/// costs more than the pixels it spares, so a GPU draws every pixel.
pub fn moving_sky_tile(device_type: wgpu::DeviceType) -> u32 {
    match device_type {
        wgpu::DeviceType::Cpu => 4,
        _ => 1,
    }
}

/// Most pixels on a side of a moving frame's tiles.
pub const MAX_SKY_TILE: u32 = 16;

/// Whether the sky pass runs in bands of what the rows see with the sun's disk apart
/// (`Engine::set_view_bands`), by adapter: on a CPU adapter, which runs both sides of every
/// branch for every lane, yes; on a GPU, where each dispatch costs a fixed time and a branch
/// only the warps that straddle it, one dispatch.
pub fn view_bands(device_type: wgpu::DeviceType) -> bool {
    device_type == wgpu::DeviceType::Cpu
}

/// Largest relative spread of a tile's four corners, per linear sRGB channel, that is still
/// interpolated ((max − min) ≤ this × max(|max|, |min|)); a tile with more is computed pixel
/// by pixel.
pub const SKY_TILE_CONTRAST: f64 = 0.2;

/// One view of a scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    pub projection: Projection,
    pub mode: DisplayMode,
    /// Pixels, 1–8192 each.
    pub width: u32,
    pub height: u32,
}

impl View {
    pub fn new(projection: Projection, width: u32, height: u32) -> View {
        View {
            projection,
            mode: DisplayMode::Colour,
            width,
            height,
        }
    }

    /// The same view as a luminance map with the default range.
    pub fn luminance(self) -> View {
        View {
            mode: DisplayMode::LUMINANCE,
            ..self
        }
    }
}
