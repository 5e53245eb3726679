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

use std::mem::MaybeUninit;

use super::frustum::Frustum;
use super::stack::Stack;
use super::traverse::{CULL_SLACK, EXIT_SCALE, STACK_LEVELS, STACK_SIZE};
use super::triangle::{PACK, Tri4};
use super::wide::{EMPTY, LANES, LEAF_BIT, WIDTH, WideNode, leaf_range};
use super::{Bvh, Hit, PADDING};
use crate::geometry::Ray;
#[cfg(target_arch = "x86_64")]
use crate::lanes8::Avx8;
use crate::lanes8::{Lanes8, Mask8, Scalar8, ray_rows};

/// Rays per packet.
pub const PACKET: usize = 8;

/// A bit for every child of a node.
const ALL_CHILDREN: u32 = (1 << WIDTH) - 1;

/// Stack entries: a packet pushes at most every child of a node.
const PACKET_STACK: usize = STACK_SIZE + WIDTH;

/// Eight rays prepared for box tests. Lanes past the rays given repeat the first ray and are
/// never active.
#[derive(Clone, Copy)]
struct Rays8<L: Lanes8> {
    /// Bit per lane holding a ray.
    active: u32,
    origin: [L; 3],
    dir: [L; 3],
    inv_dir: [L; 3],
    inv_dir_exit: [L; 3],
    /// Per axis: lanes whose direction is negative (entering a box through its maximum).
    negative: [L::Mask; 3],
    /// When every lane has the same sign on every axis (the common case), the rows of a
    /// node's bounds holding the entry planes (`[..3]`) and the exit planes (`[3..]`): two
    /// broadcasts per axis and child, no blend and no branch.
    planes: Option<[usize; 6]>,
    t_min: L,
    t_max: L,
    /// See `cull_reach`.
    reach: L,
    /// The packet as a whole, when its rays share their signs and all is finite.
    frustum: Option<Frustum>,
}

/// Whether the lanes `active` of `bits` are all set (`Some(true)`), all clear, or mixed.
#[inline(always)]
fn uniform(bits: u32, active: u32) -> Option<bool> {
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
    fn new(n: usize, rows: &[L; 8], frustum: Option<Frustum>) -> Self {
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
    fn candidates(&self, node: &WideNode, limit: f32, root: &mut Option<u32>) -> u32 {
        match (root.take(), &self.frustum) {
            (Some(bits), _) => bits,
            (None, Some(f)) => f.candidates::<L>(node, limit),
            (None, None) => ALL_CHILDREN,
        }
    }

    /// Which lanes of `lanes` meet child `c`'s box of `node` within `[t_min, limit[lane]]`
    /// (a finite cull limit), and where each enters it (the portable slab test, per lane).
    #[inline(always)]
    fn enter(&self, node: &WideNode, c: usize, limit: L, lanes: u32) -> (u32, L) {
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
    fn slab(&self, axis: usize, np: L, fp: L, near: L, far: L) -> (L, L) {
        let o = self.origin[axis];
        let tn = np.sub(o).mul(self.inv_dir[axis]);
        let tf = fp.sub(o).mul(self.inv_dir_exit[axis]);
        // NaN (origin on the plane, zero direction) keeps the other side.
        (tn.max_or(near), tf.min_or(far))
    }
}

/// The watertight triangle test's frame per lane (`RayTriangles::new`, per lane): the
/// origin's coordinates along kx, ky, kz and the shear; which lanes take x (`axis_is[j][0]`)
/// or y (`axis_is[j][1]`) as axis j (else z), and the axes when every lane has the same (the
/// common case: plain broadcasts). Made when a packet reaches its first leaf: most packets of
/// a frame around a small object reach none.
#[derive(Clone, Copy)]
struct TriangleFrame<L: Lanes8> {
    origin_k: [L; 3],
    shear: [L; 3],
    axis_is: [[L::Mask; 2]; 3],
    uniform_axes: Option<[usize; 3]>,
    t_min: L,
}

/// The triangle frame of `r`, made on first use.
#[inline(always)]
fn triangle_frame<'f, L: Lanes8>(
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
    fn new(r: &Rays8<L>) -> Self {
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
    fn frame(&self, p: [f32; 3]) -> [L; 3] {
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
    fn pick(&self, p: [f32; 3], j: usize) -> L {
        let [is_x, is_y] = self.axis_is[j];
        let yz = L::select(is_y, L::splat(p[1]), L::splat(p[2]));
        L::select(is_x, L::splat(p[0]), yz)
    }

    /// Triangle `j` of `pack` against the lanes `lanes` (the watertight test, as `Tri4::lanes`
    /// does it per triangle): those hit with `t` in `[t_min, t_max[lane]]`, and `t`, the
    /// unnormalised `v`, `w` and `1 / det` (zeros when none passes the edge tests).
    #[inline(always)]
    fn triangle(&self, pack: &Tri4, j: usize, t_max: L, lanes: u32) -> (u32, [L; 4]) {
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
fn by_axis<L: Lanes8>(kz_x: L::Mask, kz_y: L::Mask, a: L, b: L, c: L) -> L {
    L::select(kz_x, a, L::select(kz_y, b, c))
}

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
