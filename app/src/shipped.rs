//! Files the repository ships beside the program (the view suite's path-traced references,
//! the last benchmark results),
//! found from any working directory: under the working directory, or under a folder above the
//! program (a program run from a clone or its `target/` folder).

use std::path::{Path, PathBuf};

/// The view suite's path-traced references, relative to the repository's root.
pub const REFERENCES: &str = "tests/data/references";

/// The last committed quick run of `bench methods`, which the Bench tab shows first.
pub const BENCH_RESULTS: &str = "docs/bench/results.csv";

/// `rel` under the working directory or under a folder above the running program, where it
/// exists.
pub fn near_program(rel: &Path) -> Option<PathBuf> {
    let exe = std::env::current_exe().ok();
    std::iter::once(rel.to_path_buf())
        .chain(
            exe.iter()
                .flat_map(|e| e.ancestors().skip(1))
                .map(|d| d.join(rel)),
        )
        .find(|p| p.exists())
}

/// The references a command reads: `given` (`--refs`) as it is, else the shipped ones found
/// near the program; an error that says how to point at them where there are none.
pub fn references(given: Option<&Path>) -> anyhow::Result<PathBuf> {
    match given {
        Some(dir) => Ok(dir.to_path_buf()),
        None => near_program(Path::new(REFERENCES))
            .filter(|p| p.is_dir())
            .ok_or_else(|| {
                anyhow::anyhow!(
                    "the shipped references ({REFERENCES}) are neither under the working directory nor above the program: \
                     run from a clone of the repository, pass --refs DIR, or render them with \
                     `atmoscope reference --suite --ci-size --out-dir DIR` (results are cached)"
                )
            }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shipped_references_are_found_from_the_program_or_a_given_folder() {
        // Tests run from the crate's folder, below the repository's root, and the test program
        // lives in its target/ folder: the references are found above it.
        let found = references(None).expect("found above the program");
        assert!(found.join("README.md").is_file(), "{found:?}");
        assert_eq!(
            references(Some(Path::new("elsewhere"))).expect("given"),
            PathBuf::from("elsewhere")
        );
        assert!(near_program(Path::new("no/such/file/anywhere")).is_none());
    }
}
