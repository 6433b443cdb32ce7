//! Numerical stress: scenes drawn from the whole parameter space, each rendered by a model on
//! the GPU and by its f64 CPU twin, and checked — radiance finite and non-negative, the GPU
//! within [`GPU_CPU_BOUND`] of the twin, more aerosol never raising the direct transmittance,
//! a higher sun never darkening the zenith. The draws put weight on the edges where f32 and
//! the geometry break first: exactly 0 m, 1 m, just below, at and just above the top of the
//! atmosphere, 1e8 m; the zenith, the nadir and 1e-6 rad either side of the horizon; the sun
//! at ±90° and on the horizon; no aerosol and AOD 5.
//!
//! A scene is a point of the unit cube (`[f64; DIMENSIONS]`), so property tests (proptest) and
//! the long seeded run (`atmoscope stress`) cover the same space.

use crate::engine::{Engine, EngineError};
use crate::views::View;
use atmoscope_model::Atmosphere;
use atmoscope_model::aerosol::AerosolType;
use atmoscope_model::camera::{Camera, Projection};
use atmoscope_model::colour::linear_srgb_to_xyz;
use atmoscope_model::constants::{AOD_REFERENCE_NM, MAX_LUMINOUS_EFFICACY_LM_PER_W};
use atmoscope_model::geometry::direction_from_angles;
use atmoscope_model::methods::{self, SkyModel, render_with};
use atmoscope_model::scene::{AerosolSettings, Method, Scene, SunSettings, WavelengthSet};
use atmoscope_model::wavelengths::to_linear_srgb;

/// Coordinates of a scene in the unit cube: 5 for the atmosphere, 6 for the viewpoint.
pub const DIMENSIONS: usize = 11;

/// Largest relative luminance difference allowed between a GPU pixel and its CPU twin's on the
/// model's domain, relative to the twin's pixel plus a floor: [`GPU_CPU_FLOOR`] of the
/// brightest pixel of the view, at least [`GPU_CPU_DARKEST_CD_M2`]. The tables are f32 on the
/// GPU: under thick aerosol high in the atmosphere (AOD ≥ 1 of the background or polar types)
/// Elek's and Bruneton's differ from their f64 twins by up to 98 % (measured by the 10 000-case
/// run: the cases it reports as failing); the usual views agree to 1 % (`render/tests/methods.rs`). Outside a model's domain the difference is reported, not
/// bounded (Bruneton below −12° reads the last row of its tables).
pub const GPU_CPU_BOUND: f64 = 0.10;
/// The share of the view's brightest pixel below which differences count as absolute.
pub const GPU_CPU_FLOOR: f64 = 1e-3;
/// Differences darker than the eye's absolute threshold (about 1e-6 cd/m²) are invisible and
/// count as absolute: deep in the night both sides are products of transmittances of e^-60 and
/// less, whose f32 rounding is all that differs (seen: 1e-27 W·m⁻²·sr⁻¹ off by 19 %).
pub const GPU_CPU_DARKEST_CD_M2: f64 = 1e-6;
/// Each view is this many pixels on a side; odd, so the centre pixel looks exactly along the
/// drawn direction.
pub const VIEW_SIZE: u32 = 5;

/// One step of the sun for the monotonicity check, degrees.
const SUN_STEP_DEG: f64 = 2.0;
/// Relative slack of the monotonicity check: table interpolation may wobble this much.
const MONOTONIC_SLACK: f64 = 1e-3;

/// Picks `special[i]` while `u` is in the first `share` of the unit interval, else maps the rest
/// of the interval through `rest`.
fn edge_or(u: f64, share: f64, special: &[f64], rest: impl Fn(f64) -> f64) -> f64 {
    if u < share {
        let i = ((u / share) * special.len() as f64) as usize;
        special[i.min(special.len() - 1)]
    } else {
        rest((u - share) / (1.0 - share))
    }
}

fn index(u: f64, len: usize) -> usize {
    ((u * len as f64) as usize).min(len - 1)
}

/// The scene at `u` for `method`: `u[0..5]` the atmosphere (aerosol type, AOD 0–5, albedo 0–1,
/// ozone 0–600 DU, wavelength set), `u[5..11]` the viewpoint (camera altitude 0–1e8 m, sun
/// elevation −90–90° and azimuth, view pitch, heading and field of view).
pub fn scene_at(u: &[f64; DIMENSIONS], method: Method) -> Scene {
    let mut s = Scene::default();
    s.render.method = method;
    let a = &mut s.atmosphere;
    a.aerosol = AerosolSettings {
        kind: AerosolType::ALL[index(u[0], AerosolType::ALL.len())],
        aod550: edge_or(u[1], 0.2, &[0.0, 5.0], |t| 5.0 * t * t),
        ..a.aerosol.clone()
    };
    a.ground_albedo = edge_or(u[2], 0.1, &[0.0, 1.0], |t| t);
    a.ozone.column =
        atmoscope_model::scene::OzoneColumn::Du(edge_or(u[3], 0.1, &[0.0, 600.0], |t| 600.0 * t));
    s.render.wavelengths = [
        WavelengthSet::Rgb3,
        WavelengthSet::Spectral4,
        WavelengthSet::Spectral4,
        WavelengthSet::SpectralN(8),
        WavelengthSet::SpectralN(32),
    ][index(u[4], 5)];
    let top_m = a.top_km * 1000.0;
    let max_m = atmoscope_model::scene::MAX_CAMERA_ALTITUDE_M;
    s.camera.altitude_m = edge_or(
        u[5],
        0.5,
        &[0.0, 1.0, top_m - 1.0, top_m, top_m + 1.0, max_m],
        |t| max_m.powf(t),
    );
    s.sun = SunSettings::Angles {
        elevation_deg: edge_or(u[6], 0.2, &[-90.0, -6.0, -0.5, 0.0, 0.5, 90.0], |t| {
            -90.0 + 180.0 * t
        }),
        azimuth_deg: 360.0 * u[7],
    };
    let horizon_deg = 1e-6_f64.to_degrees();
    s.camera.pitch_deg = edge_or(
        u[8],
        0.5,
        &[90.0, -90.0, horizon_deg, -horizon_deg, 0.0],
        |t| -90.0 + 180.0 * t,
    );
    s.camera.heading_deg = 360.0 * u[9];
    s.camera.fov_deg = 1.0 + 169.0 * u[10];
    // A model that refuses views outside its domain is stressed inside it (the same edges,
    // clamped); its refusals are checked wherever a scene strays out (`Stress::check`).
    let d = methods::info(method).domain;
    if d.refuses {
        s.camera.altitude_m = s.camera.altitude_m.min(d.max_altitude_m);
        let a = s.sun.angles();
        s.sun = SunSettings::Angles {
            elevation_deg: a.elevation_deg.max(d.min_sun_elevation_deg),
            azimuth_deg: a.azimuth_deg,
        };
    }
    s
}

/// What one case found.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Findings {
    /// Pixels (GPU and CPU together) whose radiance is NaN, infinite or of negative luminance.
    pub nan: usize,
    pub inf: usize,
    pub negative: usize,
    /// Whether the scene lies in the model's domain (where [`GPU_CPU_BOUND`] applies).
    pub in_domain: bool,
    /// Worst relative luminance difference of a GPU pixel from its twin (see [`GPU_CPU_BOUND`]).
    pub worst_gpu_cpu: f64,
    /// Pixels beyond [`GPU_CPU_BOUND`] on the model's domain.
    pub out_of_bound: usize,
    /// Broken monotonicity, in words.
    pub monotonicity: Vec<String>,
    /// A GPU fault.
    pub fault: Option<String>,
    /// Whether the model refuses the scene (`ModelInfo::cannot_draw`): then only that the GPU
    /// refuses it too is checked.
    pub refused: bool,
}

impl Findings {
    pub fn failed(&self) -> bool {
        self.nan + self.inf + self.negative + self.out_of_bound > 0
            || !self.monotonicity.is_empty()
            || self.fault.is_some()
    }
}

/// Counts the non-finite and negative pixels of `rgb` into `f`; returns each pixel's luminance.
fn luminances(rgb: &[[f64; 3]], f: &mut Findings) -> Vec<f64> {
    rgb.iter()
        .map(|p| {
            if p.iter().any(|c| c.is_nan()) {
                f.nan += 1;
            } else if p.iter().any(|c| c.is_infinite()) {
                f.inf += 1;
            }
            let y = linear_srgb_to_xyz(*p).y;
            if y < 0.0 {
                f.negative += 1;
            }
            y
        })
        .collect()
}

/// Renders cases on one device, keeping an engine per model and the last CPU twin of each, so
/// that consecutive cases with the same atmosphere reuse their tables.
pub struct Stress {
    device: wgpu::Device,
    queue: wgpu::Queue,
    engines: Vec<(Method, Engine)>,
    twins: Vec<(Method, Scene, Box<dyn SkyModel>)>,
}

impl Stress {
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Stress {
        Stress {
            device: device.clone(),
            queue: queue.clone(),
            engines: Vec::new(),
            twins: Vec::new(),
        }
    }

    /// The CPU twin for `scene`, built again only when its tables would differ, and moved to
    /// the scene's viewpoint where only the tables there would (`SkyModel::move_to`).
    fn twin(&mut self, scene: &Scene, camera: &Camera) -> &dyn SkyModel {
        let model = methods::info(scene.render.method);
        let same_atmosphere =
            |kept: &Scene| kept.atmosphere == scene.atmosphere && kept.render == scene.render;
        let same_viewpoint = |kept: &Scene| {
            !model.reads_viewpoint()
                || (kept.camera.altitude_m == scene.camera.altitude_m && kept.sun == scene.sun)
        };
        let mut reusable = None;
        if let Some(i) = self
            .twins
            .iter()
            .position(|(m, kept, _)| *m == model.method && same_atmosphere(kept))
        {
            let (_, kept, twin) = &mut self.twins[i];
            if same_viewpoint(kept) {
                reusable = Some(i);
            } else if twin.move_to(methods::shared::viewpoint(scene, camera)) {
                *kept = scene.clone();
                reusable = Some(i);
            }
        }
        let i = match reusable {
            Some(i) => i,
            None => {
                self.twins.retain(|(m, _, _)| *m != model.method);
                let built = methods::build(scene, camera).expect("a real-time model");
                self.twins.push((model.method, scene.clone(), built));
                self.twins.len() - 1
            }
        };
        self.twins[i].2.as_ref()
    }

    fn gpu_radiance(&mut self, scene: &Scene, view: &View) -> Result<Vec<[f64; 3]>, EngineError> {
        let method = scene.render.method;
        let i = match self.engines.iter().position(|(m, _)| *m == method) {
            Some(i) => i,
            None => {
                self.engines
                    .push((method, Engine::new(&self.device, &self.queue)));
                self.engines.len() - 1
            }
        };
        let engine = &mut self.engines[i].1;
        engine.try_render(scene, view)?;
        Ok(engine
            .read_radiance()?
            .iter()
            .map(|p| [p[0], p[1], p[2]].map(f64::from))
            .collect())
    }

    /// Luminance of the sky straight up from the camera of `scene` as the CPU twin sees it (the
    /// single direction, without the sun's disk).
    fn zenith_luminance(&mut self, scene: &Scene) -> f64 {
        let camera = Camera::new(
            &scene.camera,
            scene.atmosphere.planet_radius_km * 1000.0,
            Projection::Perspective,
        );
        let a = scene.sun.angles();
        let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
        let up = camera.position.normalize();
        let at = (camera.position, scene.camera.altitude_m);
        let twin = self.twin(scene, &camera);
        let p = twin.params();
        let lanes: Vec<_> = (0..p.batches.len())
            .map(|layer| twin.radiance(layer, at, up, sun))
            .collect();
        let colours: Vec<_> = p.batches.iter().map(|b| b.colour.clone()).collect();
        linear_srgb_to_xyz(to_linear_srgb(&colours, &lanes)).y
    }

    /// Runs every check on `scene` (its model must be a real-time one).
    pub fn check(&mut self, scene: &Scene) -> Findings {
        let model = methods::info(scene.render.method);
        let mut f = Findings {
            in_domain: model
                .domain
                .excludes(scene.camera.altitude_m, scene.sun.angles().elevation_deg)
                .is_none(),
            ..Findings::default()
        };
        let view = View::new(Projection::Perspective, VIEW_SIZE, VIEW_SIZE);
        if let Some(why) = model.cannot_draw(scene) {
            f.refused = true;
            match self.gpu_radiance(scene, &view) {
                Err(EngineError::CannotDraw(_)) => {}
                Err(e) => f.fault = Some(e.to_string()),
                Ok(_) => f.fault = Some(format!("the GPU drew a view the model refuses: {why}")),
            }
            return f;
        }
        let camera = Camera::new(
            &scene.camera,
            scene.atmosphere.planet_radius_km * 1000.0,
            view.projection,
        );
        let cpu = render_with(
            self.twin(scene, &camera),
            scene,
            &camera,
            view.width,
            view.height,
        );
        let cpu = luminances(&cpu, &mut f);
        match self.gpu_radiance(scene, &view) {
            Err(e) => f.fault = Some(e.to_string()),
            Ok(gpu) => {
                let gpu = luminances(&gpu, &mut f);
                let darkest = GPU_CPU_DARKEST_CD_M2 / MAX_LUMINOUS_EFFICACY_LM_PER_W;
                let floor =
                    (GPU_CPU_FLOOR * cpu.iter().fold(0.0_f64, |m, y| m.max(*y))).max(darkest);
                for (g, c) in gpu.iter().zip(&cpu) {
                    let d = (g - c).abs();
                    if d == 0.0 {
                        continue;
                    }
                    let e = if d.is_finite() {
                        d / (c.abs() + floor)
                    } else {
                        f64::INFINITY
                    };
                    f.worst_gpu_cpu = f.worst_gpu_cpu.max(e);
                    if e > GPU_CPU_BOUND && f.in_domain {
                        f.out_of_bound += 1;
                    }
                }
            }
        }
        if f.in_domain {
            self.check_monotonic(scene, &camera, &mut f);
        }
        f
    }

    fn check_monotonic(&mut self, scene: &Scene, camera: &Camera, f: &mut Findings) {
        let sun_angles = scene.sun.angles();
        let sun = direction_from_angles(sun_angles.elevation_deg, sun_angles.azimuth_deg);
        let direct = |aod550: f64| {
            let mut s = scene.atmosphere.clone();
            s.aerosol.aod550 = aod550;
            let atm = Atmosphere::new(&s);
            atm.transmittance_to_sun(&atm.optics(AOD_REFERENCE_NM), camera.position, sun)
        };
        let aod = scene.atmosphere.aerosol.aod550;
        let more = (aod * 1.5 + 0.05).min(5.0);
        if more > aod {
            let (t, t_more) = (direct(aod), direct(more));
            if t_more > t * (1.0 + 1e-12) {
                f.monotonicity.push(format!(
                    "direct transmittance {t_more:e} at AOD {more} above {t:e} at AOD {aod}"
                ));
            }
        }
        // Noon-side: the sun climbing from the horizon, the camera inside the atmosphere.
        let e = sun_angles.elevation_deg;
        let inside = scene.camera.altitude_m < scene.atmosphere.top_km * 1000.0;
        if inside && (0.0..=90.0 - SUN_STEP_DEG).contains(&e) {
            let mut higher = scene.clone();
            higher.sun = SunSettings::Angles {
                elevation_deg: e + SUN_STEP_DEG,
                azimuth_deg: sun_angles.azimuth_deg,
            };
            let (low, high) = (self.zenith_luminance(scene), self.zenith_luminance(&higher));
            if high < low * (1.0 - MONOTONIC_SLACK) {
                f.monotonicity.push(format!(
                    "zenith luminance {high:e} with the sun at {:.2}° below {low:e} at {e:.2}°",
                    e + SUN_STEP_DEG
                ));
            }
        }
    }
}
