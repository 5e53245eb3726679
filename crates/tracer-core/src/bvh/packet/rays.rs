//! A packet's eight rays prepared for box tests: which children of a node each lane enters,
//! by the portable slab test, after the packet's frustum has dropped those none can.

// Lane loops index several arrays by lane on purpose (see `packet/mod.rs`).
#![allow(clippy::needless_range_loop)]

use super::super::frustum::Frustum;
use super::super::traverse::{CULL_SLACK, EXIT_SCALE};
use super::super::wide::{LANES, WIDTH, WideNode};
use crate::lanes8::{Lanes8, Mask8};

/// Rays per packet.
pub const PACKET: usize = 8;

/// A bit for every child of a node.
pub(super) const ALL_CHILDREN: u32 = (1 << WIDTH) - 1;

/// Eight rays prepared for box tests. Lanes past the rays given repeat the first ray and are
/// never active.
#[derive(Clone, Copy)]
pub(super) struct Rays8<L: Lanes8> {
    /// Bit per lane holding a ray.
    pub(super) active: u32,
    pub(super) origin: [L; 3],
    pub(super) dir: [L; 3],
    pub(super) inv_dir: [L; 3],
    pub(super) inv_dir_exit: [L; 3],
    /// Per axis: lanes whose direction is negative (entering a box through its maximum).
    pub(super) negative: [L::Mask; 3],
    /// When every lane has the same sign on every axis (the common case), the rows of a
    /// node's bounds holding the entry planes (`[..3]`) and the exit planes (`[3..]`): two
    /// broadcasts per axis and child, no blend and no branch.
    pub(super) planes: Option<[usize; 6]>,
    pub(super) t_min: L,
    pub(super) t_max: L,
    /// See `cull_reach`.
    pub(super) reach: L,
    /// The packet as a whole, when its rays share their signs and all is finite.
    pub(super) frustum: Option<Frustum>,
}

/// Whether the lanes `active` of `bits` are all set (`Some(true)`), all clear, or mixed.
#[inline(always)]
pub(super) fn uniform(bits: u32, active: u32) -> Option<bool> {
    if bits & active == active {
        Some(true)
    } else if bits & active == 0 {
        Some(false)
    } else {
        None
    }
}

impl<L: Lanes8> Rays8<L> {
    /// (Plain loops and straight-line lane calls: a closure would not inherit the caller's
    /// AVX target feature, and each intrinsic in it would become a call. The `row` closure
    /// only reads fields.)
    #[inline(always)]
    pub(super) fn new(n: usize, rows: &[L; 8], frustum: Option<Frustum>) -> Self {
        debug_assert!((1..=PACKET).contains(&n));
        let active = (1u32 << n) - 1;
        let [ox, oy, oz, dx, dy, dz, t_min, t_max] = L::transpose(*rows);
        let (zero, one) = (L::splat(0.0), L::splat(1.0));
        let d = [dx, dy, dz];
        let o = [ox, oy, oz];
        let inv_dir = [one.div(d[0]), one.div(d[1]), one.div(d[2])];
        // 1/d is never -0 or NaN for a finite d, so "below zero" is "sign negative".
        let negative = [
            inv_dir[0].lt(zero),
            inv_dir[1].lt(zero),
            inv_dir[2].lt(zero),
        ];
        let planes = match [
            uniform(negative[0].bits(), active),
            uniform(negative[1].bits(), active),
            uniform(negative[2].bits(), active),
        ] {
            [Some(nx), Some(ny), Some(nz)] => {
                // Entering through the minimum on axes moved along positively.
                let row = |axis: usize, neg: bool, entry: bool| {
                    if neg == entry { 3 + axis } else { axis }
                };
                Some([
                    row(0, nx, true),
                    row(1, ny, true),
                    row(2, nz, true),
                    row(0, nx, false),
                    row(1, ny, false),
                    row(2, nz, false),
                ])
            }
            _ => None,
        };
        // The cull margin's reach (`cull_reach`): origin over direction on the axes moved along.
        let infinity = L::splat(f32::INFINITY);
        let mut reach = zero;
        for a in 0..3 {
            let along = o[a].mul(inv_dir[a]).abs();
            let moves = inv_dir[a].abs().lt(infinity);
            reach = L::select(moves, along, zero).max_or(reach);
        }
        let reach = reach.mul(L::splat(CULL_SLACK));
        let exit = L::splat(EXIT_SCALE);
        Self {
            active,
            origin: o,
            dir: d,
            inv_dir,
            inv_dir_exit: [
                inv_dir[0].mul(exit),
                inv_dir[1].mul(exit),
                inv_dir[2].mul(exit),
            ],
            negative,
            planes,
            t_min,
            t_max,
            reach,
            frustum,
        }
    }

    /// The children of `node` that some lane may enter before `limit` (the farthest cull
    /// limit of the lanes). Without a frustum, every child (the caller stops at the first
    /// empty one). The root's come with the packet (`root`, taken when the root is popped:
    /// first, and once).
    #[inline(always)]
    pub(super) fn candidates(&self, node: &WideNode, limit: f32, root: &mut Option<u32>) -> u32 {
        match (root.take(), &self.frustum) {
            (Some(bits), _) => bits,
            (None, Some(f)) => f.candidates::<L>(node, limit),
            (None, None) => ALL_CHILDREN,
        }
    }

    /// Which lanes of `lanes` meet child `c`'s box of `node` within `[t_min, limit[lane]]`
    /// (a finite cull limit), and where each enters it (the portable slab test, per lane).
    #[inline(always)]
    pub(super) fn enter(&self, node: &WideNode, c: usize, limit: L, lanes: u32) -> (u32, L) {
        let (g, l) = (c / LANES, c % LANES);
        let (mut near, mut far) = (self.t_min, limit);
        match self.planes {
            Some(rows) => {
                for axis in 0..3 {
                    let np = L::splat(node.bounds[rows[axis]][g][l]);
                    let fp = L::splat(node.bounds[rows[3 + axis]][g][l]);
                    (near, far) = self.slab(axis, np, fp, near, far);
                }
            }
            None => {
                for axis in 0..3 {
                    let lo = L::splat(node.bounds[axis][g][l]);
                    let hi = L::splat(node.bounds[3 + axis][g][l]);
                    let m = self.negative[axis];
                    let (np, fp) = (L::select(m, hi, lo), L::select(m, lo, hi));
                    (near, far) = self.slab(axis, np, fp, near, far);
                }
            }
        }
        (lanes & near.le(far).bits(), near)
    }

    /// The slab of `axis` between the entry plane `np` and the exit plane `fp`, narrowing the
    /// interval (`near`, `far`) of every lane.
    #[inline(always)]
    pub(super) fn slab(&self, axis: usize, np: L, fp: L, near: L, far: L) -> (L, L) {
        let o = self.origin[axis];
        let tn = np.sub(o).mul(self.inv_dir[axis]);
        let tf = fp.sub(o).mul(self.inv_dir_exit[axis]);
        // NaN (origin on the plane, zero direction) keeps the other side.
        (tn.max_or(near), tf.min_or(far))
    }
}
