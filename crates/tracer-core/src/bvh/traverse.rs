//! Closest-hit and any-hit traversal: slab test with a precomputed reciprocal direction,
//! nearer child first, an explicit stack, and early exit when a box starts beyond the best hit.

use glam::Vec3;

use super::triangle::RayTriangles;
use super::{Bvh, Hit, Node};
use crate::geometry::Ray;

/// Stack size used when the tree is shallow enough (almost always); deeper trees use a `Vec`.
const STACK_SIZE: usize = 64;

/// Scales each slab's exit distance up by 2 gamma(3) so rounding never culls a box the ray
/// touches (Ize, "Robust BVH Ray Traversal", 2013).
const EXIT_SCALE: f32 = 1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

#[derive(Clone, Copy, Default)]
struct StackEntry {
    node: u32,
    /// Where the ray enters the node's box.
    t_enter: f32,
}

/// A ray prepared for box tests.
struct RayBoxes {
    origin: [f32; 3],
    inv_dir: [f32; 3],
    /// Per axis: is the direction negative (then the near slab plane is `max`)?
    negative: [bool; 3],
    t_min: f32,
}

impl RayBoxes {
    fn new(ray: &Ray) -> Self {
        let inv = Vec3::ONE / ray.dir;
        Self {
            origin: ray.origin.to_array(),
            inv_dir: inv.to_array(),
            negative: [
                inv.x.is_sign_negative(),
                inv.y.is_sign_negative(),
                inv.z.is_sign_negative(),
            ],
            t_min: ray.t_min,
        }
    }

    /// Where the ray enters `node`'s box within `[t_min, t_max]`, or `f32::INFINITY` if it
    /// misses. `t_max` must be finite. A zero direction component gives `±inf` or NaN slab
    /// distances; NaN (origin on the slab plane) is dropped by the comparisons, which keeps
    /// boxes closed.
    #[inline(always)]
    fn enter(&self, node: &Node, t_max: f32) -> f32 {
        let mut near = self.t_min;
        let mut far = t_max;
        for axis in 0..3 {
            let (n, f) = if self.negative[axis] {
                (node.max[axis], node.min[axis])
            } else {
                (node.min[axis], node.max[axis])
            };
            let tn = (n - self.origin[axis]) * self.inv_dir[axis];
            let tf = (f - self.origin[axis]) * self.inv_dir[axis] * EXIT_SCALE;
            near = if tn > near { tn } else { near };
            far = if tf < far { tf } else { far };
        }
        if near <= far { near } else { f32::INFINITY }
    }
}

impl Bvh {
    /// The closest hit with `t` in `[ray.t_min, ray.t_max]`; both sides of a triangle count.
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        if self.depth < STACK_SIZE {
            self.closest(ray, &mut [StackEntry::default(); STACK_SIZE])
        } else {
            self.closest(ray, &mut vec![StackEntry::default(); self.depth + 1])
        }
    }

    /// Whether anything is hit with `t` in `[ray.t_min, ray.t_max]`; stops at the first hit.
    pub fn occluded(&self, ray: &Ray) -> bool {
        if self.depth < STACK_SIZE {
            self.any(ray, &mut [0; STACK_SIZE])
        } else {
            self.any(ray, &mut vec![0; self.depth + 1])
        }
    }

    fn closest(&self, ray: &Ray, stack: &mut [StackEntry]) -> Option<Hit> {
        let root = self.nodes.first()?;
        let boxes = RayBoxes::new(ray);
        let tri_ray = RayTriangles::new(ray);
        let mut best_t = ray.t_max;
        // Box tests need a finite limit; no hit lies at t = inf.
        let limit = |t: f32| t.min(f32::MAX);
        if boxes.enter(root, limit(best_t)) == f32::INFINITY {
            return None;
        }
        let mut best: Option<(usize, f32, f32)> = None;
        let mut sp = 0;
        let mut current = 0;
        loop {
            let node = &self.nodes[current];
            let mut next = None;
            if node.is_leaf() {
                let first = node.index as usize;
                let end = first + node.count as usize;
                for (i, tri) in self.triangles[first..end].iter().enumerate() {
                    if let Some((t, u, v)) = tri.intersect(&tri_ray, best_t) {
                        best_t = t;
                        best = Some((first + i, u, v));
                    }
                }
            } else {
                let left = node.index as usize;
                let t_left = boxes.enter(&self.nodes[left], limit(best_t));
                let t_right = boxes.enter(&self.nodes[left + 1], limit(best_t));
                let (near, t_near, far, t_far) = if t_left <= t_right {
                    (left, t_left, left + 1, t_right)
                } else {
                    (left + 1, t_right, left, t_left)
                };
                if t_near != f32::INFINITY {
                    next = Some(near);
                    if t_far != f32::INFINITY {
                        stack[sp] = StackEntry {
                            node: far as u32,
                            t_enter: t_far,
                        };
                        sp += 1;
                    }
                }
            }
            current = match next {
                Some(n) => n,
                None => loop {
                    if sp == 0 {
                        return best.map(|(i, u, v)| Hit {
                            t: best_t,
                            u,
                            v,
                            prim: self.prim_ids[i],
                        });
                    }
                    sp -= 1;
                    let entry = stack[sp];
                    if entry.t_enter <= best_t {
                        break entry.node as usize;
                    }
                },
            };
        }
    }

    fn any(&self, ray: &Ray, stack: &mut [u32]) -> bool {
        let Some(root) = self.nodes.first() else {
            return false;
        };
        let boxes = RayBoxes::new(ray);
        let tri_ray = RayTriangles::new(ray);
        let limit = ray.t_max.min(f32::MAX);
        if boxes.enter(root, limit) == f32::INFINITY {
            return false;
        }
        let mut sp = 0;
        let mut current = 0;
        loop {
            let node = &self.nodes[current];
            let mut next = None;
            if node.is_leaf() {
                let first = node.index as usize;
                let end = first + node.count as usize;
                let hit = self.triangles[first..end]
                    .iter()
                    .any(|tri| tri.intersect(&tri_ray, ray.t_max).is_some());
                if hit {
                    return true;
                }
            } else {
                let left = node.index as usize;
                let hit_left = boxes.enter(&self.nodes[left], limit) != f32::INFINITY;
                let hit_right = boxes.enter(&self.nodes[left + 1], limit) != f32::INFINITY;
                if hit_left {
                    next = Some(left);
                    if hit_right {
                        stack[sp] = left as u32 + 1;
                        sp += 1;
                    }
                } else if hit_right {
                    next = Some(left + 1);
                }
            }
            current = match next {
                Some(n) => n,
                None => {
                    if sp == 0 {
                        return false;
                    }
                    sp -= 1;
                    stack[sp] as usize
                }
            };
        }
    }
}
