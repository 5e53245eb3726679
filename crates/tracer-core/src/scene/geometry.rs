//! The immutable part of a scene: world-space triangles, their breps and material slots, and the
//! BVH over them. Shared between threads behind an `Arc`; edits never touch it.

use super::error::SceneError;
use super::transform::world_from_local;
use crate::bvh::Bvh;
use crate::geometry::Aabb;
use crate::shp::{Placement, ShpDescription};
use glam::Vec3;
use std::path::PathBuf;
use std::time::Instant;

/// One brep of the scene and its material slots `first_slot .. first_slot + part_count`.
#[derive(Clone, Debug, PartialEq)]
pub struct Brep {
    pub name: String,
    pub part_count: u32,
    pub first_slot: u32,
    pub triangle_count: usize,
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
    /// Material slot of each triangle.
    pub triangle_slots: Vec<u32>,
    /// Owner of each material slot.
    pub slots: Vec<SlotOwner>,
    pub bvh: Bvh,
    pub bounds: Aabb,
    /// Wall time of the BVH build, seconds.
    pub bvh_build_secs: f64,
}

impl Scene {
    /// Applies placements and builds the BVH. Breps without a `set breps` block are placed with
    /// the identity; a placement naming no brep is ignored here (the reader reports it).
    pub fn build(desc: &ShpDescription, name: &str) -> Result<Scene, SceneError> {
        let mut breps = Vec::with_capacity(desc.breps.len());
        let mut slots = Vec::new();
        let total: usize = desc.breps.iter().map(|b| b.triangles.len()).sum();
        let mut triangles = Vec::with_capacity(total);
        let mut triangle_slots = Vec::with_capacity(total);
        let identity = Placement::default();
        for (brep_index, def) in desc.breps.iter().enumerate() {
            let placement = desc
                .placements
                .iter()
                .find(|p| p.name == def.name)
                .unwrap_or(&identity);
            let m = world_from_local(placement);
            let mut world = Vec::with_capacity(def.vertices.len());
            for v in &def.vertices {
                let p = m.transform_point3(glam::DVec3::from(*v)).as_vec3();
                if !p.is_finite() {
                    return Err(SceneError::NonFinitePlacement {
                        path: placement.source.clone(),
                        line: placement.line,
                        brep: def.name.clone(),
                    });
                }
                world.push(p);
            }
            let first_slot = slots.len() as u32;
            let part_count = def.part_count.max(1);
            slots.extend((0..part_count).map(|part| SlotOwner {
                brep: brep_index as u32,
                part,
            }));
            for (t, tri) in def.triangles.iter().enumerate() {
                let fetch = |i: u32| world.get(i as usize).copied();
                let (Some(a), Some(b), Some(c)) = (fetch(tri[0]), fetch(tri[1]), fetch(tri[2]))
                else {
                    return Err(SceneError::BadIndex {
                        brep: def.name.clone(),
                        triangle: t,
                    });
                };
                triangles.push([a, b, c]);
                let part = def.parts.get(t).copied().unwrap_or(0).min(part_count - 1);
                triangle_slots.push(first_slot + part);
            }
            breps.push(Brep {
                name: def.name.clone(),
                part_count,
                first_slot,
                triangle_count: def.triangles.len(),
            });
        }
        if triangles.is_empty() {
            return Err(SceneError::NoTriangles {
                path: desc.path.clone(),
            });
        }
        let normals = triangles
            .iter()
            .map(|[a, b, c]| (*b - *a).cross(*c - *a).normalize_or_zero())
            .collect();
        let bounds = triangles
            .iter()
            .flatten()
            .fold(Aabb::EMPTY, |b, &p| b.grow(p));
        let started = Instant::now();
        let bvh = Bvh::build(&triangles);
        let bvh_build_secs = started.elapsed().as_secs_f64();
        Ok(Scene {
            name: name.to_owned(),
            source: (!desc.path.as_os_str().is_empty()).then(|| desc.path.clone()),
            breps,
            triangles,
            normals,
            triangle_slots,
            slots,
            bvh,
            bounds,
            bvh_build_secs,
        })
    }

    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// A label for a material slot: the brep name, with `/part` when the brep has several parts.
    pub fn slot_label(&self, slot: u32) -> String {
        let Some(owner) = self.slots.get(slot as usize) else {
            return format!("slot {slot}");
        };
        let brep = &self.breps[owner.brep as usize];
        if brep.part_count > 1 {
            format!("{}/{}", brep.name, owner.part)
        } else {
            brep.name.clone()
        }
    }

    /// Finds the slots a sidecar key names: `brep` (every part) or `brep/part`.
    pub fn slots_for_key(&self, key: &str) -> Option<Vec<u32>> {
        let (name, part) = match key.rsplit_once('/') {
            Some((n, p)) => (n, Some(p.trim().parse::<u32>().ok()?)),
            None => (key, None),
        };
        let brep = self.breps.iter().find(|b| b.name == name)?;
        match part {
            Some(p) if p < brep.part_count => Some(vec![brep.first_slot + p]),
            Some(_) => None,
            None => Some((brep.first_slot..brep.first_slot + brep.part_count).collect()),
        }
    }
}
