//! The immutable part of a scene: world-space triangles, their breps and material slots, and the
//! BVH over them. Shared between threads behind an `Arc`; edits never touch it.

use super::design::Design;
use super::error::SceneError;
use super::instances::{Instance, Instances, Prototype};
use super::triangles::TriangleSet;
use crate::bvh::Bvh;
use crate::formats::{MeshDescription, SceneDescription};
use crate::geometry::Aabb;
use glam::DMat4;
use std::borrow::Cow;
use std::path::PathBuf;
use std::sync::Arc;
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
    /// Where its triangles are: its first among the scene's own triangles, or (when it is an
    /// instance of a mesh drawn several times) the instance.
    pub first_triangle: usize,
    pub instance: Option<u32>,
}

/// Which brep and part a material slot belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SlotOwner {
    pub brep: u32,
    pub part: u32,
}

/// The scene's triangles with their BVH: its own triangles in scene coordinates, and meshes
/// placed several times stored once each ([`Instances`]). Per-triangle questions go through
/// the methods below (`triangle`, `normal`, `slot`, ...), which answer for both kinds by
/// triangle id: the `prim` of a [`Hit`].
#[derive(Debug)]
pub struct Scene {
    /// A short name for titles (the file stem, or "Cornell box").
    pub name: String,
    /// The file it was read from (None for the built-in scene).
    pub source: Option<PathBuf>,
    pub breps: Vec<Brep>,
    /// The triangles drawn once, in scene coordinates (the file's numbers after `set breps`
    /// placement): ids `0 .. own.len()`.
    pub(crate) own: TriangleSet,
    /// The BVH over `own`.
    pub(super) bvh: Bvh,
    /// Meshes drawn several times: ids from `own.len()` on.
    pub(super) instances: Arc<Instances>,
    /// The crease angle the vertex normals were averaged with, degrees (0: all flat).
    pub smooth_angle_deg: f32,
    /// The images the materials' maps read, each file once.
    pub textures: std::sync::Arc<[crate::texture::Texture]>,
    /// The maps of the file's textured materials (`Material::textures` indexes them).
    pub texture_sets: Vec<crate::texture::TextureSet>,
    /// Owner of each material slot.
    pub slots: Vec<SlotOwner>,
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
    ///
    /// A mesh that another names as its [`MeshDescription::instance_of`] is stored once in its
    /// own frame, and it and each mesh naming it become instances of it.
    pub fn build_with<'a>(
        desc: impl Into<Cow<'a, SceneDescription>>,
        name: &str,
        smooth_angle_deg: f32,
    ) -> Result<Scene, SceneError> {
        Self::build_inner(desc.into(), name, smooth_angle_deg, false)
    }

    /// [`Scene::build_with`], every mesh drawn through the instance level (stored in its
    /// own frame, placed by its placement) even when it is drawn once: to compare the two
    /// levels (tests, benchmarks). Triangle ids are the same as [`Scene::build_with`] gives.
    pub fn build_instanced<'a>(
        desc: impl Into<Cow<'a, SceneDescription>>,
        name: &str,
        smooth_angle_deg: f32,
    ) -> Result<Scene, SceneError> {
        Self::build_inner(desc.into(), name, smooth_angle_deg, true)
    }

    fn build_inner(
        mut desc: Cow<'_, SceneDescription>,
        name: &str,
        smooth_angle_deg: f32,
        all_instanced: bool,
    ) -> Result<Scene, SceneError> {
        let mut reused = reused_meshes(&desc)?;
        if all_instanced {
            reused.iter_mut().for_each(|r| *r = true);
        }
        let mut breps = Vec::with_capacity(desc.meshes.len());
        let mut slots = Vec::new();
        let own_count: usize = desc
            .meshes
            .iter()
            .zip(&reused)
            .filter(|(m, r)| !**r && m.instance_of.is_none())
            .map(|(m, _)| m.triangles.len())
            .sum();
        let mut own = TriangleSet {
            triangles: Vec::with_capacity(own_count),
            slots: Vec::with_capacity(own_count),
            ..TriangleSet::default()
        };
        let mut prototypes: Vec<Prototype> = Vec::new();
        // The prototype of each reused mesh.
        let mut prototype_of: Vec<Option<u32>> = vec![None; desc.meshes.len()];
        let mut instances = Vec::new();
        let mut prototype_build_secs = 0.0;
        // Placements that flatten a reused mesh draw nothing: noted, not fatal.
        let mut flattened = Vec::new();
        for (brep_index, mesh) in desc.meshes.iter().enumerate() {
            let m = mesh
                .placement
                .as_ref()
                .map_or(DMat4::IDENTITY, |p| p.world_from_local);
            // An instance's parts are its prototype's.
            let shape = mesh.instance_of.map_or(mesh, |j| &desc.meshes[j]);
            let parts = if mesh.parts.is_empty() {
                &shape.parts
            } else {
                &mesh.parts
            };
            let first_slot = slots.len() as u32;
            let part_count = (parts.len() as u32).max(1);
            slots.extend((0..part_count).map(|part| SlotOwner {
                brep: brep_index as u32,
                part,
            }));
            let first_triangle = own.len();
            let mut instance = None;
            if reused[brep_index] || mesh.instance_of.is_some() {
                let j = mesh.instance_of.unwrap_or(brep_index);
                let p = match prototype_of[j] {
                    Some(p) => p,
                    None => {
                        let mut set = TriangleSet::default();
                        let proto = &desc.meshes[j];
                        let count = (proto.parts.len() as u32).max(1);
                        set.append_mesh(
                            proto,
                            &desc.materials,
                            DMat4::IDENTITY,
                            smooth_angle_deg,
                            0,
                            count,
                        )?;
                        set.pad();
                        let started = Instant::now();
                        let bvh = set.build_bvh();
                        prototype_build_secs += started.elapsed().as_secs_f64();
                        prototypes.push(Prototype { set, bvh });
                        prototype_of[j] = Some(prototypes.len() as u32 - 1);
                        prototypes.len() as u32 - 1
                    }
                };
                let proto = &prototypes[p as usize];
                match Instance::new(p, proto, m, brep_index as u32, first_slot) {
                    Some(placed) => {
                        instance = Some(instances.len() as u32);
                        instances.push(placed);
                    }
                    None => flattened.push(non_finite(mesh).to_string()),
                }
            } else {
                own.append_mesh(
                    mesh,
                    &desc.materials,
                    m,
                    smooth_angle_deg,
                    first_slot,
                    part_count,
                )?;
            }
            let part_names = if parts.iter().any(|p| p.name.is_some()) {
                (0..part_count as usize)
                    .map(|i| match parts.get(i).and_then(|p| p.name.clone()) {
                        Some(n) => n,
                        None => format!("part{i}"),
                    })
                    .collect()
            } else {
                Vec::new()
            };
            let material_name = |i: usize| {
                parts
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
                triangle_count: match instance {
                    Some(_) => shape.triangles.len(),
                    None => own.len() - first_triangle,
                },
                part_names,
                part_materials,
                first_triangle,
                instance,
            });
        }
        own.pad();
        let room = (crate::bvh::MAX_TRIANGLES).saturating_sub(own.len());
        let instances = Instances::new(prototypes, instances, room).ok_or_else(|| {
            SceneError::TooManyTriangles {
                path: desc.path.clone(),
                limit: crate::bvh::MAX_TRIANGLES,
            }
        })?;
        if own.is_empty() && instances.triangle_count() == 0 {
            return Err(SceneError::NoTriangles {
                path: desc.path.clone(),
            });
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
        let bounds = own
            .triangles
            .iter()
            .flatten()
            .fold(Aabb::EMPTY, |b, &p| b.grow(p))
            .union(instances.bounds());
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
        let bvh = own.build_bvh();
        let bvh_build_secs = started.elapsed().as_secs_f64() + prototype_build_secs;
        let first_slots: Vec<u32> = breps.iter().map(|b| b.first_slot).collect();
        let mut design =
            Design::from_description(&desc, &first_slots, slots.len(), &set_of_material);
        design.notes.extend(texture_notes);
        design
            .notes
            .extend(flattened.into_iter().map(|e| format!("{e}: not drawn")));
        // The build's temporaries are freed: give their memory back (a big scene's resident
        // size).
        crate::pages::release_free_memory();
        Ok(Scene {
            name: name.to_owned(),
            source: (!desc.path.as_os_str().is_empty()).then(|| desc.path.clone()),
            breps,
            own,
            bvh,
            instances: Arc::new(instances),
            textures: library.textures.into(),
            texture_sets,
            smooth_angle_deg: smooth_angle_deg.max(0.0),
            slots,
            bounds,
            bvh_build_secs,
            design,
        })
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
    ///
    /// USD names breps by prim path: a key starting with "/" is a prim path, naming the brep of
    /// that path, else a GeomSubset part (`/World/Chair/Seat`), else every brep below it
    /// (`/World/Furniture`).
    pub fn slots_for_key(&self, key: &str) -> Option<Vec<u32>> {
        if key.starts_with('/') {
            return self.slots_for_prim_path(key);
        }
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

impl Scene {
    /// [`Self::slots_for_key`] for a USD prim path.
    fn slots_for_prim_path(&self, key: &str) -> Option<Vec<u32>> {
        let all = |b: &Brep| b.first_slot..b.first_slot + b.part_count;
        if let Some(brep) = self.breps.iter().find(|b| b.name == key) {
            return Some(all(brep).collect());
        }
        if let Some((name, part)) = key.rsplit_once('/')
            && let Some(brep) = self.breps.iter().find(|b| b.name == name)
            && let Some(part) = brep.part_index(part.trim())
        {
            return Some(vec![brep.first_slot + part]);
        }
        let below = format!("{}/", key.trim_end_matches('/'));
        let slots: Vec<u32> = self
            .breps
            .iter()
            .filter(|b| b.name.starts_with(&below))
            .flat_map(all)
            .collect();
        (!slots.is_empty()).then_some(slots)
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

/// Which meshes other meshes name as their `instance_of` (they become prototypes); an error
/// for a name past the meshes, or one naming an instance itself.
fn reused_meshes(desc: &SceneDescription) -> Result<Vec<bool>, SceneError> {
    let mut reused = vec![false; desc.meshes.len()];
    for (i, mesh) in desc.meshes.iter().enumerate() {
        let Some(j) = mesh.instance_of else {
            continue;
        };
        let valid = j < i && desc.meshes[j].instance_of.is_none();
        if !valid {
            return Err(SceneError::BadInstance {
                path: mesh.source.clone(),
                line: mesh.line,
                brep: mesh.name.clone(),
            });
        }
        reused[j] = true;
    }
    Ok(reused)
}

/// The error for a placement that is not finite or not invertible.
fn non_finite(mesh: &MeshDescription) -> SceneError {
    let (path, line) = mesh.placement_source();
    SceneError::SingularPlacement {
        path,
        line,
        brep: mesh.name.clone(),
    }
}
