//! Fingerprints of the sources behind the cache's entries.
//!
//! A path-traced reference depends on the model's code and data tables, a preset thumbnail on
//! those and the engine with its shaders. The build script hashes those files and hands the
//! program their fingerprints (`ATMOSCOPE_MODEL_SOURCES`, `ATMOSCOPE_ENGINE_SOURCES`), which
//! go into the cache keys: an entry made by a build with other physics, tables or shaders is
//! then never read back as if it were current. A hand-kept version number did this before and
//! was forgotten when the tracer changed. Shared with `build.rs` (by `#[path]`), so it stands
//! alone.

use std::path::{Path, PathBuf};

/// Folders, relative to the workspace root, whose files decide a path-traced reference.
#[cfg_attr(not(test), allow(dead_code))] // read by build.rs and the tests
pub const MODEL_SOURCES: &[&str] = &["model/src", "model/data"];

/// Folders whose files decide an image of the real-time engine.
#[cfg_attr(not(test), allow(dead_code))] // read by build.rs and the tests
pub const ENGINE_SOURCES: &[&str] = &["model/src", "model/data", "render/src", "shaders"];

/// The kinds of file hashed: Rust, WGSL and the data tables. Editors' swap, lock and backup
/// files (`.a.rs.swp`, `.#a.rs`, `a.rs~`) are none of these, so saving in an editor does not
/// change a fingerprint, and a dangling lock link cannot fail the build.
const SOURCE_EXTENSIONS: &[&str] = &["rs", "wgsl", "csv"];

/// FNV-1a, 64-bit, fed in pieces.
pub struct Fnv(u64);

impl Fnv {
    pub fn new() -> Fnv {
        Fnv(0xcbf2_9ce4_8422_2325)
    }

    pub fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
    }

    pub fn finish(&self) -> u64 {
        self.0
    }
}

/// The fingerprint of every source file under `dirs` (relative to `root`; hidden names
/// skipped): each file's path relative to `root` (with `/` between parts) and its bytes, in
/// the order of the paths, so that editing, adding, removing or renaming a source file changes
/// it.
#[cfg_attr(not(test), allow(dead_code))] // the program reads build.rs's; the tests recompute it
pub fn fingerprint(root: &Path, dirs: &[&str]) -> std::io::Result<u64> {
    let mut files = Vec::new();
    for dir in dirs {
        collect(&root.join(dir), &mut files)?;
    }
    let mut named: Vec<(String, PathBuf)> = files
        .into_iter()
        .map(|f| {
            let relative = f.strip_prefix(root).unwrap_or(&f);
            let name: Vec<String> = relative
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            (name.join("/"), f)
        })
        .collect();
    named.sort();
    named.dedup_by(|a, b| a.0 == b.0);
    let mut hash = Fnv::new();
    for (name, file) in named {
        let bytes = std::fs::read(&file)?;
        // Lengths first, so that no two different lists of files hash the same bytes.
        hash.write(&(name.len() as u64).to_le_bytes());
        hash.write(name.as_bytes());
        hash.write(&(bytes.len() as u64).to_le_bytes());
        hash.write(&bytes);
    }
    Ok(hash.finish())
}

/// Whether the name of `path` starts with a dot.
fn is_hidden(path: &Path) -> bool {
    path.file_name()
        .is_some_and(|n| n.to_string_lossy().starts_with('.'))
}

/// Whether `path` names a source file by its extension, and is not hidden.
fn is_source(path: &Path) -> bool {
    let extension = path.extension().and_then(|e| e.to_str());
    !is_hidden(path) && extension.is_some_and(|e| SOURCE_EXTENSIONS.contains(&e))
}

/// Every regular source file under `dir`, recursively, without following links.
fn collect(dir: &Path, files: &mut Vec<PathBuf>) -> std::io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        let path = entry.path();
        let kind = entry.file_type()?;
        if kind.is_dir() && !is_hidden(&path) {
            collect(&path, files)?;
        } else if kind.is_file() && is_source(&path) {
            files.push(path);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fingerprints the build compiled in are those of the sources as they are now: the
    /// build script hashed these folders, and reruns when they change.
    #[test]
    fn the_build_fingerprints_the_current_sources() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let model = fingerprint(&root, MODEL_SOURCES).expect("model sources");
        let engine = fingerprint(&root, ENGINE_SOURCES).expect("engine sources");
        assert_eq!(format!("{model:016x}"), env!("ATMOSCOPE_MODEL_SOURCES"));
        assert_eq!(format!("{engine:016x}"), env!("ATMOSCOPE_ENGINE_SOURCES"));
    }

    /// Every file in the source folders is of a kind the fingerprint hashes: a data table in
    /// a new format must be added to `SOURCE_EXTENSIONS`, or edits to it would leave stale
    /// entries in the cache.
    #[test]
    fn every_source_file_is_of_a_hashed_kind() {
        fn walk(dir: &Path, unhashed: &mut Vec<PathBuf>) {
            for entry in std::fs::read_dir(dir).expect("source folder") {
                let path = entry.expect("entry").path();
                if is_hidden(&path) {
                    continue;
                }
                if path.is_dir() {
                    walk(&path, unhashed);
                } else if !is_source(&path) {
                    unhashed.push(path);
                }
            }
        }
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let mut unhashed = Vec::new();
        for dir in ENGINE_SOURCES {
            walk(&root.join(dir), &mut unhashed);
        }
        assert!(unhashed.is_empty(), "not fingerprinted: {unhashed:?}");
    }

    /// Editing a file, adding one, renaming one or moving bytes between two files each
    /// changes the fingerprint; reading the same files again, or an editor's swap, backup or
    /// dangling lock link beside them, does not.
    #[test]
    fn a_fingerprint_changes_with_any_file() {
        let root = tempfile::tempdir().expect("temporary folder");
        let dir = root.path().join("src");
        std::fs::create_dir_all(dir.join("deep")).expect("folders");
        let write = |name: &str, text: &str| std::fs::write(dir.join(name), text).expect("write");
        write("a.rs", "const A: f64 = 1.0;");
        write("deep/b.wgsl", "let b = 2.0;");
        let print = || fingerprint(root.path(), &["src"]).expect("fingerprint");
        let first = print();
        assert_eq!(first, print());
        let mut seen = vec![first];
        let mut changed = |what: &str| {
            let now = print();
            assert!(
                !seen.contains(&now),
                "{what} left the fingerprint as before"
            );
            seen.push(now);
        };
        write("a.rs", "const A: f64 = 1.5;");
        changed("an edit");
        write("c.rs", "");
        changed("an empty new file");
        std::fs::rename(dir.join("c.rs"), dir.join("d.rs")).expect("rename");
        changed("a rename");
        write("a.rs", "const A: f64 = 1.");
        write("d.rs", "5;");
        changed("bytes moved from one file to the next");
        let last = print();
        write(".a.rs.swp", "swap");
        write("a.rs~", "backup");
        write("notes.md", "text");
        assert_eq!(print(), last, "editor files changed the fingerprint");
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(dir.join("gone"), dir.join(".#a.rs")).expect("link");
            assert_eq!(print(), last, "a dangling lock link");
        }
    }
}
