//! The emitter table of a render: every drawn triangle whose material glows.

use crate::light::{EmissiveTriangle, EmitterTable};
use crate::scene::Scene;
use crate::shading::PreparedMaterial;

/// The emitter table of every drawn triangle whose material emits.
pub(super) fn emitter_table(
    scene: &Scene,
    models: &[crate::scene::Material],
    materials: &[PreparedMaterial],
    hidden: &[bool],
    front_sign: f32,
) -> EmitterTable {
    let emissive = |slot: usize| materials[slot].emission.max_element() > 0.0 && !hidden[slot];
    if !(0..materials.len()).any(emissive) {
        return EmitterTable::default();
    }
    let triangles: Vec<EmissiveTriangle> = scene
        .triangle_slots
        .iter()
        .enumerate()
        .filter(|(_, slot)| emissive(**slot as usize))
        .map(|(t, &slot)| EmissiveTriangle {
            triangle: t as u32,
            vertices: scene.triangles[t],
            front: scene.normals[t] * front_sign,
            radiance: materials[slot as usize].emission,
            sides: models[slot as usize].emission_sides,
        })
        .collect();
    EmitterTable::new(scene.triangles.len(), &triangles)
}
