//! What a ray of the render sees: the closest drawn surface and shadow tests, one by one or
//! eight at a time through the tree, skipping hidden parts.

use super::LitScene;
use crate::bvh::{Hit, PACKET};
use crate::geometry::Ray;
use crate::sampling::SampleRng;
use glam::Vec3;

/// Fewer rays than this go one by one: a packet's set-up and lanes cost more than it saves on
/// a few rays (the hits are the same either way).
const MIN_PACKET: usize = 4;

impl LitScene<'_> {
    /// Closest hit on a drawn surface.
    pub fn closest_visible(&self, ray: &Ray) -> Option<Hit> {
        if self.any_cutout() {
            return self.closest_uncut(ray, |r| self.closest_shown(r));
        }
        self.closest_shown(ray)
    }

    /// Closest hit on a surface that is not hidden (alpha aside).
    #[inline]
    fn closest_shown(&self, ray: &Ray) -> Option<Hit> {
        if self.any_hidden {
            self.scene.closest_drawn(ray, &self.hidden)
        } else {
            self.scene.intersect(ray)
        }
    }

    /// Whether rays must be tested one by one against hidden parts and alpha.
    #[inline]
    fn one_by_one(&self) -> bool {
        self.any_hidden || self.any_cutout()
    }

    /// [`LitScene::closest_visible`] of each of `rays` into `out` (as long), eight at a time
    /// through the tree (the same hits bit for bit).
    pub fn closest_visible_many(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        if self.one_by_one() {
            for (o, r) in out.iter_mut().zip(rays) {
                *o = self.closest_visible(r);
            }
            return;
        }
        for (r, o) in rays.chunks(PACKET).zip(out.chunks_mut(PACKET)) {
            if r.len() < MIN_PACKET {
                for (o, r) in o.iter_mut().zip(r) {
                    *o = self.scene.intersect(r);
                }
            } else {
                self.scene.intersect_packet(r, o);
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
        if self.one_by_one() {
            for (o, r) in out.iter_mut().zip(rays) {
                *o = self.closest_visible(r).is_some();
            }
            return;
        }
        for (r, o) in rays.chunks(PACKET).zip(out.chunks_mut(PACKET)) {
            if r.len() < MIN_PACKET {
                for (o, r) in o.iter_mut().zip(r) {
                    *o = self.scene.occluded(r);
                }
            } else {
                self.scene.occluded_packet(r, o);
            }
        }
    }

    /// Whether a drawn surface blocks the segment `origin .. origin + to_target` (exclusive of
    /// the end point).
    pub fn occluded(&self, origin: Vec3, to_target: Vec3) -> bool {
        let ray = Self::shadow_ray(origin, to_target);
        if !self.one_by_one() {
            return self.scene.occluded(&ray);
        }
        // With hidden breps or alpha, walk the closest hits and skip what is not there.
        self.closest_visible(&ray).is_some()
    }

    /// The share of light that crosses the segment `origin .. origin + to_target` (exclusive of
    /// the end point): 0 when an opaque surface blocks it, else the product of the
    /// transmittances of the thin panes on it (1 without any). A pane does not deviate light,
    /// so the segment stays straight.
    #[inline]
    pub fn transmittance(&self, origin: Vec3, to_target: Vec3) -> f32 {
        if !self.panes {
            return if self.occluded(origin, to_target) {
                0.0
            } else {
                1.0
            };
        }
        self.through_panes(Self::shadow_ray(origin, to_target))
    }

    /// [`LitScene::occluded_many`], then for scenes with panes the share each blocked ray gets
    /// through them (`through`, as long as `rays`; 1 where nothing blocks, and where a pane
    /// lets light on, `blocked` turns false).
    pub fn shadow_pass_many(&self, rays: &[Ray], blocked: &mut [bool], through: &mut Vec<f32>) {
        self.occluded_many(rays, blocked);
        through.clear();
        through.resize(rays.len(), 1.0);
        if !self.panes {
            return;
        }
        for ((ray, b), t) in rays.iter().zip(blocked.iter_mut()).zip(through.iter_mut()) {
            if *b {
                *t = self.through_panes(*ray);
                *b = *t <= 0.0;
            }
        }
    }

    /// The next drawn surface along `ray` that the walk stops at, and the weight the walk
    /// carries. A thin pane on the way is passed with probability T / (T + R) (the walk goes on
    /// along the same ray, so distances and densities stay those from the ray's origin, with
    /// weight T + R), else it is where the walk stops, with weight (T + R) / R; its scattering
    /// then reflects with R ([`crate::shading::Bsdf`]), so that either way the expected weight
    /// is the pane's T and R. Without panes: [`LitScene::closest_visible`] and weight 1, and no
    /// random number is drawn.
    #[inline]
    pub fn closest_through_panes(&self, ray: &Ray, rng: &mut SampleRng) -> (Option<Hit>, f32) {
        if !self.panes {
            return (self.closest_visible(ray), 1.0);
        }
        self.walk_panes(ray, rng)
    }

    /// [`LitScene::closest_through_panes`] in a scene with panes (out of line: the scenes
    /// without them keep their hot loop as it was).
    #[inline(never)]
    #[cold]
    fn walk_panes(&self, ray: &Ray, rng: &mut SampleRng) -> (Option<Hit>, f32) {
        let mut ray = *ray;
        let length = ray.dir.length();
        let mut weight = 1.0;
        for _ in 0..32 {
            let Some(hit) = self.closest_visible(&ray) else {
                return (None, weight);
            };
            let Some(pane) = self.material_of(hit.prim).pane else {
                return (Some(hit), weight);
            };
            let cos = self.scene.normal(hit.prim).dot(ray.dir) / length;
            let (t, r) = pane.transmit_reflect(cos.abs());
            if t + r <= 0.0 {
                return (Some(hit), 0.0);
            }
            if rng.next_f32() * (t + r) >= r {
                weight *= t + r;
                ray.t_min = hit.t + self.epsilon / length;
                continue;
            }
            return (Some(hit), weight * (t + r) / r);
        }
        (None, 0.0)
    }

    /// Walks `ray`'s hits: the product of the panes' transmittances, 0 at the first opaque
    /// surface.
    #[inline(never)]
    #[cold]
    fn through_panes(&self, mut ray: Ray) -> f32 {
        let length = ray.dir.length();
        if length <= 0.0 {
            return 1.0;
        }
        let step = self.epsilon / length;
        let mut through = 1.0;
        // A ray through more than 32 panes carries nothing worth the walk.
        for _ in 0..32 {
            let Some(hit) = self.closest_visible(&ray) else {
                return through;
            };
            let Some(pane) = self.material_of(hit.prim).pane else {
                return 0.0;
            };
            let cos = self.scene.normal(hit.prim).dot(ray.dir) / length;
            through *= pane.transmittance(cos.abs());
            if through <= 0.0 {
                return 0.0;
            }
            ray.t_min = hit.t + step;
            if ray.t_min >= ray.t_max {
                return through;
            }
        }
        0.0
    }
}
