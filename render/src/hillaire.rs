//! Hillaire (2020) on the GPU: the pipelines of `shaders/hillaire/*.wgsl` (one entry file per
//! pass), their bind group layouts, and the lookup-table textures. The f64 twin of every pass is
//! `atmoscope_model::methods::hillaire`.

use crate::engine::Pass;
use crate::prelude::{ShaderEntry, shader_source};
use crate::uniforms::{Batch, Globals};
use atmoscope_model::methods::hillaire::{
    AERIAL_PERSPECTIVE_SIZE, GROUND_IRRADIANCE_SIZE, MULTIPLE_SCATTERING_SIZE, PROFILE_SAMPLES,
    Params, SKY_VIEW_SIZE, TRANSMITTANCE_SIZE,
};

const LUT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

fn uniform(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn storage(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn texture_in(
    binding: u32,
    view_dimension: wgpu::TextureViewDimension,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: false },
            view_dimension,
            multisampled: false,
        },
        count: None,
    }
}

fn texture_out(
    binding: u32,
    format: wgpu::TextureFormat,
    view_dimension: wgpu::TextureViewDimension,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format,
            view_dimension,
        },
        count: None,
    }
}

use wgpu::TextureViewDimension::{D2, D2Array, D3};

/// The group-1 layout of each pass: its input tables, then its outputs.
fn pass_layout(pass: Pass) -> Vec<wgpu::BindGroupLayoutEntry> {
    let tables = |n: u32| (0..n).map(|b| texture_in(b, D2Array)).collect::<Vec<_>>();
    match pass {
        Pass::Transmittance => vec![texture_out(0, LUT_FORMAT, D2Array)],
        Pass::MultipleScattering => {
            let mut v = tables(1);
            v.push(texture_out(1, LUT_FORMAT, D2Array));
            v
        }
        Pass::GroundIrradiance | Pass::SkyView => {
            let mut v = tables(2);
            v.push(texture_out(2, LUT_FORMAT, D2Array));
            v
        }
        Pass::AerialPerspective => {
            let mut v = tables(2);
            v.push(texture_out(2, LUT_FORMAT, D3));
            v.push(texture_out(3, LUT_FORMAT, D3));
            v
        }
        Pass::Sky => {
            let mut v = tables(4);
            v.push(texture_in(4, D3));
            v.push(texture_in(5, D3));
            v.push(texture_out(6, LUT_FORMAT, D2));
            v
        }
        Pass::Display => vec![
            texture_in(0, D2),
            texture_out(1, wgpu::TextureFormat::Rgba8Unorm, D2),
        ],
    }
}

fn entry(pass: Pass) -> ShaderEntry {
    match pass {
        Pass::Transmittance => ShaderEntry::Transmittance,
        Pass::MultipleScattering => ShaderEntry::MultipleScattering,
        Pass::GroundIrradiance => ShaderEntry::GroundIrradiance,
        Pass::SkyView => ShaderEntry::SkyView,
        Pass::AerialPerspective => ShaderEntry::AerialPerspective,
        Pass::Sky => ShaderEntry::Sky,
        Pass::Display => ShaderEntry::Display,
    }
}

/// Compiled pipelines and layouts of every pass.
pub struct Pipelines {
    group0: wgpu::BindGroupLayout,
    layouts: Vec<wgpu::BindGroupLayout>,
    pipelines: Vec<wgpu::ComputePipeline>,
}

impl Pipelines {
    pub fn new(device: &wgpu::Device) -> Pipelines {
        let group0 = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("group 0: globals, batches, profile"),
            entries: &[uniform(0), storage(1), storage(2)],
        });
        let mut layouts = Vec::new();
        let mut pipelines = Vec::new();
        for pass in Pass::ALL {
            let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(pass.name()),
                entries: &pass_layout(pass),
            });
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(entry(pass).file().0),
                source: wgpu::ShaderSource::Wgsl(shader_source(entry(pass)).into()),
            });
            let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(pass.name()),
                bind_group_layouts: &[Some(&group0), Some(&layout)],
                immediate_size: 0,
            });
            pipelines.push(
                device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(pass.name()),
                    layout: Some(&pipeline_layout),
                    module: &module,
                    entry_point: Some("main"),
                    compilation_options: Default::default(),
                    cache: None,
                }),
            );
            layouts.push(layout);
        }
        Pipelines {
            group0,
            layouts,
            pipelines,
        }
    }

    pub fn pipeline(&self, pass: Pass) -> &wgpu::ComputePipeline {
        &self.pipelines[Pass::ALL.iter().position(|&p| p == pass).unwrap_or(0)]
    }

    fn layout(&self, pass: Pass) -> &wgpu::BindGroupLayout {
        &self.layouts[Pass::ALL.iter().position(|&p| p == pass).unwrap_or(0)]
    }

    pub fn display_group(
        &self,
        device: &wgpu::Device,
        radiance: &wgpu::Texture,
        display: &wgpu::Texture,
    ) -> wgpu::BindGroup {
        bind(
            device,
            self.layout(Pass::Display),
            &[view(radiance, D2), view(display, D2)],
        )
    }
}

fn view(t: &wgpu::Texture, dimension: wgpu::TextureViewDimension) -> wgpu::TextureView {
    t.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(dimension),
        ..Default::default()
    })
}

fn bind(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    views: &[wgpu::TextureView],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry> = views
        .iter()
        .enumerate()
        .map(|(i, v)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: wgpu::BindingResource::TextureView(v),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout,
        entries: &entries,
    })
}

/// The tables of one atmosphere and wavelength set, the buffers they are computed from, and the
/// bind groups of the table passes.
pub struct LutTextures {
    pub batches: wgpu::Buffer,
    pub profile: wgpu::Buffer,
    pub group0: wgpu::BindGroup,
    pub transmittance: wgpu::Texture,
    pub multiple_scattering: wgpu::Texture,
    pub ground_irradiance: wgpu::Texture,
    pub sky_view: wgpu::Texture,
    pub aerial_perspective_inscattering: wgpu::Texture,
    pub aerial_perspective_transmittance: wgpu::Texture,
    groups: Vec<(Pass, wgpu::BindGroup)>,
}

impl LutTextures {
    pub fn new(
        device: &wgpu::Device,
        pipelines: &Pipelines,
        globals: &wgpu::Buffer,
        params: &Params,
    ) -> LutTextures {
        let layers = params.batches.len() as u32;
        let buffer = |label, size: usize| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let batches = buffer("batches", std::mem::size_of::<Batch>() * layers as usize);
        let profile = buffer("profile", 16 * PROFILE_SAMPLES as usize);
        let group0 = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("group 0"),
            layout: &pipelines.group0,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: globals.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: batches.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: profile.as_entire_binding(),
                },
            ],
        });
        debug_assert_eq!(std::mem::size_of::<Globals>() % 16, 0);
        let texture = |label, w: u32, h: u32, depth: u32, dimension| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: w,
                    height: h,
                    depth_or_array_layers: depth,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension,
                format: LUT_FORMAT,
                usage: wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        };
        use wgpu::TextureDimension as Dim;
        let [tw, th] = TRANSMITTANCE_SIZE;
        let [mw, mh] = MULTIPLE_SCATTERING_SIZE;
        let [sw, sh] = SKY_VIEW_SIZE;
        let [aw, ah, ad] = AERIAL_PERSPECTIVE_SIZE;
        let transmittance = texture("transmittance", tw, th, layers, Dim::D2);
        let multiple_scattering = texture("multiple scattering", mw, mh, layers, Dim::D2);
        let ground_irradiance = texture(
            "ground irradiance",
            GROUND_IRRADIANCE_SIZE,
            1,
            layers,
            Dim::D2,
        );
        let sky_view = texture("sky view", sw, sh, layers, Dim::D2);
        let ap_s = texture(
            "aerial perspective in-scattering",
            aw,
            ah,
            ad * layers,
            Dim::D3,
        );
        let ap_t = texture(
            "aerial perspective transmittance",
            aw,
            ah,
            ad * layers,
            Dim::D3,
        );
        let t = || view(&transmittance, D2Array);
        let ms = || view(&multiple_scattering, D2Array);
        let groups = vec![
            (
                Pass::Transmittance,
                bind(device, pipelines.layout(Pass::Transmittance), &[t()]),
            ),
            (
                Pass::MultipleScattering,
                bind(
                    device,
                    pipelines.layout(Pass::MultipleScattering),
                    &[t(), ms()],
                ),
            ),
            (
                Pass::GroundIrradiance,
                bind(
                    device,
                    pipelines.layout(Pass::GroundIrradiance),
                    &[t(), ms(), view(&ground_irradiance, D2Array)],
                ),
            ),
            (
                Pass::SkyView,
                bind(
                    device,
                    pipelines.layout(Pass::SkyView),
                    &[t(), ms(), view(&sky_view, D2Array)],
                ),
            ),
            (
                Pass::AerialPerspective,
                bind(
                    device,
                    pipelines.layout(Pass::AerialPerspective),
                    &[t(), ms(), view(&ap_s, D3), view(&ap_t, D3)],
                ),
            ),
        ];
        LutTextures {
            batches,
            profile,
            group0,
            transmittance,
            multiple_scattering,
            ground_irradiance,
            sky_view,
            aerial_perspective_inscattering: ap_s,
            aerial_perspective_transmittance: ap_t,
            groups,
        }
    }

    /// The group-1 bind group of a table pass.
    pub fn group(&self, pass: Pass) -> &wgpu::BindGroup {
        let i = self
            .groups
            .iter()
            .position(|(p, _)| *p == pass)
            .unwrap_or(0);
        &self.groups[i].1
    }

    /// The sky pass's group: every table in, the radiance texture out.
    pub fn sky_group(
        &self,
        device: &wgpu::Device,
        pipelines: &Pipelines,
        radiance: &wgpu::Texture,
    ) -> wgpu::BindGroup {
        bind(
            device,
            pipelines.layout(Pass::Sky),
            &[
                view(&self.transmittance, D2Array),
                view(&self.multiple_scattering, D2Array),
                view(&self.ground_irradiance, D2Array),
                view(&self.sky_view, D2Array),
                view(&self.aerial_perspective_inscattering, D3),
                view(&self.aerial_perspective_transmittance, D3),
                view(radiance, D2),
            ],
        )
    }
}
