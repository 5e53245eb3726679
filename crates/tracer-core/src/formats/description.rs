//! The format-neutral scene description every scene reader produces and `scene::Scene::build`
//! consumes: meshes with named parts and optional vertex normals, and the materials, lights and
//! camera a format carries. Plain data, each item with the file and line it came from; no reader
//! knows the scene builder and the builder knows no format.
//!
//! Units: lengths in the scene unit (`metres_per_unit` when the format says it), reflectances
//! as fractions in 0..=1 (linear RGB), flux in lumen, intensity in candela, luminance in cd/m².

use crate::light::{EmissionSides, Photometry};
use crate::texture::{Maps, TextureRef};
use glam::DMat4;
use std::borrow::Cow;
use std::path::PathBuf;
use std::sync::Arc;

/// Which reader produced a description.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SceneFormat {
    /// Lumicept `.shp` (with any `NAME.brs` it names).
    #[default]
    Shp,
    /// A bare IPUR `.brs` brep file.
    Brs,
    /// An Integra bundle: `.shp` + `NAME.brs` + `NAME.prb` + folder `NAME/` (`.atr`, `.prb`,
    /// `.lgt`, `.cam`).
    Integra,
    /// Wavefront OBJ (with the MTL files it names).
    Obj,
    /// glTF 2.0 (`.gltf` with its buffers, or binary `.glb`).
    Gltf,
    /// USD (`.usda`, `.usdc`, `.usdz`, `.usd`) with the layers it composes.
    Usd,
}

/// Everything a reader found in a scene file (and the files it pulled in).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneDescription {
    /// The file opened.
    pub path: PathBuf,
    pub format: SceneFormat,
    pub meshes: Vec<MeshDescription>,
    /// Materials that parts refer to by index ([`PartDescription::material`]).
    pub materials: Vec<MaterialDescription>,
    /// Lights as designed: None when the format says nothing about lights (raygine places a
    /// default one), empty when the design has none lit.
    pub lights: Option<Vec<LightDescription>>,
    pub camera: Option<CameraDescription>,
    /// Place, time and orientation for the sun, when the format gives them (Integra's
    /// `Geography`), as the sidecar's `[daylight]` writes them.
    pub daylight: Option<crate::light::daylight::DaylightSpec>,
    /// Light from every direction at infinity, when the format designs it (USD's DomeLight).
    pub environment: Option<crate::light::Environment>,
    /// A directional light at infinity (USD's DistantLight).
    pub sun: Option<crate::light::DistantSun>,
    /// Length of one scene unit in metres, when the format states it (Integra: 1).
    pub metres_per_unit: Option<f32>,
    /// Non-fatal findings for the user: skipped blocks, features drawn without, clamped values.
    pub notes: Vec<String>,
}

/// One mesh (a brep, an OBJ group, a glTF primitive): triangles over local positions, grouped
/// into parts (material slots).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshDescription {
    pub name: String,
    /// The file and 1-based line the mesh starts at.
    pub source: PathBuf,
    pub line: usize,
    /// Positions in local coordinates (the scene unit).
    pub positions: Vec<[f64; 3]>,
    /// Vertex normals, one per position (unit length, pointing out of the visible side); empty
    /// when the format has none (the geometric normal is used).
    pub normals: Vec<[f32; 3]>,
    /// Texture coordinates per position, set 0 and set 1 (glTF `TEXCOORD_0/1`, OBJ `vt` as
    /// set 0), in the image's frame: v = 0 at the image's top row. Empty when the mesh has none.
    pub uvs: [Vec<[f32; 2]>; 2],
    /// Tangents per position (xyz unit, w ±1: B = w · N × T), when the file gives them (glTF
    /// `TANGENT`); else empty and computed where a normal map needs them.
    pub tangents: Vec<[f32; 4]>,
    /// Vertex indices into `positions`, three per triangle.
    pub triangles: Vec<[u32; 3]>,
    /// The parts, at least one when the mesh has triangles.
    pub parts: Vec<PartDescription>,
    /// Part index of each triangle (`< parts.len()`); empty: every triangle is part 0.
    pub triangle_parts: Vec<u32>,
    /// Where the mesh is placed in the scene (None: the identity).
    pub placement: Option<PlacementDescription>,
    /// Another mesh (an earlier one, not itself an instance) whose geometry this one draws,
    /// placed by its own `placement` (a glTF node reusing a mesh, a brep placed by several
    /// `set breps` blocks). Its positions and triangles are then empty, and its parts are the
    /// other's (copied, or empty to take them). The scene stores such geometry once.
    pub instance_of: Option<usize>,
}

/// One part of a mesh: a material slot.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PartDescription {
    /// The part's name when the format gives one (`proom2_0001`); else the slot is numbered.
    pub name: Option<String>,
    /// Index into [`SceneDescription::materials`] (None: the default material).
    pub material: Option<usize>,
    /// What the format says of shading: `Some(false)` flat (Integra `shading flat`),
    /// `Some(true)` smooth, None when it does not say (smooth, as raygine's default).
    pub smooth: Option<bool>,
}

/// The matrix taking a mesh's local coordinates to scene coordinates, and where it was written.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacementDescription {
    pub world_from_local: DMat4,
    pub source: PathBuf,
    pub line: usize,
}

/// A surface material in the terms raygine's model uses; the reader does the format's mapping.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MaterialDescription {
    pub name: String,
    pub source: PathBuf,
    pub line: usize,
    /// Diffuse reflectance per channel (linear RGB, 0..=1).
    pub diffuse: [f32; 3],
    /// Reflectance of the specular lobe per channel (0..=1).
    pub specular: [f32; 3],
    /// Blinn-Phong exponent of the specular lobe (0: a perfect mirror when `specular` > 0).
    pub glossiness: f32,
    /// Light let through the surface, when the format says any is.
    pub transmission: Option<TransmissionDescription>,
    /// Light the surface emits itself.
    pub emission: Option<EmissionDescription>,
    /// glTF's metallic-roughness model when the format gives it: raygine then draws it instead
    /// of `diffuse`, `specular` and `glossiness` (which stay a Blinn-Phong approximation for
    /// readers of the description) and instead of `transmission`.
    pub metal_rough: Option<MetalRoughDescription>,
    /// Image textures and alpha, when the material has any.
    pub maps: Option<Box<Maps<TextureRef<ImageSource>>>>,
}

/// Where a texture's image is.
#[derive(Clone, Debug, PartialEq)]
pub enum ImageSource {
    /// A file (absolute, or relative to the working folder).
    File(PathBuf),
    /// Bytes inside the scene file (a glTF buffer view or data URI); `name` for the user
    /// (`model.glb#image2`).
    Embedded { name: String, bytes: Arc<[u8]> },
    /// An image the file names but that cannot be found, and why.
    Missing { name: String, why: String },
}

impl ImageSource {
    /// What identifies the image: materials with the same key share one texture.
    pub fn key(&self) -> String {
        match self {
            ImageSource::File(p) => std::fs::canonicalize(p)
                .unwrap_or_else(|_| p.clone())
                .display()
                .to_string(),
            ImageSource::Embedded { name, .. } | ImageSource::Missing { name, .. } => name.clone(),
        }
    }

    /// A name for the user.
    pub fn name(&self) -> String {
        match self {
            ImageSource::File(p) => p.display().to_string(),
            ImageSource::Embedded { name, .. } | ImageSource::Missing { name, .. } => name.clone(),
        }
    }
}

/// glTF 2.0's metallic-roughness parameters (fractions in 0..=1, linear RGB).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetalRoughDescription {
    pub base_color: [f32; 3],
    pub metallic: f32,
    pub roughness: f32,
    /// Thin-walled transmission of the dielectric (`KHR_materials_transmission`).
    pub transmission: f32,
    /// Refractive index of the dielectric layer (`KHR_materials_ior`, 1.5 by default).
    pub ior: f32,
}

/// Transmission as formats describe it (fractions of the incident light).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TransmissionDescription {
    /// Specular (clear) transmittance, 0..=1.
    pub specular: f32,
    /// Diffuse (frosted) transmittance, 0..=1.
    pub diffuse: f32,
    /// Index of refraction (1: no bending).
    pub ior: f32,
}

/// A Lambertian emitter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmissionDescription {
    pub luminance_cd_m2: f32,
    /// RGB tint (any scale; the builder normalises it to luminance 1).
    pub color: [f32; 3],
    pub sides: EmissionSides,
}

/// A placed light source.
#[derive(Clone, Debug, PartialEq)]
pub struct LightDescription {
    pub name: String,
    pub source: PathBuf,
    pub line: usize,
    /// Position in scene coordinates.
    pub position: [f32; 3],
    /// The photometric axis (nadir of a distribution), any length.
    pub aim: [f32; 3],
    /// Turn of the C planes about the aim, degrees.
    pub rotation_deg: f32,
    /// RGB tint (any scale; normalised to luminance 1 when rendering, so flux stays lumen).
    pub color: [f32; 3],
    pub distribution: LightDistribution,
}

/// How a light's intensity varies with direction.
#[derive(Clone, Debug, PartialEq)]
pub enum LightDistribution {
    /// The same intensity (cd) everywhere.
    Isotropic { intensity_cd: f32 },
    /// A spot: `intensity_cd` on the axis, full out to `cone_deg`, zero from `falloff_deg`.
    Spot {
        intensity_cd: f32,
        cone_deg: f32,
        falloff_deg: f32,
    },
    /// A tabulated distribution already in candela; `label` names it (file, diagram).
    Goniometric {
        photometry: Photometry,
        label: String,
    },
}

/// A pinhole camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraDescription {
    pub line: usize,
    pub position: [f32; 3],
    pub look_at: [f32; 3],
    pub up: [f32; 3],
    /// Vertical field of view, degrees.
    pub fov_deg: f32,
    /// The image size the scene was designed for, pixels (width, height).
    pub resolution: Option<[u32; 2]>,
}

impl MeshDescription {
    /// The file and line that place the mesh: its placement's, else the mesh's own.
    pub fn placement_source(&self) -> (PathBuf, usize) {
        self.placement
            .as_ref()
            .map_or((self.source.clone(), self.line), |p| {
                (p.source.clone(), p.line)
            })
    }
}

impl SceneDescription {
    /// Total number of triangles over all meshes.
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.triangles.len()).sum()
    }
}

impl<'a> From<&'a SceneDescription> for Cow<'a, SceneDescription> {
    fn from(desc: &'a SceneDescription) -> Self {
        Cow::Borrowed(desc)
    }
}

impl From<SceneDescription> for Cow<'_, SceneDescription> {
    fn from(desc: SceneDescription) -> Self {
        Cow::Owned(desc)
    }
}

impl EmissionDescription {
    /// Emission a format gives as a colour without a unit (OBJ `Ke`, glTF emissive): `None` when
    /// black, else a Lambertian emitter of `scale` cd/m² per unit of the colour's luminance, with
    /// a note for the user naming the key (`at` names the material, `what` the format's word).
    pub fn from_unitless(
        rgb: [f32; 3],
        scale: f32,
        sides: EmissionSides,
        at: &str,
        what: &str,
        notes: &mut Vec<String>,
    ) -> Option<EmissionDescription> {
        let rgb = rgb.map(|c| c.max(0.0));
        if rgb.iter().all(|&c| c <= 0.0) {
            return None;
        }
        let luminance_cd_m2 = scale * crate::light::luminance(glam::Vec3::from(rgb));
        notes.push(format!(
            "{at}: {what} ({} {} {}) has no photometric unit: glows at {luminance_cd_m2} cd/m² \
             (emission_scale = {scale} cd/m² per unit, a sidecar key)",
            rgb[0], rgb[1], rgb[2]
        ));
        Some(EmissionDescription {
            luminance_cd_m2,
            color: rgb,
            sides,
        })
    }
}
