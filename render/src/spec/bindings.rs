//! Group 1 of every pass, generated from the registry: the view's images and buffers first,
//! then every table of every model in registry order, each a storage buffer of vec4 texels
//! named after its id (`sky-view` is `sky_view_lut`). Every pass declares them all, so that a
//! model's shared WGSL may name any of its tables; a pass's bind group layout holds only what
//! it reads or writes, and the tables it only reads are declared `read` in its module, as the
//! layout binds them, so that the GPU needs no barrier between passes that read the same
//! tables and write others. Two models may declare a table under one id with sizes of their own
//! (Bruneton's and Elek's deltas): the id names the binding, each row its buffer.

use super::{PassSpec, Resource, Table};
use atmoscope_model::methods::MODELS;
use std::fmt::Write;

/// Bindings of the view's images and buffers; the tables follow from [`FIRST_TABLE`].
const RADIANCE_OUT: u32 = 0;
const RADIANCE_IN: u32 = 1;
const DISPLAY_OUT: u32 = 2;
const EXACT_TILES: u32 = 3;
const HISTOGRAM: u32 = 4;
const FIRST_TABLE: u32 = 5;

/// Every table of the registry, once, in registry order.
pub fn tables() -> Vec<Table> {
    let mut v: Vec<Table> = Vec::new();
    for t in MODELS.iter().flat_map(|m| m.tables) {
        if !v.iter().any(|u| u.id == t.id) {
            v.push(Table(t));
        }
    }
    v
}

/// The group-1 binding of `resource` in a pass that writes it (`written`) or only reads it
/// (the radiance is a storage texture to the sky pass, a sampled one to the view passes);
/// None for a table the registry does not declare.
pub fn binding(resource: Resource, written: bool) -> Option<u32> {
    match resource {
        Resource::Radiance if written => Some(RADIANCE_OUT),
        Resource::Radiance => Some(RADIANCE_IN),
        Resource::Display => Some(DISPLAY_OUT),
        Resource::ExactTiles => Some(EXACT_TILES),
        Resource::Histogram => Some(HISTOGRAM),
        Resource::Table(t) => tables()
            .iter()
            .position(|u| *u == t)
            .and_then(|i| u32::try_from(i).ok())
            .map(|i| FIRST_TABLE + i),
    }
}

/// The WGSL name of a table's buffer.
pub fn wgsl_name(table: &Table) -> String {
    format!("{}_lut", table.id.replace('-', "_"))
}

/// The group-1 declarations of `pass`'s module.
pub fn wgsl(pass: &PassSpec) -> String {
    let mut s = String::from("// Group 1, generated from the registry (render::spec::bindings).\n");
    let images = [
        (
            RADIANCE_OUT,
            "radiance_out: texture_storage_2d<rgba32float, write>",
        ),
        (RADIANCE_IN, "radiance_in: texture_2d<f32>"),
        (
            DISPLAY_OUT,
            "display_out: texture_storage_2d<rgba8unorm, write>",
        ),
    ];
    for (n, decl) in images {
        let _ = writeln!(s, "@group(1) @binding({n}) var {decl};");
    }
    let buffers = [
        (EXACT_TILES, "exact_tiles: ExactTiles"),
        (HISTOGRAM, "histogram: array<atomic<u32>>"),
    ];
    for (n, decl) in buffers {
        let _ = writeln!(
            s,
            "@group(1) @binding({n}) var<storage, read_write> {decl};"
        );
    }
    for (i, t) in tables().iter().enumerate() {
        let access = if pass.reads_only(Resource::Table(*t)) {
            "read"
        } else {
            "read_write"
        };
        let _ = writeln!(
            s,
            "@group(1) @binding({}) var<storage, {access}> {}: array<vec4<f32>>;",
            FIRST_TABLE as usize + i,
            wgsl_name(t)
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_resource_has_its_own_binding() {
        let mut all: Vec<u32> = tables()
            .into_iter()
            .filter_map(|t| binding(Resource::Table(t), false))
            .chain(
                [true, false]
                    .map(|w| binding(Resource::Radiance, w))
                    .into_iter()
                    .flatten(),
            )
            .chain(
                [Resource::Display, Resource::ExactTiles, Resource::Histogram]
                    .into_iter()
                    .filter_map(|r| binding(r, true)),
            )
            .collect();
        let n = all.len();
        assert_eq!(n, tables().len() + 5);
        all.sort();
        all.dedup();
        assert_eq!(all.len(), n, "two resources share a binding");
    }
}
