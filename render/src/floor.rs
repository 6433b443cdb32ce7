//! The floor pass: a trivial full-screen compute pass of the view's size and output format
//! (one `rgba32float` write per pixel). `atmoscope bench gpu` times it in the same run as the
//! model's passes and reports them as multiples of it, since absolute times move from run to
//! run on a shared or software GPU while ratios measured together do not.

use crate::engine::TimingSource;
use crate::prelude::{WORKGROUP_SIZE, wgsl_prelude};
use web_time::Instant;

/// The compiled floor pass.
pub struct FloorPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl FloorPass {
    pub fn new(device: &wgpu::Device) -> FloorPass {
        let source = wgsl_prelude() + include_str!("../../shaders/views/floor.wgsl");
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("floor"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("floor"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::StorageTexture {
                    access: wgpu::StorageTextureAccess::WriteOnly,
                    format: wgpu::TextureFormat::Rgba32Float,
                    view_dimension: wgpu::TextureViewDimension::D2,
                },
                count: None,
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("floor"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("floor"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        FloorPass { pipeline, layout }
    }

    /// Milliseconds of each of `repeats` runs over a `width` × `height` image, timed like the
    /// engine's passes: GPU timestamps, or fenced wall time (`TimingSource::CpuFenced`).
    pub fn time_ms(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        [width, height]: [u32; 2],
        timing: TimingSource,
        repeats: usize,
    ) -> Vec<f64> {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("floor"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Float,
            usage: wgpu::TextureUsages::STORAGE_BINDING,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("floor"),
            layout: &self.layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&view),
            }],
        });
        let gpu = matches!(timing, TimingSource::GpuTimestamps)
            .then(|| crate::engine::Timestamps::new(device, queue, 1));
        (0..repeats)
            .map(|_| {
                let start = Instant::now();
                let mut encoder = device.create_command_encoder(&Default::default());
                {
                    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                        label: Some("floor"),
                        timestamp_writes: gpu.as_ref().map(|t| t.writes(0)),
                    });
                    pass.set_pipeline(&self.pipeline);
                    pass.set_bind_group(0, &group, &[]);
                    pass.dispatch_workgroups(
                        width.div_ceil(WORKGROUP_SIZE),
                        height.div_ceil(WORKGROUP_SIZE),
                        1,
                    );
                }
                match &gpu {
                    Some(t) => {
                        t.resolve(&mut encoder, 2);
                        queue.submit([encoder.finish()]);
                        t.read_ms(device, 1).first().copied().unwrap_or(f64::NAN)
                    }
                    None => {
                        queue.submit([encoder.finish()]);
                        let _ = device.poll(wgpu::PollType::wait_indefinitely());
                        start.elapsed().as_secs_f64() * 1e3
                    }
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_floor_shader_parses_and_validates() {
        let src = super::wgsl_prelude() + include_str!("../../shaders/views/floor.wgsl");
        let module = naga::front::wgsl::parse_str(&src)
            .unwrap_or_else(|e| panic!("{}", e.emit_to_string(&src)));
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{}", e.emit_to_string(&src)));
    }
}
