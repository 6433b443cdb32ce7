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
    /// In the browser only: the bytes are on their way; ask again next frame (module `browser`).
    #[error("the read-back is on its way: the next frame has it")]
    Pending,
}

#[cfg(target_arch = "wasm32")]
pub use browser::{set_waker, written};

/// What a read-back reads: a texture or a buffer (in a browser, the key of its request).
#[derive(Clone, Copy)]
pub enum Source<'a> {
    Texture(&'a wgpu::Texture),
    Buffer(&'a wgpu::Buffer),
}

/// Bytes of a row of `texture`'s texels, and of that row padded as a copy into a buffer
/// needs it.
fn row_bytes(texture: &wgpu::Texture) -> (u32, u32) {
    let texel = texture
        .format()
        .block_copy_size(None)
        .expect("colour formats have a copy size");
    let row = texture.size().width * texel;
    let padded =
        row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    (row, padded)
}

/// Every texel of every layer/slice of `texture` (mip 0), tightly packed, in the order
/// layer/slice, row, column.
#[cfg(not(target_arch = "wasm32"))]
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<u8>, ReadbackError> {
    let size = texture.size();
    let (row, padded) = row_bytes(texture);
    let images = size.depth_or_array_layers;
    let mut out = Vec::with_capacity(row as usize * size.height as usize * images as usize);
    for layer in 0..images {
        for (y, rows) in bands(size.height, padded, device.limits().max_buffer_size) {
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("read-back"),
                size: u64::from(padded) * u64::from(rows),
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let mut encoder = device.create_command_encoder(&Default::default());
            encoder.copy_texture_to_buffer(
                wgpu::TexelCopyTextureInfo {
                    texture,
                    mip_level: 0,
                    origin: wgpu::Origin3d { x: 0, y, z: layer },
                    aspect: wgpu::TextureAspect::All,
                },
                wgpu::TexelCopyBufferInfo {
                    buffer: &buffer,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(padded),
                        rows_per_image: Some(rows),
                    },
                },
                wgpu::Extent3d {
                    width: size.width,
                    height: rows,
                    depth_or_array_layers: 1,
                },
            );
            queue.submit([encoder.finish()]);
            let data = map(device, &buffer)?;
            for chunk in data.chunks_exact(padded as usize) {
                out.extend_from_slice(&chunk[..row as usize]);
            }
        }
    }
    Ok(out)
}

/// The bands of rows (first row, row count) of an image `height` rows high, `padded` bytes a
/// row, each small enough for one buffer of at most `max_buffer` bytes: a large view exceeds
/// the device's largest buffer (256 MiB by default) long before its largest texture.
#[cfg_attr(target_arch = "wasm32", allow(dead_code))]
fn bands(height: u32, padded: u32, max_buffer: u64) -> Vec<(u32, u32)> {
    let band = (max_buffer / u64::from(padded)).clamp(1, u64::from(height.max(1))) as u32;
    (0..height)
        .step_by(band as usize)
        .map(|y| (y, band.min(height - y)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::bands;

    #[test]
    fn bands_cover_every_row_once_within_the_buffer_limit() {
        // 5000×5000 RGBA32F: 80 000 bytes a row, 400 MB in all, over a 256 MiB limit.
        let b = bands(5000, 80_128, 256 << 20);
        assert_eq!(b.len(), 2);
        assert!(b.iter().all(|&(_, n)| u64::from(n) * 80_128 <= 256 << 20));
        assert_eq!(b.iter().map(|&(_, n)| n).sum::<u32>(), 5000);
        assert!(b.windows(2).all(|w| w[0].0 + w[0].1 == w[1].0));
        assert_eq!(bands(720, 20_480, 256 << 20), vec![(0, 720)]);
        assert_eq!(bands(3, 100, 10), vec![(0, 1), (1, 1), (2, 1)]);
    }
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
    Ok(bytemuck::pod_collect_to_vec(&read_buffer(
        device, queue, source,
    )?))
}

/// Reads a buffer of u32 back.
pub fn read_buffer_u32(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    source: &wgpu::Buffer,
) -> Result<Vec<u32>, ReadbackError> {
    Ok(bytemuck::pod_collect_to_vec(&read_buffer(
        device, queue, source,
    )?))
}

#[cfg(not(target_arch = "wasm32"))]
fn read_buffer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    source: &wgpu::Buffer,
) -> Result<Vec<u8>, ReadbackError> {
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read-back"),
        size: source.size(),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(source, 0, &buffer, 0, source.size());
    queue.submit([encoder.finish()]);
    map(device, &buffer)
}

#[cfg(not(target_arch = "wasm32"))]
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

/// `read_texture` in the browser: the whole texture in one copy (a browser's largest buffer,
/// 256 MiB at least, holds any view it can show), as a request (module `browser`).
#[cfg(target_arch = "wasm32")]
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<u8>, ReadbackError> {
    let size = texture.size();
    let (row, padded) = row_bytes(texture);
    let bytes = u64::from(padded) * u64::from(size.height) * u64::from(size.depth_or_array_layers);
    let data = browser::read(
        browser::Source::Texture(texture.clone()),
        device,
        queue,
        bytes,
        |encoder, buffer| {
            encoder.copy_texture_to_buffer(
                texture.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(padded),
                        rows_per_image: Some(size.height),
                    },
                },
                size,
            );
        },
    )?;
    Ok(data
        .chunks_exact(padded as usize)
        .flat_map(|chunk| &chunk[..row as usize])
        .copied()
        .collect())
}

#[cfg(target_arch = "wasm32")]
fn read_buffer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    source: &wgpu::Buffer,
) -> Result<Vec<u8>, ReadbackError> {
    browser::read(
        browser::Source::Buffer(source.clone()),
        device,
        queue,
        source.size(),
        |encoder, buffer| encoder.copy_buffer_to_buffer(source, 0, buffer, 0, source.size()),
    )
}

/// Read-backs in a web page, which cannot block until the GPU is done: the browser maps a
/// buffer only once the page has gone back to its event loop. A read is therefore a request.
/// The first call copies the source and starts mapping, and answers [`ReadbackError::Pending`];
/// when the mapping is done the waker ([`set_waker`]: the window asks for a frame) runs, and
/// the next call answers the bytes. [`written`] forgets the reads of the sources the GPU wrote,
/// done or on their way, so the bytes answered always show what a source holds now.
#[cfg(target_arch = "wasm32")]
mod browser {
    use super::ReadbackError;
    use std::cell::RefCell;
    use std::collections::HashMap;
    use std::sync::{Arc, Mutex};

    /// What is read back, owned: the key of its read.
    #[derive(Clone, PartialEq, Eq, Hash)]
    pub(super) enum Source {
        Texture(wgpu::Texture),
        Buffer(wgpu::Buffer),
    }

    /// Reads kept at most: past that, all are dropped (those of sources no engine holds any
    /// more, a rebuild's old tables say, would otherwise keep their buffers alive).
    const MAX_READS: usize = 64;

    /// Set by the mapping's callback (which wgpu wants `Send`, hence not an `Rc`).
    type Mapped = Arc<Mutex<Option<Result<(), wgpu::BufferAsyncError>>>>;

    enum Read {
        OnItsWay(wgpu::Buffer, Mapped),
        Done(Vec<u8>),
    }

    thread_local! {
        static READS: RefCell<HashMap<Source, Read>> = RefCell::new(HashMap::new());
        static WAKER: RefCell<Option<Box<dyn Fn()>>> = const { RefCell::new(None) };
    }

    /// Notes that the GPU may have changed what `sources` hold (an engine calls it with its
    /// own after each frame that ran passes): their reads so far are stale.
    pub fn written(sources: &[super::Source]) {
        READS.with_borrow_mut(|reads| {
            for source in sources {
                reads.remove(&match *source {
                    super::Source::Texture(t) => Source::Texture(t.clone()),
                    super::Source::Buffer(b) => Source::Buffer(b.clone()),
                });
            }
        });
    }

    /// What runs when a mapping is done: the window asks itself for a frame.
    pub fn set_waker(wake: impl Fn() + 'static) {
        WAKER.with_borrow_mut(|w| *w = Some(Box::new(wake)));
    }

    pub(super) fn read(
        source: Source,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        bytes: u64,
        copy: impl FnOnce(&mut wgpu::CommandEncoder, &wgpu::Buffer),
    ) -> Result<Vec<u8>, ReadbackError> {
        READS.with_borrow_mut(|reads| {
            let finished = match reads.get(&source) {
                Some(Read::Done(data)) => return Ok(data.clone()),
                Some(Read::OnItsWay(buffer, mapped)) => {
                    match mapped.lock().ok().and_then(|mut m| m.take()) {
                        None => return Err(ReadbackError::Pending),
                        Some(result) => result.map(|()| buffer.clone()),
                    }
                }
                None => {
                    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some("read-back"),
                        size: bytes,
                        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                        mapped_at_creation: false,
                    });
                    let mut encoder = device.create_command_encoder(&Default::default());
                    copy(&mut encoder, &buffer);
                    queue.submit([encoder.finish()]);
                    let mapped: Mapped = Arc::new(Mutex::new(None));
                    let done = mapped.clone();
                    buffer.slice(..).map_async(wgpu::MapMode::Read, move |r| {
                        if let Ok(mut d) = done.lock() {
                            *d = Some(r);
                        }
                        WAKER.with_borrow(|w| w.as_ref().map(|wake| wake()));
                    });
                    if reads.len() >= MAX_READS {
                        reads.clear();
                    }
                    reads.insert(source, Read::OnItsWay(buffer, mapped));
                    return Err(ReadbackError::Pending);
                }
            };
            let buffer = match finished {
                Ok(buffer) => buffer,
                Err(e) => {
                    reads.remove(&source);
                    return Err(ReadbackError::Map(e));
                }
            };
            let data = buffer
                .slice(..)
                .get_mapped_range()
                .map(|range| range.to_vec())
                .map_err(|e| ReadbackError::Range(e.to_string()));
            buffer.unmap();
            match &data {
                Ok(bytes) => reads.insert(source, Read::Done(bytes.clone())),
                Err(_) => reads.remove(&source),
            };
            data
        })
    }
}
