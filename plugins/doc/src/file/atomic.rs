//! Atomic writes: a synced temporary file in the same folder, the old
//! file kept as a backup, a rename into place.

use super::errors::FileError;
use std::io::Write;
use std::path::{Path, PathBuf};

pub(super) fn io(path: &Path) -> impl FnOnce(std::io::Error) -> FileError + '_ {
    move |source| FileError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Writes `text` to `path` atomically: a temporary file in the same folder,
/// synced, the previous file kept as `<path>.bak`, then a rename. A failure
/// at any point leaves the old file in place.
///
/// # Errors
/// [`FileError::Io`] naming the path.
pub fn write_atomic(path: &Path, text: &str) -> Result<(), FileError> {
    write_atomic_bytes(path, text.as_bytes())
}

/// [`write_atomic`] for binary contents (binary STL).
///
/// # Errors
/// [`FileError::Io`] naming the path.
pub fn write_atomic_bytes(path: &Path, bytes: &[u8]) -> Result<(), FileError> {
    write_atomic_impl(path, bytes, true)
}

/// [`write_atomic_bytes`] without the `.bak` copy (recovery files, preferences).
///
/// # Errors
/// [`FileError::Io`] naming the path.
pub fn write_atomic_without_backup(path: &Path, bytes: &[u8]) -> Result<(), FileError> {
    write_atomic_impl(path, bytes, false)
}

/// [`write_atomic_bytes`] with the contents streamed by `write` into the
/// temporary file (buffered; `write` may seek, as the STL writer does to
/// fill in its triangle count), so that a large export is never held in
/// memory whole. A `write` error leaves the old file in place.
///
/// # Errors
/// [`FileError::Io`] naming the path.
pub fn write_atomic_streamed(
    path: &Path,
    write: impl FnOnce(&mut std::io::BufWriter<&mut std::fs::File>) -> std::io::Result<()>,
) -> Result<(), FileError> {
    write_atomic_with(path, true, |f| {
        let mut out = std::io::BufWriter::with_capacity(1 << 20, f);
        write(&mut out)?;
        out.flush()
    })
}

fn write_atomic_impl(path: &Path, bytes: &[u8], keep_backup: bool) -> Result<(), FileError> {
    write_atomic_with(path, keep_backup, |f| f.write_all(bytes))
}

fn write_atomic_with(
    path: &Path,
    keep_backup: bool,
    write: impl FnOnce(&mut std::fs::File) -> std::io::Result<()>,
) -> Result<(), FileError> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path.file_name().ok_or_else(|| FileError::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file name"),
    })?;
    // Messages name the file asked for and its folder, never the
    // temporary file, which the user did not ask for and never sees.
    let in_folder = |source: std::io::Error| FileError::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(
            source.kind(),
            format!("cannot write in folder '{}': {source}", dir.display()),
        ),
    };
    if !dir.is_dir() {
        return Err(FileError::Io {
            path: path.to_path_buf(),
            source: std::io::Error::new(
                std::io::ErrorKind::NotFound,
                format!("folder '{}' does not exist", dir.display()),
            ),
        });
    }
    let tmp = dir.join(format!(
        ".{}.tmp-{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp).map_err(in_folder)?;
        write(&mut f).map_err(in_folder)?;
        f.sync_all().map_err(in_folder)?;
        drop(f);
        if keep_backup && path.exists() {
            let mut bak = path.as_os_str().to_owned();
            bak.push(".bak");
            let bak = PathBuf::from(bak);
            let _ = std::fs::remove_file(&bak);
            if std::fs::hard_link(path, &bak).is_err() {
                std::fs::copy(path, &bak).map_err(io(&bak))?;
            }
        }
        std::fs::rename(&tmp, path).map_err(io(path))?;
        if let Ok(d) = std::fs::File::open(&dir) {
            let _ = d.sync_all();
        }
        remove_abandoned_temporaries(&dir, &name.to_string_lossy());
        Ok(())
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Removes temporary files of `name` left by saves whose process was killed
/// (Linux: their pid is gone from `/proc`).
fn remove_abandoned_temporaries(dir: &Path, name: &str) {
    let prefix = format!(".{name}.tmp-");
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        let Some(pid) = file_name.to_str().and_then(|n| n.strip_prefix(&prefix)) else {
            continue;
        };
        let alive = Path::new("/proc").join(pid).exists() || !Path::new("/proc/self").exists();
        if !alive {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}
