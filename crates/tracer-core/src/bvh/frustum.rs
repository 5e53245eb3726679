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
    /// `lanes8::ray_rows` lays them out), when the rays share their direction's sign on every
    /// axis and every origin, direction and `t_min` is finite (so no distance is NaN).
    #[inline(always)]
    pub(super) fn new<L: Lanes8>(rays: &[L; 8]) -> Option<Self> {
        // The least and greatest of each quantity over the rays, and their sum, which is
        // finite only when every term is (NaN and infinities carry through): seven steps
        // each, no shuffle.
        let (mut lo, mut hi, mut sum) = (rays[0], rays[0], rays[0]);
        for r in &rays[1..] {
            lo = lo.min_or(*r);
            hi = hi.max_or(*r);
            sum = sum.add(*r);
        }
        let zero = L::splat(0.0);
        let finite = sum.abs().lt(L::splat(f32::INFINITY)).bits();
        let (positive, negative) = (lo.gt(zero).bits(), hi.lt(zero).bits());
        // Lanes 0-6 finite; lanes 3-5 (the direction) of one sign, never zero.
        if finite & 0x7f != 0x7f || (positive | negative) & 0x38 != 0x38 {
            return None;
        }
        // 1/d falls as d grows on either side of zero, and the rounded division keeps that
        // order: the least 1/d is that of the greatest d, computed the lanes' way.
        let one = L::splat(1.0);
        let (inv_lo, inv_hi) = (one.div(hi).to_array(), one.div(lo).to_array());
        let (lo, hi) = (lo.to_array(), hi.to_array());
        let mut f = Self {
            rows: [0; 6],
            entry_origin: [0.0; 3],
            exit_origin: [0.0; 3],
            inv: [[0.0; 2]; 3],
            inv_exit: [[0.0; 2]; 3],
            t_min: lo[6],
        };
        for a in 0..3 {
            // Moving positively: in through the minimum, out through the maximum, and the
            // greatest origin nearest.
            if positive & (8 << a) != 0 {
                f.rows[a] = a;
                f.rows[3 + a] = 3 + a;
                (f.entry_origin[a], f.exit_origin[a]) = (hi[a], lo[a]);
            } else {
                f.rows[a] = 3 + a;
                f.rows[3 + a] = a;
                (f.entry_origin[a], f.exit_origin[a]) = (lo[a], hi[a]);
            }
            let (a_lo, a_hi) = (inv_lo[3 + a], inv_hi[3 + a]);
            // Both ends finite: |d| is bounded away from zero by the end nearer to it.
            if !(a_lo.is_finite() && a_hi.is_finite()) {
                return None;
            }
            f.inv[a] = [a_lo, a_hi];
            // Scaling keeps order, so the scaled ends are the ends of the scaled lanes.
            f.inv_exit[a] = [a_lo * EXIT_SCALE, a_hi * EXIT_SCALE];
        }
        Some(f)
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
