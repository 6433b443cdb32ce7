//! A view's render targets: its radiance and display textures, histogram, tile lists and
//! the bind groups of the view passes.

use super::*;

pub(super) struct Target {
    pub(super) size: [u32; 2],
    pub(super) radiance: wgpu::Texture,
    pub(super) display: wgpu::Texture,
    /// The view's luminance histogram (`METER_PASS`).
    pub(super) histogram: wgpu::Buffer,
    /// The tiles a sky drawn in tiles computes pixel by pixel (`methods::EXACT_TILES`).
    pub(super) exact_tiles: wgpu::Buffer,
    /// The workgroups of the dispatch that computes them, copied from `exact_tiles`.
    pub(super) exact_groups: wgpu::Buffer,
    /// Group 1 of each view pass, by pass index (None for table passes).
    pub(super) groups: Vec<Option<wgpu::BindGroup>>,
}

impl Target {
    pub(super) fn new(
        device: &wgpu::Device,
        pipelines: &Pipelines,
        tables: &TableBuffers,
        size: [u32; 2],
        sky_tile: u32,
    ) -> Target {
        let texture = |label, format| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: size[0],
                    height: size[1],
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        };
        let radiance = texture("radiance", wgpu::TextureFormat::Rgba32Float);
        let display = texture("display", wgpu::TextureFormat::Rgba8Unorm);
        let radiance_view = radiance.create_view(&Default::default());
        let display_view = display.create_view(&Default::default());
        let histogram = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("histogram"),
            size: 4 * HISTOGRAM_BINS as u64,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        // Room for every tile of the view; one word when frames are not drawn in tiles.
        let tiles = if sky_tile > 1 {
            u64::from(size[0].div_ceil(sky_tile)) * u64::from(size[1].div_ceil(sky_tile))
        } else {
            1
        };
        let exact_tiles = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("exact tiles"),
            size: EXACT_TILES_HEADER_BYTES + 4 * tiles,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let exact_groups = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("exact tiles' workgroups"),
            size: 12,
            usage: wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let groups = pipelines
            .specs()
            .enumerate()
            .map(|(i, spec)| {
                if spec.is_table() {
                    return None;
                }
                pipelines.bind(device, i, |r| match r {
                    Resource::Radiance => Some(wgpu::BindingResource::TextureView(&radiance_view)),
                    Resource::Display => Some(wgpu::BindingResource::TextureView(&display_view)),
                    Resource::Histogram => Some(histogram.as_entire_binding()),
                    Resource::ExactTiles => Some(exact_tiles.as_entire_binding()),
                    Resource::Table(t) => tables.buffer(t.id).map(|b| b.as_entire_binding()),
                })
            })
            .collect();
        Target {
            size,
            radiance,
            display,
            histogram,
            exact_tiles,
            exact_groups,
            groups,
        }
    }
}
