//! Lists the models' GPU passes: every file `src/methods/<model>.rs` (but `mod.rs`) is a
//! module that exports `METHODS`, its registry rows' passes. Adding a model's file is all it
//! takes for the engine to find them; `methods::tests` checks that every real-time row of the
//! registry has its passes. `cargo fmt` does not reach modules declared here: format them
//! with `rustfmt --edition 2024 render/src/methods/*.rs`.

use std::fmt::Write;

fn main() {
    let dir = std::path::Path::new("src/methods");
    println!("cargo:rerun-if-changed=src/methods");
    let mut stems: Vec<String> = std::fs::read_dir(dir)
        .expect("src/methods")
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "rs"))
        .filter_map(|p| Some(p.file_stem()?.to_str()?.to_string()))
        // A module name, not an editor's lock file or backup.
        .filter(|s| {
            s != "mod"
                && s.starts_with(|c: char| c.is_ascii_lowercase() || c == '_')
                && s.chars()
                    .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
        })
        .collect();
    stems.sort();
    let manifest = std::env::var("CARGO_MANIFEST_DIR").expect("CARGO_MANIFEST_DIR");
    let mut out = String::new();
    for s in &stems {
        let path = std::path::Path::new(&manifest)
            .join(dir)
            .join(format!("{s}.rs"));
        writeln!(
            out,
            "#[path = {:?}]\npub mod {s};",
            path.display().to_string()
        )
        .unwrap();
    }
    writeln!(
        out,
        "/// Every model file's rows, by file name.\nconst BY_FILE: &[&[GpuMethod]] = &["
    )
    .unwrap();
    for s in &stems {
        writeln!(out, "    {s}::METHODS,").unwrap();
    }
    writeln!(out, "];").unwrap();
    let dest = std::path::Path::new(&std::env::var("OUT_DIR").expect("OUT_DIR")).join("methods.rs");
    std::fs::write(dest, out).expect("write methods.rs");
}
