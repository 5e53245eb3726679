//! The error of the readers without a grammar of their own (OBJ, glTF): one line naming the
//! file, the line (or the glTF item) and the reason.

use std::path::{Path, PathBuf};

/// A rejected scene file: the file, where in it (a 1-based line, or 0 with the item named in
/// the reason) and why.
#[derive(Debug, thiserror::Error)]
#[error("{}{}: {reason}", path.display(), if *line > 0 { format!(":{line}") } else { String::new() })]
pub struct FormatError {
    pub path: PathBuf,
    pub line: usize,
    pub reason: String,
}

impl FormatError {
    pub fn new(path: &Path, line: usize, reason: impl Into<String>) -> Self {
        Self {
            path: path.to_owned(),
            line,
            reason: reason.into(),
        }
    }
}

/// Largest scene file read whole into memory, bytes (OBJ text, glTF JSON, a `.glb`, one buffer).
pub const MAX_SCENE_FILE_BYTES: u64 = 4 << 30;

/// Refuses `triangles` and `vertices` when the scene they build would not fit in the memory the
/// machine has available (the estimate `.shp` uses), before anything is allocated for them.
pub fn check_memory(
    path: &Path,
    line: usize,
    triangles: u64,
    vertices: u64,
) -> Result<(), FormatError> {
    use super::shp::memory::{BYTES_PER_TRIANGLE, BYTES_PER_VERTEX, available_memory_bytes};
    let needed = triangles
        .saturating_mul(BYTES_PER_TRIANGLE)
        .saturating_add(vertices.saturating_mul(BYTES_PER_VERTEX));
    if triangles > u64::from(u32::MAX) || vertices > u64::from(u32::MAX) {
        return Err(FormatError::new(
            path,
            line,
            format!(
                "{triangles} triangles, {vertices} vertices: more than raygine can index (2^32)"
            ),
        ));
    }
    if needed >= 256 << 20
        && let Some(available) = available_memory_bytes()
        && needed > available
    {
        return Err(FormatError::new(
            path,
            line,
            format!(
                "{triangles} triangles need about {:.1} GB, more than the {:.1} GB available",
                needed as f64 / 1e9,
                available as f64 / 1e9
            ),
        ));
    }
    Ok(())
}

/// Reads a whole file after checking its size against [`MAX_SCENE_FILE_BYTES`].
pub fn read_limited(path: &Path, what: &str) -> Result<Vec<u8>, FormatError> {
    check_size(path, what)?;
    std::fs::read(path).map_err(|e| FormatError::new(path, 0, format!("cannot read {what}: {e}")))
}

/// The size of a file `what` names, refused above [`MAX_SCENE_FILE_BYTES`].
pub fn check_size(path: &Path, what: &str) -> Result<u64, FormatError> {
    let meta = std::fs::metadata(path)
        .map_err(|e| FormatError::new(path, 0, format!("cannot read {what}: {e}")))?;
    if meta.len() > MAX_SCENE_FILE_BYTES {
        return Err(FormatError::new(
            path,
            0,
            format!(
                "{what} of {} bytes is larger than raygine reads ({MAX_SCENE_FILE_BYTES})",
                meta.len()
            ),
        ));
    }
    Ok(meta.len())
}
