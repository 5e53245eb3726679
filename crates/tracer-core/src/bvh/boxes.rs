//! A binary tree over boxes: the top level of a scene with instances, where each box is one
//! placed copy of a mesh. Built by splitting at the median of the longest axis of the boxes'
//! centres (instances are few, thousands at most, so the build is quick and the tree good
//! enough); walked nearest box first, so a closest-hit search can stop at boxes that start
//! beyond the best hit.
//!
//! ```ignore
//! let tree = BoxTree::build(&boxes);
//! tree.walk(&ray, ray.t_max, |item, t_max| /* the new t_max */ t_max);
//! ```

use super::stack::Stack;
use super::traverse::EXIT_SCALE;
use crate::geometry::{Aabb, Ray};
use std::mem::MaybeUninit;

/// Items per leaf at most.
const LEAF_ITEMS: usize = 2;

/// Traversal stack entries: one pending sibling per level. Median splits make at most
/// log2(items) + 1 levels, 33 for 2³² items.
const STACK: usize = 64;

#[derive(Clone, Debug)]
struct BoxNode {
    bounds: Aabb,
    /// Leaf: the first of its `count` entries in `BoxTree::order`. Inner node: the index of
    /// its second child (the first follows it).
    start: u32,
    /// Items of a leaf; 0 for an inner node.
    count: u32,
}

/// The tree: nodes root first, and the items in the order leaves reference them.
#[derive(Clone, Debug, Default)]
pub struct BoxTree {
    nodes: Vec<BoxNode>,
    order: Vec<u32>,
    /// The box of each entry of `order` (tested before the item is visited).
    boxes: Vec<Aabb>,
}

/// A ray prepared for slab tests.
struct Slabs {
    origin: [f32; 3],
    inv: [f32; 3],
    t_min: f32,
}

impl Slabs {
    fn new(ray: &Ray) -> Self {
        Slabs {
            origin: ray.origin.to_array(),
            inv: [1.0 / ray.dir.x, 1.0 / ray.dir.y, 1.0 / ray.dir.z],
            t_min: ray.t_min,
        }
    }

    /// Where the ray enters `b` when it meets it within `[t_min, t_max]` (exit distances
    /// scaled up as the triangle tree's are, so rounding never closes a box the ray touches).
    /// An origin on a slab plane with a zero direction gives NaN, which the comparisons drop.
    fn enter(&self, b: &Aabb, t_max: f32) -> Option<f32> {
        let (min, max) = (b.min.to_array(), b.max.to_array());
        let mut near = self.t_min;
        let mut far = t_max;
        for a in 0..3 {
            let t0 = (min[a] - self.origin[a]) * self.inv[a];
            let t1 = (max[a] - self.origin[a]) * self.inv[a];
            let (lo, hi) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
            let hi = hi * EXIT_SCALE;
            if lo > near {
                near = lo;
            }
            if hi < far {
                far = hi;
            }
        }
        (near <= far).then_some(near)
    }
}

impl BoxTree {
    /// The tree over `boxes` (an item's index is its position in the slice; empty boxes are
    /// left out).
    pub fn build(boxes: &[Aabb]) -> BoxTree {
        let mut order: Vec<u32> = (0..boxes.len() as u32)
            .filter(|&i| !boxes[i as usize].is_empty())
            .collect();
        let mut nodes = Vec::with_capacity(2 * order.len() / LEAF_ITEMS + 1);
        if !order.is_empty() {
            split(boxes, &mut order, 0, &mut nodes);
        }
        let boxes = order.iter().map(|&i| boxes[i as usize]).collect();
        BoxTree {
            nodes,
            order,
            boxes,
        }
    }

    /// Bounds of every item ([`Aabb::EMPTY`] without any).
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| n.bounds)
    }

    /// Calls `visit(item, t_max)` for each item whose box the ray meets within
    /// `[ray.t_min, t_max]`, nearest box first; `visit` returns the new `t_max` (the best hit
    /// so far), and boxes entered beyond it are skipped.
    pub fn walk(&self, ray: &Ray, mut t_max: f32, mut visit: impl FnMut(u32, f32) -> f32) -> f32 {
        let Some(root) = self.nodes.first() else {
            return t_max;
        };
        let slabs = Slabs::new(ray);
        let Some(t) = slabs.enter(&root.bounds, t_max) else {
            return t_max;
        };
        let mut buf = [MaybeUninit::uninit(); STACK];
        let mut stack = Stack::new(&mut buf);
        stack.push((0u32, t));
        while let Some((index, t_enter)) = stack.pop() {
            if t_enter > t_max {
                continue;
            }
            let node = &self.nodes[index as usize];
            if node.count > 0 {
                let start = node.start as usize;
                for k in start..start + node.count as usize {
                    if slabs.enter(&self.boxes[k], t_max).is_some() {
                        t_max = visit(self.order[k], t_max);
                    }
                }
                continue;
            }
            let (a, b) = (index + 1, node.start);
            let ta = slabs.enter(&self.nodes[a as usize].bounds, t_max);
            let tb = slabs.enter(&self.nodes[b as usize].bounds, t_max);
            match (ta, tb) {
                (Some(ta), Some(tb)) => {
                    // The nearer child is popped first.
                    if ta <= tb {
                        stack.push((b, tb));
                        stack.push((a, ta));
                    } else {
                        stack.push((a, ta));
                        stack.push((b, tb));
                    }
                }
                (Some(ta), None) => stack.push((a, ta)),
                (None, Some(tb)) => stack.push((b, tb)),
                (None, None) => {}
            }
        }
        t_max
    }

    /// Whether `test(item)` holds for some item whose box the ray meets within
    /// `[ray.t_min, ray.t_max]` (any order; stops at the first).
    pub fn any(&self, ray: &Ray, mut test: impl FnMut(u32) -> bool) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let slabs = Slabs::new(ray);
        let mut buf = [MaybeUninit::uninit(); STACK];
        let mut stack = Stack::new(&mut buf);
        stack.push(0u32);
        while let Some(index) = stack.pop() {
            let node = &self.nodes[index as usize];
            if slabs.enter(&node.bounds, ray.t_max).is_none() {
                continue;
            }
            if node.count > 0 {
                let start = node.start as usize;
                let hit = (start..start + node.count as usize).any(|k| {
                    slabs.enter(&self.boxes[k], ray.t_max).is_some() && test(self.order[k])
                });
                if hit {
                    return true;
                }
                continue;
            }
            stack.push(node.start);
            stack.push(index + 1);
        }
        false
    }
}

/// Appends the subtree over `items` (whose first entry is `offset` into the tree's order) to
/// `nodes`, reordering `items` as its leaves reference them.
fn split(boxes: &[Aabb], items: &mut [u32], offset: usize, nodes: &mut Vec<BoxNode>) {
    let bounds = items
        .iter()
        .fold(Aabb::EMPTY, |b, &i| b.union(boxes[i as usize]));
    let here = nodes.len();
    nodes.push(BoxNode {
        bounds,
        start: offset as u32,
        count: items.len() as u32,
    });
    if items.len() <= LEAF_ITEMS {
        return;
    }
    let centres = items
        .iter()
        .fold(Aabb::EMPTY, |b, &i| b.grow(boxes[i as usize].center()));
    let extent = centres.extent();
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |&a, &b| {
        let ca = boxes[a as usize].center()[axis];
        let cb = boxes[b as usize].center()[axis];
        ca.total_cmp(&cb).then(a.cmp(&b))
    });
    let (left, right) = items.split_at_mut(mid);
    split(boxes, left, offset, nodes);
    let second = nodes.len() as u32;
    split(boxes, right, offset + mid, nodes);
    nodes[here].start = second;
    nodes[here].count = 0;
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use glam::Vec3;

    fn unit_box(at: Vec3) -> Aabb {
        Aabb::EMPTY.grow(at).grow(at + Vec3::ONE)
    }

    /// Every box the ray crosses is visited, nearest first when nothing shortens the ray, and
    /// no box it misses.
    #[test]
    fn the_walk_visits_exactly_the_boxes_the_ray_crosses_nearest_first() {
        let boxes: Vec<Aabb> = (0..37)
            .map(|i| unit_box(Vec3::new(i as f32 * 2.0, (i % 3) as f32 * 2.0, 0.0)))
            .collect();
        let tree = BoxTree::build(&boxes);
        assert_eq!(tree.bounds().max.x, 73.0);
        let ray = Ray::new(Vec3::new(-5.0, 0.5, 0.5), Vec3::X);
        let mut seen = Vec::new();
        tree.walk(&ray, f32::INFINITY, |i, t| {
            seen.push(i);
            t
        });
        let expected: Vec<u32> = (0..37).filter(|i| i % 3 == 0).collect();
        let mut sorted = seen.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, expected);
        // Nearest first, but for the order of a leaf's two items.
        assert!(seen.windows(3).all(|w| w[0] < w[2]), "{seen:?}");
        assert!(tree.any(&ray, |i| i == 36));
        assert!(!tree.any(&ray, |i| i == 1));
        // A hit at t = 8 in the first box (entered at t = 5) skips the next (entered at 11).
        let mut seen = Vec::new();
        tree.walk(&ray, f32::INFINITY, |i, _| {
            seen.push(i);
            8.0
        });
        assert_eq!(seen, vec![0]);
    }

    #[test]
    fn empty_trees_and_empty_boxes_are_never_visited() {
        let tree = BoxTree::build(&[]);
        let ray = Ray::new(Vec3::ZERO, Vec3::X);
        assert_eq!(tree.walk(&ray, 5.0, |_, _| 0.0), 5.0);
        let tree = BoxTree::build(&[Aabb::EMPTY, unit_box(Vec3::new(2.0, -0.5, -0.5))]);
        let mut seen = Vec::new();
        tree.walk(&ray, f32::INFINITY, |i, t| {
            seen.push(i);
            t
        });
        assert_eq!(seen, vec![1]);
    }
}
