//! Writing outputs so that nothing is lost or half-written: a temporary file in the target's
//! folder, flushed to disk, then renamed over the target. A crash or a failed build leaves
//! the previous file untouched.
//!
//! The temporary file is named `.<name>.<pid>.tmp` (hidden, and never ending in the target's
//! extension), so it cannot be mistaken for the output. Only a process killed while writing
//! (SIGKILL, power loss) can leave one behind; the next write of the same target removes such
//! files when the process named in them is no longer running (Linux, via `/proc`).

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// A file that could not be written: the target's path and the operating system's error. The
/// commands report it as [`crate::Error::Io`].
#[derive(Debug, thiserror::Error)]
#[error("{}: {reason}", path.display())]
pub struct WriteError {
    /// The file.
    pub path: PathBuf,
    /// The operating system's error.
    pub reason: std::io::Error,
}

/// Writes `bytes` to `path` atomically.
pub fn write(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    let io = |reason| WriteError {
        path: path.to_path_buf(),
        reason,
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    remove_stale(&dir, &name);
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let mut f = fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        let _ = fs::remove_file(&tmp);
        return Err(io(e));
    }
    // Make the rename itself durable where the platform allows it.
    if let Ok(d) = fs::File::open(&dir) {
        let _ = d.sync_all();
    }
    Ok(())
}

/// Removes `.<name>.<pid>.tmp` files in `dir` left by processes that are no longer running.
/// Where the platform cannot tell (no `/proc`), nothing is removed.
fn remove_stale(dir: &Path, name: &str) {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    let prefix = format!(".{name}.");
    for entry in entries.flatten() {
        let file = entry.file_name();
        let Some(pid) = file
            .to_str()
            .and_then(|f| f.strip_prefix(&prefix))
            .and_then(|rest| rest.strip_suffix(".tmp"))
            .and_then(|pid| pid.parse::<u32>().ok())
        else {
            continue;
        };
        if pid != std::process::id() && !Path::new(&format!("/proc/{pid}")).exists() {
            let _ = fs::remove_file(entry.path());
        }
    }
}
