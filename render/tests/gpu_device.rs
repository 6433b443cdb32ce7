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

/// wgpu's default handler panics on a validation error; the engine turns faults into errors.
#[test]
fn gpu_faults_are_errors_not_panics() {
    use atmoscope_model::camera::Projection;
    use atmoscope_model::scene::Scene;
    use atmoscope_render::engine::capture;
    use atmoscope_render::{Engine, EngineError, View};
    let Some(gpu) = context() else { return };
    let too_big = gpu.device.limits().max_buffer_size.saturating_add(1);
    let fault = capture(&gpu.device, || {
        gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("larger than the device allows"),
            size: too_big,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        })
    });
    assert!(matches!(fault, Err(EngineError::Gpu(_))), "{fault:?}");

    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    let view = View::new(Projection::Perspective, 8, 8);
    engine
        .try_render(&Scene::default(), &view)
        .expect("a first frame");
    gpu.device.destroy();
    let mut scene = Scene::default();
    scene.atmosphere.aerosol.aod550 = 0.3;
    let lost = engine.try_render(&scene, &view).map(|_| ());
    assert!(matches!(lost, Err(EngineError::Gpu(_))), "{lost:?}");
}
