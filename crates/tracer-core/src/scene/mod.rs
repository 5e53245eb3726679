//! From a neutral scene description (`formats`) to a renderable scene: world-space geometry with its BVH
//! ([`Scene`], immutable, shared) and the editable [`Setup`] (camera, lights, materials).

mod builtin;
mod camera;
mod default_light;
mod design;
mod environment_spec;
mod error;
mod framing;
mod geometry;
mod ground;
mod instances;
mod light;
mod light_spec;
mod lookup;
mod material;
mod material_keys;
mod notes;
mod observer;
mod pick;
mod setup;
mod sidecar;
mod sidecar_open;
mod smoothing;
mod tangents;
mod triangles;
mod units;

pub use builtin::{BUILTIN_NAME, builtin_cornell_box};
pub use camera::{
    Camera, CameraBasis, DEFAULT_FOV_DEG, Lens, MAX_FISHEYE_FOV_DEG, Projection, Radial,
};
pub use default_light::default_light;
pub use design::{Design, light_from_description, material_from_description};
pub use environment_spec::EnvironmentSpec;
pub use error::SceneError;
pub use framing::{framing_camera, framing_side, outline_areas};
pub use geometry::{Brep, Scene, SlotOwner};
pub use ground::{GROUND_NAME, GROUND_REFLECTANCE, ground_material};
pub use instances::{Instance, Instances, Prototype};
pub use light::{
    KindTag, LUMINANCE_WEIGHTS, Light, LightKind, LuminairePlacement, LuminousShape, ShapeChoice,
    Spot, luminance,
};
pub use light_spec::{GridContext, GridSpec, LightKindSpec, LightSpec, en12464_spacing_m};
pub use material::{Glazing, Material, PANE_IOR, Pbr};
pub use material_keys::MaterialKeys;
pub use notes::{SourceText, luminaire_near_surface, luminaire_shape, relative_below};
pub use observer::{Observer, check_observers};
pub use setup::Setup;
pub use sidecar::{Sidecar, sidecar_path};
pub use sidecar_open::{
    SIDECAR_SUFFIX, builtin_with_sidecar, is_sidecar_file, load_sidecar, scene_of_sidecar,
};
pub use smoothing::{DEFAULT_SMOOTH_ANGLE_DEG, corner_normals};
pub use triangles::TriangleSet;
pub use units::{Handedness, LengthUnit};

use std::path::Path;
use std::time::Instant;

/// A scene ready to render, with the setup its sidecar (or the defaults) gave it.
#[derive(Debug)]
pub struct LoadedScene {
    pub scene: Scene,
    pub setup: Setup,
    /// Non-fatal problems to show the user (unknown material keys, clamped values, unit hints).
    pub warnings: Vec<String>,
    /// Wall time of reading and parsing the files, seconds (the BVH build is in the scene).
    pub parse_secs: f64,
}

/// Where the setup comes from when loading.
#[derive(Clone, Debug, Default)]
pub struct LoadOptions<'a> {
    /// `--units`: wins over the sidecar.
    pub unit: Option<crate::scene::LengthUnit>,
    /// An explicit sidecar file instead of `NAME.raygine.toml` next to the scene.
    pub sidecar: Option<&'a Path>,
    /// `--usd-time`: the time code USD attributes are read at; wins over the sidecar.
    pub usd_time: Option<f64>,
}

/// Reads a scene file with the reader its content and extension call for (`.shp` with the
/// `.brs` files it names and any Integra bundle beside it, or a bare `.brs`), builds the scene
/// and applies its sidecar, which overrides what the file designed.
pub fn load(path: &Path, options: &LoadOptions<'_>) -> Result<LoadedScene, SceneError> {
    let started = Instant::now();
    // The sidecar first: its crease angle and emission scale shape how the file is read.
    let sidecar_file = options
        .sidecar
        .map(Path::to_path_buf)
        .unwrap_or_else(|| sidecar_path(path));
    let sidecar = match options.sidecar {
        Some(p) => Some(Sidecar::parse(
            &std::fs::read_to_string(p).map_err(|error| SceneError::SidecarIo {
                path: p.to_owned(),
                error,
            })?,
            p,
        )?),
        None => Sidecar::read_if_present(&sidecar_file)?,
    }
    .unwrap_or_default();
    let read_options = crate::formats::ReadOptions {
        emission_scale: sidecar.emission_scale,
        usd_time: options.usd_time.or(sidecar.usd_time),
        ..crate::formats::ReadOptions::default()
    };
    let desc = crate::formats::read_scene_with(path, &read_options)?;
    let parse_secs = started.elapsed().as_secs_f64();
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".to_owned());
    let smooth_angle_deg = sidecar
        .smooth_angle_deg
        .filter(|a| a.is_finite())
        .unwrap_or(DEFAULT_SMOOTH_ANGLE_DEG);
    // By value: its vertex arrays are freed before the BVH build.
    let scene = Scene::build_with(desc, &name, smooth_angle_deg)?;
    let mut warnings = scene.design.notes.clone();
    let setup = sidecar.apply(&scene, options.unit, &mut warnings);
    if let Some(hint) = setup.unit.size_hint(scene.bounds.extent().length()) {
        warnings.push(format!("hint: {hint}"));
    }
    Ok(LoadedScene {
        scene,
        setup,
        warnings,
        parse_secs,
    })
}
