//! Hillaire (2020) on the GPU: the pipelines of `shaders/hillaire/*.wgsl` (one entry file per
//! pass), their bind group layouts, and the lookup tables (storage buffers of vec4 texels). The f64 twin of every pass is
//! `atmoscope_model::methods::hillaire`.

use crate::engine::Pass;
use crate::prelude::shader_source;
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

use wgpu::TextureViewDimension::D2;

fn table(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: false },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// The lookup tables, with their group-1 binding numbers (bindings.wgsl).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Table {
    Transmittance,
    MultipleScattering,
    GroundIrradiance,
    SkyView,
    AerialPerspectiveInscattering,
    AerialPerspectiveTransmittance,
}

impl Table {
    pub const ALL: [Table; 6] = [
        Table::Transmittance,
        Table::MultipleScattering,
        Table::GroundIrradiance,
        Table::SkyView,
        Table::AerialPerspectiveInscattering,
        Table::AerialPerspectiveTransmittance,
    ];

    pub fn binding(self) -> u32 {
        Table::ALL.iter().position(|&t| t == self).unwrap_or(0) as u32
    }

    pub fn name(self) -> &'static str {
        match self {
            Table::Transmittance => "transmittance",
            Table::MultipleScattering => "multiple scattering",
            Table::GroundIrradiance => "ground irradiance",
            Table::SkyView => "sky view",
            Table::AerialPerspectiveInscattering => "aerial perspective (in-scattering)",
            Table::AerialPerspectiveTransmittance => "aerial perspective (transmittance)",
        }
    }

    /// Width, height and depth of one layer (batch).
    pub fn size(self) -> [u32; 3] {
        match self {
            Table::Transmittance => [TRANSMITTANCE_SIZE[0], TRANSMITTANCE_SIZE[1], 1],
            Table::MultipleScattering => {
                [MULTIPLE_SCATTERING_SIZE[0], MULTIPLE_SCATTERING_SIZE[1], 1]
            }
            Table::GroundIrradiance => [GROUND_IRRADIANCE_SIZE, 1, 1],
            Table::SkyView => [SKY_VIEW_SIZE[0], SKY_VIEW_SIZE[1], 1],
            Table::AerialPerspectiveInscattering | Table::AerialPerspectiveTransmittance => {
                AERIAL_PERSPECTIVE_SIZE
            }
        }
    }

    /// The tables a pass reads or writes.
    pub fn of_pass(pass: Pass) -> &'static [Table] {
        use Table::*;
        match pass {
            Pass::Transmittance => &[Transmittance],
            Pass::MultipleScattering => &[Transmittance, MultipleScattering],
            Pass::GroundIrradiance => &[Transmittance, MultipleScattering, GroundIrradiance],
            Pass::SkyView => &[Transmittance, MultipleScattering, SkyView],
            Pass::AerialPerspective => &[
                Transmittance,
                MultipleScattering,
                AerialPerspectiveInscattering,
                AerialPerspectiveTransmittance,
            ],
            Pass::Sky => &Table::ALL,
            Pass::Display => &[],
        }
    }
}

/// Binding of the sky pass's radiance output and of the display pass's input and output.
const RADIANCE_OUT: u32 = 6;
const RADIANCE_IN: u32 = 7;
const DISPLAY_OUT: u32 = 8;

/// The group-1 layout of each pass: the tables it uses, then its image inputs and outputs.
fn pass_layout(pass: Pass) -> Vec<wgpu::BindGroupLayoutEntry> {
    let mut v: Vec<_> = Table::of_pass(pass)
        .iter()
        .map(|t| table(t.binding()))
        .collect();
    match pass {
        Pass::Sky => v.push(texture_out(RADIANCE_OUT, LUT_FORMAT, D2)),
        Pass::Display => {
            v.push(texture_in(RADIANCE_IN, D2));
            v.push(texture_out(
                DISPLAY_OUT,
                wgpu::TextureFormat::Rgba8Unorm,
                D2,
            ));
        }
        _ => {}
    }
    v
}

/// Which variant of a pass's pipeline a frame needs: the values of its pipeline constants
/// (projection and camera above the atmosphere for the sky pass, display mode and tone map for
/// the display pass; none for the tables).
pub type Variant = [u32; 2];

/// Compiled pipelines and layouts of every pass; pipeline variants are compiled on first use.
pub struct Pipelines {
    group0: wgpu::BindGroupLayout,
    layouts: Vec<wgpu::BindGroupLayout>,
    pipeline_layouts: Vec<wgpu::PipelineLayout>,
    modules: Vec<wgpu::ShaderModule>,
    pipelines: Vec<(Pass, Variant, wgpu::ComputePipeline)>,
}

fn pass_index(pass: Pass) -> usize {
    Pass::ALL.iter().position(|&p| p == pass).unwrap_or(0)
}

impl Pipelines {
    pub fn new(device: &wgpu::Device) -> Pipelines {
        let group0 = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("group 0: globals, batches, profile"),
            entries: &[uniform(0), storage(1), storage(2)],
        });
        let mut p = Pipelines {
            group0,
            layouts: Vec::new(),
            pipeline_layouts: Vec::new(),
            modules: Vec::new(),
            pipelines: Vec::new(),
        };
        for pass in Pass::ALL {
            let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(pass.name()),
                entries: &pass_layout(pass),
            });
            p.modules
                .push(device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(pass.shader_file().0),
                    source: wgpu::ShaderSource::Wgsl(shader_source(pass).into()),
                }));
            p.pipeline_layouts.push(device.create_pipeline_layout(
                &wgpu::PipelineLayoutDescriptor {
                    label: Some(pass.name()),
                    bind_group_layouts: &[Some(&p.group0), Some(&layout)],
                    immediate_size: 0,
                },
            ));
            p.layouts.push(layout);
        }
        for pass in Pass::ALL.into_iter().filter(|p| p.is_lut()) {
            p.ensure(device, pass, [0, 0]);
        }
        p
    }

    /// Compiles the pipeline of `pass` for `variant` unless it exists.
    pub fn ensure(&mut self, device: &wgpu::Device, pass: Pass, variant: Variant) {
        if self
            .pipelines
            .iter()
            .any(|(p, v, _)| *p == pass && *v == variant)
        {
            return;
        }
        let names: &[&str] = match pass {
            Pass::Sky => &["PROJECTION", "ABOVE_ATMOSPHERE"],
            Pass::Display => &["DISPLAY_MODE", "TONE_MAP"],
            _ => &[],
        };
        let constants: Vec<(&str, f64)> = names
            .iter()
            .zip(variant)
            .map(|(n, v)| (*n, f64::from(v)))
            .collect();
        let i = pass_index(pass);
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(pass.name()),
            layout: Some(&self.pipeline_layouts[i]),
            module: &self.modules[i],
            entry_point: Some("main"),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: &constants,
                ..Default::default()
            },
            cache: None,
        });
        self.pipelines.push((pass, variant, pipeline));
    }

    /// The pipeline of `pass` for `variant` (compiled by `ensure`).
    pub fn pipeline(&self, pass: Pass, variant: Variant) -> Option<&wgpu::ComputePipeline> {
        self.pipelines
            .iter()
            .find(|(p, v, _)| *p == pass && *v == variant)
            .map(|(_, _, pipeline)| pipeline)
    }

    fn layout(&self, pass: Pass) -> &wgpu::BindGroupLayout {
        &self.layouts[pass_index(pass)]
    }

    pub fn display_group(
        &self,
        device: &wgpu::Device,
        radiance: &wgpu::Texture,
        display: &wgpu::Texture,
    ) -> wgpu::BindGroup {
        let (radiance, display) = (view(radiance, D2), view(display, D2));
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("display"),
            layout: self.layout(Pass::Display),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: RADIANCE_IN,
                    resource: wgpu::BindingResource::TextureView(&radiance),
                },
                wgpu::BindGroupEntry {
                    binding: DISPLAY_OUT,
                    resource: wgpu::BindingResource::TextureView(&display),
                },
            ],
        })
    }
}

fn view(t: &wgpu::Texture, dimension: wgpu::TextureViewDimension) -> wgpu::TextureView {
    t.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(dimension),
        ..Default::default()
    })
}

/// The tables of one atmosphere and wavelength set, the buffers they are computed from, and the
/// bind groups of the table passes.
pub struct LutBuffers {
    pub batches: wgpu::Buffer,
    pub profile: wgpu::Buffer,
    pub group0: wgpu::BindGroup,
    tables: Vec<(Table, wgpu::Buffer)>,
    groups: Vec<(Pass, wgpu::BindGroup)>,
}

impl LutBuffers {
    pub fn new(
        device: &wgpu::Device,
        pipelines: &Pipelines,
        globals: &wgpu::Buffer,
        params: &Params,
    ) -> LutBuffers {
        let layers = params.batches.len() as u64;
        let buffer = |label, size: u64, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        let input = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
        let batches = buffer(
            "batches",
            std::mem::size_of::<Batch>() as u64 * layers,
            input,
        );
        let profile = buffer("profile", 16 * u64::from(PROFILE_SAMPLES), input);
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
        let tables: Vec<(Table, wgpu::Buffer)> = Table::ALL
            .iter()
            .map(|&t| {
                let [w, h, d] = t.size();
                let texels = u64::from(w * h * d) * layers;
                let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC;
                (t, buffer(t.name(), 16 * texels, usage))
            })
            .collect();
        let mut luts = LutBuffers {
            batches,
            profile,
            group0,
            tables,
            groups: Vec::new(),
        };
        luts.groups = Pass::ALL
            .iter()
            .filter(|p| p.is_lut())
            .map(|&p| (p, luts.bind(device, pipelines, p, None)))
            .collect();
        luts
    }

    /// The storage buffer of a table.
    pub fn buffer(&self, table: Table) -> &wgpu::Buffer {
        let i = self
            .tables
            .iter()
            .position(|(t, _)| *t == table)
            .unwrap_or(0);
        &self.tables[i].1
    }

    fn bind(
        &self,
        device: &wgpu::Device,
        pipelines: &Pipelines,
        pass: Pass,
        radiance: Option<&wgpu::TextureView>,
    ) -> wgpu::BindGroup {
        let mut entries: Vec<wgpu::BindGroupEntry> = Table::of_pass(pass)
            .iter()
            .map(|&t| wgpu::BindGroupEntry {
                binding: t.binding(),
                resource: self.buffer(t).as_entire_binding(),
            })
            .collect();
        if let Some(view) = radiance {
            entries.push(wgpu::BindGroupEntry {
                binding: RADIANCE_OUT,
                resource: wgpu::BindingResource::TextureView(view),
            });
        }
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(pass.name()),
            layout: pipelines.layout(pass),
            entries: &entries,
        })
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
        self.bind(device, pipelines, Pass::Sky, Some(&view(radiance, D2)))
    }
}
