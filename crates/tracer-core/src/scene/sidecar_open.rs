//! Opening a sidecar by itself: the scene it belongs to (NAME.raygine.toml beside NAME.shp,
//! .obj, …), or the built-in Cornell box when none is beside it (a saved box setup).

use super::{LengthUnit, LoadOptions, LoadedScene, SceneError, Sidecar, builtin_cornell_box, load};
use std::path::{Path, PathBuf};

/// The suffix of sidecar files.
pub const SIDECAR_SUFFIX: &str = ".raygine.toml";

/// Whether `path` names a sidecar (NAME.raygine.toml, any case).
pub fn is_sidecar_file(path: &Path) -> bool {
    path.file_name().is_some_and(|n| {
        n.to_string_lossy()
            .to_ascii_lowercase()
            .ends_with(SIDECAR_SUFFIX)
    })
}

/// The scene file a sidecar belongs to: NAME with a scene extension in the sidecar's folder.
pub fn scene_of_sidecar(sidecar: &Path) -> Option<PathBuf> {
    let name = sidecar.file_name()?.to_string_lossy().into_owned();
    let stem = &name[..name.len().checked_sub(SIDECAR_SUFFIX.len())?];
    let dir = sidecar.parent().unwrap_or(Path::new(""));
    crate::formats::SCENE_EXTENSIONS
        .iter()
        .flat_map(|ext| [ext.to_string(), ext.to_ascii_uppercase()])
        .map(|ext| dir.join(format!("{stem}.{ext}")))
        .find(|p| p.is_file())
}

/// Loads what a sidecar describes: its scene with it, or the built-in box with it. Returns the
/// scene's path too (None for the box).
pub fn load_sidecar(
    sidecar: &Path,
    unit: Option<LengthUnit>,
) -> Result<(LoadedScene, Option<PathBuf>), SceneError> {
    match scene_of_sidecar(sidecar) {
        Some(scene) => {
            let options = LoadOptions {
                unit,
                sidecar: Some(sidecar),
                ..LoadOptions::default()
            };
            Ok((load(&scene, &options)?, Some(scene)))
        }
        None => Ok((builtin_with_sidecar(sidecar, unit)?, None)),
    }
}

/// The built-in Cornell box set up by `sidecar`.
pub fn builtin_with_sidecar(
    sidecar: &Path,
    unit: Option<LengthUnit>,
) -> Result<LoadedScene, SceneError> {
    let mut loaded = builtin_cornell_box(unit)?;
    let text = std::fs::read_to_string(sidecar).map_err(|error| SceneError::SidecarIo {
        path: sidecar.to_owned(),
        error,
    })?;
    let parsed = Sidecar::parse(&text, sidecar)?;
    loaded.setup = parsed.apply(&loaded.scene, unit, &mut loaded.warnings);
    Ok(loaded)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn a_sidecar_finds_its_scene_or_sets_up_the_box() {
        let dir = std::env::temp_dir().join(format!("raygine-sidecar-open-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let box_setup = dir.join("cornell_box.raygine.toml");
        std::fs::write(&box_setup, "[camera]\nposition = [278.0, 273.0, -900.0]\nlook_at = [278.0, 273.0, 0.0]\nfov_deg = 30.0\n").unwrap();
        assert!(is_sidecar_file(&box_setup));
        assert_eq!(scene_of_sidecar(&box_setup), None);
        let (loaded, scene) = load_sidecar(&box_setup, None).unwrap();
        assert_eq!(scene, None);
        assert_eq!(loaded.setup.camera.fov_deg, 30.0);
        assert_eq!(loaded.setup.camera.position[2], -900.0);

        let obj = dir.join("tri.obj");
        std::fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        let side = dir.join("tri.raygine.toml");
        std::fs::write(
            &side,
            "[camera]\nposition = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_deg = 20.0\n",
        )
        .unwrap();
        assert_eq!(scene_of_sidecar(&side), Some(obj.clone()));
        let (loaded, scene) = load_sidecar(&side, None).unwrap();
        assert_eq!(scene, Some(obj));
        assert_eq!(loaded.setup.camera.fov_deg, 20.0);
        std::fs::remove_dir_all(&dir).ok();
    }
}
