//! glTF 2.0 scenes (`.gltf` with its buffers, or binary `.glb`), read with the `gltf` crate.
//!
//! - The default scene (else the first, else every root node) is walked from its roots; each
//!   node's transform is applied to its mesh, lights and camera, so everything arrives in scene
//!   coordinates: metres, right-handed, Y up (glTF's own frame).
//! - A node with a mesh is a brep named after the node, else the mesh, else `mesh{i}` (a second
//!   brep of the same name gets `#2`, ...); its primitives are its parts, named after their
//!   materials (`primitive{j}` without one). These names are the sidecar's keys.
//! - Triangles, strips and fans; points and lines are skipped with a note. `NORMAL` gives the
//!   vertex normals for smooth shading.
//! - `KHR_lights_punctual`: point and spot lights in candela, as glTF defines them, at the node's
//!   position, spots aimed along its −Z; directional lights are skipped with a note. A file
//!   without the extension gets raygine's default light.
//! - The first perspective camera met becomes the scene's camera (looking along −Z, +Y up).
//! - Materials map as [`material`] documents.

mod buffers;
mod material;

pub use buffers::{ExternalLoader, read_beside};

use super::error::{FormatError, check_memory, read_limited};
use super::{
    CameraDescription, LightDescription, LightDistribution, MeshDescription, PartDescription,
    ReadOptions, SceneDescription, SceneFormat,
};
use glam::{DMat3, DMat4, DVec3};
use std::collections::HashMap;
use std::path::Path;

/// Triangles a primitive of `corners` indices (or vertices) makes in `mode`: the memory check
/// counts triangles, not corners (a triangle list has three per triangle).
fn triangles_of(mode: ::gltf::mesh::Mode, corners: u64) -> u64 {
    use ::gltf::mesh::Mode;
    match mode {
        Mode::Triangles => corners / 3,
        Mode::TriangleStrip | Mode::TriangleFan => corners.saturating_sub(2),
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => 0,
    }
}

/// Deepest node hierarchy walked (real files are a few levels deep; deeper is a cycle or junk).
const MAX_DEPTH: usize = 256;

/// Reads a `.gltf` or `.glb` file with the buffers it names beside it.
pub fn read(path: &Path, options: &ReadOptions) -> Result<SceneDescription, FormatError> {
    let bytes = read_limited(path, "the glTF file")?;
    let folder = path.parent().unwrap_or(Path::new("")).to_owned();
    parse(
        &bytes,
        path,
        &|relative| read_beside(&folder, relative),
        options,
    )
}

/// Parses glTF JSON or GLB bytes; `external` loads buffer files by their path relative to the
/// file's folder.
pub fn parse(
    bytes: &[u8],
    path: &Path,
    external: &ExternalLoader<'_>,
    options: &ReadOptions,
) -> Result<SceneDescription, FormatError> {
    let invalid = |e: String| FormatError::new(path, 0, format!("not a valid glTF file: {e}"));
    let raw =
        ::gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| invalid(e.to_string()))?;
    let blob = raw.blob;
    let json = raw.document.into_json();
    // gltf-json 1.4's validation looks up each primitive's POSITION accessor before checking
    // that the index exists (and panics when it does not): check that first.
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            for (semantic, index) in &primitive.attributes {
                if index.value() >= json.accessors.len() {
                    return Err(invalid(format!(
                        "meshes[{m}].primitives[{p}].attributes.{semantic:?}: accessor {} \
                         does not exist",
                        index.value()
                    )));
                }
            }
        }
    }
    let gltf = ::gltf::Document::from_json(json).map_err(|e| invalid(e.to_string()))?;
    let buffers = buffers::load(&gltf, blob.as_deref(), path, external)?;
    let images = buffers::images(&gltf, &buffers, path);
    let mut reader = Reader {
        path,
        buffers: &buffers,
        images: &images,
        emission_scale: options.emission_scale(),
        desc: SceneDescription {
            path: path.to_owned(),
            format: SceneFormat::Gltf,
            metres_per_unit: Some(1.0),
            lights: gltf.lights().map(|_| Vec::new()),
            ..SceneDescription::default()
        },
        materials: HashMap::new(),
        names: HashMap::new(),
        skipped_modes: 0,
        directional: 0,
        reused: {
            let mut users = vec![0usize; gltf.meshes().len()];
            for n in gltf.nodes() {
                if let Some(m) = n.mesh() {
                    users[m.index()] += 1;
                }
            }
            users.iter().map(|&u| u > 1).collect()
        },
        first_use: HashMap::new(),
    };
    // Counts before reading any data.
    let (triangles, vertices) =
        gltf.meshes()
            .flat_map(|m| m.primitives())
            .fold((0u64, 0u64), |(t, v), p| {
                let verts = p
                    .get(&::gltf::Semantic::Positions)
                    .map_or(0, |a| a.count() as u64);
                let corners = p.indices().map_or(verts, |a| a.count() as u64);
                let tris = triangles_of(p.mode(), corners);
                (t.saturating_add(tris), v.saturating_add(verts))
            });
    check_memory(path, 0, triangles, vertices)?;
    let scene = gltf.default_scene().or_else(|| gltf.scenes().next());
    match scene {
        Some(scene) => {
            for node in scene.nodes() {
                reader.node(&node, DMat4::IDENTITY, 0)?;
            }
        }
        None => {
            let children: std::collections::HashSet<usize> = gltf
                .nodes()
                .flat_map(|n| n.children().map(|c| c.index()).collect::<Vec<_>>())
                .collect();
            for node in gltf.nodes().filter(|n| !children.contains(&n.index())) {
                reader.node(&node, DMat4::IDENTITY, 0)?;
            }
        }
    }
    if reader.skipped_modes > 0 {
        reader.desc.notes.push(format!(
            "{}: {} primitives of points or lines are not surfaces; skipped",
            path.display(),
            reader.skipped_modes
        ));
    }
    if reader.directional > 0 {
        reader.desc.notes.push(format!(
            "{}: {} directional lights skipped (raygine has no lights at infinity yet)",
            path.display(),
            reader.directional
        ));
    }
    if reader
        .desc
        .meshes
        .iter()
        .all(|m| m.triangles.is_empty() && m.instance_of.is_none())
    {
        return Err(FormatError::new(path, 0, "no triangles: nothing to draw"));
    }
    Ok(reader.desc)
}

struct Reader<'r> {
    path: &'r Path,
    buffers: &'r [Vec<u8>],
    /// Where each of the file's images is.
    images: &'r [super::ImageSource],
    emission_scale: f32,
    desc: SceneDescription,
    /// glTF material index (None: the default material) to description index.
    materials: HashMap<Option<usize>, usize>,
    /// How many breps took each name so far.
    names: HashMap<String, usize>,
    skipped_modes: usize,
    directional: usize,
    /// Per glTF mesh: whether several nodes draw it (it is then read once, in its own frame,
    /// and each node places an instance of it).
    reused: Vec<bool>,
    /// The description mesh each reused glTF mesh was read into.
    first_use: HashMap<usize, usize>,
}

impl Reader<'_> {
    fn error(&self, what: String) -> FormatError {
        FormatError::new(self.path, 0, what)
    }

    fn node(
        &mut self,
        node: &::gltf::Node<'_>,
        parent: DMat4,
        depth: usize,
    ) -> Result<(), FormatError> {
        if depth > MAX_DEPTH {
            return Err(self.error(format!(
                "node {}: the hierarchy is deeper than {MAX_DEPTH} levels (a cycle?)",
                node.index()
            )));
        }
        let local = DMat4::from_cols_array_2d(&node.transform().matrix().map(|c| c.map(f64::from)));
        let world = parent * local;
        if !world.is_finite() {
            return Err(self.error(format!(
                "node {}: its transform is not finite",
                node.index()
            )));
        }
        if let Some(mesh) = node.mesh() {
            self.mesh(node, &mesh, world)?;
        }
        if let Some(light) = node.light() {
            self.light(node, &light, world);
        }
        if let Some(camera) = node.camera()
            && self.desc.camera.is_none()
            && let ::gltf::camera::Projection::Perspective(p) = camera.projection()
        {
            let position = world.transform_point3(DVec3::ZERO);
            let forward = world.transform_vector3(-DVec3::Z).normalize_or_zero();
            let up = world.transform_vector3(DVec3::Y).normalize_or_zero();
            if forward != DVec3::ZERO && up != DVec3::ZERO && p.yfov().is_finite() {
                self.desc.camera = Some(CameraDescription {
                    line: 0,
                    position: position.as_vec3().to_array(),
                    look_at: (position + forward).as_vec3().to_array(),
                    up: up.as_vec3().to_array(),
                    fov_deg: p.yfov().to_degrees().clamp(1.0, 170.0),
                    resolution: None,
                });
            }
        }
        for child in node.children() {
            self.node(&child, world, depth + 1)?;
        }
        Ok(())
    }

    fn mesh(
        &mut self,
        node: &::gltf::Node<'_>,
        mesh: &::gltf::Mesh<'_>,
        world: DMat4,
    ) -> Result<(), FormatError> {
        let base = node
            .name()
            .or(mesh.name())
            .map_or_else(|| format!("mesh{}", mesh.index()), str::to_owned);
        let seen = self.names.entry(base.clone()).or_insert(0);
        *seen += 1;
        let name = if *seen == 1 {
            base
        } else {
            format!("{base}#{seen}")
        };
        // A mesh several nodes draw is read once in its own frame; each node places it.
        let reused = self.reused.get(mesh.index()).copied().unwrap_or(false);
        let placement = reused.then(|| super::PlacementDescription {
            world_from_local: world,
            source: self.path.to_owned(),
            line: 0,
        });
        if let Some(&first) = self.first_use.get(&mesh.index()) {
            let parts = self.desc.meshes[first].parts.clone();
            self.desc.meshes.push(MeshDescription {
                name,
                source: self.path.to_owned(),
                parts,
                placement,
                instance_of: Some(first),
                ..MeshDescription::default()
            });
            return Ok(());
        }
        let world = if reused { DMat4::IDENTITY } else { world };
        let normal_matrix = DMat3::from_mat4(world).inverse().transpose();
        let mut out = MeshDescription {
            name: name.clone(),
            source: self.path.to_owned(),
            placement,
            ..MeshDescription::default()
        };
        let mut all_normals = true;
        for primitive in mesh.primitives() {
            let at = |why: String| {
                format!(
                    "mesh {} ({name}) primitive {}: {why}",
                    mesh.index(),
                    primitive.index()
                )
            };
            use ::gltf::mesh::Mode;
            let mode = primitive.mode();
            if !matches!(
                mode,
                Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
            ) {
                self.skipped_modes += 1;
                continue;
            }
            let Some(positions) = primitive.get(&::gltf::Semantic::Positions) else {
                return Err(self.error(at("has no POSITION".into())));
            };
            let positions = buffers::read_vec3(&positions, self.buffers)
                .map_err(|e| self.error(at(format!("POSITION: {e}"))))?;
            let normals = match primitive.get(&::gltf::Semantic::Normals) {
                Some(a) => Some(
                    buffers::read_vec3(&a, self.buffers)
                        .map_err(|e| self.error(at(format!("NORMAL: {e}"))))?,
                ),
                None => None,
            };
            let mut uvs: [Option<Vec<[f32; 2]>>; 2] = [None, None];
            // Notes on texture coordinates name the material whose textures they move.
            let material_name = primitive.material().name().map_or_else(
                || format!("material{}", primitive.material().index().unwrap_or(0)),
                str::to_owned,
            );
            for (set, uv) in uvs.iter_mut().enumerate() {
                if let Some(a) = primitive.get(&::gltf::Semantic::TexCoords(set as u32)) {
                    match buffers::read_vec2(&a, self.buffers) {
                        Ok(v) if v.len() == positions.len() => *uv = Some(v),
                        Ok(v) => self.desc.notes.push(at(format!(
                            "TEXCOORD_{set}: {} coordinates for {} vertices; material \
                             {material_name}'s textures there read at (0, 0)",
                            v.len(),
                            positions.len()
                        ))),
                        Err(e) => self.desc.notes.push(at(format!(
                            "TEXCOORD_{set}: {e}; material {material_name}'s textures there \
                             read at (0, 0)"
                        ))),
                    }
                }
            }
            let tangents = match primitive.get(&::gltf::Semantic::Tangents) {
                Some(a) => match buffers::read_vec4(&a, self.buffers) {
                    Ok(t) if t.len() == positions.len() => Some(t),
                    Ok(_) | Err(_) => {
                        self.desc.notes.push(at(
                            "TANGENT is unusable; tangents are computed (MikkTSpace)".into(),
                        ));
                        None
                    }
                },
                None => None,
            };
            let indices = match primitive.indices() {
                Some(a) => buffers::read_indices(&a, self.buffers)
                    .map_err(|e| self.error(at(format!("indices: {e}"))))?,
                None => (0..positions.len() as u32).collect(),
            };
            if let Some(&bad) = indices.iter().find(|&&i| i as usize >= positions.len()) {
                return Err(self.error(at(format!(
                    "index {bad} past the {} vertices",
                    positions.len()
                ))));
            }
            let triangles: Vec<[u32; 3]> = match mode {
                Mode::Triangles => indices
                    .chunks_exact(3)
                    .map(|t| [t[0], t[1], t[2]])
                    .collect(),
                Mode::TriangleStrip => indices
                    .windows(3)
                    .enumerate()
                    .map(|(i, w)| {
                        if i % 2 == 0 {
                            [w[0], w[1], w[2]]
                        } else {
                            [w[1], w[0], w[2]]
                        }
                    })
                    .collect(),
                _ => indices
                    .get(1..)
                    .unwrap_or_default()
                    .windows(2)
                    .map(|w| [indices[0], w[0], w[1]])
                    .collect(),
            };
            let material_key = primitive.material().index();
            let material = match self.materials.get(&material_key) {
                Some(&i) => i,
                None => {
                    let d = material::to_description(
                        &primitive.material(),
                        self.path,
                        self.emission_scale,
                        self.images,
                        &mut self.desc.notes,
                    );
                    self.desc.materials.push(d);
                    self.materials
                        .insert(material_key, self.desc.materials.len() - 1);
                    self.desc.materials.len() - 1
                }
            };
            let part_name = primitive
                .material()
                .name()
                .map_or_else(|| format!("primitive{}", primitive.index()), str::to_owned);
            let part = match out
                .parts
                .iter()
                .position(|p| p.name.as_deref() == Some(&part_name))
            {
                Some(p) => p,
                None => {
                    out.parts.push(PartDescription {
                        name: Some(part_name),
                        material: Some(material),
                        smooth: None,
                    });
                    out.parts.len() - 1
                }
            };
            let first = out.positions.len() as u32;
            for (set, uv) in uvs.iter().enumerate() {
                if uv.is_some() || !out.uvs[set].is_empty() {
                    out.uvs[set].resize(first as usize, [0.0; 2]);
                    match uv {
                        Some(v) => out.uvs[set].extend_from_slice(v),
                        None => out.uvs[set].resize(first as usize + positions.len(), [0.0; 2]),
                    }
                }
            }
            out.positions.extend(positions.iter().map(|p| {
                world
                    .transform_point3(DVec3::from(p.map(f64::from)))
                    .to_array()
            }));
            match (&normals, all_normals) {
                (Some(ns), true) if ns.len() == positions.len() => {
                    out.normals.extend(ns.iter().map(|n| {
                        (normal_matrix * DVec3::from(n.map(f64::from)))
                            .normalize_or_zero()
                            .as_vec3()
                            .to_array()
                    }))
                }
                _ => {
                    all_normals = false;
                    out.normals.clear();
                }
            }
            // Tangents only when every primitive so far gave them.
            match tangents {
                Some(ts) if out.tangents.len() == first as usize => {
                    out.tangents.extend(ts.iter().map(|t| {
                        let xyz = world
                            .transform_vector3(DVec3::new(
                                f64::from(t[0]),
                                f64::from(t[1]),
                                f64::from(t[2]),
                            ))
                            .normalize_or_zero()
                            .as_vec3();
                        let flip = if DMat3::from_mat4(world).determinant() < 0.0 {
                            -1.0
                        } else {
                            1.0
                        };
                        [xyz.x, xyz.y, xyz.z, t[3] * flip]
                    }))
                }
                _ => out.tangents.clear(),
            }
            for t in triangles {
                out.triangles.push(t.map(|i| i + first));
                out.triangle_parts.push(part as u32);
            }
        }
        for uv in &mut out.uvs {
            if !uv.is_empty() {
                uv.resize(out.positions.len(), [0.0; 2]);
            }
        }
        if !out.triangles.is_empty() {
            if reused {
                self.first_use.insert(mesh.index(), self.desc.meshes.len());
            }
            self.desc.meshes.push(out);
        }
        Ok(())
    }

    fn light(
        &mut self,
        node: &::gltf::Node<'_>,
        light: &::gltf::khr_lights_punctual::Light<'_>,
        world: DMat4,
    ) {
        use ::gltf::khr_lights_punctual::Kind;
        let position = world.transform_point3(DVec3::ZERO).as_vec3();
        let aim = world
            .transform_vector3(-DVec3::Z)
            .normalize_or_zero()
            .as_vec3();
        let intensity_cd = light.intensity().max(0.0);
        let distribution = match light.kind() {
            Kind::Directional => {
                self.directional += 1;
                return;
            }
            Kind::Point => LightDistribution::Isotropic { intensity_cd },
            Kind::Spot {
                inner_cone_angle,
                outer_cone_angle,
            } => LightDistribution::Spot {
                intensity_cd,
                cone_deg: inner_cone_angle.to_degrees().clamp(0.0, 90.0),
                falloff_deg: outer_cone_angle.to_degrees().clamp(0.0, 90.0),
            },
        };
        let name = light
            .name()
            .or(node.name())
            .map_or_else(|| format!("light{}", light.index()), str::to_owned);
        if let Some(lights) = &mut self.desc.lights {
            lights.push(LightDescription {
                name,
                source: self.path.to_owned(),
                line: 0,
                position: position.to_array(),
                aim: if aim == glam::Vec3::ZERO {
                    [0.0, -1.0, 0.0]
                } else {
                    aim.to_array()
                },
                rotation_deg: 0.0,
                color: light.color(),
                distribution,
            });
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    #[test]
    fn the_memory_check_counts_triangles_not_corners() {
        use ::gltf::mesh::Mode;
        // A 10-million-triangle list has 30 million indices; it was estimated as 30 million
        // triangles (6.2 GB instead of about 2 GB), refusing files that fit.
        assert_eq!(triangles_of(Mode::Triangles, 30_000_000), 10_000_000);
        assert_eq!(triangles_of(Mode::TriangleStrip, 12), 10);
        assert_eq!(triangles_of(Mode::TriangleFan, 1), 0);
        assert_eq!(triangles_of(Mode::Lines, 30), 0);
    }

    fn parse_text(text: &str) -> Result<SceneDescription, FormatError> {
        let external = |_: &Path| Err("no files".to_owned());
        parse(
            text.as_bytes(),
            Path::new("t.gltf"),
            &external,
            &ReadOptions::default(),
        )
    }

    #[test]
    fn an_attribute_naming_a_missing_accessor_is_an_error_not_a_panic() {
        // The fuzz find: gltf-json's validation indexed the accessors with this index.
        let e = parse_text(
            r#"{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":5}}]}],
               "accessors":[]}"#,
        )
        .expect_err("refused");
        assert!(e.to_string().contains("accessor 5 does not exist"), "{e}");
    }

    #[test]
    fn a_file_without_triangles_says_so() {
        let e = parse_text(r#"{"asset":{"version":"2.0"}}"#).expect_err("refused");
        assert_eq!(e.to_string(), "t.gltf: no triangles: nothing to draw");
    }

    /// A point light's intensity reaches the model in candela unchanged (no trip through lumen
    /// and back, which rounded it).
    #[test]
    fn point_light_candela_is_kept_exactly() {
        let d = parse_text(
            r#"{"asset":{"version":"2.0"},"extensionsUsed":["KHR_lights_punctual"],
               "extensions":{"KHR_lights_punctual":{"lights":[
                 {"type":"point","intensity":123.456,"color":[1,1,1]}]}},
               "buffers":[{"byteLength":36,
                 "uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
               "bufferViews":[{"buffer":0,"byteLength":36}],
               "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
                 "min":[0,0,0],"max":[1,1,0]}],
               "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
               "nodes":[{"mesh":0},{"extensions":{"KHR_lights_punctual":{"light":0}},
                 "translation":[0,2,0]}],
               "scenes":[{"nodes":[0,1]}],"scene":0}"#,
        )
        .expect("reads");
        let lights = d.lights.expect("lights");
        assert_eq!(
            lights[0].distribution,
            LightDistribution::Isotropic {
                intensity_cd: 123.456
            }
        );
        let model = crate::scene::light_from_description(&lights[0]);
        assert_eq!(model.intensity_cd(), Some(123.456));
    }
}
