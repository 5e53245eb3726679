//! Closest-hit and any-hit traversal of the wide tree: one ray against all of a node's boxes
//! (a slab test with a precomputed reciprocal direction; eight lanes in one AVX register when
//! the CPU has AVX2, else two groups of four), the children hit visited nearest first from an
//! explicit stack, and early exit when a box starts beyond the best hit. The traversal is
//! written once, generic over the node test, and compiled twice.

use super::simd::F4;
#[cfg(target_arch = "x86_64")]
use super::simd::{Avx2, Slabs8};
use std::mem::MaybeUninit;

use super::stack::Stack;
use super::triangle::{RayTriangles, closer};
use super::wide::{EMPTY, GROUPS, LANES, LEAF_BIT, WIDTH, WideNode, leaf_range};
use super::{Bvh, Hit};
use crate::geometry::Ray;

/// Levels handled by the fixed-size stack (almost always enough); deeper trees use a `Vec`.
pub(super) const STACK_LEVELS: usize = 24;
pub(super) const STACK_SIZE: usize = STACK_LEVELS * (WIDTH - 1) + 1;

/// How far past the best hit (relative to `t` and to the ray's origin over its direction) boxes
/// are still opened. A triangle hit at `t` lies in boxes the ray enters no later than `t`
/// exactly, but the rounded entry distance can come out a few ulps later than the rounded `t`;
/// without the margin such a box could be skipped when it holds a triangle hit at the same `t`
/// with a smaller id, and which triangle wins a tie would depend on the order boxes are opened
/// in (node test, single ray or packet). With it every tie is seen, and every traversal returns
/// the least (t, id), as the brute-force reference does.
pub(super) const CULL_SLACK: f32 = 16.0 * f32::EPSILON;

/// Per ray: the absolute part of the cull margin (origin over direction per axis, the scale of
/// the rounding in slab and triangle distances; axes the ray does not move along are exact).
/// Three lanes at once and no branch: this is on every ray's path, as the packets compute it
/// in lanes (the same operations, so the same value).
#[inline(always)]
pub(super) fn cull_reach(origin: [f32; 3], inv_dir: [f32; 3]) -> f32 {
    let inv = F4::load(&[inv_dir[0], inv_dir[1], inv_dir[2], 0.0]);
    let o = F4::load(&[origin[0], origin[1], origin[2], 0.0]);
    let moved = inv.abs().lt(F4::splat(f32::INFINITY));
    let along = (o * inv).abs().keep(moved).to_array();
    // NaN `along` (a NaN origin) keeps `reach`, as `max_or` does in lanes.
    let mut reach = 0.0f32;
    for a in along.into_iter().take(3) {
        reach = if a > reach { a } else { reach };
    }
    reach * CULL_SLACK
}

/// The distance up to which boxes are opened when the best hit so far is at `t` (finite, as
/// box tests need).
#[inline(always)]
pub(super) fn cull_limit(t: f32, reach: f32) -> f32 {
    let limit = t + t.abs() * CULL_SLACK + reach;
    // `+inf` and NaN become `f32::MAX`, as `f32::min` would give, in one compare and select.
    if limit < f32::MAX { limit } else { f32::MAX }
}

/// Scales each slab's exit distance up so rounding never culls a box the ray touches: 2 gamma(4)
/// covers the subtraction, the product and the rounded reciprocal and its scaling (Ize, "Robust
/// BVH Ray Traversal", 2013).
pub(super) const EXIT_SCALE: f32 =
    1.0 + 2.0 * (4.0 * f32::EPSILON * 0.5) / (1.0 - 4.0 * f32::EPSILON * 0.5);

#[derive(Clone, Copy, Default)]
struct StackEntry {
    /// A child reference (see `wide.rs`).
    child: u32,
    /// Where the ray enters the child's box.
    t_enter: f32,
}

/// A ray prepared for box tests.
#[derive(Clone, Copy)]
struct RayBoxes {
    origin: [f32; 3],
    inv_dir: [f32; 3],
    /// `inv_dir` scaled by [`EXIT_SCALE`], for exit distances.
    inv_dir_exit: [f32; 3],
    /// Per axis, the `WideNode::bounds` row the ray enters through (the maximum when the
    /// direction is negative) and the row it leaves through.
    near_row: [usize; 3],
    far_row: [usize; 3],
    t_min: f32,
}

impl RayBoxes {
    /// See [`cull_reach`]: computed only once the root is known to be hit, since most rays of
    /// a small object miss it and cost little else.
    fn reach(&self) -> f32 {
        cull_reach(self.origin, self.inv_dir)
    }

    fn new(ray: &Ray) -> Self {
        let inv = [1.0 / ray.dir.x, 1.0 / ray.dir.y, 1.0 / ray.dir.z];
        let negative = inv.map(f32::is_sign_negative);
        Self {
            origin: ray.origin.to_array(),
            inv_dir: inv,
            inv_dir_exit: inv.map(|i| i * EXIT_SCALE),
            near_row: std::array::from_fn(|a| if negative[a] { 3 + a } else { a }),
            far_row: std::array::from_fn(|a| if negative[a] { a } else { 3 + a }),
            t_min: ray.t_min,
        }
    }
}

/// A way to test one ray against a node's eight boxes: which children's boxes the ray meets
/// within `[t_min, t_max]` (bit per lane) and where it enters each. `t_max` must be finite. A
/// zero direction component gives `±inf` or NaN slab distances; NaN (origin on the slab
/// plane) is dropped by the min/max, which keeps boxes closed. Empty lanes (`+inf` minima,
/// `-inf` maxima) miss.
trait NodeTest: Copy {
    /// The ray in the form this test wants.
    type LitScene: Copy;
    fn prepare(self, boxes: &RayBoxes) -> Self::LitScene;
    fn enter(self, ray: &Self::LitScene, node: &WideNode, t_max: f32) -> (u32, [f32; WIDTH]);
}

/// Four lanes at a time ([`F4`]: SSE on x86_64, plain arrays elsewhere).
#[derive(Clone, Copy)]
struct Portable;

impl NodeTest for Portable {
    type LitScene = RayBoxes;

    #[inline(always)]
    fn prepare(self, boxes: &RayBoxes) -> RayBoxes {
        *boxes
    }

    #[inline(always)]
    fn enter(self, r: &RayBoxes, node: &WideNode, t_max: f32) -> (u32, [f32; WIDTH]) {
        let mut bits = 0;
        let mut enter = [f32::INFINITY; WIDTH];
        for group in 0..GROUPS {
            // Lanes fill in order: a group starting with an unused lane is unused.
            if group > 0 && node.children[LANES * group] == EMPTY {
                break;
            }
            let mut near = F4::splat(r.t_min);
            let mut far = F4::splat(t_max);
            for axis in 0..3 {
                let lo = &node.bounds[r.near_row[axis]][group];
                let hi = &node.bounds[r.far_row[axis]][group];
                let o = F4::splat(r.origin[axis]);
                let tn = (F4::load(lo) - o) * F4::splat(r.inv_dir[axis]);
                let tf = (F4::load(hi) - o) * F4::splat(r.inv_dir_exit[axis]);
                near = tn.max_or(near);
                far = tf.min_or(far);
            }
            bits |= near.le(far).bits() << (LANES * group);
            enter[LANES * group..][..LANES].copy_from_slice(&near.to_array());
        }
        (bits, enter)
    }
}

/// The ray for [`Avx2`]: its slab planes in AVX registers and the rows to test.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
struct Avx2Ray {
    slabs: Slabs8,
    near_row: [usize; 3],
    far_row: [usize; 3],
}

/// All eight lanes at once (x86_64 with AVX2 and FMA, detected at run time).
#[cfg(target_arch = "x86_64")]
impl NodeTest for Avx2 {
    type LitScene = Avx2Ray;

    #[inline(always)]
    fn prepare(self, b: &RayBoxes) -> Avx2Ray {
        Avx2Ray {
            slabs: self.slabs(b.origin, b.inv_dir, EXIT_SCALE, b.t_min),
            near_row: b.near_row,
            far_row: b.far_row,
        }
    }

    #[inline(always)]
    fn enter(self, r: &Avx2Ray, node: &WideNode, t_max: f32) -> (u32, [f32; WIDTH]) {
        let rows = |row: [usize; 3]| row.map(|i| &node.bounds[i]);
        self.enter(&r.slabs, rows(r.near_row), rows(r.far_row), t_max)
    }
}

/// Pushes the children hit (`bits`, entry distances `enter`) of `node` farthest first and
/// returns the nearest, which is visited next; `None` when no child is hit.
#[inline(always)]
fn visit_sorted(
    node: &WideNode,
    (mut bits, enter): (u32, [f32; WIDTH]),
    stack: &mut Stack<StackEntry>,
) -> Option<u32> {
    if bits == 0 {
        return None;
    }
    let entry = |lane: u32| StackEntry {
        child: node.children[lane as usize],
        t_enter: enter[lane as usize],
    };
    let first = bits.trailing_zeros();
    bits &= bits - 1;
    if bits == 0 {
        // One child hit, the common case.
        return Some(node.children[first as usize]);
    }
    let second = bits.trailing_zeros();
    bits &= bits - 1;
    if bits == 0 {
        let (a, b) = (entry(first), entry(second));
        let (near, far) = if b.t_enter <= a.t_enter {
            (b, a)
        } else {
            (a, b)
        };
        stack.push(far);
        return Some(near.child);
    }
    // Three or more: push them all, sort the pushed run farthest first, pop the nearest.
    stack.push(entry(first));
    stack.push(entry(second));
    let mut n = 2;
    while bits != 0 {
        stack.push(entry(bits.trailing_zeros()));
        bits &= bits - 1;
        n += 1;
    }
    let run = stack.top_mut(n);
    for i in 1..n {
        let mut j = i;
        while j > 0 && run[j - 1].t_enter < run[j].t_enter {
            run.swap(j - 1, j);
            j -= 1;
        }
    }
    let nearest = run[n - 1].child;
    stack.pop();
    Some(nearest)
}

/// Pushes all children hit but one, which it returns; `None` when no child is hit.
#[inline(always)]
fn visit_any(node: &WideNode, mut bits: u32, stack: &mut Stack<u32>) -> Option<u32> {
    if bits == 0 {
        return None;
    }
    let next = node.children[bits.trailing_zeros() as usize];
    bits &= bits - 1;
    while bits != 0 {
        stack.push(node.children[bits.trailing_zeros() as usize]);
        bits &= bits - 1;
    }
    Some(next)
}

/// Which node test the traversal uses: AVX2 where the CPU has it, else [`Portable`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Kernel {
    /// The best this CPU supports (checked once per process).
    #[default]
    Auto,
    /// Four lanes at a time (SSE2 on x86_64), on every CPU; for tests and comparisons.
    Portable,
}

impl Bvh {
    /// Selects the node test (default [`Kernel::Auto`]); results are the same either way.
    pub fn set_kernel(&mut self, kernel: Kernel) {
        self.kernel = kernel;
        #[cfg(target_arch = "x86_64")]
        {
            self.avx2 = match kernel {
                Kernel::Auto => Avx2::detect(),
                Kernel::Portable => None,
            };
        }
    }

    /// The closest hit with `t` in `[ray.t_min, ray.t_max]`; both sides of a triangle count.
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = self.avx2 {
            // SAFETY: `avx2` proves the CPU has AVX2, the feature `intersect_avx2` is
            // compiled for.
            return unsafe { self.intersect_avx2(avx2, ray) };
        }
        self.intersect_with(Portable, ray)
    }

    /// Whether anything is hit with `t` in `[ray.t_min, ray.t_max]`; stops at the first hit.
    pub fn occluded(&self, ray: &Ray) -> bool {
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = self.avx2 {
            // SAFETY: as in `intersect`.
            return unsafe { self.occluded_avx2(avx2, ray) };
        }
        self.occluded_with(Portable, ray)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn intersect_avx2(&self, avx2: Avx2, ray: &Ray) -> Option<Hit> {
        self.intersect_with(avx2, ray)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn occluded_avx2(&self, avx2: Avx2, ray: &Ray) -> bool {
        self.occluded_with(avx2, ray)
    }

    #[inline(always)]
    fn intersect_with<T: NodeTest>(&self, test: T, ray: &Ray) -> Option<Hit> {
        // Rays that miss everything (most primary rays of a small object) cost one node test:
        // no stack, no triangle set-up.
        let ray_boxes = RayBoxes::new(ray);
        let boxes = test.prepare(&ray_boxes);
        // Without a finite t_max the margin cannot matter before the first hit: a ray that
        // misses the root costs no more than the box test.
        let (reach, root) = if ray.t_max.is_finite() {
            let reach = ray_boxes.reach();
            let root = test.enter(&boxes, self.nodes.first()?, cull_limit(ray.t_max, reach));
            (reach, root)
        } else {
            let root = test.enter(&boxes, self.nodes.first()?, f32::MAX);
            (0.0, root)
        };
        if root.0 == 0 {
            return None;
        }
        let reach = if ray.t_max.is_finite() {
            reach
        } else {
            ray_boxes.reach()
        };
        if self.depth <= STACK_LEVELS {
            let buf = &mut [MaybeUninit::uninit(); STACK_SIZE];
            self.closest(test, ray, &boxes, reach, root, Stack::new(buf))
        } else {
            let buf = &mut vec![MaybeUninit::uninit(); self.depth * (WIDTH - 1) + 1];
            self.closest(test, ray, &boxes, reach, root, Stack::new(buf))
        }
    }

    #[inline(always)]
    fn occluded_with<T: NodeTest>(&self, test: T, ray: &Ray) -> bool {
        let ray_boxes = RayBoxes::new(ray);
        let limit = cull_limit(ray.t_max, ray_boxes.reach());
        let boxes = test.prepare(&ray_boxes);
        let Some(root) = self.nodes.first() else {
            return false;
        };
        let root = test.enter(&boxes, root, limit).0;
        if root == 0 {
            return false;
        }
        if self.depth <= STACK_LEVELS {
            let buf = &mut [MaybeUninit::uninit(); STACK_SIZE];
            self.any(test, ray, &boxes, limit, root, Stack::new(buf))
        } else {
            let buf = &mut vec![MaybeUninit::uninit(); self.depth * (WIDTH - 1) + 1];
            self.any(test, ray, &boxes, limit, root, Stack::new(buf))
        }
    }

    /// Closest hit; `root` is the root node's box test, already known to hit.
    #[inline(always)]
    fn closest<T: NodeTest>(
        &self,
        test: T,
        ray: &Ray,
        boxes: &T::LitScene,
        reach: f32,
        root: (u32, [f32; WIDTH]),
        mut stack: Stack<StackEntry>,
    ) -> Option<Hit> {
        let tri_ray = RayTriangles::new(ray);
        let mut best_t = ray.t_max;
        let mut cull_t = cull_limit(best_t, reach);
        let mut best_id = u32::MAX;
        let mut best: Option<(u32, f32, f32)> = None;
        let mut next = visit_sorted(&self.nodes[0], root, &mut stack);
        loop {
            let current = match next {
                Some(c) => c,
                None => loop {
                    let Some(entry) = stack.pop() else {
                        return best.map(|(prim, u, v)| Hit {
                            t: best_t,
                            u,
                            v,
                            prim,
                        });
                    };
                    if entry.t_enter <= cull_t {
                        break entry.child;
                    }
                },
            };
            if current & LEAF_BIT == 0 {
                let node = &self.nodes[current as usize];
                let hits = test.enter(boxes, node, cull_t);
                next = visit_sorted(node, hits, &mut stack);
            } else {
                let (first, count) = leaf_range(current);
                for pack in &self.triangles[first..first + count] {
                    if let Some((lane, t, u, v)) = pack.intersect(&tri_ray, best_t)
                        && closer(t, pack.ids[lane], best_t, best_id)
                    {
                        best_t = t;
                        cull_t = cull_limit(t, reach);
                        best_id = pack.ids[lane];
                        best = Some((best_id, u, v));
                    }
                }
                next = None;
            }
        }
    }

    /// Any hit; `root` is the root node's box test bits, already known to be non-zero.
    #[inline(always)]
    fn any<T: NodeTest>(
        &self,
        test: T,
        ray: &Ray,
        boxes: &T::LitScene,
        limit: f32,
        root: u32,
        mut stack: Stack<u32>,
    ) -> bool {
        let tri_ray = RayTriangles::new(ray);
        let mut next = visit_any(&self.nodes[0], root, &mut stack);
        loop {
            let Some(current) = next.or_else(|| stack.pop()) else {
                return false;
            };
            if current & LEAF_BIT == 0 {
                let node = &self.nodes[current as usize];
                next = visit_any(node, test.enter(boxes, node, limit).0, &mut stack);
            } else {
                let (first, count) = leaf_range(current);
                let hit = self.triangles[first..first + count]
                    .iter()
                    .any(|pack| pack.occludes(&tri_ray, ray.t_max));
                if hit {
                    return true;
                }
                next = None;
            }
        }
    }
}
