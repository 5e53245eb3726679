//! The built-in scene: raygine's own Cornell box (`assets/scenes/cornell_box.shp`, written from
//! the published Cornell box measurements) with its sidecar, compiled into the binary.

use super::geometry::Scene;
use super::sidecar::Sidecar;
use super::{LengthUnit, LoadedScene, SceneError};
use std::path::Path;

/// Name shown for the built-in scene.
pub const BUILTIN_NAME: &str = "Cornell box (built-in)";

const SHP: &str = include_str!("../../../../assets/scenes/cornell_box.shp");
const SIDECAR: &str = include_str!("../../../../assets/scenes/cornell_box.raygine.toml");

/// The built-in Cornell box. `unit` overrides the sidecar's millimetres.
pub fn builtin_cornell_box(unit: Option<LengthUnit>) -> Result<LoadedScene, SceneError> {
    let started = std::time::Instant::now();
    let path = Path::new("cornell_box.shp");
    let desc = crate::shp::parse_shp(SHP.as_bytes(), path)?;
    let parse_secs = started.elapsed().as_secs_f64();
    let mut scene = Scene::build(&desc, BUILTIN_NAME)?;
    scene.source = None;
    let sidecar = Sidecar::parse(SIDECAR, Path::new("cornell_box.raygine.toml"))?;
    let mut warnings = Vec::new();
    let setup = sidecar.apply(&scene, unit, &mut warnings);
    Ok(LoadedScene {
        scene,
        setup,
        warnings,
        parse_secs,
    })
}
