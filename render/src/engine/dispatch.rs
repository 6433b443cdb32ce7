//! Splitting a pass's dispatch: its grid of workgroups, the units a slice counts, where a
//! slice of them lies, and the dispatches (`Work`) the encoder records.

use super::*;

/// Workgroups of the whole dispatch of pass `i`.
pub(super) fn grid(pipelines: &Pipelines, i: usize, layers: u32, size: [u32; 2]) -> [u32; 3] {
    let Some(spec) = pipelines.specs().nth(i) else {
        return [0; 3];
    };
    match spec.dispatch {
        Dispatch::View => [groups(size[0]), groups(size[1]), 1],
        Dispatch::Table(t) => [groups(t.size[0]), groups(t.size[1]), layers],
        Dispatch::TexelGroups(t) => [t.size[0], t.size[1], layers],
        Dispatch::TexelRuns(t) => [
            t.size[0].div_ceil(texel_run(pipelines.texel_group_size)),
            t.size[1],
            layers,
        ],
        Dispatch::Volume(t) => [groups(t.size[0]), groups(t.size[1]), t.size[2] * layers],
    }
}

/// Units of work a pass is cut into when it runs in slices: its workgroups (a layer of a 3D
/// table being one of its slices of one batch; workgroups are one deep in z). Not rows: on a
/// CPU adapter one row of Bruneton's scattering density takes longer than a frame may.
pub(super) fn units(grid: [u32; 3]) -> u32 {
    grid[0] * grid[1] * grid[2]
}

/// Where a slice of `count` units from unit `start` of a pass's `grid` lies: its origin
/// (invocations), its workgroups and the units it covers. A slice stays within one row of
/// workgroups when it starts inside one or is smaller than one, within one layer likewise;
/// otherwise it covers whole rows, or whole layers.
pub(super) fn slice(grid: [u32; 3], start: u32, count: u32) -> ([u32; 3], [u32; 3], u32) {
    let row = grid[0].max(1);
    let layer = row * grid[1].max(1);
    let (z, x, y) = (start / layer, start % row, start % layer / row);
    if x != 0 || count < row {
        let n = count.clamp(1, row - x);
        ([x * WORKGROUP_SIZE, y * WORKGROUP_SIZE, z], [n, 1, 1], n)
    } else if y != 0 || count < layer {
        let rows = (count / row).clamp(1, grid[1] - y);
        ([0, y * WORKGROUP_SIZE, z], [row, rows, 1], rows * row)
    } else {
        let layers = (count / layer).clamp(1, grid[2] - z);
        ([0, 0, z], [row, grid[1], layers], layers * layer)
    }
}

/// One dispatch of a pass: its pipeline constants, where it starts in the pass's grid
/// (invocations) and its workgroups.
#[derive(Debug, Clone, Copy)]
pub(super) struct Work {
    pub(super) pass: usize,
    pub(super) variant: Variant,
    pub(super) origin: [u32; 3],
    pub(super) groups: [u32; 3],
    pub(super) tiles: TilePhase,
}

/// What a dispatch does with the list of tiles a sky drawn in tiles computes exactly.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum TilePhase {
    /// Nothing.
    None,
    /// Empties it, then fills it (the tiles' corners and their interpolation).
    Fill,
    /// Computes its tiles: an indirect dispatch of as many workgroups as it says.
    Compute,
}

impl Work {
    pub(super) fn whole(pass: usize, variant: Variant, grid: [u32; 3]) -> Work {
        Work {
            pass,
            variant,
            origin: [0; 3],
            groups: grid,
            tiles: TilePhase::None,
        }
    }
}

pub(super) fn groups(n: u32) -> u32 {
    n.div_ceil(crate::prelude::WORKGROUP_SIZE)
}
