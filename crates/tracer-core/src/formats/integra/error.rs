//! The one error of the Integra readers: the file, the line and why, on one line.

use std::path::{Path, PathBuf};

/// A rejected Integra file. Displays as `path:line: reason` (no line when it concerns the
/// whole file).
#[derive(Debug, thiserror::Error)]
#[error("{}{}: {reason}", path.display(), if *line > 0 { format!(":{line}") } else { String::new() })]
pub struct IntegraError {
    pub path: PathBuf,
    /// 1-based line; 0 for the whole file.
    pub line: usize,
    pub reason: String,
}

impl IntegraError {
    pub fn new(path: &Path, line: usize, reason: impl Into<String>) -> Self {
        Self {
            path: path.to_owned(),
            line,
            reason: reason.into(),
        }
    }
}
