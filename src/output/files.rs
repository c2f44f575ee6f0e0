//! Atomic file output: write to a temporary file beside the target, then
//! rename, so an error never leaves a half-written file. The one
//! implementation for every output (text, CSV, JSON, figures).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Why an output file could not be written.
#[derive(Debug, thiserror::Error)]
#[error("{}: cannot write: {io}", path.display())]
pub struct WriteError {
    pub path: PathBuf,
    pub io: std::io::Error,
}

/// Writes `bytes` to `path` atomically: into a temporary file in the same
/// directory (a fresh name per call, so concurrent writes do not collide),
/// flushed, then renamed over `path`. On failure the temporary file is
/// removed and `path` is untouched; a missing directory is reported as such
/// and nothing is created.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    let err = |io| WriteError {
        path: path.to_path_buf(),
        io,
    };
    let name = path.file_name().ok_or_else(|| {
        err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a file name",
        ))
    })?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        return Err(err(std::io::Error::new(
            std::io::ErrorKind::NotFound,
            format!("directory {} does not exist", dir.display()),
        )));
    }
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let tmp = dir.join(format!(
        ".{}.{}-{}.tmp",
        name.to_string_lossy(),
        std::process::id(),
        n
    ));
    let result = (|| {
        let mut file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&tmp, path)
    })();
    result.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        err(e)
    })
}
