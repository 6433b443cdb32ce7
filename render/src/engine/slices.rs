//! Work spread across frames under a time budget: the slices of a rebuild of the tables and of
//! the moving sky, each slice steered by how long the last took.

use super::*;

/// Bytes a unit of the clearing of a rebuild's tables covers.
pub(super) const CLEAR_UNIT_BYTES: u64 = 1 << 20;

/// How a rebuild runs in slices.
#[derive(Debug, Clone, Copy)]
pub(super) struct Slicing {
    /// GPU time each slice aims at (zero: half a row of workgroups each, so that slices also
    /// start inside rows, and 16 MiB of the tables' zeroing).
    pub(super) target: Duration,
    /// Whether each slice is timed alone, waited for with the GPU idle before it (a CPU
    /// adapter, `Engine::new`), rather than by the interval until a later frame sees it done.
    pub(super) alone: bool,
}

/// Share of the target a slice timed alone aims at. Its time is its own, where an interval
/// until a later frame saw it done also held a share of that frame's work, which had left
/// room for a slice costing more per workgroup than the last (rows of the sky with the sun or
/// the horizon in them, Bruneton's scattering density): aimed at the whole target, such a
/// slice overshoots the frame's budget several times over.
pub(super) const ALONE_AIM: f64 = 0.75;

/// How long a slice took: timed alone ([`Slicing::alone`]), or from its submission to the
/// frame that sees it finished (the flag set once the GPU has), that frame's own work included.
#[derive(Debug, Clone)]
pub(super) enum SliceClock {
    Alone(f64),
    Since(Instant, Arc<AtomicBool>),
}

impl SliceClock {
    /// Submits a slice through `submit` and starts its clock. Timed alone, it waits for the
    /// GPU to be idle, then for the slice: on a CPU adapter the GPU is the CPU's other threads,
    /// so waiting costs the frame nothing, and the interval until a later frame saw a slice
    /// done was mostly that frame's own work, whose spread from frame to frame (20–40 ms on
    /// lavapipe) the steering took for the slice's cost and held slices to a workgroup.
    pub(super) fn start(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        alone: bool,
        submit: impl FnOnce(),
    ) -> SliceClock {
        if !alone {
            submit();
            return SliceClock::Since(Instant::now(), when_done(queue));
        }
        let _ = device.poll(wgpu::PollType::wait_indefinitely());
        let start = Instant::now();
        submit();
        let _ = device.poll(wgpu::PollType::wait_indefinitely());
        SliceClock::Alone(start.elapsed().as_secs_f64())
    }

    /// Units for the next slice of the same work after this one of `count` units, aimed at
    /// `target_s`; `shortest_s` is the shortest interval the job has seen (`steered_units`),
    /// which a slice timed alone neither needs nor changes.
    pub(super) fn steer(&self, count: u32, shortest_s: &mut f64, target_s: f64) -> u32 {
        match *self {
            SliceClock::Alone(took) => steered_units(count, took, 0.0, ALONE_AIM * target_s),
            SliceClock::Since(started, _) => {
                let took = started.elapsed().as_secs_f64();
                *shortest_s = shortest_s.min(took);
                steered_units(count, took, *shortest_s, target_s)
            }
        }
    }

    /// Whether the slice has finished (one timed alone has).
    pub(super) fn finished(&self) -> bool {
        match self {
            SliceClock::Alone(_) => true,
            SliceClock::Since(_, done) => done.load(Ordering::Acquire),
        }
    }
}

/// A new atmosphere built a slice per frame while the previous one stays on screen.
pub(super) struct Rebuild {
    pub(super) state: AtmosphereState,
    pub(super) target: Target,
    /// The frame the rebuild draws, and the passes it left stale (as a frame's).
    pub(super) snapshot: Snapshot,
    pub(super) deferred: Vec<bool>,
    pub(super) variants: Vec<Variant>,
    /// The passes to run, in order, the order loop unrolled.
    pub(super) run: Vec<Step>,
    /// The next slice: index into `run`, and its first unit (workgroups counted along rows,
    /// then rows, then layers).
    pub(super) next: (usize, u32),
    /// Bytes of the new tables zeroed so far: the first slices clear them
    /// (`TableBuffers::clear`), `CLEAR_UNIT_BYTES` a unit.
    pub(super) cleared: u64,
    /// Units per slice of each pass, and last those of the clearing, steered towards the
    /// target time (passes differ in cost per unit by a thousandfold, so a pass not met
    /// before starts with one unit; the engine keeps what it learnt for the model's next
    /// rebuild).
    pub(super) units: Vec<u32>,
    /// The slice on the GPU: its clock, its pass (the
    /// last slot of `units` for the zeroing) and units, and the slice a zero target asks for
    /// (half a row of the pass's workgroups; 16 MiB of zeroing).
    pub(super) in_flight: Option<(SliceClock, usize, u32, u32)>,
    pub(super) done_units: u64,
    pub(super) total_units: u64,
    /// The shortest interval from a slice's submission to seeing it finished, s.
    pub(super) shortest_s: f64,
}

impl Rebuild {
    pub(super) fn progress(&self) -> RebuildProgress {
        RebuildProgress {
            done: self.done_units,
            total: self.total_units,
        }
    }
}

/// Units for a pass's next slice: `count` units took `took_s` from submission to being seen
/// finished. That end is seen a frame later, so `took_s` holds the frame's own work too: most
/// of `shortest_s`, the shortest such interval of the job, is taken for that and set aside,
/// or a cheap pass would grow its slices by little more than target / frame per frame.
pub(super) fn steered_units(count: u32, took_s: f64, shortest_s: f64, target_s: f64) -> u32 {
    let own = (took_s - 0.8 * shortest_s).max(0.1 * took_s).max(1e-4);
    let scaled = f64::from(count) * target_s / own;
    scaled.clamp(1.0, f64::from(count) * 16.0) as u32
}

/// Dispatches run a slice per frame where the engine slices its work
/// (`Engine::set_rebuild_slices`): the still frame after frames in tiles, drawn at full
/// resolution (a march per pixel takes seconds on a software adapter; the image in tiles stays
/// on screen and sharpens from the top down), and the next moving sky of a march per pixel
/// (`MovingSky`). Slices are counted in workgroups along rows, as a rebuild's ([`units`],
/// [`slice`]): on a CPU adapter one row of workgroups across a wide view takes longer than a
/// frame may for the nested marches.
pub(super) struct Slices {
    /// The frame's dispatches at full resolution, in order.
    pub(super) work: Vec<Work>,
    /// The next slice: index into `work`, and its first workgroup (counted along rows).
    pub(super) next: (usize, u32),
    /// Workgroups per slice, steered towards the target time.
    pub(super) units: u32,
    /// The slice on the GPU: its clock and workgroups.
    pub(super) in_flight: Option<(SliceClock, u32)>,
    /// The shortest interval from a slice's submission to seeing it finished, s.
    pub(super) shortest_s: f64,
}

impl Slices {
    /// Slices of `work`, the first of one workgroup.
    pub(super) fn new(work: Vec<Work>) -> Slices {
        Slices::steered(work, 1, f64::INFINITY)
    }

    /// Slices of `work` steered on from where earlier slices of the same dispatches left off:
    /// `units` workgroups first, `shortest_s` the shortest interval seen. Without the latter
    /// the first slice's whole interval, the frame's own work included, would be taken for
    /// the shortest, and the second slice sized five times too large.
    pub(super) fn steered(work: Vec<Work>, units: u32, shortest_s: f64) -> Slices {
        Slices {
            work,
            next: (0, 0),
            units: units.max(1),
            in_flight: None,
            shortest_s,
        }
    }

    /// The next slice's dispatches: none while the last slice is on the GPU, None once every
    /// slice has finished. A slice runs on across rows (the rest of one, whole rows, the
    /// start of the next: up to three dispatches) so that it holds the units asked for, but
    /// stops at the end of a dispatch of the frame. A zero target takes half a row of
    /// workgroups a slice, so that slices also start inside rows.
    pub(super) fn next_slice(&mut self, slicing: Slicing) -> Option<Vec<Work>> {
        let target = slicing.target.as_secs_f64();
        if let Some((clock, count)) = &self.in_flight {
            if !clock.finished() {
                return Some(Vec::new());
            }
            let steered = clock.steer(*count, &mut self.shortest_s, target);
            // A slice cut short at the end of a dispatch says little of the cost per
            // workgroup (the frame's own work can be most of its time): the size stays.
            if target > 0.0 && *count >= self.units {
                self.units = steered;
            }
            self.in_flight = None;
        }
        let (k, mut unit) = self.next;
        let w = *self.work.get(k)?;
        if target <= 0.0 {
            self.units = w.groups[0].div_ceil(2);
        }
        let (total, mut left) = (units(w.groups), self.units);
        let mut slice_work = Vec::new();
        while left > 0 && unit < total {
            let (origin, groups, count) = slice(w.groups, unit, left);
            slice_work.push(Work {
                origin: [
                    w.origin[0] + origin[0],
                    w.origin[1] + origin[1],
                    w.origin[2] + origin[2],
                ],
                groups,
                ..w
            });
            unit += count;
            left = left.saturating_sub(count);
        }
        self.next = if unit >= total { (k + 1, 0) } else { (k, unit) };
        Some(slice_work)
    }

    /// Marks the slice just submitted, with its `clock`, as on the GPU.
    pub(super) fn submitted(&mut self, clock: SliceClock, work: &[Work]) {
        if !work.is_empty() {
            let count = work.iter().map(|w| units(w.groups)).sum();
            self.in_flight = Some((clock, count));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{SliceClock, WORKGROUP_SIZE, slice, units};
    use std::sync::Arc;
    use std::sync::atomic::AtomicBool;
    use std::time::{Duration, Instant};

    /// A slice timed alone is steered by its own time, whatever frames came between: 4
    /// workgroups in 5 ms ask for 12 at a 20 ms target (aiming at 15 ms), and the shortest
    /// interval is left as it was. One seen done 40 ms after its submission, with 20 ms the
    /// shortest interval, sets most of that aside as the frame's own work.
    #[test]
    fn slices_timed_alone_are_steered_by_their_own_time() {
        let mut shortest = 0.020;
        assert_eq!(SliceClock::Alone(0.005).steer(4, &mut shortest, 0.020), 12);
        assert_eq!(SliceClock::Alone(0.080).steer(4, &mut shortest, 0.020), 1);
        // Growth stays within 16 times a slice.
        assert_eq!(SliceClock::Alone(1e-6).steer(4, &mut shortest, 0.020), 64);
        assert_eq!(shortest, 0.020);
        let submitted = Instant::now() - Duration::from_millis(40);
        let seen = Arc::new(AtomicBool::new(true));
        let steered = SliceClock::Since(submitted, seen).steer(4, &mut shortest, 0.020);
        // own = 40 − 0.8 × 20 = 24 ms (a little more, as time passed since): 4 × 20 / 24 → 3.
        assert_eq!(steered, 3);
        assert_eq!(shortest, 0.020);
    }

    /// Slices of any size, taken one after another, cover every workgroup of a pass exactly
    /// once, each slice a box inside the grid.
    #[test]
    fn slices_tile_the_grid_exactly_once() {
        for grid in [[3, 4, 5], [1, 1, 1], [16, 8, 16], [2, 7, 1]] {
            for size in [1, 2, 3, 4, 7, 8, 9, 30, 1000] {
                let mut hits = vec![0u32; (grid[0] * grid[1] * grid[2]) as usize];
                let mut start = 0;
                while start < units(grid) {
                    let (origin, groups, n) = slice(grid, start, size);
                    assert!(n >= 1 && n <= size, "{grid:?} {size}: {n}");
                    assert_eq!(n, groups[0] * groups[1] * groups[2]);
                    let x0 = origin[0] / WORKGROUP_SIZE;
                    let (y0, z0) = (origin[1] / WORKGROUP_SIZE, origin[2]);
                    for z in z0..z0 + groups[2] {
                        for y in y0..y0 + groups[1] {
                            for x in x0..x0 + groups[0] {
                                hits[((z * grid[1] + y) * grid[0] + x) as usize] += 1;
                            }
                        }
                    }
                    start += n;
                }
                assert!(hits.iter().all(|&h| h == 1), "{grid:?} in slices of {size}");
            }
        }
    }
}
