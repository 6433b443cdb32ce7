//! Atmoscope's cache on disk (path-traced references, preset thumbnails): where it lives and
//! how entries are keyed. Entries are untrusted on read: each user checks what it reads back
//! and renders anew when an entry is cut short, corrupt or of another size.

use std::path::PathBuf;

/// The cache folder for one kind of entry: `$ATMOSCOPE_CACHE_DIR/<kind>`, else
/// `$XDG_CACHE_HOME/atmoscope/<kind>`, else `~/.cache/atmoscope/<kind>`.
pub fn dir(kind: &str) -> PathBuf {
    if let Some(d) = std::env::var_os("ATMOSCOPE_CACHE_DIR") {
        return PathBuf::from(d).join(kind);
    }
    let base = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
        // A browser page has no folders at all (asking for one panics there): it caches nothing.
        .unwrap_or_else(|| {
            if cfg!(target_arch = "wasm32") {
                PathBuf::new()
            } else {
                std::env::temp_dir()
            }
        });
    base.join("atmoscope").join(kind)
}

/// A stable 64-bit key of `bytes` (FNV-1a): names a cache entry after everything it depends on.
pub fn key(bytes: &[u8]) -> u64 {
    let mut hash = crate::source_key::Fnv::new();
    hash.write(bytes);
    hash.finish()
}
