//! GPU-side data: `#[repr(C)]` Pod structs built `From` the model's settings, and the integer
//! codes of the enums the shaders switch on. `shaders/common/bindings.wgsl` declares the same
//! layouts; a test checks the sizes with naga.

use atmoscope_model::aerosol::{MIE_PHASE_ANGLES, MIE_PHASE_WAVELENGTHS_NM, MiePhase};
use atmoscope_model::camera::{Camera, Projection, Sees};
use atmoscope_model::display::{EXPOSURE_SCALE, LUMINANCE_LOG10_RANGE};
use atmoscope_model::geometry::horizon_beta;
use atmoscope_model::methods::shared::{
    BATCH_MODEL_ROWS, BatchOptics, Params, Spacing, Viewpoint, sun_rows::RowsFn,
};
use atmoscope_model::scene::{AerosolPhase, Scene, ToneMap};
use bytemuck::{Pod, Zeroable};
use glam::DVec3;

/// What the display pass shows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DisplayMode {
    /// Exposure, tone map and sRGB encoding of the linear radiance.
    Colour,
    /// Luminance (cd/m²) in false colour, log scale from 10^log10_min to 10^log10_max.
    Luminance { log10_min: f64, log10_max: f64 },
    /// The degree of polarisation of the real-time sky's light (`model::polarisation::
    /// realtime`) in false colour, 0 to 1; the radiance image then holds the Stokes vector
    /// (I_Y, Q_Y, U_Y) weighted by ȳ like the luminance, referred to up in the picture.
    Polarisation,
}

impl DisplayMode {
    /// The default luminance map (`model::display::LUMINANCE_LOG10_RANGE`).
    pub const LUMINANCE: DisplayMode = DisplayMode::Luminance {
        log10_min: LUMINANCE_LOG10_RANGE[0],
        log10_max: LUMINANCE_LOG10_RANGE[1],
    };
}

pub fn projection_code(p: Projection) -> u32 {
    match p {
        Projection::Perspective => 0,
        Projection::Fisheye => 1,
        Projection::Panorama => 2,
    }
}

/// `VIEW_REGION` of a band of rows of the view (`Camera::rows_see`).
pub fn region_code(s: Sees) -> u32 {
    match s {
        Sees::Sky => 0,
        Sees::Ground => 1,
        Sees::Both => 2,
    }
}

pub fn tone_map_code(t: ToneMap) -> u32 {
    match t {
        ToneMap::Exponential => 0,
        ToneMap::Filmic => 1,
        ToneMap::Linear => 2,
        ToneMap::AgX => 3,
        ToneMap::PbrNeutral => 4,
    }
}

pub fn phase_code(p: AerosolPhase) -> u32 {
    match p {
        AerosolPhase::HenyeyGreenstein => 0,
        AerosolPhase::CornetteShanks => 1,
        AerosolPhase::Mie => 2,
    }
}

pub fn display_code(d: DisplayMode) -> u32 {
    match d {
        DisplayMode::Colour => 0,
        DisplayMode::Luminance { .. } => 1,
        DisplayMode::Polarisation => 2,
    }
}

/// `POLARISATION` of the sky pass: what the view shows of the light's polarisation
/// (`shaders/views/polarisation.wgsl`).
pub fn polarisation_code(mode: DisplayMode, polariser_deg: Option<f64>) -> u32 {
    match (mode, polariser_deg) {
        (DisplayMode::Polarisation, _) => 2,
        (_, Some(_)) => 1,
        _ => 0,
    }
}

pub fn spacing_code(s: Spacing) -> u32 {
    match s {
        Spacing::Uniform => 0,
        Spacing::Quadratic => 1,
        Spacing::QuadraticToEnd => 2,
    }
}

/// `Globals` in bindings.wgsl.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Globals {
    pub planet: [f32; 4],
    pub camera_position: [f32; 4],
    pub camera_east: [f32; 4],
    pub camera_north: [f32; 4],
    pub camera_up: [f32; 4],
    pub camera: [f32; 4],
    pub view_forward: [f32; 4],
    pub view_right: [f32; 4],
    pub view_up: [f32; 4],
    pub sun: [f32; 4],
    pub sun_view: [f32; 4],
    pub view: [u32; 4],
    pub options: [u32; 4],
    pub steps_a: [u32; 4],
    pub steps_b: [u32; 4],
    pub display: [f32; 4],
    pub glare: [f32; 4],
    pub sunlight: [f32; 4],
    pub white_balance: [[f32; 4]; 3],
    pub model: [[f32; 4]; 3],
}

fn v4(v: DVec3, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

/// Everything a frame needs besides the atmosphere's tables.
pub struct FrameInputs<'a> {
    pub scene: &'a Scene,
    pub params: &'a Params,
    pub camera: &'a Camera,
    pub sun: DVec3,
    pub viewpoint: Viewpoint,
    pub size: [u32; 2],
    pub mode: DisplayMode,
    /// The constants of the model on screen.
    pub model: crate::methods::ModelConstants,
    /// The display's white balance (rows, on linear sRGB).
    pub balance: [[f64; 3]; 3],
    /// The sun's irradiance at the camera (linear sRGB, W·m⁻²) where the display adds its
    /// glare (`model::display::glare`); None: no glare.
    pub glare: Option<[f64; 3]>,
}

impl From<&FrameInputs<'_>> for Globals {
    fn from(f: &FrameInputs<'_>) -> Globals {
        let p = f.params;
        let c = f.camera;
        let axes = c.perspective_axes();
        let (log10_min, log10_max) = match f.mode {
            DisplayMode::Luminance {
                log10_min,
                log10_max,
            } => (log10_min, log10_max),
            DisplayMode::Colour | DisplayMode::Polarisation => (0.0, 1.0),
        };
        let sunlight = f.scene.sun.sunlight_scale();
        Globals {
            planet: [
                p.bottom_radius_m as f32,
                p.top_radius_m as f32,
                p.thickness_m() as f32,
                0.0,
            ],
            camera_position: v4(c.position, f.viewpoint.h),
            camera_east: v4(c.frame.x_axis, 0.0),
            camera_north: v4(c.frame.y_axis, 0.0),
            camera_up: v4(c.frame.z_axis, 0.0),
            camera: [
                c.heading_deg.to_radians() as f32,
                c.pitch_deg.to_radians() as f32,
                (c.fov_deg.to_radians() * 0.5).tan() as f32,
                horizon_beta(f.viewpoint.h, p.bottom_radius_m) as f32,
            ],
            view_forward: v4(axes[0], 0.0),
            view_right: v4(axes[1], 0.0),
            view_up: v4(axes[2], 0.0),
            sun: v4(f.sun, f.viewpoint.mu_s),
            sun_view: c
                .sun_in_view(f.sun, f.size[0], f.size[1])
                .map_or([0.0; 4], |s| {
                    [s.x, s.y, s.pixel_width_rad, s.pixel_height_rad].map(|v| v as f32)
                }),
            view: [f.size[0], f.size[1], 0, 0],
            options: [
                // A type without a Mie table (Custom) falls back as the CPU's twin does.
                phase_code(match (p.aerosol_phase, p.mie_phase) {
                    (AerosolPhase::Mie, None) => AerosolPhase::HenyeyGreenstein,
                    (kind, _) => kind,
                }),
                p.batches.len() as u32,
                u32::from(p.has_aerosol()),
                0,
            ],
            steps_a: [
                p.steps.transmittance,
                p.steps.multiple_scattering,
                p.steps.ground_irradiance,
                p.steps.sky_view,
            ],
            steps_b: [
                p.steps.aerial_perspective_per_slice,
                p.steps.ray_march,
                p.steps.scattering,
                p.steps.sphere_directions,
            ],
            display: [
                (EXPOSURE_SCALE * f.scene.display.exposure_ev.exp2()) as f32,
                log10_min as f32,
                log10_max as f32,
                f32::from(u8::from(f.scene.display.dither)),
            ],
            glare: f.glare.map_or([0.0; 4], |e| {
                let e = e.map(|c| c * sunlight);
                [e[0] as f32, e[1] as f32, e[2] as f32, 0.0]
            }),
            sunlight: [
                sunlight as f32,
                f.scene.camera.polariser_deg.unwrap_or(0.0).to_radians() as f32,
                0.0,
                0.0,
            ],
            white_balance: f
                .balance
                .map(|r| [r[0] as f32, r[1] as f32, r[2] as f32, 0.0]),
            model: std::array::from_fn(|row| std::array::from_fn(|i| f.model[4 * row + i] as f32)),
        }
    }
}

/// `Batch` in bindings.wgsl.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Batch {
    pub rayleigh_scattering: [f32; 4],
    pub rayleigh_depolarisation: [f32; 4],
    pub ozone_absorption: [f32; 4],
    pub aerosol_scattering: [f32; 4],
    pub aerosol_absorption: [f32; 4],
    pub aerosol_g: [f32; 4],
    pub solar_irradiance: [f32; 4],
    pub ground_albedo: [f32; 4],
    pub to_srgb_r: [f32; 4],
    pub to_srgb_g: [f32; 4],
    pub to_srgb_b: [f32; 4],
    pub wavelengths_nm: [f32; 4],
    /// Each lane's fractional row of the tabulated Mie phase function (`MiePhase::node_at`).
    pub aerosol_phase_node: [f32; 4],
    /// Rows a model computes for the batch on the CPU (`GpuMethod::batch_rows`), zeros for
    /// the others.
    pub model: [[f32; 4]; BATCH_MODEL_ROWS],
}

fn f4(v: impl Into<[f64; 4]>) -> [f32; 4] {
    let v: [f64; 4] = v.into();
    v.map(|x| x as f32)
}

impl From<&BatchOptics> for Batch {
    fn from(b: &BatchOptics) -> Batch {
        Batch {
            rayleigh_scattering: f4(b.rayleigh_scattering),
            rayleigh_depolarisation: f4(b.rayleigh_depolarisation),
            ozone_absorption: f4(b.ozone_absorption),
            aerosol_scattering: f4(b.aerosol_scattering),
            aerosol_absorption: f4(b.aerosol_absorption),
            aerosol_g: f4(b.aerosol_g),
            solar_irradiance: f4(b.solar_irradiance),
            ground_albedo: f4(b.ground_albedo),
            to_srgb_r: f4(b.colour.to_srgb[0]),
            to_srgb_g: f4(b.colour.to_srgb[1]),
            to_srgb_b: f4(b.colour.to_srgb[2]),
            wavelengths_nm: f4(b.colour.wavelengths_nm),
            aerosol_phase_node: f4(b.colour.wavelengths_nm.map(MiePhase::node_at)),
            model: [[0.0; 4]; BATCH_MODEL_ROWS],
        }
    }
}

/// Every batch of `p`, with the model's rows for the sun at zenith cosine `mu_s` where it has
/// them (`GpuMethod::batch_rows`).
pub fn batches(p: &Params, rows: Option<RowsFn>, mu_s: f64) -> Vec<Batch> {
    p.batches
        .iter()
        .enumerate()
        .map(|(layer, b)| {
            let mut batch = Batch::from(b);
            if let Some(rows) = rows {
                batch.model = rows(p, layer, mu_s).map(f4);
            }
            batch
        })
        .collect()
}

/// The tabulated Mie phase function's rows (ln p), four to a vec4 of the shader's uniform: the
/// type's where the scene asks for it, else zeros (never read).
pub fn mie_phase_rows(p: &Params) -> Vec<f32> {
    match p.mie_phase {
        Some(m) if p.aerosol_phase == AerosolPhase::Mie => {
            m.ln_rows.iter().map(|&v| v as f32).collect()
        }
        _ => vec![0.0; MIE_PHASE_ROWS_LEN],
    }
}

/// Length of the Mie phase rows' buffer (every row of every wavelength), a whole number of
/// vec4 as a uniform array needs.
pub const MIE_PHASE_ROWS_LEN: usize = MIE_PHASE_ANGLES * MIE_PHASE_WAVELENGTHS_NM.len();
const _: () = assert!(MIE_PHASE_ROWS_LEN.is_multiple_of(4));

/// The density profile as the shader's `array<vec4<f32>>`.
pub fn profile(p: &Params) -> Vec<[f32; 4]> {
    p.profile.iter().map(|&v| f4(v)).collect()
}
