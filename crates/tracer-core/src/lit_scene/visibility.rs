//! What a ray of the render sees: the closest drawn surface and shadow tests, one by one or
//! eight at a time through the tree, skipping hidden parts.

use super::LitScene;
use crate::bvh::{Hit, PACKET};
use crate::geometry::Ray;
use glam::Vec3;

/// Fewer rays than this go one by one: a packet's set-up and lanes cost more than it saves on
/// a few rays (the hits are the same either way).
const MIN_PACKET: usize = 4;

impl LitScene<'_> {
    /// Closest hit on a drawn surface.
    pub fn closest_visible(&self, ray: &Ray) -> Option<Hit> {
        if self.any_hidden {
            self.scene.closest_drawn(ray, &self.hidden)
        } else {
            self.scene.bvh.intersect(ray)
        }
    }

    /// [`LitScene::closest_visible`] of each of `rays` into `out` (as long), eight at a time
    /// through the tree (the same hits bit for bit).
    pub fn closest_visible_many(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        if self.any_hidden {
            for (o, r) in out.iter_mut().zip(rays) {
                *o = self.closest_visible(r);
            }
            return;
        }
        for (r, o) in rays.chunks(PACKET).zip(out.chunks_mut(PACKET)) {
            if r.len() < MIN_PACKET {
                for (o, r) in o.iter_mut().zip(r) {
                    *o = self.scene.bvh.intersect(r);
                }
            } else {
                self.scene.bvh.intersect_packet(r, o);
            }
        }
    }

    /// The ray of a shadow test from `origin` towards `origin + to_target`, stopping just short
    /// of the end point.
    pub fn shadow_ray(origin: Vec3, to_target: Vec3) -> Ray {
        let mut ray = Ray::new(origin, to_target);
        ray.t_max = 1.0 - 1e-4;
        ray
    }

    /// [`LitScene::occluded`] of each shadow ray (see [`LitScene::shadow_ray`]) into `out`,
    /// eight at a time through the tree.
    pub fn occluded_many(&self, rays: &[Ray], out: &mut [bool]) {
        if self.any_hidden {
            for (o, r) in out.iter_mut().zip(rays) {
                *o = self.closest_visible(r).is_some();
            }
            return;
        }
        for (r, o) in rays.chunks(PACKET).zip(out.chunks_mut(PACKET)) {
            if r.len() < MIN_PACKET {
                for (o, r) in o.iter_mut().zip(r) {
                    *o = self.scene.bvh.occluded(r);
                }
            } else {
                self.scene.bvh.occluded_packet(r, o);
            }
        }
    }

    /// Whether a drawn surface blocks the segment `origin .. origin + to_target` (exclusive of
    /// the end point).
    pub fn occluded(&self, origin: Vec3, to_target: Vec3) -> bool {
        let ray = Self::shadow_ray(origin, to_target);
        if !self.any_hidden {
            return self.scene.bvh.occluded(&ray);
        }
        // With hidden breps, walk the closest hits and ignore hidden ones.
        self.closest_visible(&ray).is_some()
    }
}
