//! Encoding and submitting a frame's dispatches over one atmosphere's tables and one view's
//! images, timed per pass, as spans, or not at all.

use super::*;

/// A flag set once the GPU has finished the work submitted to `queue` so far.
pub(super) fn when_done(queue: &wgpu::Queue) -> Arc<AtomicBool> {
    let done = Arc::new(AtomicBool::new(false));
    let flag = done.clone();
    queue.on_submitted_work_done(move || flag.store(true, Ordering::Release));
    done
}

/// Encodes dispatches of one model over one atmosphere's tables and one view's images.
pub(super) struct Encoder<'a> {
    pub(super) device: &'a wgpu::Device,
    pub(super) queue: &'a wgpu::Queue,
    pub(super) pipelines: &'a Pipelines,
    pub(super) tables: &'a TableBuffers,
    pub(super) target: &'a Target,
    /// Where the work is a slice of the next moving sky, what it binds instead of the
    /// frame's globals and the table the sky pass reads.
    pub(super) next_moving_sky: Option<&'a NextMovingSky>,
}

impl Encoder<'_> {
    /// Encodes and submits `work` (each at its origin) and returns per-pass times when
    /// `timer` is given: GPU timestamps, or fenced CPU time (one submission per pass). With
    /// `spans`, GPU timestamps are written only where the tables begin and end and where the
    /// last dispatch ends; fenced CPU time sums the passes. Untimed or in spans, consecutive
    /// dispatches share a compute pass: on an H100 dispatches in separate compute passes ran
    /// one after another even with no barrier between them, in one they overlap.
    pub(super) fn submit(&self, work: &[Work], timer: Option<&Timer>, spans: bool) -> Timings {
        let gpu_timer = match timer {
            Some(Timer::Gpu(t)) => Some(t),
            _ => None,
        };
        let fenced = matches!(timer, Some(Timer::Cpu));
        let work = &work[..work.len().min(MAX_PASSES).min(ORIGIN_SLOTS)];
        let next = self.next_moving_sky;
        let group0 = next.map_or(&self.tables.group0, |n| &n.group0);
        let mut origins = vec![0u8; self.tables.origin_stride as usize * work.len()];
        for (slot, w) in work.iter().enumerate() {
            let origin = [w.origin[0], w.origin[1], w.origin[2], 0];
            let at = slot * self.tables.origin_stride as usize;
            origins[at..at + 16].copy_from_slice(bytemuck::cast_slice(&origin));
        }
        self.queue.write_buffer(&self.tables.origins, 0, &origins);
        let specs: Vec<_> = self.pipelines.specs().copied().collect();
        let last_table = work.iter().rposition(|w| specs[w.pass].is_table());
        let last = work.len().saturating_sub(1);
        // Span queries: 0 the first pass's start, 1 the end of the tables (or of the frame
        // when no table runs), 2 the frame's end when view passes follow the tables.
        let frame_end: u32 = match last_table {
            Some(t) if t != last => 2,
            _ => 1,
        };
        let mut timings = Vec::new();
        // Whether work needs the encoder itself before its dispatch (clears and copies,
        // which no compute pass may hold).
        // Histogram counts start from zero with the dispatch (or the first slice) that covers
        // the view's first pixel.
        let clears_histogram =
            |w: &Work| specs[w.pass].writes.contains(&HISTOGRAM) && w.origin == [0; 3];
        let needs_encoder = |w: &Work| clears_histogram(w) || w.tiles != TilePhase::None;
        // Untimed, or timed in spans, consecutive dispatches share one compute pass (wgpu
        // still puts a barrier wherever one reads what another wrote); the tables end theirs.
        let merge = !fenced && (spans || gpu_timer.is_none());
        let starts_pass =
            |s: usize| !merge || s == 0 || needs_encoder(&work[s]) || Some(s - 1) == last_table;
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let mut pass: Option<wgpu::ComputePass<'static>> = None;
        for (slot, w) in work.iter().enumerate() {
            let i = w.pass;
            let spec = &specs[i];
            let start = Instant::now();
            if starts_pass(slot) {
                drop(pass.take());
                if clears_histogram(w) {
                    encoder.clear_buffer(&self.target.histogram, 0, None);
                }
                match w.tiles {
                    TilePhase::Fill => encoder.clear_buffer(
                        &self.target.exact_tiles,
                        0,
                        Some(EXACT_TILES_HEADER_BYTES),
                    ),
                    // A dispatch may not bind the buffer that holds its own workgroup counts.
                    TilePhase::Compute => encoder.copy_buffer_to_buffer(
                        &self.target.exact_tiles,
                        0,
                        &self.target.exact_groups,
                        0,
                        Some(12),
                    ),
                    TilePhase::None => {}
                }
                // The last slot of this compute pass.
                let ends = (slot + 1..work.len())
                    .find(|&s| starts_pass(s))
                    .map_or(last, |s| s - 1);
                let timestamp_writes = gpu_timer.and_then(|t| {
                    if spans {
                        let end = if Some(ends) == last_table {
                            Some(1)
                        } else {
                            (ends == last).then_some(frame_end)
                        };
                        t.span_writes(slot == 0, end)
                    } else {
                        Some(t.writes(slot as u32))
                    }
                });
                pass = Some(
                    encoder
                        .begin_compute_pass(&wgpu::ComputePassDescriptor {
                            label: Some(spec.name),
                            timestamp_writes,
                        })
                        .forget_lifetime(),
                );
            }
            if let Some(cpass) = pass.as_mut() {
                let group = match (spec.dispatch, next) {
                    (Dispatch::View, _) => self.target.groups[i].as_ref(),
                    (_, Some(n)) => Some(&n.group1),
                    (_, None) => self.tables.group(i),
                };
                let dispatch = w.groups;
                if let (Some(group), Some(pipeline)) =
                    (group, self.pipelines.pipeline(i, w.variant))
                {
                    let offset = (slot as u64 * self.tables.origin_stride) as u32;
                    cpass.set_pipeline(pipeline);
                    cpass.set_bind_group(0, group0, &[offset]);
                    cpass.set_bind_group(1, group, &[]);
                    if w.tiles == TilePhase::Compute {
                        cpass.dispatch_workgroups_indirect(&self.target.exact_groups, 0);
                    } else {
                        cpass.dispatch_workgroups(dispatch[0], dispatch[1], dispatch[2]);
                    }
                }
            }
            if fenced {
                drop(pass.take());
                self.queue.submit([encoder.finish()]);
                let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
                timings.push((i, start.elapsed().as_secs_f64() * 1e3));
                encoder = self.device.create_command_encoder(&Default::default());
            }
        }
        drop(pass.take());
        match gpu_timer {
            Some(t) if spans => {
                // Only queries written this frame: resolving one never written waits forever.
                t.resolve(&mut encoder, frame_end + 1);
                self.queue.submit([encoder.finish()]);
                let ticks = t.read_ticks(self.device, frame_end + 1);
                let ms = |from: usize, to: u32| match (ticks.get(from), ticks.get(to as usize)) {
                    (Some(&a), Some(&b)) => b.saturating_sub(a) as f64 * t.period_ns * 1e-6,
                    _ => f64::NAN,
                };
                return Timings {
                    passes: Vec::new(),
                    spans: Some(Spans {
                        tables_ms: last_table.map(|_| ms(0, 1)),
                        frame_ms: ms(0, frame_end),
                    }),
                };
            }
            Some(t) => {
                t.resolve(&mut encoder, 2 * work.len() as u32);
                self.queue.submit([encoder.finish()]);
                timings.extend(
                    work.iter()
                        .map(|w| w.pass)
                        .zip(t.read_ms(self.device, work.len())),
                );
            }
            None => {
                self.queue.submit([encoder.finish()]);
            }
        }
        let spans = (spans && fenced).then(|| {
            let sum = |tables_only: bool| -> f64 {
                timings
                    .iter()
                    .filter(|(i, _)| !tables_only || specs[*i].is_table())
                    .map(|(_, ms)| ms)
                    .sum()
            };
            Spans {
                tables_ms: last_table.map(|_| sum(true)),
                frame_ms: sum(false),
            }
        });
        Timings {
            passes: if spans.is_some() { Vec::new() } else { timings },
            spans,
        }
    }
}
