//! A `.shp` description in the neutral form: one mesh per brep, its `set breps` placement as a
//! matrix, numbered parts, no materials, lights or camera (Lumicept exports geometry only).

use super::description::ShpDescription;
use super::placement::world_from_local;
use crate::formats::description::{
    MeshDescription, PartDescription, PlacementDescription, SceneDescription, SceneFormat,
};
use std::borrow::Cow;

impl ShpDescription {
    /// The neutral description: breps in definition order, each with the first `set breps`
    /// block that names it (breps without one stay where they are; a placement naming no brep
    /// is ignored, the reader has reported it).
    pub fn to_scene_description(&self) -> SceneDescription {
        let meshes = self
            .breps
            .iter()
            .map(|brep| {
                let placement = self
                    .placements
                    .iter()
                    .find(|p| p.name == brep.name)
                    .map(|p| PlacementDescription {
                        world_from_local: world_from_local(p),
                        source: p.source.clone(),
                        line: p.line,
                    });
                MeshDescription {
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
                    placement,
                }
            })
            .collect();
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
