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
    // Brep by brep, so that the triangles of breps with no glowing part are never visited
    // (instances of big meshes would make that slow).
    let glowing_brep = |b: &crate::scene::Brep| {
        (b.first_slot..b.first_slot + b.part_count).any(|s| emissive(s as usize))
    };
    let triangles: Vec<EmissiveTriangle> = (0..scene.breps.len())
        .filter(|&b| glowing_brep(&scene.breps[b]))
        .flat_map(|b| scene.brep_triangles(b))
        .filter_map(|t| {
            let t = t as u32;
            let slot = scene.slot(t) as usize;
            emissive(slot).then(|| EmissiveTriangle {
                triangle: t,
                vertices: scene.triangle(t),
                front: scene.normal(t) * front_sign,
                radiance: materials[slot].emission,
                sides: models[slot].emission_sides,
            })
        })
        .collect();
    EmitterTable::new(scene.triangle_count(), &triangles)
}
