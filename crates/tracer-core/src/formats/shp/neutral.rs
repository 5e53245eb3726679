//! A `.shp` description in the neutral form: one mesh per brep, its `set breps` placement as a
//! matrix, numbered parts, no materials, lights or camera (Lumicept exports geometry only).

use super::description::ShpDescription;
use super::placement::world_from_local;
use crate::formats::description::{
    MeshDescription, PartDescription, PlacementDescription, SceneDescription, SceneFormat,
};
use std::borrow::Cow;

impl ShpDescription {
    /// The neutral description: breps in definition order, each placed by the first
    /// `set breps` block that names it (breps without one stay where they are; a placement
    /// naming no brep is ignored, the reader has reported it). Each further block naming a
    /// brep places another copy of it, `NAME#2`, `NAME#3`, ..., after all breps: an instance
    /// of its geometry, stored once.
    pub fn to_scene_description(&self) -> SceneDescription {
        let placement_of = |p: &super::description::Placement| PlacementDescription {
            world_from_local: world_from_local(p),
            source: p.source.clone(),
            line: p.line,
        };
        let mut meshes: Vec<MeshDescription> = self
            .breps
            .iter()
            .map(|brep| MeshDescription {
                name: brep.name.clone(),
                source: brep.source.clone(),
                line: brep.line,
                positions: brep.vertices.clone(),
                normals: Vec::new(),
                uvs: [Vec::new(), Vec::new()],
                tangents: Vec::new(),
                triangles: brep.triangles.clone(),
                parts: vec![PartDescription::default(); brep.part_count.max(1) as usize],
                triangle_parts: brep.parts.clone(),
                placement: self
                    .placements
                    .iter()
                    .find(|p| p.name == brep.name)
                    .map(placement_of),
                instance_of: None,
            })
            .collect();
        let mut copies = vec![1usize; self.breps.len()];
        for p in &self.placements {
            let Some(b) = self.breps.iter().position(|b| b.name == p.name) else {
                continue;
            };
            copies[b] += 1;
            if copies[b] == 2 {
                // The first block placed the brep itself.
                continue;
            }
            let brep = &self.breps[b];
            meshes.push(MeshDescription {
                name: format!("{}#{}", brep.name, copies[b] - 1),
                source: p.source.clone(),
                line: p.line,
                parts: meshes[b].parts.clone(),
                placement: Some(placement_of(p)),
                instance_of: Some(b),
                ..MeshDescription::default()
            });
        }
        SceneDescription {
            path: self.path.clone(),
            format: SceneFormat::Shp,
            meshes,
            ..SceneDescription::default()
        }
    }
}

impl<'a> From<&'a ShpDescription> for Cow<'a, SceneDescription> {
    fn from(desc: &'a ShpDescription) -> Self {
        Cow::Owned(desc.to_scene_description())
    }
}
