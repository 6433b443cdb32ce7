//! The engine: GPU resources for one scene and one view, a pass graph with dirty tracking, and
//! per-pass timing. It takes a `wgpu::Device` and `Queue` from its caller (a window, the command
//! line or a test) and renders into textures.
//!
//! Each pass declares the inputs it reads; a frame compares the inputs with the previous
//! frame's and runs exactly the passes that read something that changed (DESIGN.md §7): physics
//! rebuilds the whole chain, the sun or the camera's altitude rebuilds the view tables, turning
//! the camera redraws the view, exposure re-runs only the display pass, an unchanged frame runs
//! nothing.

use crate::hillaire::{LutBuffers, Pipelines, Table, Variant};
use crate::readback::{ReadbackError, read_buffer_f32x4, read_texture, read_texture_f32x4};
use crate::uniforms::{self, DisplayMode, FrameInputs, Globals};
use crate::views::View;
use atmoscope_model::Atmosphere;
use atmoscope_model::camera::{Camera, Projection};
use atmoscope_model::geometry::direction_from_angles;
use atmoscope_model::methods::hillaire::{self, Params};
use atmoscope_model::scene::{
    AtmosphereSettings, CameraSettings, Quality, Scene, ToneMap, WavelengthSet,
};
use std::time::Instant;

/// What a pass can read; a set of these is a bit mask.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Inputs(u8);

impl Inputs {
    pub const NONE: Inputs = Inputs(0);
    /// Atmosphere settings, wavelength set and quality.
    pub const ATMOSPHERE: Inputs = Inputs(1);
    /// The camera's altitude and the sun's zenith angle there (what the view tables depend on).
    pub const VIEWPOINT: Inputs = Inputs(2);
    /// The sun's direction in the world.
    pub const SUN: Inputs = Inputs(4);
    /// The camera's position, orientation, field of view and projection.
    pub const CAMERA: Inputs = Inputs(8);
    pub const VIEW_SIZE: Inputs = Inputs(16);
    /// Exposure, tone map and display mode.
    pub const DISPLAY: Inputs = Inputs(32);
    pub const ALL: Inputs = Inputs(63);

    pub const fn union(self, other: Inputs) -> Inputs {
        Inputs(self.0 | other.0)
    }

    pub fn intersects(self, other: Inputs) -> bool {
        self.0 & other.0 != 0
    }

    pub fn is_empty(self) -> bool {
        self.0 == 0
    }
}

/// The passes, in execution order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Pass {
    Transmittance,
    MultipleScattering,
    GroundIrradiance,
    SkyView,
    AerialPerspective,
    Sky,
    Display,
}

impl Pass {
    pub const ALL: [Pass; 7] = [
        Pass::Transmittance,
        Pass::MultipleScattering,
        Pass::GroundIrradiance,
        Pass::SkyView,
        Pass::AerialPerspective,
        Pass::Sky,
        Pass::Display,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Pass::Transmittance => "transmittance",
            Pass::MultipleScattering => "multiple-scattering",
            Pass::GroundIrradiance => "ground-irradiance",
            Pass::SkyView => "sky-view",
            Pass::AerialPerspective => "aerial-perspective",
            Pass::Sky => "sky",
            Pass::Display => "display",
        }
    }

    /// Whether the pass builds a lookup table (as opposed to drawing the view).
    pub fn is_lut(self) -> bool {
        !matches!(self, Pass::Sky | Pass::Display)
    }

    /// The inputs the pass reads, including those of the passes whose output it reads.
    pub fn reads(self) -> Inputs {
        let view_tables = Inputs::ATMOSPHERE.union(Inputs::VIEWPOINT);
        let sky = view_tables
            .union(Inputs::SUN)
            .union(Inputs::CAMERA)
            .union(Inputs::VIEW_SIZE);
        match self {
            Pass::Transmittance | Pass::MultipleScattering | Pass::GroundIrradiance => {
                Inputs::ATMOSPHERE
            }
            Pass::SkyView | Pass::AerialPerspective => view_tables,
            Pass::Sky => sky,
            Pass::Display => sky.union(Inputs::DISPLAY),
        }
    }

    fn index(self) -> usize {
        Pass::ALL.iter().position(|&p| p == self).unwrap_or(0)
    }
}

/// How a pass's time was measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimingSource {
    /// GPU timestamp queries around the pass.
    GpuTimestamps,
    /// Wall time from submission to completion, each pass submitted and waited for alone.
    CpuFenced,
}

impl TimingSource {
    pub fn label(self) -> &'static str {
        match self {
            TimingSource::GpuTimestamps => "GPU timestamps",
            TimingSource::CpuFenced => "CPU-fenced wall time",
        }
    }
}

/// What the last frame did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FrameStats {
    pub run: Vec<Pass>,
    pub skipped: Vec<Pass>,
    /// Milliseconds per pass run, when timing is on.
    pub timings_ms: Vec<(Pass, f64)>,
    pub timing_source: Option<TimingSource>,
}

impl FrameStats {
    pub fn ran(&self, pass: Pass) -> bool {
        self.run.contains(&pass)
    }

    pub fn ran_any_lut(&self) -> bool {
        self.run.iter().any(|p| p.is_lut())
    }
}

/// Why the engine could not do what was asked.
#[derive(Debug, thiserror::Error)]
pub enum EngineError {
    #[error("nothing has been rendered yet")]
    NotRendered,
    #[error(transparent)]
    Readback(#[from] ReadbackError),
}

#[derive(Debug, Clone, PartialEq)]
struct AtmosphereKey {
    settings: AtmosphereSettings,
    wavelengths: WavelengthSet,
    quality: Quality,
}

#[derive(Debug, Clone, PartialEq)]
struct Snapshot {
    atmosphere: AtmosphereKey,
    viewpoint: [f64; 2],
    sun: [f64; 3],
    camera: (CameraSettings, Projection),
    size: [u32; 2],
    display: (f64, ToneMap, DisplayMode),
}

impl Snapshot {
    fn changes_from(&self, previous: Option<&Snapshot>) -> Inputs {
        let Some(p) = previous else {
            return Inputs::ALL;
        };
        let mut c = Inputs::NONE;
        let mut mark = |changed: bool, i: Inputs| {
            if changed {
                c = c.union(i);
            }
        };
        mark(self.atmosphere != p.atmosphere, Inputs::ATMOSPHERE);
        mark(self.viewpoint != p.viewpoint, Inputs::VIEWPOINT);
        mark(self.sun != p.sun, Inputs::SUN);
        mark(self.camera != p.camera, Inputs::CAMERA);
        mark(self.size != p.size, Inputs::VIEW_SIZE);
        mark(self.display != p.display, Inputs::DISPLAY);
        c
    }
}

struct AtmosphereState {
    key: AtmosphereKey,
    params: Params,
    luts: LutBuffers,
}

struct Target {
    size: [u32; 2],
    radiance: wgpu::Texture,
    display: wgpu::Texture,
    sky_group: wgpu::BindGroup,
    display_group: wgpu::BindGroup,
}

enum Timer {
    Gpu {
        queries: wgpu::QuerySet,
        resolve: wgpu::Buffer,
        readback: wgpu::Buffer,
        period_ns: f64,
    },
    Cpu,
}

/// Renders views of scenes with the Hillaire (2020) method.
pub struct Engine {
    device: wgpu::Device,
    queue: wgpu::Queue,
    pipelines: Pipelines,
    globals: wgpu::Buffer,
    atmosphere: Option<AtmosphereState>,
    target: Option<Target>,
    last: Option<Snapshot>,
    timer: Timer,
    measure: bool,
    stats: FrameStats,
}

impl Engine {
    /// Compiles the passes on `device`. Timestamp queries are used when the device has the
    /// `TIMESTAMP_QUERY` feature; otherwise timing falls back to fenced CPU wall time.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Engine {
        let pipelines = Pipelines::new(device);
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("globals"),
            size: std::mem::size_of::<Globals>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let timer = if device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            let count = 2 * Pass::ALL.len() as u32;
            let bytes = u64::from(count) * 8;
            Timer::Gpu {
                queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                    label: Some("pass timestamps"),
                    ty: wgpu::QueryType::Timestamp,
                    count,
                }),
                resolve: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("timestamp resolve"),
                    size: bytes,
                    usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: false,
                }),
                readback: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("timestamp read-back"),
                    size: bytes,
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                period_ns: f64::from(queue.get_timestamp_period()),
            }
        } else {
            Timer::Cpu
        };
        Engine {
            device: device.clone(),
            queue: queue.clone(),
            pipelines,
            globals,
            atmosphere: None,
            target: None,
            last: None,
            timer,
            measure: false,
            stats: FrameStats::default(),
        }
    }

    /// Forgets the previous frame, so the next one runs every pass (a full rebuild).
    pub fn invalidate(&mut self) {
        self.last = None;
    }

    /// Turns per-pass timing on or off. Timing waits for the GPU at the end of each frame.
    pub fn set_timing(&mut self, on: bool) {
        self.measure = on;
    }

    /// Measures with fenced CPU wall time even where timestamp queries exist (software
    /// drivers such as lavapipe stamp commands when they are recorded, not when they run).
    pub fn force_cpu_timing(&mut self) {
        self.timer = Timer::Cpu;
    }

    /// Where per-pass times come from on this device.
    pub fn timing_source(&self) -> TimingSource {
        match self.timer {
            Timer::Gpu { .. } => TimingSource::GpuTimestamps,
            Timer::Cpu => TimingSource::CpuFenced,
        }
    }

    /// What the last frame ran, skipped and measured.
    pub fn stats(&self) -> &FrameStats {
        &self.stats
    }

    /// The method's parameters for the current atmosphere.
    pub fn params(&self) -> Option<&Params> {
        self.atmosphere.as_ref().map(|a| &a.params)
    }

    /// Renders `view` of `scene`, running only the passes whose inputs changed since the last
    /// frame. Returns the frame's statistics. The work is submitted; it finishes on the GPU.
    pub fn render(&mut self, scene: &Scene, view: &View) -> &FrameStats {
        let key = AtmosphereKey {
            settings: scene.atmosphere.clone(),
            wavelengths: scene.render.wavelengths,
            quality: scene.render.quality,
        };
        let rebuilt = self.atmosphere.as_ref().is_none_or(|a| a.key != key);
        if rebuilt {
            let params = Params::new(
                &Atmosphere::new(&scene.atmosphere),
                key.wavelengths,
                key.quality,
            );
            let luts = LutBuffers::new(&self.device, &self.pipelines, &self.globals, &params);
            self.queue.write_buffer(
                &luts.batches,
                0,
                bytemuck::cast_slice(
                    &params
                        .batches
                        .iter()
                        .map(uniforms::Batch::from)
                        .collect::<Vec<_>>(),
                ),
            );
            self.queue.write_buffer(
                &luts.profile,
                0,
                bytemuck::cast_slice(&uniforms::profile(&params)),
            );
            self.atmosphere = Some(AtmosphereState { key, params, luts });
        }
        let Some(state) = self.atmosphere.as_ref() else {
            unreachable!("the atmosphere was just built");
        };
        let params = &state.params;
        let camera = Camera::new(&scene.camera, params.bottom_radius_m, view.projection);
        let a = scene.sun.angles();
        let sun = direction_from_angles(a.elevation_deg, a.azimuth_deg);
        let viewpoint = hillaire::viewpoint(scene, &camera);
        let size = [view.width.max(1), view.height.max(1)];
        let snapshot = Snapshot {
            atmosphere: state.key.clone(),
            viewpoint: [viewpoint.h, viewpoint.mu_s],
            sun: sun.to_array(),
            camera: (scene.camera.clone(), view.projection),
            size,
            display: (scene.display.exposure_ev, scene.display.tone_map, view.mode),
        };
        let changed = snapshot.changes_from(self.last.as_ref());
        if rebuilt || self.target.as_ref().is_none_or(|t| t.size != size) {
            self.target = Some(Target::new(
                &self.device,
                &self.pipelines,
                &state.luts,
                size,
            ));
        }
        let globals = Globals::from(&FrameInputs {
            scene,
            params,
            camera: &camera,
            sun,
            viewpoint,
            size,
            mode: view.mode,
        });
        if !changed.is_empty() {
            self.queue
                .write_buffer(&self.globals, 0, bytemuck::bytes_of(&globals));
        }
        let (run, skipped): (Vec<Pass>, Vec<Pass>) = Pass::ALL
            .iter()
            .partition(|p| p.reads().intersects(changed));
        let above = viewpoint.h > params.thickness_m();
        let variants = [
            (
                Pass::Sky,
                [uniforms::projection_code(view.projection), u32::from(above)],
            ),
            (
                Pass::Display,
                [
                    uniforms::display_code(view.mode),
                    uniforms::tone_map_code(scene.display.tone_map),
                ],
            ),
        ];
        let layers = params.batches.len() as u32;
        for (pass, variant) in variants {
            self.pipelines.ensure(&self.device, pass, variant);
        }
        let timings_ms = if run.is_empty() {
            Vec::new()
        } else {
            self.encode_and_submit(&run, &variants, layers, size)
        };
        self.last = Some(snapshot);
        self.stats = FrameStats {
            timing_source: (self.measure && !run.is_empty()).then(|| self.timing_source()),
            run,
            skipped,
            timings_ms,
        };
        &self.stats
    }

    fn encode_and_submit(
        &self,
        run: &[Pass],
        variants: &[(Pass, Variant)],
        layers: u32,
        size: [u32; 2],
    ) -> Vec<(Pass, f64)> {
        let (Some(state), Some(target)) = (&self.atmosphere, &self.target) else {
            return Vec::new();
        };
        let gpu_timer = match &self.timer {
            Timer::Gpu { queries, .. } if self.measure => Some(queries),
            _ => None,
        };
        let fenced = self.measure && gpu_timer.is_none();
        let mut timings = Vec::new();
        let mut encoder = self.device.create_command_encoder(&Default::default());
        for &pass in run {
            let start = Instant::now();
            {
                let i = pass.index() as u32;
                let timestamp_writes = gpu_timer.map(|q| wgpu::ComputePassTimestampWrites {
                    query_set: q,
                    beginning_of_pass_write_index: Some(2 * i),
                    end_of_pass_write_index: Some(2 * i + 1),
                });
                let mut cpass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(pass.name()),
                    timestamp_writes,
                });
                let (group, dispatch) = match pass {
                    Pass::Sky => (&target.sky_group, view_dispatch(size)),
                    Pass::Display => (&target.display_group, view_dispatch(size)),
                    lut => (state.luts.group(lut), lut_dispatch(lut, layers)),
                };
                let variant = variants
                    .iter()
                    .find(|(p, _)| *p == pass)
                    .map_or([0, 0], |(_, v)| *v);
                let Some(pipeline) = self.pipelines.pipeline(pass, variant) else {
                    continue;
                };
                cpass.set_pipeline(pipeline);
                cpass.set_bind_group(0, &state.luts.group0, &[]);
                cpass.set_bind_group(1, group, &[]);
                cpass.dispatch_workgroups(dispatch[0], dispatch[1], dispatch[2]);
            }
            if fenced {
                self.queue.submit([encoder.finish()]);
                let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
                timings.push((pass, start.elapsed().as_secs_f64() * 1e3));
                encoder = self.device.create_command_encoder(&Default::default());
            }
        }
        if let Timer::Gpu {
            queries,
            resolve,
            readback,
            period_ns,
        } = &self.timer
            && self.measure
        {
            let count = 2 * Pass::ALL.len() as u32;
            encoder.resolve_query_set(queries, 0..count, resolve, 0);
            encoder.copy_buffer_to_buffer(resolve, 0, readback, 0, resolve.size());
            self.queue.submit([encoder.finish()]);
            if let Some(ticks) = map_u64(&self.device, readback) {
                for &pass in run {
                    let i = pass.index();
                    let ns = ticks[2 * i + 1].saturating_sub(ticks[2 * i]) as f64 * period_ns;
                    timings.push((pass, ns * 1e-6));
                }
            }
        } else {
            self.queue.submit([encoder.finish()]);
        }
        timings
    }

    /// Blocks until the GPU has finished all submitted work.
    pub fn wait(&self) {
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
    }

    /// The view's linear radiance: linear sRGB with Y = ∫ȳL dλ (W·m⁻²·sr⁻¹), alpha 1 where the
    /// projection shows the sky and 0 outside (the fisheye's corners). Rgba32Float.
    pub fn radiance_texture(&self) -> Option<&wgpu::Texture> {
        self.target.as_ref().map(|t| &t.radiance)
    }

    /// The view as displayed: sRGB-encoded Rgba8Unorm.
    pub fn display_texture(&self) -> Option<&wgpu::Texture> {
        self.target.as_ref().map(|t| &t.display)
    }

    /// A sampled view of the displayed image that decodes its sRGB bytes to linear colour, for
    /// compositors that work in linear light (egui-wgpu). Recreated when the view's size changes.
    pub fn display_view_srgb(&self) -> Option<wgpu::TextureView> {
        self.display_texture().map(|t| {
            t.create_view(&wgpu::TextureViewDescriptor {
                label: Some("display (sRGB view)"),
                format: Some(wgpu::TextureFormat::Rgba8UnormSrgb),
                usage: Some(wgpu::TextureUsages::TEXTURE_BINDING),
                ..Default::default()
            })
        })
    }

    /// Reads the linear radiance back, row-major from the top row.
    pub fn read_radiance(&self) -> Result<Vec<[f32; 4]>, EngineError> {
        let t = self.radiance_texture().ok_or(EngineError::NotRendered)?;
        Ok(read_texture_f32x4(&self.device, &self.queue, t)?)
    }

    /// Reads the displayed image back as RGBA8, row-major from the top row.
    pub fn read_display(&self) -> Result<Vec<u8>, EngineError> {
        let t = self.display_texture().ok_or(EngineError::NotRendered)?;
        Ok(read_texture(&self.device, &self.queue, t)?)
    }

    /// Reads one lookup table back: every texel of every layer (batch), in the order of
    /// `model::methods::hillaire::Lut`.
    pub fn read_table(&self, table: Table) -> Result<Vec<[f32; 4]>, EngineError> {
        let luts = &self
            .atmosphere
            .as_ref()
            .ok_or(EngineError::NotRendered)?
            .luts;
        Ok(read_buffer_f32x4(
            &self.device,
            &self.queue,
            luts.buffer(table),
        )?)
    }
}

fn map_u64(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Option<Vec<u64>> {
    let (tx, rx) = std::sync::mpsc::channel();
    buffer.slice(..).map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).ok()?;
    rx.recv().ok()?.ok()?;
    let ticks = {
        let data = buffer.slice(..).get_mapped_range().ok()?;
        bytemuck::pod_collect_to_vec(&data)
    };
    buffer.unmap();
    Some(ticks)
}

fn groups(n: u32) -> u32 {
    n.div_ceil(crate::prelude::WORKGROUP_SIZE)
}

fn view_dispatch(size: [u32; 2]) -> [u32; 3] {
    [groups(size[0]), groups(size[1]), 1]
}

fn lut_dispatch(pass: Pass, layers: u32) -> [u32; 3] {
    use atmoscope_model::methods::hillaire as h;
    let [w, hh] = match pass {
        Pass::Transmittance => h::TRANSMITTANCE_SIZE,
        Pass::MultipleScattering => h::MULTIPLE_SCATTERING_SIZE,
        Pass::GroundIrradiance => [h::GROUND_IRRADIANCE_SIZE, 1],
        Pass::SkyView => h::SKY_VIEW_SIZE,
        Pass::AerialPerspective => [h::AERIAL_PERSPECTIVE_SIZE[0], h::AERIAL_PERSPECTIVE_SIZE[1]],
        Pass::Sky | Pass::Display => [1, 1],
    };
    [groups(w), groups(hh), layers]
}

impl Target {
    fn new(
        device: &wgpu::Device,
        pipelines: &Pipelines,
        luts: &LutBuffers,
        size: [u32; 2],
    ) -> Target {
        let texture = |label, format, view_formats: &[wgpu::TextureFormat]| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: size[0],
                    height: size[1],
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats,
            })
        };
        let radiance = texture("radiance", wgpu::TextureFormat::Rgba32Float, &[]);
        // The sRGB view lets a UI sample the encoded bytes as linear colour (egui decodes).
        let display = texture(
            "display",
            wgpu::TextureFormat::Rgba8Unorm,
            &[wgpu::TextureFormat::Rgba8UnormSrgb],
        );
        let sky_group = luts.sky_group(device, pipelines, &radiance);
        let display_group = pipelines.display_group(device, &radiance, &display);
        Target {
            size,
            radiance,
            display,
            sky_group,
            display_group,
        }
    }
}
