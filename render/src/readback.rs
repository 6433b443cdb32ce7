//! Reading textures back to the CPU (for files, tests and the twins' comparisons).

/// Why a read-back failed.
#[derive(Debug, thiserror::Error)]
pub enum ReadbackError {
    #[error("mapping the read-back buffer failed: {0}")]
    Map(#[from] wgpu::BufferAsyncError),
    #[error("waiting for the GPU failed: {0}")]
    Poll(#[from] wgpu::PollError),
    #[error("the read-back buffer could not be read: {0}")]
    Range(String),
}

/// Every texel of every layer/slice of `texture` (mip 0), tightly packed, in the order
/// layer/slice, row, column.
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<u8>, ReadbackError> {
    let size = texture.size();
    let texel = texture
        .format()
        .block_copy_size(None)
        .expect("colour formats have a copy size");
    let row = size.width * texel;
    let padded =
        row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let images = size.depth_or_array_layers;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read-back"),
        size: u64::from(padded) * u64::from(size.height) * u64::from(images),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(size.height),
            },
        },
        size,
    );
    queue.submit([encoder.finish()]);
    let data = map(device, &buffer)?;
    let mut out = Vec::with_capacity((row * size.height * images) as usize);
    for chunk in data.chunks_exact(padded as usize) {
        out.extend_from_slice(&chunk[..row as usize]);
    }
    Ok(out)
}

/// `read_texture` for four-channel f32 textures.
pub fn read_texture_f32x4(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<[f32; 4]>, ReadbackError> {
    let bytes = read_texture(device, queue, texture)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}

/// Every f32×4 element of a storage buffer (which needs `COPY_SRC` usage).
pub fn read_buffer_f32x4(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    source: &wgpu::Buffer,
) -> Result<Vec<[f32; 4]>, ReadbackError> {
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read-back"),
        size: source.size(),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(source, 0, &buffer, 0, source.size());
    queue.submit([encoder.finish()]);
    let bytes = map(device, &buffer)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}

fn map(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Result<Vec<u8>, ReadbackError> {
    let (tx, rx) = std::sync::mpsc::channel();
    buffer.slice(..).map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely())?;
    rx.recv()
        .map_err(|e| ReadbackError::Range(e.to_string()))??;
    let data = buffer
        .slice(..)
        .get_mapped_range()
        .map_err(|e| ReadbackError::Range(e.to_string()))?;
    Ok(data.to_vec())
}
