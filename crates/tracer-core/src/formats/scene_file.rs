//! Picking the scene reader for a file, by extension and content: `.shp` (with its `.brs` files,
//! and the Integra bundle when one sits beside it), a bare `.brs`, `.obj`, `.gltf`, `.glb` and
//! USD (`.usda`, `.usdc`, `.usdz`, `.usd`);
//! other extensions are read as a `.brs` when the first line with data is `vertices N`, else as
//! a `.shp`.

use super::ReadOptions;
use super::description::{SceneDescription, SceneFormat};
use super::error::FormatError;
use super::integra::{self, IntegraError};
use super::shp::{self, ShpDescription, ShpError};
use std::path::Path;

/// Why a scene file could not be read: always one line naming the file (and line).
#[derive(Debug, thiserror::Error)]
pub enum SceneFileError {
    #[error(transparent)]
    Shp(#[from] ShpError),
    #[error(transparent)]
    Integra(#[from] IntegraError),
    #[error(transparent)]
    Format(#[from] FormatError),
}

/// The extensions raygine opens as scenes (lower case), for dialogs and drag-and-drop.
pub const SCENE_EXTENSIONS: [&str; 9] = [
    "shp", "brs", "obj", "gltf", "glb", "usda", "usdc", "usdz", "usd",
];

/// Whether `path` has one of [`SCENE_EXTENSIONS`] (any case).
pub fn is_scene_file(path: &Path) -> bool {
    path.extension().is_some_and(|e| {
        let e = e.to_string_lossy().to_ascii_lowercase();
        SCENE_EXTENSIONS.contains(&e.as_str())
    })
}

/// Reads a scene file into the neutral description, with the default options.
pub fn read_scene(path: &Path) -> Result<SceneDescription, SceneFileError> {
    read_scene_with(path, &ReadOptions::default())
}

/// Reads a scene file into the neutral description.
pub fn read_scene_with(
    path: &Path,
    options: &ReadOptions,
) -> Result<SceneDescription, SceneFileError> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "obj" => return Ok(super::obj::read(path, options)?),
        "gltf" | "glb" => return Ok(super::gltf::read(path, options)?),
        "usda" | "usdc" | "usdz" | "usd" => return Ok(super::usd::read(path, options)?),
        _ => {}
    }
    let bare_brs = match ext.as_str() {
        "shp" => false,
        "brs" => true,
        _ => starts_like_brs(path),
    };
    if bare_brs {
        let bytes = std::fs::read(path).map_err(|error| ShpError::Io {
            path: path.to_path_buf(),
            error,
        })?;
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "brep".to_owned());
        let brep = shp::parse_brs(&bytes, path, &name)?;
        let mut desc = ShpDescription {
            path: path.to_path_buf(),
            breps: vec![brep],
            placements: Vec::new(),
        }
        .to_scene_description();
        desc.format = SceneFormat::Brs;
        return Ok(desc);
    }
    let mut desc = shp::load(path)?.to_scene_description();
    if let Some(bundle) = integra::Bundle::beside(path) {
        integra::read_bundle(&bundle, &mut desc)?;
    }
    Ok(desc)
}

/// Whether the first line holding data (not blank, not a `;;` comment) is `vertices ...`.
fn starts_like_brs(path: &Path) -> bool {
    use std::io::Read;
    let mut head = Vec::new();
    let read = std::fs::File::open(path).and_then(|f| f.take(64 * 1024).read_to_end(&mut head));
    if read.is_err() {
        return false;
    }
    String::from_utf8_lossy(&head)
        .lines()
        .map(|l| l.split(";;").next().unwrap_or("").trim())
        .find(|l| !l.is_empty())
        .is_some_and(|l| {
            l.split_whitespace()
                .next()
                .is_some_and(|w| w.eq_ignore_ascii_case("vertices"))
        })
}
