//! Scene queries that need no shading: the closest drawn surface along a ray (the viewer's
//! picking and hover read-outs), and the offset rays leave surfaces with.

use super::geometry::Scene;
use crate::bvh::Hit;
use crate::geometry::Ray;

impl Scene {
    /// How far a ray leaving a surface starts from it, in scene units: relative to the scene's
    /// size and its distance from the origin (f32 precision).
    pub fn ray_epsilon(&self) -> f32 {
        let b = self.bounds;
        let scale = b
            .radius()
            .max(b.min.abs().max_element())
            .max(b.max.abs().max_element());
        (scale * 2e-5).max(1e-6)
    }

    /// The closest hit along `ray` on a drawn surface: one whose material slot is not hidden
    /// (`hidden` is indexed by slot; slots past its end are drawn).
    pub fn closest_drawn(&self, ray: &Ray, hidden: &[bool]) -> Option<Hit> {
        let epsilon = self.ray_epsilon();
        let mut r = *ray;
        loop {
            let hit = self.intersect(&r)?;
            let slot = self.slot_of(hit.prim);
            if !slot.is_some_and(|s| hidden.get(s as usize).copied().unwrap_or(false)) {
                return Some(hit);
            }
            r.t_min = hit.t + epsilon / r.dir.length().max(1e-20);
        }
    }

    /// The material slot of the closest drawn surface along `ray` (picking).
    pub fn pick_slot(&self, ray: &Ray, hidden: &[bool]) -> Option<u32> {
        let hit = self.closest_drawn(ray, hidden)?;
        self.slot_of(hit.prim)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;
    use glam::Vec3;

    /// The built-in Cornell box seen through its middle: the first slot hit is the back wall
    /// unless that is hidden, then what lies behind it (nothing: the ray leaves the box).
    #[test]
    fn picks_the_closest_drawn_slot_and_skips_hidden_ones() {
        let loaded = crate::scene::builtin_cornell_box(None).unwrap();
        let scene = &loaded.scene;
        let c = scene.bounds.center();
        // From the middle of the box straight down: the floor.
        let down = Ray::new(c, Vec3::new(0.0, -1.0, 0.0));
        let floor = scene
            .pick_slot(&down, &[])
            .expect("the floor is below the middle");
        let hit = scene.closest_drawn(&down, &[]).unwrap();
        let p = c + down.dir * hit.t;
        assert!((p.y - scene.bounds.min.y).abs() < 1e-3 * scene.bounds.radius());
        // Hide the floor's slot: the ray now meets whatever is below it, or nothing.
        let mut hidden = vec![false; floor as usize + 1];
        hidden[floor as usize] = true;
        assert_ne!(scene.pick_slot(&down, &hidden), Some(floor));
    }
}
