//! Files the app writes: every one goes to a temporary file beside its place and is renamed
//! into place, so a full disk or a crash never leaves half a file. In the browser a file the
//! explorer writes is a download of that name instead.

/// Refuses an output path whose directory does not exist, before any work starts.
pub fn check_writable(path: &std::path::Path) -> anyhow::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => std::path::Path::new("."),
    };
    if !dir.is_dir() {
        anyhow::bail!(
            "{}: the directory {} does not exist",
            path.display(),
            dir.display()
        );
    }
    Ok(())
}

/// Writes `bytes` to `path` atomically (`atmoscope_model::files::write_atomic`).
#[cfg(not(target_arch = "wasm32"))]
pub fn write_atomic(path: &std::path::Path, bytes: &[u8]) -> anyhow::Result<()> {
    use anyhow::Context;
    atmoscope_model::files::write_atomic(path, bytes)
        .with_context(|| format!("cannot write {}", path.display()))
}

/// In the browser: the browser downloads `bytes` as a file named as `path`'s last part.
#[cfg(target_arch = "wasm32")]
pub fn write_atomic(path: &std::path::Path, bytes: &[u8]) -> anyhow::Result<()> {
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("atmoscope");
    crate::web::download(name, bytes)
}
