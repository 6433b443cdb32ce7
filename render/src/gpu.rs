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
}

/// A device and queue with the adapter they came from.
pub struct GpuContext {
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
}

/// Features the engine uses when present.
pub fn optional_features() -> wgpu::Features {
    wgpu::Features::TIMESTAMP_QUERY
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
        let features = adapter.features() & optional_features();
        let (device, queue) =
            pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
                label: Some("atmoscope headless"),
                required_features: features,
                required_limits: wgpu::Limits::default().using_resolution(adapter.limits()),
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
