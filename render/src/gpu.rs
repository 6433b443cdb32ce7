//! Headless device acquisition for the command line and the tests.
//!
//! Backends come from `WGPU_BACKEND` when set (CI sets `vulkan`, so Mesa's lavapipe is used and
//! the silent GL fallback, which reads 3D storage textures back as zeros, cannot happen).
//! The optional feature the engine uses (timestamp queries) is requested only when the adapter
//! offers it.

/// Why no GPU device could be had.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error(
        "no GPU adapter found ({0}); on a machine without a GPU install Mesa's software Vulkan \
         driver (Debian: mesa-vulkan-drivers) and set WGPU_BACKEND=vulkan"
    )]
    NoAdapter(String),
    #[error("the GPU adapter refused a device: {0}")]
    Device(#[from] wgpu::RequestDeviceError),
    #[error(
        "the GPU adapter binds {0} storage buffers per shader stage; the engine needs {STORAGE_BUFFERS_PER_STAGE}"
    )]
    TooFewStorageBuffers(u32),
}

/// Storage buffers one shader stage of the engine binds at most: group 0's batches and
/// profile, up to six tables, and a sky pass's list of tiles to compute exactly. One more
/// than WebGPU's default limit; native adapters offer more (lavapipe, desktop Vulkan, Metal
/// and D3D12 at least 16 in practice).
pub const STORAGE_BUFFERS_PER_STAGE: u32 = 9;

/// The limits the engine asks a device for: `base` (wgpu's defaults, or a window's choice)
/// with at least [`STORAGE_BUFFERS_PER_STAGE`] storage buffers per shader stage.
pub fn required_limits(base: wgpu::Limits) -> wgpu::Limits {
    wgpu::Limits {
        max_storage_buffers_per_shader_stage: base
            .max_storage_buffers_per_shader_stage
            .max(STORAGE_BUFFERS_PER_STAGE),
        ..base
    }
}

/// Whether `adapter` can give the engine what it asks for ([`required_limits`]); the web
/// explorer asks before it opens, to explain a refusal instead of failing later.
pub fn check_adapter(adapter: &wgpu::Adapter) -> Result<(), GpuError> {
    let offered = adapter.limits().max_storage_buffers_per_shader_stage;
    if offered < STORAGE_BUFFERS_PER_STAGE {
        return Err(GpuError::TooFewStorageBuffers(offered));
    }
    Ok(())
}

/// A device and queue with the adapter they came from.
pub struct GpuContext {
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
}

/// Features the engine uses when present. In the browser none: reading timestamps back would
/// wait for the GPU, which a web page cannot do, so timing falls back to wall time there.
pub fn optional_features() -> wgpu::Features {
    if cfg!(target_arch = "wasm32") {
        wgpu::Features::empty()
    } else {
        wgpu::Features::TIMESTAMP_QUERY
    }
}

impl GpuContext {
    /// Opens the best adapter the environment allows, without a window.
    pub fn headless() -> Result<GpuContext, GpuError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            compatible_surface: None,
            ..Default::default()
        }))
        .map_err(|e| GpuError::NoAdapter(e.to_string()))?;
        check_adapter(&adapter)?;
        let features = adapter.features() & optional_features();
        let (device, queue) =
            pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
                label: Some("atmoscope headless"),
                required_features: features,
                required_limits: required_limits(
                    wgpu::Limits::default().using_resolution(adapter.limits()),
                ),
                ..Default::default()
            }))?;
        Ok(GpuContext {
            adapter,
            device,
            queue,
        })
    }

    /// Whether the adapter rasterises on the CPU (lavapipe, llvmpipe, WARP), whose timestamp
    /// queries do not time passes reliably.
    pub fn is_software(&self) -> bool {
        self.adapter.get_info().device_type == wgpu::DeviceType::Cpu
    }

    /// One line naming the adapter, its backend and device type.
    pub fn describe(&self) -> String {
        let i = self.adapter.get_info();
        format!(
            "{} ({:?}, {:?}, driver {} {})",
            i.name, i.backend, i.device_type, i.driver, i.driver_info
        )
    }
}
