//! Files written whole or not at all: the bytes go to a temporary file beside the target, are
//! flushed to the disk, and the temporary file is renamed over the target, so a full disk, a
//! crash or a cancelled export never leaves a truncated preset, image or cache entry behind
//! (a rename within one directory is atomic on the platforms we run on). And files read with a
//! limit: a pipe, a device or a huge file named where a small text file belongs is refused
//! rather than read until the memory runs out.

use std::io::{Read, Write};

/// Reads the regular file at `path` as UTF-8 text of at most `max_bytes` bytes. Anything else
/// (a pipe, a device, a folder, a longer file, or one that grows past the limit while read)
/// is an error that says what was found.
pub fn read_text_limited(path: &Path, max_bytes: u64) -> std::io::Result<String> {
    use std::io::{Error, ErrorKind};
    let file = std::fs::File::open(path)?;
    let meta = file.metadata()?;
    if !meta.is_file() {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            "not a regular file (a folder, a pipe or a device)",
        ));
    }
    let too_long = |n: u64| {
        Error::new(
            ErrorKind::InvalidData,
            format!("{n} bytes or more, past the {max_bytes} bytes such a file may have"),
        )
    };
    if meta.len() > max_bytes {
        return Err(too_long(meta.len()));
    }
    let mut bytes = Vec::new();
    file.take(max_bytes + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_long(bytes.len() as u64));
    }
    String::from_utf8(bytes).map_err(|e| Error::new(ErrorKind::InvalidData, e))
}
use std::path::{Path, PathBuf};

/// Writes `bytes` to `path` atomically; on any error the target is untouched and the
/// temporary file removed.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let tmp = temporary_beside(path);
    let result = std::fs::File::create(&tmp)
        .and_then(|mut f| f.write_all(bytes).and_then(|()| f.sync_all()))
        .and_then(|()| std::fs::rename(&tmp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// A hidden name in `path`'s directory, unique to this process and call.
fn temporary_beside(path: &Path) -> PathBuf {
    use std::sync::atomic::{AtomicU64, Ordering};
    static COUNT: AtomicU64 = AtomicU64::new(0);
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let unique = format!(
        ".{name}.{}-{}.tmp",
        std::process::id(),
        COUNT.fetch_add(1, Ordering::Relaxed)
    );
    path.with_file_name(unique)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_limited_read_refuses_devices_folders_and_long_files() {
        let dir = std::env::temp_dir().join(format!("atmoscope-limited-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let small = dir.join("small.ron");
        std::fs::write(&small, "(name: \"a\")").unwrap();
        assert_eq!(read_text_limited(&small, 100).unwrap(), "(name: \"a\")");
        let long = dir.join("long.ron");
        std::fs::write(&long, vec![b' '; 101]).unwrap();
        let e = read_text_limited(&long, 100).unwrap_err();
        assert!(e.to_string().contains("101 bytes"), "{e}");
        assert!(read_text_limited(&dir, 100).is_err(), "a folder");
        #[cfg(unix)]
        {
            let e = read_text_limited(Path::new("/dev/zero"), 100).unwrap_err();
            assert!(e.to_string().contains("not a regular file"), "{e}");
        }
        let binary = dir.join("binary.ron");
        std::fs::write(&binary, [0xff, 0xfe]).unwrap();
        assert!(read_text_limited(&binary, 100).is_err(), "not UTF-8");
    }

    #[test]
    fn a_write_replaces_the_file_whole_and_a_failed_one_leaves_it() {
        let dir = std::env::temp_dir().join(format!("atmoscope-files-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("scene.ron");
        write_atomic(&path, b"first").unwrap();
        write_atomic(&path, b"second, longer").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"second, longer");
        // A directory where the file should go: the write fails and leaves no temporary file.
        let blocked = dir.join("blocked");
        std::fs::create_dir_all(blocked.join("inside")).unwrap();
        assert!(write_atomic(&blocked, b"x").is_err());
        assert!(blocked.join("inside").is_dir(), "the target is untouched");
        let leftovers: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect();
        assert!(leftovers.is_empty(), "{leftovers:?}");
        assert!(write_atomic(&dir.join("no/such/dir/x"), b"x").is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
