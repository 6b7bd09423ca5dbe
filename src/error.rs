//! One error type for the whole crate. Every variant carries enough context (file, line,
//! group, key) for a user to act on it; `Display` gives the full message.

use std::path::Path;

#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Reading or writing a file failed at the operating-system level.
    #[error("{path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    /// Malformed input text or binary: `place` is "file:line" or "file (byte N)".
    #[error("{place}: {msg}")]
    Parse { place: String, msg: String },
    /// Well-formed input that describes an invalid model (bad cell, missing group, ...).
    #[error("{0}")]
    Model(String),
    /// The numerical solution failed (singular matrix, Newton divergence, ...).
    #[error("{0}")]
    Solve(String),
    /// Not enough memory: an estimate beyond what is available, or a failed allocation.
    #[error("{0}")]
    Memory(String),
}

pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    pub fn io(path: &Path, source: std::io::Error) -> Self {
        Error::Io {
            path: path.display().to_string(),
            source,
        }
    }
    pub fn parse(place: impl Into<String>, msg: impl Into<String>) -> Self {
        Error::Parse {
            place: place.into(),
            msg: msg.into(),
        }
    }
    pub fn model(msg: impl Into<String>) -> Self {
        Error::Model(msg.into())
    }
    pub fn solve(msg: impl Into<String>) -> Self {
        Error::Solve(msg.into())
    }
}

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename, so
/// that a reader never sees a half-written file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty());
    if let Some(dir) = dir {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    }
    let file_name = path
        .file_name()
        .ok_or_else(|| Error::model(format!("{}: not a file path", path.display())))?;
    let tmp = path.with_file_name(format!(
        ".{}.tmp{}",
        file_name.to_string_lossy(),
        std::process::id()
    ));
    std::fs::write(&tmp, bytes).map_err(|e| Error::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        Error::io(path, e)
    })
}
