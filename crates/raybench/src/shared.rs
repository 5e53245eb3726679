//! Where the shared scenes live: `$RAYGINE_SHARED`, else the `shared/` folder beside the
//! workspace (`../shared` from the repository root).

use std::path::PathBuf;

/// The shared folder, if it exists.
pub fn shared_dir() -> Option<PathBuf> {
    if let Some(dir) = std::env::var_os("RAYGINE_SHARED") {
        return Some(PathBuf::from(dir)).filter(|p| p.is_dir());
    }
    let workspace = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    [workspace.join("../shared"), workspace.join("shared")]
        .into_iter()
        .find(|p| p.join("scenes").is_dir())
}

/// The shared folder, or an error that says how to point at it.
pub fn require_shared() -> anyhow::Result<PathBuf> {
    shared_dir().ok_or_else(|| {
        anyhow::anyhow!(
            "the shared folder was not found: set RAYGINE_SHARED to the folder holding scenes/"
        )
    })
}

/// The workspace root (for `target/release/raygine`).
pub fn workspace_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}
