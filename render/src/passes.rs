//! GPU objects for any model's passes: bind group layouts built from what each pass reads and
//! writes, shader modules, pipeline variants compiled on first use, and the storage buffers of
//! the model's tables (vec4 texels in the order of `model::methods::shared::Lut`).

use crate::prelude::{march_split, texel_run, wgsl_prelude};
use crate::spec::{Constant, GpuMethod, MOVING_SKY, PassSpec, RADIANCE, Resource, bindings};
use crate::uniforms::{Batch, Globals, MIE_PHASE_ROWS_LEN};
use atmoscope_model::methods::shared::{PROFILE_SAMPLES, Params};
use atmoscope_model::methods::{ModelInfo, shared::TableSpec};

/// Most pipeline constants a pass takes.
pub const MAX_CONSTANTS: usize = 11;

/// Values of a pass's pipeline constants, in the order of its `constants`.
pub type Variant = [u32; MAX_CONSTANTS];

fn entry(binding: u32, ty: wgpu::BindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty,
        count: None,
    }
}

fn buffer_entry(binding: u32, ty: wgpu::BufferBindingType) -> wgpu::BindGroupLayoutEntry {
    entry(
        binding,
        wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
    )
}

fn storage_texture(binding: u32, format: wgpu::TextureFormat) -> wgpu::BindGroupLayoutEntry {
    entry(
        binding,
        wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format,
            view_dimension: wgpu::TextureViewDimension::D2,
        },
    )
}

/// The group-1 binding of `resource` in `pass` (`spec::bindings`); every resource a pass
/// binds is declared in the registry or is one of the view's (the registry tests check it).
fn bound(pass: &PassSpec, resource: Resource) -> u32 {
    bindings::binding(resource, pass.writes.contains(&resource)).unwrap_or(u32::MAX)
}

/// The group-1 layout of a pass: what it reads, then what it writes.
fn pass_layout(pass: &PassSpec) -> Vec<wgpu::BindGroupLayoutEntry> {
    pass.resources()
        .into_iter()
        .map(|r| {
            let binding = bound(pass, r);
            match r {
                Resource::Radiance if pass.writes.contains(&RADIANCE) => {
                    storage_texture(binding, wgpu::TextureFormat::Rgba32Float)
                }
                Resource::Radiance => entry(
                    binding,
                    wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                ),
                Resource::Display => storage_texture(binding, wgpu::TextureFormat::Rgba8Unorm),
                _ => buffer_entry(
                    binding,
                    wgpu::BufferBindingType::Storage {
                        read_only: pass.reads_only(r),
                    },
                ),
            }
        })
        .collect()
}

/// The complete WGSL module of a pass of `method`: the generated prelude and group-1
/// bindings, then the files `GpuMethod::files` lists, for workgroups of `texel_group_size`
/// where a workgroup shares a texel (`prelude::texel_group_size`).
pub fn shader_source(method: &GpuMethod, pass: &PassSpec, texel_group_size: u32) -> String {
    let mut s = wgsl_prelude();
    s.push_str(&format!(
        "const TEXEL_GROUP_SIZE: u32 = {texel_group_size}u;\nconst MARCH_SPLIT: u32 = {}u;\n\
         const TEXEL_RUN: u32 = {}u;\n",
        march_split(texel_group_size),
        texel_run(texel_group_size)
    ));
    s.push_str(&bindings::wgsl(pass));
    for file in method.files(pass) {
        s.push_str(file.source);
    }
    s
}

struct PassObjects {
    spec: PassSpec,
    layout: wgpu::BindGroupLayout,
    pipeline_layout: wgpu::PipelineLayout,
    module: wgpu::ShaderModule,
    variants: Vec<(Variant, wgpu::ComputePipeline)>,
}

/// Compiled passes of one model, the display pass last.
pub struct Pipelines {
    pub method: GpuMethod,
    /// Invocations of a workgroup that shares a texel, as compiled.
    pub texel_group_size: u32,
    group0: wgpu::BindGroupLayout,
    passes: Vec<PassObjects>,
}

impl Pipelines {
    /// The passes of `method` compiled on `device`, with workgroups of `texel_group_size` (a
    /// power of two, 1–256; `prelude::texel_group_size` gives the adapter's) where a workgroup
    /// shares a texel.
    pub fn new(device: &wgpu::Device, method: &GpuMethod, texel_group_size: u32) -> Pipelines {
        let group0 = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("group 0: globals, batches, profile, origin, Mie phase"),
            entries: &[
                buffer_entry(0, wgpu::BufferBindingType::Uniform),
                buffer_entry(1, wgpu::BufferBindingType::Storage { read_only: true }),
                buffer_entry(2, wgpu::BufferBindingType::Storage { read_only: true }),
                entry(
                    3,
                    wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: true,
                        min_binding_size: wgpu::BufferSize::new(ORIGIN_BYTES),
                    },
                ),
                // A uniform: the sky passes already bind as many storage buffers as a stage
                // may (8).
                buffer_entry(4, wgpu::BufferBindingType::Uniform),
            ],
        });
        let passes = method
            .passes
            .iter()
            .chain(&crate::spec::VIEW_PASSES)
            .map(|&spec| {
                // The model and the pass with its own file, for validation messages.
                let label = format!(
                    "{} {} ({})",
                    method.info().id,
                    spec.name,
                    spec.own_file().map_or("", |f| f.path)
                );
                let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some(&label),
                    entries: &pass_layout(&spec),
                });
                let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(&label),
                    source: wgpu::ShaderSource::Wgsl(
                        shader_source(method, &spec, texel_group_size).into(),
                    ),
                });
                let pipeline_layout =
                    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                        label: Some(&label),
                        bind_group_layouts: &[Some(&group0), Some(&layout)],
                        immediate_size: 0,
                    });
                PassObjects {
                    spec,
                    layout,
                    pipeline_layout,
                    module,
                    variants: Vec::new(),
                }
            })
            .collect();
        let mut p = Pipelines {
            method: *method,
            texel_group_size,
            group0,
            passes,
        };
        for i in 0..p.passes.len() {
            if p.passes[i].spec.constants.is_empty() {
                p.ensure(device, i, [0; MAX_CONSTANTS]);
            }
        }
        p
    }

    /// Every pass, the display pass last.
    pub fn specs(&self) -> impl Iterator<Item = &PassSpec> {
        self.passes.iter().map(|p| &p.spec)
    }

    /// The index of the pass that builds the moving sky of a march per pixel, if any.
    pub fn moving_sky_pass(&self) -> Option<usize> {
        self.specs()
            .position(|s| s.is_table() && s.writes.contains(&MOVING_SKY))
    }

    pub fn len(&self) -> usize {
        self.passes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.passes.is_empty()
    }

    /// Compiles pass `i` for `variant` unless it exists.
    pub fn ensure(&mut self, device: &wgpu::Device, i: usize, variant: Variant) {
        let p = &mut self.passes[i];
        if p.variants.iter().any(|(v, _)| *v == variant) {
            return;
        }
        let constants: Vec<(&str, f64)> = p
            .spec
            .constants
            .iter()
            .zip(variant)
            .map(|(c, v)| (c.name(), f64::from(v)))
            .collect();
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(p.spec.name),
            layout: Some(&p.pipeline_layout),
            module: &p.module,
            entry_point: Some("main"),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: &constants,
                ..Default::default()
            },
            cache: None,
        });
        p.variants.push((variant, pipeline));
    }

    /// The pipeline of pass `i` for `variant` (compiled by `ensure`).
    pub fn pipeline(&self, i: usize, variant: Variant) -> Option<&wgpu::ComputePipeline> {
        self.passes[i]
            .variants
            .iter()
            .find(|(v, _)| *v == variant)
            .map(|(_, p)| p)
    }

    /// The values of pass `i`'s constants for a frame, from every constant's value.
    pub fn variant(&self, i: usize, value: impl Fn(Constant) -> u32) -> Variant {
        let mut v = [0; MAX_CONSTANTS];
        for (slot, &c) in v.iter_mut().zip(self.passes[i].spec.constants) {
            *slot = value(c);
        }
        v
    }

    /// `variant` of pass `i` with constant `c` set to `value` (unchanged if the pass does not
    /// take `c`).
    pub fn with_constant(
        &self,
        i: usize,
        mut variant: Variant,
        c: Constant,
        value: u32,
    ) -> Variant {
        if let Some(slot) = self.passes[i].spec.constants.iter().position(|&k| k == c) {
            variant[slot] = value;
        }
        variant
    }

    /// A bind group for pass `i` over `resource` (each binding's resource).
    pub fn bind<'a>(
        &self,
        device: &wgpu::Device,
        i: usize,
        resource: impl Fn(Resource) -> Option<wgpu::BindingResource<'a>>,
    ) -> Option<wgpu::BindGroup> {
        let spec = &self.passes[i].spec;
        let mut entries = Vec::new();
        for r in spec.resources() {
            entries.push(wgpu::BindGroupEntry {
                binding: bound(spec, r),
                resource: resource(r)?,
            });
        }
        Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(spec.name),
            layout: &self.passes[i].layout,
            entries: &entries,
        }))
    }
}

/// Bytes of one dispatch origin (`origin` in `shaders/common/bindings.wgsl`: vec4<u32>).
const ORIGIN_BYTES: u64 = 16;

/// Dispatches one frame may place at their own origin (slots of the origins buffer).
pub const ORIGIN_SLOTS: usize = 256;

/// The tables of one atmosphere and wavelength set and the buffers they are computed from.
pub struct TableBuffers {
    pub globals: wgpu::Buffer,
    /// One origin per dispatch of a frame, `origin_stride` bytes apart (the device's uniform
    /// offset alignment), bound with a dynamic offset.
    pub origins: wgpu::Buffer,
    pub origin_stride: u64,
    pub batches: wgpu::Buffer,
    pub profile: wgpu::Buffer,
    /// The tabulated Mie phase function's rows (`uniforms::mie_phase_rows`).
    pub mie_phase: wgpu::Buffer,
    pub group0: wgpu::BindGroup,
    tables: Vec<(TableSpec, wgpu::Buffer)>,
    /// Group 1 of each table pass, by pass index (None for the view passes).
    groups: Vec<Option<wgpu::BindGroup>>,
    /// Where a model with a moving sky builds the next one in slices (None for the others).
    pub next_moving_sky: Option<NextMovingSky>,
}

/// The moving sky being built a slice per frame while the sky pass reads the last complete
/// one (`methods::MOVING_SKY`): a table of its own, and the globals of the frame that started
/// it, which every slice reads whatever the frames in between change.
pub struct NextMovingSky {
    pub globals: wgpu::Buffer,
    table: wgpu::Buffer,
    pub group0: wgpu::BindGroup,
    /// Group 1 of the moving-sky pass over `table`.
    pub group1: wgpu::BindGroup,
}

impl TableBuffers {
    pub fn new(
        device: &wgpu::Device,
        pipelines: &Pipelines,
        model: &ModelInfo,
        params: &Params,
    ) -> TableBuffers {
        let layers = params.batches.len();
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
            std::mem::size_of::<Batch>() as u64 * layers as u64,
            input,
        );
        let profile = buffer("profile", 16 * u64::from(PROFILE_SAMPLES), input);
        let uniform = wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST;
        let mie_phase = buffer("Mie phase", 4 * MIE_PHASE_ROWS_LEN as u64, uniform);
        let globals = buffer("globals", std::mem::size_of::<Globals>() as u64, uniform);
        let origin_stride =
            u64::from(device.limits().min_uniform_buffer_offset_alignment).max(ORIGIN_BYTES);
        let origins = buffer("origins", origin_stride * ORIGIN_SLOTS as u64, uniform);
        let group0 = |globals: &wgpu::Buffer, origins: &wgpu::Buffer| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
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
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                            buffer: origins,
                            offset: 0,
                            size: wgpu::BufferSize::new(ORIGIN_BYTES),
                        }),
                    },
                    wgpu::BindGroupEntry {
                        binding: 4,
                        resource: mie_phase.as_entire_binding(),
                    },
                ],
            })
        };
        let table_usage = wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST;
        let tables = model
            .tables
            .iter()
            // COPY_DST: a rebuild in slices clears them itself (`clear`).
            .map(|t| (*t, buffer(t.label, t.bytes(layers), table_usage)))
            .collect::<Vec<_>>();
        let next_moving_sky = pipelines.moving_sky_pass().and_then(|i| {
            let spec = model.table(MOVING_SKY.id())?;
            let table = buffer("moving sky (next)", spec.bytes(layers), table_usage);
            let globals = buffer(
                "globals (next moving sky)",
                std::mem::size_of::<Globals>() as u64,
                uniform,
            );
            let group1 = pipelines.bind(device, i, |r| {
                if r == MOVING_SKY {
                    Some(table.as_entire_binding())
                } else {
                    tables
                        .iter()
                        .find(|(t, _): &&(TableSpec, wgpu::Buffer)| t.id == r.id())
                        .map(|(_, b)| b.as_entire_binding())
                }
            })?;
            Some(NextMovingSky {
                group0: group0(&globals, &origins),
                globals,
                table,
                group1,
            })
        });
        let mut b = TableBuffers {
            group0: group0(&globals, &origins),
            globals,
            origins,
            origin_stride,
            batches,
            profile,
            mie_phase,
            tables,
            groups: Vec::new(),
            next_moving_sky,
        };
        let groups = (0..pipelines.len())
            .map(|i| {
                let spec = &pipelines.passes[i].spec;
                if spec.is_table() {
                    pipelines.bind(device, i, |r| {
                        b.buffer(r.id()).map(|buf| buf.as_entire_binding())
                    })
                } else {
                    None
                }
            })
            .collect();
        b.groups = groups;
        b
    }

    /// The storage buffer of a table.
    pub fn buffer(&self, id: &str) -> Option<&wgpu::Buffer> {
        self.tables.iter().find(|(t, _)| t.id == id).map(|(_, b)| b)
    }

    /// Every table's buffer.
    pub fn table_buffers(&self) -> impl Iterator<Item = &wgpu::Buffer> {
        self.tables.iter().map(|(_, b)| b)
    }

    /// Group 1 of table pass `i`.
    pub fn group(&self, i: usize) -> Option<&wgpu::BindGroup> {
        self.groups.get(i).and_then(|g| g.as_ref())
    }

    /// Encodes the copy of the next moving sky, once every slice of it has finished, over the
    /// one the sky pass reads.
    pub fn publish_next_moving_sky(&self, encoder: &mut wgpu::CommandEncoder) {
        if let (Some(next), Some(table)) = (&self.next_moving_sky, self.buffer(MOVING_SKY.id())) {
            encoder.copy_buffer_to_buffer(&next.table, 0, table, 0, None);
        }
    }

    /// Bytes of every table together.
    pub fn bytes(&self) -> u64 {
        self.tables.iter().map(|(_, b)| b.size()).sum()
    }

    /// Zeroes up to `len` bytes of the tables from byte `start` of all of them laid end to end,
    /// and returns how many it zeroed. wgpu zero-fills a buffer where it is first used, all of
    /// it in that submission (a large frame for tables of hundreds of MB, such as Bruneton's at
    /// Spectral32); cleared ahead in pieces they are not filled again.
    pub fn clear(&self, encoder: &mut wgpu::CommandEncoder, start: u64, len: u64) -> u64 {
        let sizes: Vec<u64> = self.tables.iter().map(|(_, b)| b.size()).collect();
        let mut cleared = 0;
        for (i, offset, size) in clear_spans(&sizes, start, len) {
            encoder.clear_buffer(&self.tables[i].1, offset, Some(size));
            cleared += size;
        }
        cleared
    }
}

/// The pieces of buffers of `sizes` bytes, laid end to end, that bytes `start..start + len`
/// cover: (buffer, offset, size). Sizes are multiples of 4 bytes (vec4 texels), as
/// `clear_buffer` needs; `start` and `len` are taken to be too.
fn clear_spans(sizes: &[u64], start: u64, len: u64) -> Vec<(usize, u64, u64)> {
    let end = start.saturating_add(len);
    let mut spans = Vec::new();
    let mut base = 0;
    for (i, &size) in sizes.iter().enumerate() {
        let (from, to) = (start.max(base), end.min(base + size));
        if from < to {
            spans.push((i, from - base, to - from));
        }
        base += size;
    }
    spans
}

#[cfg(test)]
mod tests {
    use super::clear_spans;

    /// Clears of any size, taken one after another, cover every byte of every table once.
    #[test]
    fn clear_spans_cover_every_byte_once() {
        let sizes = [48, 16, 0, 160, 32];
        let total: u64 = sizes.iter().sum();
        for step in [4, 16, 20, 64, 1000] {
            let mut hits = vec![0u32; total as usize];
            let mut start = 0;
            while start < total {
                let spans = clear_spans(&sizes, start, step);
                let n: u64 = spans.iter().map(|s| s.2).sum();
                assert!(n > 0 && n <= step, "{step}: {spans:?}");
                for (i, offset, size) in spans {
                    assert!(offset + size <= sizes[i], "{step}: past buffer {i}");
                    let base: u64 = sizes[..i].iter().sum();
                    for b in base + offset..base + offset + size {
                        hits[b as usize] += 1;
                    }
                }
                start += n;
            }
            assert!(hits.iter().all(|&h| h == 1), "in pieces of {step}");
        }
    }
}
