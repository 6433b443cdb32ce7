//! Each model's GPU passes as data, one file per model named as in `model::methods`
//! (`hillaire.rs` beside `model/src/methods/hillaire/`), in the vocabulary of [`crate::spec`].
//! Every file exports `METHODS`, the passes of its registry rows (a model and its `-ms` row
//! share a file); the build script lists the files, so adding a model's file is all it takes
//! for the engine to find it.

pub use crate::spec::*;

use atmoscope_model::methods;
use atmoscope_model::scene::Method;

include!(concat!(env!("OUT_DIR"), "/methods.rs"));

/// The passes of `method`, or None for a model with no real-time passes (the path tracer).
pub fn gpu_method(method: Method) -> Option<&'static GpuMethod> {
    BY_FILE
        .iter()
        .flat_map(|f| f.iter())
        .find(|m| m.method == method)
}

/// Every real-time model's passes, in registry order.
pub fn gpu_methods() -> impl Iterator<Item = &'static GpuMethod> {
    methods::realtime().filter_map(|row| gpu_method(row.method))
}

#[cfg(test)]
mod tests {
    use super::*;
    use atmoscope_model::methods::Inputs;

    /// No pass takes more pipeline constants than a variant holds (`passes::MAX_CONSTANTS`): one
    /// more would be dropped and compiled at its default.
    #[test]
    fn no_pass_takes_more_constants_than_a_variant_holds() {
        for method in gpu_methods() {
            for pass in method.specs() {
                assert!(
                    pass.constants.len() <= crate::passes::MAX_CONSTANTS,
                    "{:?} {}: {} constants",
                    method.method,
                    pass.name,
                    pass.constants.len()
                );
            }
        }
    }

    /// Every file's rows are real-time rows of the registry, each once.
    #[test]
    fn every_file_lists_rows_of_the_registry_once() {
        let all: Vec<Method> = BY_FILE
            .iter()
            .flat_map(|f| f.iter().map(|m| m.method))
            .collect();
        for m in &all {
            assert!(
                methods::info(*m).is_realtime(),
                "{m:?} is not a real-time row"
            );
            assert_eq!(all.iter().filter(|n| *n == m).count(), 1, "{m:?} twice");
        }
        assert_eq!(all.len(), methods::realtime().count());
    }

    #[test]
    fn every_real_time_model_of_the_registry_has_passes_and_every_table_a_writer() {
        for row in methods::realtime() {
            let gpu =
                gpu_method(row.method).unwrap_or_else(|| panic!("{} has no GPU passes", row.id));
            for t in row.tables {
                // One writer outside the order loop at most; the loop's passes may rewrite it.
                let writers: Vec<_> = gpu
                    .passes
                    .iter()
                    .filter(|p| p.writes.contains(&Resource::table(t)))
                    .collect();
                let once = writers.iter().filter(|p| p.repeat == Repeat::Once).count();
                assert!(
                    !writers.is_empty() && once <= 1,
                    "{}: table {} is written by {} passes, {once} outside the order loop",
                    row.id,
                    t.id,
                    writers.len()
                );
            }
            let looped: Vec<usize> = (0..gpu.passes.len())
                .filter(|&i| gpu.passes[i].repeat == Repeat::PerOrder)
                .collect();
            assert!(
                looped.windows(2).all(|w| w[1] == w[0] + 1),
                "{}: the order loop's passes are consecutive",
                row.id
            );
            let last = gpu.passes.last().expect("passes");
            assert!(
                last.writes.contains(&RADIANCE),
                "{}: the sky pass comes last",
                row.id
            );
            // The engine recreates the view's images when the size changes.
            assert!(
                last.inputs.intersects(Inputs::VIEW_SIZE),
                "{}: the sky pass reads the view size",
                row.id
            );
            for (i, p) in gpu.passes.iter().enumerate() {
                let tables = p
                    .resources()
                    .iter()
                    .filter(|r| r.as_table().is_some())
                    .count();
                assert!(
                    tables <= MAX_TABLES_PER_PASS,
                    "{}: {} binds {tables} tables",
                    row.id,
                    p.name
                );
                // Every table a pass binds or runs over is its row's own declaration (Bruneton
                // and Elek share ids with sizes of their own).
                let own = |t: &atmoscope_model::methods::shared::TableSpec| {
                    row.table(t.id).is_some_and(|o| {
                        (o.size, o.axes, o.invalidated_by, o.label)
                            == (t.size, t.axes, t.invalidated_by, t.label)
                    })
                };
                for r in p.resources() {
                    if let Some(t) = r.as_table() {
                        assert!(
                            own(t),
                            "{}: {} binds {}, not the row's table",
                            row.id,
                            p.name,
                            t.id
                        );
                    }
                }
                if p.writes.contains(&MOVING_SKY) {
                    // The moving sky evaluates the sky pass's radiance: it reads what that
                    // reads, but for a nested march's way to the sun, which it reads from its
                    // table instead of the mesh the way is integrated over.
                    let tabulated = p.reads(SUN_ROUTE_TABLE);
                    let mesh = Resource::table(&atmoscope_model::methods::galaj_spline::MESH);
                    let sky: Vec<Resource> = last
                        .reads
                        .iter()
                        .map(|r| r.resource)
                        .filter(|&r| r != MOVING_SKY && !(tabulated && r == mesh))
                        .collect();
                    let own: Vec<Resource> = p
                        .reads
                        .iter()
                        .map(|r| r.resource)
                        .filter(|&r| r != SUN_ROUTE_TABLE)
                        .collect();
                    assert_eq!(
                        own, sky,
                        "{}: the moving sky reads what the sky pass reads",
                        row.id
                    );
                    assert_eq!(
                        last.own_file(),
                        p.own_file(),
                        "{}: the same sky file",
                        row.id
                    );
                    assert!(
                        last.reads.contains(&read(MOVING_SKY).in_motion()),
                        "{}: the sky reads the moving sky in motion",
                        row.id
                    );
                }
                for r in p.reads {
                    let earlier = gpu.passes[..i]
                        .iter()
                        .any(|q| q.writes.contains(&r.resource));
                    assert!(
                        earlier,
                        "{}: {} reads {} before it is written",
                        row.id,
                        p.name,
                        r.resource.id()
                    );
                }
                if let Some(t) = p.dispatch.table() {
                    assert!(
                        own(t.0),
                        "{}: {} dispatches over {}, not the row's table",
                        row.id,
                        p.name,
                        t.id
                    );
                }
            }
        }
    }

    /// The files each pass lists make the module the engine compiles, by the rules the
    /// entry points need: what writes the display has the tone map before its own file, a sky
    /// pass ends with the entry point after the radiance it draws (the moving sky's in motion
    /// when it reads that) and the polarisation it draws on, the moving sky's pass with its own entry point, and a pass that
    /// defines the way to the sun has one `sun_transmittance_by_way`, from the table only when
    /// it reads that table.
    #[test]
    fn every_pass_lists_the_files_its_entry_point_needs() {
        for gpu in gpu_methods() {
            for p in gpu.specs() {
                let files = gpu.files(p);
                let at = |f: Shader| files.iter().position(|g| *g == f);
                let name = format!("{:?} {}", gpu.method, p.name);
                if p.writes.contains(&DISPLAY) {
                    assert!(at(TONE).is_some(), "{name}: no tone map");
                }
                if p.writes.contains(&RADIANCE) {
                    let radiance = if p.reads(MOVING_SKY) {
                        MOVING_SKY_RADIANCE
                    } else {
                        VIEW_RADIANCE
                    };
                    assert_eq!(
                        &files[files.len() - 3..],
                        [radiance, SKY_POLARISATION, SKY_ENTRY_POINT],
                        "{name}: its entry point"
                    );
                }
                if p.writes.contains(&MOVING_SKY) {
                    assert_eq!(files.last(), Some(&MOVING_SKY_ENTRY_POINT), "{name}");
                }
                if at(SUN_ROUTE).is_some() {
                    let way = if p.reads(SUN_ROUTE_TABLE) {
                        SUN_ROUTE_FROM_TABLE
                    } else {
                        SUN_ROUTE_MARCHED
                    };
                    assert!(at(way).is_some(), "{name}: its way to the sun");
                }
                let unique: std::collections::HashSet<&str> =
                    files.iter().map(|f| f.path).collect();
                assert_eq!(unique.len(), files.len(), "{name}: a file twice");
            }
        }
    }

    /// What a pass reads in any frame is among what it declares, and a frame from inside the
    /// atmosphere, with the ground and in motion, reads it all.
    #[test]
    fn a_frame_that_needs_everything_reads_every_declared_read() {
        for gpu in gpu_methods() {
            for p in gpu.specs() {
                let all: Vec<Resource> = p.reads_in(&Situation::EVERYTHING_INSIDE).collect();
                let declared: Vec<Resource> = p.reads.iter().map(|r| r.resource).collect();
                assert_eq!(all, declared, "{:?} {}", gpu.method, p.name);
            }
        }
    }
}
