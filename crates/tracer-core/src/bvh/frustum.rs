//! A packet's rays taken as a whole (interval arithmetic over its lanes), to tell with one
//! vector test per node which children no ray of the packet can enter, before each child is
//! tested lane by lane.
//!
//! Per axis a lane's entry distance is `(entry plane - origin) · (1 / d)`, each step rounded.
//! Rounding keeps order, so over lanes whose origin lies in `[lo, hi]` and whose `1 / d` (of one
//! sign) lies in `[a, b]`, it is at least the lesser of `(plane - o*) · a` and `(plane - o*) ·
//! b`, rounded the same way, with `o*` the end of the origins that makes the first factor least
//! (the greatest origin when moving positively). Exit distances are bounded above likewise. A
//! child whose greatest entry exceeds its least exit, or the farthest cull limit, is entered by
//! no lane, so skipping it changes no hit.

use super::traverse::EXIT_SCALE;
use super::wide::WideNode;
use crate::lanes8::{Lanes8, Mask8};

/// The bounds of a packet whose rays share their signs on every axis.
#[derive(Clone, Copy)]
pub(super) struct Frustum {
    /// Per axis the `WideNode::bounds` rows of the entry planes (`[..3]`) and the exit planes.
    rows: [usize; 6],
    /// Per axis the origin coordinate that gives the least entry distances, and the one that
    /// gives the greatest exit distances.
    entry_origin: [f32; 3],
    exit_origin: [f32; 3],
    /// Per axis the least and the greatest `1 / d`, and the same of `1 / d` scaled for exits.
    inv: [[f32; 2]; 3],
    inv_exit: [[f32; 2]; 3],
    /// The least `t_min` of the lanes.
    t_min: f32,
}

impl Frustum {
    /// From the packet's rows (row `i`: ray `i`'s origin, direction, `t_min` and `t_max`, as
    /// `lanes8::ray_rows` lays them out), for rays that enter and leave boxes through the rows
    /// `rows`. The caller checks that every origin and `1 / d` is finite and every `t_min`
    /// below infinity, so no distance is NaN.
    #[inline(always)]
    pub(super) fn new<L: Lanes8>(rows: [usize; 6], rays: &[L; 8]) -> Self {
        // The least and greatest of each quantity over the rays: seven steps each, no shuffle.
        let (mut lo, mut hi) = (rays[0], rays[0]);
        for r in &rays[1..] {
            lo = lo.min_or(*r);
            hi = hi.max_or(*r);
        }
        // 1/d falls as d grows on either side of zero, and the rounded division keeps that
        // order: the least 1/d is that of the greatest d, computed the lanes' way.
        let one = L::splat(1.0);
        let (inv_lo, inv_hi) = (one.div(hi).to_array(), one.div(lo).to_array());
        let (lo, hi) = (lo.to_array(), hi.to_array());
        let mut f = Self {
            rows,
            entry_origin: [0.0; 3],
            exit_origin: [0.0; 3],
            inv: [[0.0; 2]; 3],
            inv_exit: [[0.0; 2]; 3],
            t_min: lo[6],
        };
        for a in 0..3 {
            // Entering through the minimum (moving positively) the greatest origin is nearest.
            let positive = rows[a] == a;
            (f.entry_origin[a], f.exit_origin[a]) = if positive {
                (hi[a], lo[a])
            } else {
                (lo[a], hi[a])
            };
            let (a_lo, a_hi) = (inv_lo[3 + a], inv_hi[3 + a]);
            f.inv[a] = [a_lo, a_hi];
            // Scaling keeps order, so the scaled ends are the ends of the scaled lanes.
            f.inv_exit[a] = [a_lo * EXIT_SCALE, a_hi * EXIT_SCALE];
        }
        f
    }

    /// The children of `node` that some lane may enter before `limit` (the farthest cull
    /// limit of the lanes): a bit per child, empty children never set (their boxes are
    /// inverted).
    #[inline(always)]
    pub(super) fn candidates<L: Lanes8>(&self, node: &WideNode, limit: f32) -> u32 {
        let (mut near, mut far) = (L::splat(self.t_min), L::splat(limit));
        for axis in 0..3 {
            let entry = L::from_array(node.row(self.rows[axis]));
            let exit = L::from_array(node.row(self.rows[3 + axis]));
            let dn = entry.sub(L::splat(self.entry_origin[axis]));
            let df = exit.sub(L::splat(self.exit_origin[axis]));
            let [a, b] = self.inv[axis];
            let tn = dn.mul(L::splat(a)).min_or(dn.mul(L::splat(b)));
            let [a, b] = self.inv_exit[axis];
            let tf = df.mul(L::splat(a)).max_or(df.mul(L::splat(b)));
            (near, far) = (tn.max_or(near), tf.min_or(far));
        }
        near.le(far).bits()
    }
}
