//! The immutable part of a scene: world-space triangles, their breps and material slots, and the
//! BVH over them. Shared between threads behind an `Arc`; edits never touch it.

use super::design::Design;
use super::error::SceneError;
use crate::bvh::Bvh;
use crate::formats::SceneDescription;
use crate::geometry::Aabb;
use glam::{DMat4, Vec2, Vec3};
use std::borrow::Cow;
use std::path::PathBuf;
use std::time::Instant;

/// One brep of the scene and its material slots `first_slot .. first_slot + part_count`.
#[derive(Clone, Debug, PartialEq)]
pub struct Brep {
    pub name: String,
    pub part_count: u32,
    pub first_slot: u32,
    pub triangle_count: usize,
    /// One name per part when the format names parts (Integra `.prb`), else empty (parts are
    /// numbered).
    pub part_names: Vec<String>,
    /// The name of each part's material in the file (an Integra `.atr` attribute, an OBJ
    /// `usemtl`, a glTF material) when the file names any, else empty; "" for a part without.
    pub part_materials: Vec<String>,
}

/// Which brep and part a material slot belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SlotOwner {
    pub brep: u32,
    pub part: u32,
}

/// World-space triangles with their BVH.
#[derive(Debug)]
pub struct Scene {
    /// A short name for titles (the file stem, or "Cornell box").
    pub name: String,
    /// The file it was read from (None for the built-in scene).
    pub source: Option<PathBuf>,
    pub breps: Vec<Brep>,
    /// Triangle vertices in scene coordinates (the file's numbers after `set breps` placement).
    pub triangles: Vec<[Vec3; 3]>,
    /// Unit geometric normal per triangle, `(v1 - v0) × (v2 - v0)` normalised (zero when degenerate).
    pub normals: Vec<Vec3>,
    /// Vertex normals per triangle corner for smooth shading (unit, scene coordinates); zero
    /// for a triangle shaded flat. Empty when every triangle is flat.
    pub corner_normals: Vec<[Vec3; 3]>,
    /// The crease angle the vertex normals were averaged with, degrees (0: all flat).
    pub smooth_angle_deg: f32,
    /// Texture coordinates per triangle corner, UV set 0 and set 1 (the image's frame, v = 0
    /// at its top row); each empty when no mesh has that set.
    pub uvs: [Vec<[Vec2; 3]>; 2],
    /// Tangent (xyz unit, w the handedness: B = w · N × T) per triangle corner where a normal
    /// map needs one (scene coordinates); zero elsewhere, empty when no normal map is used.
    pub corner_tangents: Vec<[glam::Vec4; 3]>,
    /// The images the materials' maps read, each file once.
    pub textures: std::sync::Arc<[crate::texture::Texture]>,
    /// The maps of the file's textured materials (`Material::textures` indexes them).
    pub texture_sets: Vec<crate::texture::TextureSet>,
    /// Material slot of each triangle.
    pub triangle_slots: Vec<u32>,
    /// Owner of each material slot.
    pub slots: Vec<SlotOwner>,
    pub bvh: Bvh,
    pub bounds: Aabb,
    /// Wall time of the BVH build, seconds.
    pub bvh_build_secs: f64,
    /// What the file says about materials, lights, camera and unit: the setup before a sidecar.
    pub design: Design,
}

impl Scene {
    /// Places the meshes, builds the BVH and turns what the description says about materials,
    /// lights, camera and unit into the scene's [`Design`]. Takes a neutral description (or
    /// anything a reader converts into one, such as a `ShpDescription`). Curved meshes are
    /// shaded smooth with the default crease angle (see [`Scene::build_with`]).
    pub fn build<'a>(
        desc: impl Into<Cow<'a, SceneDescription>>,
        name: &str,
    ) -> Result<Scene, SceneError> {
        Self::build_with(desc, name, super::smoothing::DEFAULT_SMOOTH_ANGLE_DEG)
    }

    /// [`Scene::build`] with vertex normals averaged within `smooth_angle_deg` where the file
    /// has none (the sidecar's `smooth_angle_deg`); 0 shades every triangle flat.
    pub fn build_with<'a>(
        desc: impl Into<Cow<'a, SceneDescription>>,
        name: &str,
        smooth_angle_deg: f32,
    ) -> Result<Scene, SceneError> {
        let mut desc: Cow<'a, SceneDescription> = desc.into();
        let mut corner_normals: Vec<[Vec3; 3]> = Vec::new();
        let mut any_smooth = false;
        let mut breps = Vec::with_capacity(desc.meshes.len());
        let mut slots = Vec::new();
        let total = desc.triangle_count();
        let mut triangles = Vec::with_capacity(total);
        let mut triangle_slots = Vec::with_capacity(total);
        let mut uvs: [Vec<[Vec2; 3]>; 2] = [Vec::new(), Vec::new()];
        let mut corner_tangents: Vec<[glam::Vec4; 3]> = Vec::new();
        for (brep_index, mesh) in desc.meshes.iter().enumerate() {
            let m = mesh
                .placement
                .as_ref()
                .map_or(DMat4::IDENTITY, |p| p.world_from_local);
            let mut world = Vec::with_capacity(mesh.positions.len());
            for v in &mesh.positions {
                let p = m.transform_point3(glam::DVec3::from(*v)).as_vec3();
                if !p.is_finite() {
                    let (path, line) = mesh
                        .placement
                        .as_ref()
                        .map_or((mesh.source.clone(), mesh.line), |p| {
                            (p.source.clone(), p.line)
                        });
                    return Err(SceneError::NonFinitePlacement {
                        path,
                        line,
                        brep: mesh.name.clone(),
                    });
                }
                world.push(p);
            }
            // Normals go through the inverse transpose of the placement.
            let normal_matrix = glam::DMat3::from_mat4(m).inverse().transpose();
            // Tangents where a part's material has a normal map (in the map's UV set): they
            // need the mesh's corner normals kept; other meshes take them one by one.
            let normal_set = mesh.parts.iter().find_map(|p| {
                let maps = desc.materials.get(p.material?)?.maps.as_ref()?;
                maps.normal.as_ref().map(|n| usize::from(n.set.min(1)))
            });
            let mut mesh_normals = Vec::new();
            let first_triangle = triangles.len();
            super::smoothing::for_each_corner_normals(mesh, smooth_angle_deg, |t, corners| {
                if normal_set.is_some() {
                    mesh_normals.push(corners);
                }
                let face = mesh.triangles[t].map(|i| world.get(i as usize).copied());
                let face_normal = match face {
                    [Some(a), Some(b), Some(c)] => (b - a).cross(c - a).normalize_or_zero(),
                    _ => Vec3::ZERO,
                };
                let world = corners.and_then(|c| {
                    let out = c.map(|n| (normal_matrix * n).normalize_or_zero().as_vec3());
                    let usable = out.iter().all(|n| n.is_finite() && *n != Vec3::ZERO);
                    // Corners that all lie along the face normal (a plane) are shaded flat:
                    // the same picture, without the cost.
                    let planar = out.iter().all(|n| n.dot(face_normal).abs() >= 1.0 - 1e-6);
                    (usable && !planar).then_some(out)
                });
                if world.is_some() && !any_smooth {
                    any_smooth = true;
                    corner_normals.resize(first_triangle, [Vec3::ZERO; 3]);
                }
                if any_smooth {
                    corner_normals.push(world.unwrap_or([Vec3::ZERO; 3]));
                }
            });
            if let Some(set) = normal_set {
                let local = super::tangents::mesh_tangents(mesh, &mesh_normals, set);
                if !local.is_empty() {
                    let linear = glam::DMat3::from_mat4(m);
                    let handedness = linear.determinant().signum() as f32;
                    corner_tangents.resize(first_triangle, [glam::Vec4::ZERO; 3]);
                    corner_tangents.extend(local.iter().map(|t| {
                        t.map(|c| {
                            let xyz = (linear * c.truncate().as_dvec3()).normalize_or_zero();
                            xyz.as_vec3().extend(c.w * handedness)
                        })
                    }));
                }
            }
            let first_slot = slots.len() as u32;
            let part_count = (mesh.parts.len() as u32).max(1);
            slots.extend((0..part_count).map(|part| SlotOwner {
                brep: brep_index as u32,
                part,
            }));
            for (t, tri) in mesh.triangles.iter().enumerate() {
                let fetch = |i: u32| world.get(i as usize).copied();
                let (Some(a), Some(b), Some(c)) = (fetch(tri[0]), fetch(tri[1]), fetch(tri[2]))
                else {
                    return Err(SceneError::BadIndex {
                        brep: mesh.name.clone(),
                        triangle: t,
                    });
                };
                triangles.push([a, b, c]);
                for (set, out) in uvs.iter_mut().enumerate() {
                    let given = &mesh.uvs[set];
                    if given.is_empty() && out.is_empty() {
                        continue;
                    }
                    // Meshes before the first with this set, and corners without, read (0, 0).
                    out.resize(triangles.len() - 1, [Vec2::ZERO; 3]);
                    out.push(tri.map(|i| {
                        given
                            .get(i as usize)
                            .map_or(Vec2::ZERO, |&uv| Vec2::from(uv))
                    }));
                }
                let part = mesh
                    .triangle_parts
                    .get(t)
                    .copied()
                    .unwrap_or(0)
                    .min(part_count - 1);
                triangle_slots.push(first_slot + part);
            }
            let part_names = if mesh.parts.iter().any(|p| p.name.is_some()) {
                (0..part_count as usize)
                    .map(|i| match mesh.parts.get(i).and_then(|p| p.name.clone()) {
                        Some(n) => n,
                        None => format!("part{i}"),
                    })
                    .collect()
            } else {
                Vec::new()
            };
            let material_name = |i: usize| {
                mesh.parts
                    .get(i)
                    .and_then(|p| p.material)
                    .and_then(|m| desc.materials.get(m))
                    .map(|m| m.name.clone())
            };
            let part_materials = if (0..part_count as usize).any(|i| material_name(i).is_some()) {
                (0..part_count as usize)
                    .map(|i| material_name(i).unwrap_or_default())
                    .collect()
            } else {
                Vec::new()
            };
            breps.push(Brep {
                name: mesh.name.clone(),
                part_count,
                first_slot,
                triangle_count: mesh.triangles.len(),
                part_names,
                part_materials,
            });
        }
        if triangles.is_empty() {
            return Err(SceneError::NoTriangles {
                path: desc.path.clone(),
            });
        }
        if any_smooth {
            corner_normals.resize(triangles.len(), [Vec3::ZERO; 3]);
        }
        for out in &mut uvs {
            if !out.is_empty() {
                out.resize(triangles.len(), [Vec2::ZERO; 3]);
            }
        }
        if !corner_tangents.is_empty() {
            corner_tangents.resize(triangles.len(), [glam::Vec4::ZERO; 3]);
        }
        // The images each material names, loaded once each; a map that cannot be used is
        // noted and left out.
        let mut library = crate::texture::Library::default();
        let mut texture_sets = Vec::new();
        let mut texture_notes = Vec::new();
        let set_of_material: Vec<Option<u32>> = desc
            .materials
            .iter()
            .map(|m| {
                let at = if m.line > 0 {
                    format!("{}:{}: material {}", m.source.display(), m.line, m.name)
                } else {
                    format!("{}: material {}", m.source.display(), m.name)
                };
                let set = library.resolve(m.maps.as_deref()?, &at, &mut texture_notes);
                if set.is_empty() {
                    return None;
                }
                texture_sets.push(set);
                Some((texture_sets.len() - 1) as u32)
            })
            .collect();
        let bounds = triangles
            .iter()
            .flatten()
            .fold(Aabb::EMPTY, |b, &p| b.grow(p));
        // A description given by value has served its triangles: its vertex and index arrays
        // go before the BVH build, the peak of a load (about 30 bytes a triangle).
        if let Cow::Owned(d) = &mut desc {
            for m in &mut d.meshes {
                m.positions = Vec::new();
                m.normals = Vec::new();
                m.uvs = [Vec::new(), Vec::new()];
                m.tangents = Vec::new();
                m.triangles = Vec::new();
                m.triangle_parts = Vec::new();
            }
        }
        let started = Instant::now();
        let bvh = Bvh::build(&triangles);
        let bvh_build_secs = started.elapsed().as_secs_f64();
        // Face normals after the BVH build, whose peak they would add to.
        let normals = triangles
            .iter()
            .map(|[a, b, c]| (*b - *a).cross(*c - *a).normalize_or_zero())
            .collect();
        let first_slots: Vec<u32> = breps.iter().map(|b| b.first_slot).collect();
        let mut design =
            Design::from_description(&desc, &first_slots, slots.len(), &set_of_material);
        design.notes.extend(texture_notes);
        Ok(Scene {
            name: name.to_owned(),
            source: (!desc.path.as_os_str().is_empty()).then(|| desc.path.clone()),
            breps,
            triangles,
            normals,
            corner_normals,
            uvs,
            corner_tangents,
            textures: library.textures.into(),
            texture_sets,
            smooth_angle_deg: smooth_angle_deg.max(0.0),
            triangle_slots,
            slots,
            bvh,
            bounds,
            bvh_build_secs,
            design,
        })
    }

    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// A label for a material slot, which is also the sidecar key that `Sidecar::from_setup`
    /// (the viewer's Ctrl+S) writes for it: the brep name, with `/part` when the brep has
    /// several parts; `part` is the part's name when the format names parts
    /// (`room2/proom2_0001`), else its number (`brs_0/1`).
    pub fn slot_label(&self, slot: u32) -> String {
        let Some(owner) = self.slots.get(slot as usize) else {
            return format!("slot {slot}");
        };
        let brep = &self.breps[owner.brep as usize];
        if brep.part_count > 1 {
            format!("{}/{}", brep.name, brep.part_label(owner.part))
        } else {
            brep.name.clone()
        }
    }

    /// Finds the slots a sidecar key names: `brep` (every part), `brep/N` (part number N,
    /// from 0), `brep/NAME` or a bare part `NAME` (a part the format named; a brep of that name
    /// wins).
    pub fn slots_for_key(&self, key: &str) -> Option<Vec<u32>> {
        if let Some((name, part)) = key.rsplit_once('/') {
            let brep = self.breps.iter().find(|b| b.name == name)?;
            let part = brep.part_index(part.trim())?;
            return Some(vec![brep.first_slot + part]);
        }
        if let Some(brep) = self.breps.iter().find(|b| b.name == key) {
            return Some((brep.first_slot..brep.first_slot + brep.part_count).collect());
        }
        let mut named = self.breps.iter().filter_map(|b| {
            let i = b.part_names.iter().position(|n| n == key)?;
            Some(b.first_slot + i as u32)
        });
        let first = named.next()?;
        // A name two breps share is ambiguous: refuse rather than guess.
        named.next().is_none().then(|| vec![first])
    }
}

impl Brep {
    /// The name of the part's material in the file, when it names one.
    pub fn part_material(&self, part: u32) -> Option<&str> {
        self.part_materials
            .get(part as usize)
            .map(String::as_str)
            .filter(|n| !n.is_empty())
    }

    /// The part's name when the format names parts, else its number.
    pub fn part_label(&self, part: u32) -> String {
        self.part_names
            .get(part as usize)
            .cloned()
            .unwrap_or_else(|| part.to_string())
    }

    /// The part a key names: its number (from 0) or its name.
    pub fn part_index(&self, key: &str) -> Option<u32> {
        match key.parse::<u32>() {
            Ok(p) => (p < self.part_count).then_some(p),
            Err(_) => self
                .part_names
                .iter()
                .position(|n| n == key)
                .map(|i| i as u32),
        }
    }
}
