//! The one error type of the output module: every failure names the file it concerns.

use std::fmt;
use std::path::{Path, PathBuf};

/// A failed write or read, with the path of the file or directory involved.
#[derive(Debug)]
pub struct OutputError {
    /// File or directory the operation was about.
    pub path: PathBuf,
    /// What went wrong, in words a user can act on.
    pub message: String,
    /// The underlying I/O error, when there is one.
    pub source: Option<std::io::Error>,
}

impl OutputError {
    /// An I/O failure while doing `what` on `path`.
    pub fn io(path: &Path, what: &str, source: std::io::Error) -> Self {
        OutputError {
            path: path.to_path_buf(),
            message: format!("{what}: {source}"),
            source: Some(source),
        }
    }

    /// Bad content or bad arguments, no I/O error behind it.
    pub fn invalid(path: &Path, message: impl Into<String>) -> Self {
        OutputError {
            path: path.to_path_buf(),
            message: message.into(),
            source: None,
        }
    }
}

impl fmt::Display for OutputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.message)
    }
}

impl std::error::Error for OutputError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.source
            .as_ref()
            .map(|e| e as &(dyn std::error::Error + 'static))
    }
}
