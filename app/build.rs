//! Embeds the shipped presets (`presets/*.ron` at the workspace root) and the Learn menu's
//! lessons (`presets/learn/*.ron`) into the binary, so the explorer and the commands that list
//! them work from any directory; and fingerprints the sources the cache's entries depend on
//! (`src/source_key.rs`).

#[path = "src/source_key.rs"]
mod source_key;

use std::fmt::Write;
use std::path::Path;

/// Writes `OUT_DIR/<out>` declaring `name`: every `.ron` file of `dir` as (file name, text).
fn embed(dir: &Path, name: &str, doc: &str, out: &str) {
    println!("cargo:rerun-if-changed={}", dir.display());
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .collect();
    files.sort();
    let mut code =
        format!("/// {doc}: (file name, RON text).\npub static {name}: &[(&str, &str)] = &[\n");
    for f in &files {
        println!("cargo:rerun-if-changed={}", f.display());
        let file = f
            .file_name()
            .and_then(|n| n.to_str())
            .expect("UTF-8 file name");
        let abs = f.canonicalize().expect("file path");
        writeln!(
            code,
            "    ({file:?}, include_str!({:?})),",
            abs.display().to_string()
        )
        .expect("write to string");
    }
    code.push_str("];\n");
    let dest = Path::new(&std::env::var("OUT_DIR").expect("OUT_DIR")).join(out);
    std::fs::write(dest, code).expect("write embedded file list");
}

/// Sets `ATMOSCOPE_<NAME>` at compile time to the fingerprint of `dirs`, and reruns when a
/// file in them changes.
fn fingerprint(root: &Path, name: &str, dirs: &[&str]) {
    for dir in dirs {
        println!("cargo:rerun-if-changed={}", root.join(dir).display());
    }
    let key = source_key::fingerprint(root, dirs)
        .unwrap_or_else(|e| panic!("fingerprint of {dirs:?}: {e}"));
    println!("cargo:rustc-env=ATMOSCOPE_{name}={key:016x}");
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    fingerprint(&root, "MODEL_SOURCES", source_key::MODEL_SOURCES);
    fingerprint(&root, "ENGINE_SOURCES", source_key::ENGINE_SOURCES);
    let presets = root.join("presets");
    embed(&presets, "SHIPPED", "Shipped presets", "presets.rs");
    embed(
        &presets.join("learn"),
        "LESSONS",
        "The Learn menu's lessons",
        "lessons.rs",
    );
}
