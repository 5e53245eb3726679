//! A ground plane for a lone object: a grey diffuse floor (reflectance 0.2 unless edited) under
//! the object's bounds, so it stands on something and throws a shadow. It is a surface like any
//! other, listed as the brep `ground_plane`, and the light it reflects is counted as any
//! surface's is. The scene's bounds stay the object's (framing, light placement and the
//! sliders follow the object, not the plane).

use super::Material;
use super::geometry::{Brep, Scene, SlotOwner};
use glam::Vec3;

/// The ground plane's brep name.
pub const GROUND_NAME: &str = "ground_plane";

/// The ground plane's reflectance (grey, each channel).
pub const GROUND_REFLECTANCE: f32 = 0.2;

/// The ground plane's material: diffuse grey of [`GROUND_REFLECTANCE`].
pub fn ground_material() -> Material {
    Material {
        kd: [GROUND_REFLECTANCE; 3],
        ks: [0.0; 3],
        ..Material::default()
    }
}

impl Scene {
    /// Whether the scene's last brep is the ground plane.
    pub fn has_ground(&self) -> bool {
        self.breps.last().is_some_and(|b| b.name == GROUND_NAME)
    }

    /// This scene with a ground plane: a square 4 times the bounds' larger horizontal side
    /// across, centred under them, at the bounds' bottom (y), facing up. Its slot is the last.
    pub fn with_ground(&self) -> Scene {
        let b = self.bounds;
        let c = b.center();
        let half = 2.0 * b.extent().x.max(b.extent().z).max(1e-3);
        let y = b.min.y;
        let p = |x: f32, z: f32| Vec3::new(c.x + x, y, c.z + z);
        // Wound so (v1 − v0) × (v2 − v0) points up.
        let quad = [
            [p(-half, -half), p(-half, half), p(half, half)],
            [p(-half, -half), p(half, half), p(half, -half)],
        ];
        let mut own = self.own.clone();
        let first_triangle = own.len();
        own.triangles = (0..first_triangle).map(|t| self.bvh.triangle(t)).collect();
        own.triangles.extend(quad);
        let slot = self.slots.len() as u32;
        own.slots.extend([slot, slot]);
        let mut slots = self.slots.clone();
        slots.push(SlotOwner {
            brep: self.breps.len() as u32,
            part: 0,
        });
        let mut breps = self.breps.clone();
        breps.push(Brep {
            name: GROUND_NAME.to_owned(),
            part_count: 1,
            first_slot: slot,
            triangle_count: 2,
            part_names: Vec::new(),
            part_materials: Vec::new(),
            first_triangle,
            instance: None,
        });
        // Flat: zero corner normals, (0, 0) texture coordinates, no tangents.
        own.pad();
        let mut design = self.design.clone();
        design.materials.push(Some(ground_material()));
        let started = std::time::Instant::now();
        let bvh = own.build_bvh();
        Scene {
            name: self.name.clone(),
            source: self.source.clone(),
            breps,
            own,
            bvh,
            instances: self.instances.clone(),
            textures: self.textures.clone(),
            texture_sets: self.texture_sets.clone(),
            smooth_angle_deg: self.smooth_angle_deg,
            slots,
            bounds: self.bounds,
            bvh_build_secs: started.elapsed().as_secs_f64(),
            design,
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use crate::geometry::Ray;

    /// Under a lone triangle the plane is hit straight down, as a surface of its own slot,
    /// facing up; the scene without it is not.
    #[test]
    fn the_ground_lies_under_the_object_as_a_slot_of_its_own() {
        let text =
            "define breps tent\nvertices 3\n0 1 0\n1 1 0\n0 2 0\ntriangles 1\n0 1 2\nenddef\n";
        let desc = crate::shp::parse_shp(text.as_bytes(), std::path::Path::new("t.shp")).unwrap();
        let scene = Scene::build(&desc, "t").unwrap();
        assert!(!scene.has_ground());
        let g = scene.with_ground();
        assert!(g.has_ground());
        assert_eq!(g.slots.len(), scene.slots.len() + 1);
        assert_eq!(g.bounds, scene.bounds);
        let down = Ray::new(Vec3::new(2.0, 5.0, 0.5), Vec3::NEG_Y);
        assert!(scene.intersect(&down).is_none());
        let hit = g.intersect(&down).unwrap();
        assert!(
            (hit.t - 4.0).abs() < 1e-4,
            "the plane is at the bounds' bottom, y = 1"
        );
        assert_eq!(g.slot(hit.prim), g.slots.len() as u32 - 1);
        assert_eq!(g.normal(hit.prim), Vec3::Y);
        assert_eq!(g.design.materials.last().unwrap().unwrap().kd, [0.2; 3]);
    }
}
