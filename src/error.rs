//! The two ways a run can end badly, and the exit code each one gives.
//!
//! Bad input (a malformed case, a value fsim cannot honour) stops before anything is written,
//! with exit code 2; a run that fails once started (divergence, an I/O error) exits with 1 and
//! keeps its last good time directory.

use std::fmt;

use crate::case::quote::bound_message;

/// An error that ends `fsimFoam`.
#[derive(Debug)]
pub enum FsimError {
    /// The case is wrong: `reason` is one line naming file, line and column (or the particle);
    /// `excerpt` optionally shows the offending source line with a caret.
    Input {
        reason: String,
        excerpt: Option<String>,
    },
    /// The run started and failed (diverged, could not write).
    Run { reason: String },
}

impl FsimError {
    pub fn input(reason: impl Into<String>) -> Self {
        FsimError::Input {
            reason: reason.into(),
            excerpt: None,
        }
    }

    pub fn run(reason: impl Into<String>) -> Self {
        FsimError::Run {
            reason: reason.into(),
        }
    }

    /// Process exit code: 2 for bad input, 1 for a failed run.
    pub fn exit_code(&self) -> i32 {
        match self {
            FsimError::Input { .. } => 2,
            FsimError::Run { .. } => 1,
        }
    }
}

impl fmt::Display for FsimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            // bounded: a reason may echo case text (docs/security.md, "Numbers and messages")
            FsimError::Input { reason, .. } | FsimError::Run { reason } => {
                write!(f, "{}", bound_message(reason))
            }
        }
    }
}

impl std::error::Error for FsimError {}

impl From<crate::case::CaseError> for FsimError {
    fn from(e: crate::case::CaseError) -> Self {
        FsimError::Input {
            reason: e.to_string(),
            excerpt: e.excerpt(),
        }
    }
}

impl From<std::io::Error> for FsimError {
    fn from(e: std::io::Error) -> Self {
        FsimError::run(format!("I/O error: {e}"))
    }
}
