//! The watertight triangle test per lane: each lane's shear frame, made when a packet first
//! reaches a leaf, and four triangles against eight rays.

// Lane loops index several arrays by lane on purpose (see `packet/mod.rs`).
#![allow(clippy::needless_range_loop)]

use super::super::triangle::Tri4;
use super::rays::{Rays8, uniform};
use crate::lanes8::{Lanes8, Mask8};

/// The watertight triangle test's frame per lane (`RayTriangles::new`, per lane): the
/// origin's coordinates along kx, ky, kz and the shear; which lanes take x (`axis_is[j][0]`)
/// or y (`axis_is[j][1]`) as axis j (else z), and the axes when every lane has the same (the
/// common case: plain broadcasts). Made when a packet reaches its first leaf: most packets of
/// a frame around a small object reach none.
#[derive(Clone, Copy)]
pub(super) struct TriangleFrame<L: Lanes8> {
    pub(super) origin_k: [L; 3],
    pub(super) shear: [L; 3],
    pub(super) axis_is: [[L::Mask; 2]; 3],
    pub(super) uniform_axes: Option<[usize; 3]>,
    pub(super) t_min: L,
}

/// The triangle frame of `r`, made on first use.
#[inline(always)]
pub(super) fn triangle_frame<'f, L: Lanes8>(
    slot: &'f mut Option<TriangleFrame<L>>,
    r: &Rays8<L>,
) -> &'f TriangleFrame<L> {
    match slot {
        Some(f) => f,
        None => slot.insert(TriangleFrame::new(r)),
    }
}

impl<L: Lanes8> TriangleFrame<L> {
    #[inline(always)]
    pub(super) fn new(r: &Rays8<L>) -> Self {
        let (d, o) = (r.dir, r.origin);
        let (zero, one) = (L::splat(0.0), L::splat(1.0));
        // kz the dominant axis (x when |dx| is largest, ties to the earlier axis), kx and ky
        // the next two.
        let (ax, ay, az) = (d[0].abs(), d[1].abs(), d[2].abs());
        let kz_x = ax.ge(ay).and(ax.ge(az));
        let kz_y = ay.ge(az).and_not(kz_x);
        let kz_z = zero.le(zero).and_not(kz_x.or(kz_y));
        // Along kx: y, z, x for kz = x, y, z; along ky: z, x, y.
        let dir_k = [
            by_axis(kz_x, kz_y, d[1], d[2], d[0]),
            by_axis(kz_x, kz_y, d[2], d[0], d[1]),
            by_axis(kz_x, kz_y, d[0], d[1], d[2]),
        ];
        let origin_k = [
            by_axis(kz_x, kz_y, o[1], o[2], o[0]),
            by_axis(kz_x, kz_y, o[2], o[0], o[1]),
            by_axis(kz_x, kz_y, o[0], o[1], o[2]),
        ];
        let inv_z = one.div(dir_k[2]);
        let active = r.active;
        let uniform_axes = match (uniform(kz_x.bits(), active), uniform(kz_y.bits(), active)) {
            (Some(true), _) => Some([1, 2, 0]),
            (Some(false), Some(true)) => Some([2, 0, 1]),
            (Some(false), Some(false)) => Some([0, 1, 2]),
            _ => None,
        };
        Self {
            origin_k,
            shear: [dir_k[0].mul(inv_z), dir_k[1].mul(inv_z), inv_z],
            // Which lanes take x, y as axis kx (kz = z, x), ky (kz = y, z) and kz (x, y).
            axis_is: [[kz_z, kz_x], [kz_y, kz_z], [kz_x, kz_y]],
            uniform_axes,
            t_min: r.t_min,
        }
    }

    /// One vertex in every lane's ray frame: (x, y) sheared, z along the ray (the single-ray
    /// test's `frame`).
    #[inline(always)]
    pub(super) fn frame(&self, p: [f32; 3]) -> [L; 3] {
        let (px, py, pz) = match self.uniform_axes {
            Some(k) => (L::splat(p[k[0]]), L::splat(p[k[1]]), L::splat(p[k[2]])),
            None => (self.pick(p, 0), self.pick(p, 1), self.pick(p, 2)),
        };
        let z = pz.sub(self.origin_k[2]);
        let x = px.sub(self.origin_k[0]).sub(self.shear[0].mul(z));
        let y = py.sub(self.origin_k[1]).sub(self.shear[1].mul(z));
        [x, y, z]
    }

    /// Per lane the coordinate of `p` along that lane's axis `j`.
    #[inline(always)]
    pub(super) fn pick(&self, p: [f32; 3], j: usize) -> L {
        let [is_x, is_y] = self.axis_is[j];
        let yz = L::select(is_y, L::splat(p[1]), L::splat(p[2]));
        L::select(is_x, L::splat(p[0]), yz)
    }

    /// Triangle `j` of `pack` against the lanes `lanes` (the watertight test, as `Tri4::lanes`
    /// does it per triangle): those hit with `t` in `[t_min, t_max[lane]]`, and `t`, the
    /// unnormalised `v`, `w` and `1 / det` (zeros when none passes the edge tests).
    #[inline(always)]
    pub(super) fn triangle(&self, pack: &Tri4, j: usize, t_max: L, lanes: u32) -> (u32, [L; 4]) {
        let vertex = |v: usize| [pack.v[v][0][j], pack.v[v][1][j], pack.v[v][2][j]];
        let [ax, ay, az] = self.frame(vertex(0));
        let [bx, by, bz] = self.frame(vertex(1));
        let [cx, cy, cz] = self.frame(vertex(2));
        let u = cx.mul(by).sub(cy.mul(bx));
        let v = ax.mul(cy).sub(ay.mul(cx));
        let w = bx.mul(ay).sub(by.mul(ax));
        let zero = L::splat(0.0);
        let negative = u.lt(zero).or(v.lt(zero)).or(w.lt(zero));
        let positive = u.gt(zero).or(v.gt(zero)).or(w.gt(zero));
        let det = u.add(v).add(w);
        let inside = det.ne(zero).and_not(negative.and(positive));
        if inside.bits() & lanes == 0 {
            // Every ray asked about passes beside the triangle: no division, no distances.
            return (0, [zero; 4]);
        }
        let t_scaled = self.shear[2].mul(u.mul(az).add(v.mul(bz)).add(w.mul(cz)));
        let inv_det = L::splat(1.0).div(det);
        let t = t_scaled.mul(inv_det);
        let hit = inside.and(t.ge(self.t_min)).and(t.le(t_max));
        (hit.bits() & lanes, [t, v, w, inv_det])
    }
}

/// Per lane `a` where the ray's dominant axis is x, `b` where it is y, else `c`.
#[inline(always)]
pub(super) fn by_axis<L: Lanes8>(kz_x: L::Mask, kz_y: L::Mask, a: L, b: L, c: L) -> L {
    L::select(kz_x, a, L::select(kz_y, b, c))
}
