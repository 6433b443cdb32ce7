//! The GPU test harness itself: a headless device exists, is the backend CI asked for, and
//! computes. With `CI=true` (or `ATMOSCOPE_REQUIRE_GPU=1`) a missing adapter fails the run;
//! elsewhere the test says loudly that it skipped.

mod common;

use atmoscope_render::wgpu;
use common::context;

#[test]
fn headless_device_is_the_requested_backend_and_computes() {
    let Some(gpu) = context() else { return };
    eprintln!("adapter: {}", gpu.describe());
    if std::env::var("WGPU_BACKEND").is_ok_and(|b| b.eq_ignore_ascii_case("vulkan")) {
        assert_eq!(
            gpu.adapter.get_info().backend,
            wgpu::Backend::Vulkan,
            "WGPU_BACKEND=vulkan was not honoured"
        );
    }
    let shader = gpu
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("square"),
            source: wgpu::ShaderSource::Wgsl(
                "@group(0) @binding(0) var<storage, read_write> data: array<f32>;
             @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) id: vec3<u32>) {
                 if id.x < arrayLength(&data) { data[id.x] = data[id.x] * data[id.x] + 0.5; }
             }"
                .into(),
            ),
        });
    let input: Vec<f32> = (0..256).map(|i| i as f32 * 0.25).collect();
    let bytes: Vec<u8> = input.iter().flat_map(|v| v.to_le_bytes()).collect();
    let size = bytes.len() as u64;
    let storage = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size,
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    gpu.queue.write_buffer(&storage, 0, &bytes);
    let readback = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let pipeline = gpu
        .device
        .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: None,
            layout: None,
            module: &shader,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
    let bind = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: storage.as_entire_binding(),
        }],
    });
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.dispatch_workgroups(4, 1, 1);
    }
    encoder.copy_buffer_to_buffer(&storage, 0, &readback, 0, size);
    gpu.queue.submit([encoder.finish()]);
    readback
        .slice(..)
        .map_async(wgpu::MapMode::Read, |r| r.expect("map readback"));
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .expect("poll");
    let data = readback
        .slice(..)
        .get_mapped_range()
        .expect("mapped readback");
    for (i, chunk) in data.chunks_exact(4).enumerate() {
        let got = f32::from_le_bytes([chunk[0], chunk[1], chunk[2], chunk[3]]);
        let want = input[i] * input[i] + 0.5;
        assert_eq!(got, want, "element {i}");
    }
}
