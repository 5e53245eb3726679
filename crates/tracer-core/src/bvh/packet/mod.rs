//! Eight rays through the tree together (a packet). Camera rays of one pixel's samples, and
//! shadow rays from neighbouring hits to one light, go the same way: a node's boxes and a
//! leaf's triangles are read once for all eight, and each triangle is tested against the eight
//! rays in one vector instead of each ray against four triangles. Before a node's children
//! are tested lane by lane, one vector test of the packet as a whole ([`Frustum`], interval
//! arithmetic over its lanes) drops the children no lane can enter.
//!
//! Per ray the arithmetic is that of the single-ray traversal: the portable slab test (which
//! only decides which boxes are opened, conservatively) and the watertight triangle test with
//! the same operations in the same order. The closest hit is the least (t, triangle id) of all
//! triangles hit ([`super::triangle::closer`]), which does not depend on the order boxes are
//! opened in, so a packet's hits equal [`Bvh::intersect`]'s bit for bit (`bvh_differential`
//! checks it). The lane loops compile to AVX2 where the CPU has it (chosen at run time) and to
//! SSE2 elsewhere; rounding is per lane IEEE single precision either way, no fused operations.

// Lane loops index several arrays by lane on purpose: that is the shape the compiler turns
// into one vector instruction per step.
#![allow(clippy::needless_range_loop)]

mod rays;
mod triangles;

pub use rays::PACKET;

use rays::{ALL_CHILDREN, Rays8};
use std::mem::MaybeUninit;
use triangles::triangle_frame;

use super::frustum::Frustum;
use super::stack::Stack;
use super::traverse::{CULL_SLACK, STACK_LEVELS, STACK_SIZE};
use super::triangle::PACK;
use super::wide::{EMPTY, LEAF_BIT, WIDTH, leaf_range};
use super::{Bvh, Hit, PADDING};
use crate::geometry::Ray;
#[cfg(target_arch = "x86_64")]
use crate::lanes8::Avx8;
use crate::lanes8::{Lanes8, Mask8, Scalar8, ray_rows};

/// Stack entries: a packet pushes at most every child of a node.
const PACKET_STACK: usize = STACK_SIZE + WIDTH;

#[derive(Clone, Copy)]
struct Entry<L: Lanes8> {
    child: u32,
    lanes: u32,
    /// Where each lane enters the child's box.
    t_enter: L,
}

/// The best hit per lane so far, and the distance up to which boxes are still opened.
struct Best8<L: Lanes8> {
    t: L,
    id: [u32; PACKET],
    u: L,
    v: L,
    cull: L,
}

/// `traverse::cull_limit` per lane, with the same operations in the same order.
#[inline(always)]
fn cull_limits<L: Lanes8>(t: L, reach: L) -> L {
    let limit = t.add(t.abs().mul(L::splat(CULL_SLACK))).add(reach);
    let max = L::splat(f32::MAX);
    L::select(limit.lt(max), limit, max)
}

impl Bvh {
    /// Closest hits of `rays` (at most [`PACKET`]) into `out` (as long): bit for bit what
    /// [`Bvh::intersect`] gives each.
    pub fn intersect_packet(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        assert!(rays.len() <= PACKET && rays.len() == out.len());
        if rays.is_empty() {
            return;
        }
        if self.nodes.is_empty() || self.depth > STACK_LEVELS {
            for (o, r) in out.iter_mut().zip(rays) {
                *o = self.intersect(r);
            }
            return;
        }
        #[cfg(target_arch = "x86_64")]
        if self.avx2.is_some() {
            // SAFETY: `avx2` is only set when the CPU has AVX2 (and FMA), the features
            // `closest8_avx2` needs.
            unsafe { self.closest8_avx2(rays, out) };
            return;
        }
        self.closest8::<Scalar8>(rays, out);
    }

    /// Whether each of `rays` (at most [`PACKET`]) hits anything, into `out` (as long): what
    /// [`Bvh::occluded`] gives each.
    pub fn occluded_packet(&self, rays: &[Ray], out: &mut [bool]) {
        assert!(rays.len() <= PACKET && rays.len() == out.len());
        if rays.is_empty() {
            return;
        }
        if self.nodes.is_empty() || self.depth > STACK_LEVELS {
            for (o, r) in out.iter_mut().zip(rays) {
                *o = self.occluded(r);
            }
            return;
        }
        #[cfg(target_arch = "x86_64")]
        if self.avx2.is_some() {
            // SAFETY: as in `intersect_packet`.
            unsafe { self.any8_avx2(rays, out) };
            return;
        }
        self.any8::<Scalar8>(rays, out);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn closest8_avx2(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        self.closest8::<Avx8>(rays, out);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn any8_avx2(&self, rays: &[Ray], out: &mut [bool]) {
        self.any8::<Avx8>(rays, out);
    }

    /// `rays` (lanes past them repeat the first) prepared for the tests, with the root's
    /// children their frustum may enter (all without a frustum), which the traversal takes for
    /// its first node. None when it enters none: no ray of the packet hits anything. Most
    /// packets aimed past a small object end there, before the lanes' set-up.
    #[inline(always)]
    fn packet<L: Lanes8>(&self, rays: &[Ray]) -> Option<(Rays8<L>, u32)> {
        let rows = ray_rows::<L>(|i| rays.get(i).unwrap_or(&rays[0]));
        let frustum = Frustum::new(&rows);
        let root = match &frustum {
            // No lane's cull limit exceeds f32::MAX (`cull_limits`).
            Some(f) => f.candidates::<L>(&self.nodes[0], f32::MAX),
            None => ALL_CHILDREN,
        };
        (root != 0).then(|| (Rays8::new(rays.len(), &rows, frustum), root))
    }

    #[inline(always)]
    fn closest8<L: Lanes8>(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        let Some((r, root)) = self.packet::<L>(rays) else {
            out.fill(None);
            return;
        };
        let mut root = Some(root);
        // Lanes without a ray never open a box, so the farthest limit is that of the rays.
        let holds_ray = L::Mask::from_bits(r.active);
        let cull = cull_limits(r.t_max, r.reach);
        let mut best = Best8 {
            t: r.t_max,
            id: [u32::MAX; PACKET],
            u: L::splat(0.0),
            v: L::splat(0.0),
            cull: L::select(holds_ray, cull, L::splat(f32::NEG_INFINITY)),
        };
        let mut farthest = best.cull.max_lane();
        let mut tri = None;
        let buf = &mut [MaybeUninit::uninit(); PACKET_STACK];
        let mut stack = Stack::new(buf);
        stack.push(Entry {
            child: 0,
            lanes: r.active,
            t_enter: r.t_min,
        });
        // The children a node's box tests let through: where the first of their rays enters
        // (the visit key), and the entry to push, kept apart so the sort moves bytes only.
        let mut keys = [0.0f32; WIDTH];
        let mut found = [Entry {
            child: 0,
            lanes: 0,
            t_enter: r.t_min,
        }; WIDTH];
        while let Some(e) = stack.pop() {
            // Lanes that found a hit nearer than where they enter this box need not open it.
            let lanes = e.lanes & e.t_enter.le(best.cull).bits();
            if lanes == 0 {
                continue;
            }
            if e.child & LEAF_BIT == 0 {
                let node = &self.nodes[e.child as usize];
                let mut n = 0;
                let mut candidates = r.candidates(node, farthest, &mut root);
                while candidates != 0 {
                    let c = candidates.trailing_zeros() as usize;
                    candidates &= candidates - 1;
                    let child = node.children[c];
                    if child == EMPTY {
                        break;
                    }
                    let (hit, near) = r.enter(node, c, best.cull, lanes);
                    if hit != 0 {
                        keys[n] = near.to_array()[hit.trailing_zeros() as usize];
                        found[n] = Entry {
                            child,
                            lanes: hit,
                            t_enter: near,
                        };
                        n += 1;
                    }
                }
                // Nearest on top of the stack: indices sorted by key, farthest first.
                let mut order = [0u8, 1, 2, 3, 4, 5, 6, 7];
                for i in 1..n {
                    let mut j = i;
                    while j > 0 && keys[order[j - 1] as usize] < keys[order[j] as usize] {
                        order.swap(j - 1, j);
                        j -= 1;
                    }
                }
                for &k in &order[..n] {
                    stack.push(found[k as usize]);
                }
            } else {
                let tri = triangle_frame(&mut tri, &r);
                let (first, count) = leaf_range(e.child);
                for pack in &self.triangles[first..first + count] {
                    for j in 0..PACK {
                        let id = pack.ids[j];
                        if id == PADDING {
                            continue;
                        }
                        let (hit, [t, v, w, inv_det]) = tri.triangle(pack, j, best.t, lanes);
                        if hit == 0 {
                            continue;
                        }
                        // Hits lie within the best distance: nearer wins, and on a tie the
                        // lower id (`triangle::closer`).
                        let mut take = hit & t.lt(best.t).bits();
                        let mut tied = hit & !take;
                        while tied != 0 {
                            let i = tied.trailing_zeros() as usize;
                            tied &= tied - 1;
                            if id < best.id[i] {
                                take |= 1 << i;
                            }
                        }
                        if take == 0 {
                            continue;
                        }
                        let m = L::Mask::from_bits(take);
                        best.t = L::select(m, t, best.t);
                        best.u = L::select(m, v.mul(inv_det), best.u);
                        best.v = L::select(m, w.mul(inv_det), best.v);
                        best.cull = L::select(m, cull_limits(t, r.reach), best.cull);
                        farthest = best.cull.max_lane();
                        while take != 0 {
                            best.id[take.trailing_zeros() as usize] = id;
                            take &= take - 1;
                        }
                    }
                }
            }
        }
        let (t, u, v) = (best.t.to_array(), best.u.to_array(), best.v.to_array());
        for (i, o) in out.iter_mut().enumerate() {
            *o = (best.id[i] != u32::MAX).then(|| Hit {
                t: t[i],
                u: u[i],
                v: v[i],
                prim: best.id[i],
            });
        }
    }

    #[inline(always)]
    fn any8<L: Lanes8>(&self, rays: &[Ray], out: &mut [bool]) {
        let Some((r, root)) = self.packet::<L>(rays) else {
            out.fill(false);
            return;
        };
        let mut root = Some(root);
        let limit = cull_limits(r.t_max, r.reach);
        let farthest = L::select(
            L::Mask::from_bits(r.active),
            limit,
            L::splat(f32::NEG_INFINITY),
        )
        .max_lane();
        let mut tri = None;
        let mut done = 0u32;
        let buf = &mut [MaybeUninit::uninit(); PACKET_STACK];
        let mut stack: Stack<Entry<L>> = Stack::new(buf);
        stack.push(Entry {
            child: 0,
            lanes: r.active,
            t_enter: r.t_min,
        });
        while let Some(e) = stack.pop() {
            let lanes = e.lanes & !done;
            if lanes == 0 {
                continue;
            }
            if e.child & LEAF_BIT == 0 {
                let node = &self.nodes[e.child as usize];
                let mut candidates = r.candidates(node, farthest, &mut root);
                while candidates != 0 {
                    let c = candidates.trailing_zeros() as usize;
                    candidates &= candidates - 1;
                    let child = node.children[c];
                    if child == EMPTY {
                        break;
                    }
                    let (hit, near) = r.enter(node, c, limit, lanes);
                    if hit != 0 {
                        stack.push(Entry {
                            child,
                            lanes: hit,
                            t_enter: near,
                        });
                    }
                }
            } else {
                let tri = triangle_frame(&mut tri, &r);
                let (first, count) = leaf_range(e.child);
                'packs: for pack in &self.triangles[first..first + count] {
                    for j in 0..PACK {
                        if pack.ids[j] == PADDING {
                            continue;
                        }
                        done |= tri.triangle(pack, j, r.t_max, lanes).0;
                        if done & lanes == lanes {
                            break 'packs;
                        }
                    }
                }
                if done == r.active {
                    break;
                }
            }
        }
        for (i, o) in out.iter_mut().enumerate() {
            *o = done & (1 << i) != 0;
        }
    }
}
