//! GPU timestamp queries around passes, and their read-back.

use super::*;

/// GPU timestamp queries around up to `passes` compute passes, and their read-back.
pub struct Timestamps {
    pub(super) queries: wgpu::QuerySet,
    pub(super) resolve: wgpu::Buffer,
    pub(super) readback: wgpu::Buffer,
    pub(super) period_ns: f64,
}

impl Timestamps {
    /// Queries for `passes` passes (the device must have `TIMESTAMP_QUERY`).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, passes: u32) -> Timestamps {
        let count = 2 * passes;
        let bytes = u64::from(count) * 8;
        let buffer = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        Timestamps {
            queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: buffer(
                "timestamp resolve",
                wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            ),
            readback: buffer(
                "timestamp read-back",
                wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            ),
            period_ns: f64::from(queue.get_timestamp_period()),
        }
    }

    /// The timestamp writes of the pass in `slot`.
    pub fn writes(&self, slot: u32) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(2 * slot),
            end_of_pass_write_index: Some(2 * slot + 1),
        }
    }

    /// The stamps of a pass in a frame timed in spans, if any: query 0 at its start where it
    /// is the frame's first pass, query `end` at its end.
    pub(super) fn span_writes(
        &self,
        first: bool,
        end: Option<u32>,
    ) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        (first || end.is_some()).then(|| wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: first.then_some(0),
            end_of_pass_write_index: end,
        })
    }

    /// Encodes the copy of the first `count` queries for [`Timestamps::read_ticks`].
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder, count: u32) {
        encoder.resolve_query_set(&self.queries, 0..count, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, 8 * u64::from(count));
    }

    /// The first `count` queries in ticks, once the resolving submission has run (waits for
    /// it); empty if the read-back failed.
    pub fn read_ticks(&self, device: &wgpu::Device, count: u32) -> Vec<u64> {
        map_u64(device, &self.readback).map_or_else(Vec::new, |mut ticks| {
            ticks.truncate(count as usize);
            ticks
        })
    }

    /// Milliseconds of the first `passes` slots (each a pass's start and end), once the
    /// resolving submission has run; empty if the read-back failed.
    pub fn read_ms(&self, device: &wgpu::Device, passes: usize) -> Vec<f64> {
        let ticks = self.read_ticks(device, 2 * passes as u32);
        ticks
            .chunks_exact(2)
            .map(|t| t[1].saturating_sub(t[0]) as f64 * self.period_ns * 1e-6)
            .collect()
    }
}

pub(super) enum Timer {
    Gpu(Timestamps),
    Cpu,
}

/// What `Encoder::submit` measured: per-pass times (pass index, ms), or the frame's spans.
#[derive(Default)]
pub(super) struct Timings {
    pub(super) passes: Vec<(usize, f64)>,
    pub(super) spans: Option<Spans>,
}

pub(super) fn map_u64(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Option<Vec<u64>> {
    let (tx, rx) = std::sync::mpsc::channel();
    buffer.slice(..).map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).ok()?;
    rx.recv().ok()?.ok()?;
    let ticks = {
        let data = buffer.slice(..).get_mapped_range().ok()?;
        bytemuck::pod_collect_to_vec(&data)
    };
    buffer.unmap();
    Some(ticks)
}
