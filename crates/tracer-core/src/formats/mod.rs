//! One module per file format: each turns a file into plain data and knows nothing of the scene
//! builder. Scene readers produce the neutral [`SceneDescription`]; [`read_scene`] picks one.
//!
//! - [`shp`]: Lumicept `.shp` and IPUR `.brs` geometry.
//! - [`integra`]: the Integra bundle beside a `.shp` (`.atr`, `.prb`, `.lgt`, `.cam`).
//! - [`ies`]: IES LM-63 photometric files (1986/1991, 1995, 2002, 2019).
//! - [`ldt`]: EULUMDAT photometric files.
//! - [`obj`]: Wavefront OBJ with MTL materials.
//! - [`gltf`]: glTF 2.0 (`.gltf`, `.glb`) with punctual lights and cameras.
//! - [`usd`]: USD (`.usda`, `.usdc`, `.usdz`, `.usd`) composed, with UsdLux lights,
//!   UsdPreviewSurface materials and cameras.
//! - [`metal_rough`]: the metallic-roughness mapping glTF and USD share.

pub mod description;
pub mod error;
pub mod gltf;
pub mod ies;
pub mod integra;
pub mod ldt;
pub(crate) mod metal_rough;
pub mod obj;
mod scene_file;
pub mod shp;
pub mod usd;

pub use description::{
    CameraDescription, EmissionDescription, ImageSource, LightDescription, LightDistribution,
    MaterialDescription, MeshDescription, MetalRoughDescription, PartDescription,
    PlacementDescription, SceneDescription, SceneFormat, TransmissionDescription,
};
pub use error::FormatError;
pub use scene_file::{
    SCENE_EXTENSIONS, SceneFileError, is_scene_file, read_scene, read_scene_with,
};

/// What the sidecar says about reading a file (before the scene is built).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReadOptions {
    /// cd/m² per unit of OBJ `Ke` and glTF emissive (None: 1).
    pub emission_scale: Option<f32>,
    /// The USD time code attributes are read at (`--usd-time`, the sidecar's `usd_time`);
    /// None: their default values.
    pub usd_time: Option<f64>,
    /// How long a USD file's trial read may take, seconds (None: `RAYGINE_USD_TRIAL_SECS`,
    /// else 60 s and 2 s a megabyte).
    pub usd_trial_secs: Option<f64>,
}

impl ReadOptions {
    /// The emission scale in use (1 cd/m² per unit unless the sidecar says otherwise).
    pub fn emission_scale(&self) -> f32 {
        self.emission_scale
            .filter(|s| s.is_finite() && *s >= 0.0)
            .unwrap_or(1.0)
    }
}

use crate::light::Photometry;
use std::path::{Path, PathBuf};

/// Largest photometric file read (bytes): real files are a few hundred kB at most.
pub const MAX_PHOTOMETRY_BYTES: u64 = 16 << 20;
/// Largest number of angles on either axis, checked before allocating.
pub const MAX_ANGLES: usize = 100_000;
/// Largest number of intensity values.
pub const MAX_VALUES: usize = 4_000_000;

/// A rejected photometric file: the file, the line (1-based; 0 for the whole file) and why.
#[derive(Debug, thiserror::Error)]
#[error("{}{}: {reason}", path.display(), if *line > 0 { format!(":{line}") } else { String::new() })]
pub struct PhotometryFileError {
    pub path: PathBuf,
    pub line: usize,
    pub reason: String,
}

impl PhotometryFileError {
    pub fn new(path: &Path, line: usize, reason: impl Into<String>) -> Self {
        Self {
            path: path.to_owned(),
            line,
            reason: reason.into(),
        }
    }
}

/// Reads an `.ies` or `.ldt` file (chosen by extension, else by content).
pub fn read_photometry(path: &Path) -> Result<Photometry, PhotometryFileError> {
    let meta = std::fs::metadata(path)
        .map_err(|e| PhotometryFileError::new(path, 0, format!("cannot read: {e}")))?;
    if meta.len() > MAX_PHOTOMETRY_BYTES {
        return Err(PhotometryFileError::new(
            path,
            0,
            format!(
                "{} bytes: larger than any photometric file ({MAX_PHOTOMETRY_BYTES})",
                meta.len()
            ),
        ));
    }
    let bytes = std::fs::read(path)
        .map_err(|e| PhotometryFileError::new(path, 0, format!("cannot read: {e}")))?;
    parse_photometry(&bytes, path)
}

/// Parses photometric file content; `path` names it in errors and picks the format by its
/// extension (`.ldt` is EULUMDAT, anything else is tried as IES unless it has no IES marker and
/// looks like EULUMDAT).
pub fn parse_photometry(bytes: &[u8], path: &Path) -> Result<Photometry, PhotometryFileError> {
    let text = decode_text(bytes).map_err(|r| PhotometryFileError::new(path, 0, r))?;
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "ldt" | "eul" => ldt::parse(&text, path),
        "ies" => ies::parse(&text, path),
        _ if text.contains("TILT=") || text.contains("TILT =") => ies::parse(&text, path),
        _ => ldt::parse(&text, path),
    }
}

/// The file as text: UTF-8, else Latin-1 (old EULUMDAT files); binary data is refused.
fn decode_text(bytes: &[u8]) -> Result<String, String> {
    let control = bytes
        .iter()
        .filter(|&&b| b < 0x20 && !matches!(b, b'\n' | b'\r' | b'\t' | 0x0c | 0x1a))
        .count();
    if bytes.contains(&0) || control > 0 {
        return Err("binary data: not a text photometric file".into());
    }
    Ok(match std::str::from_utf8(bytes) {
        Ok(s) => s.to_owned(),
        Err(_) => bytes.iter().map(|&b| char::from(b)).collect(),
    })
}

/// The symmetry a file's planes leave out, to be unfolded to a full 0–360° table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Symmetry {
    /// One plane: the same in every C plane.
    Rotational,
    /// Planes 0–90: mirrored about the C0–C180 and C90–C270 planes.
    Quadrants,
    /// Planes 0–180 (or 180–360): mirrored about the C0–C180 plane.
    AboutC0C180,
    /// Planes 90–270 (or 270–90 through 0): mirrored about the C90–C270 plane.
    AboutC90C270,
    /// Planes all around.
    None,
}

/// Adds the planes that `symmetry` implies (C → 360 − C, C → 180 − C, ...).
pub(crate) fn unfold(
    symmetry: Symmetry,
    planes: Vec<crate::light::Plane>,
) -> Vec<crate::light::Plane> {
    let mirror = |planes: &[crate::light::Plane], f: &dyn Fn(f32) -> f32| {
        planes
            .iter()
            .map(|p| crate::light::Plane {
                c_deg: f(p.c_deg).rem_euclid(360.0),
                cd: p.cd.clone(),
            })
            .collect::<Vec<_>>()
    };
    let mut out = planes.clone();
    match symmetry {
        Symmetry::Rotational | Symmetry::None => {}
        Symmetry::AboutC0C180 => out.extend(mirror(&planes, &|c| 360.0 - c)),
        Symmetry::AboutC90C270 => out.extend(mirror(&planes, &|c| 180.0 - c)),
        Symmetry::Quadrants => {
            let half: Vec<_> = planes
                .iter()
                .cloned()
                .chain(mirror(&planes, &|c| 180.0 - c))
                .collect();
            out = half.clone();
            out.extend(mirror(&half, &|c| 360.0 - c));
        }
    }
    // A mirrored 0 lands on 360 (rem_euclid gives 0): keep the planes in 0..360 and let the
    // table add its 360 copy.
    out
}
