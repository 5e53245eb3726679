//! Eight rays through the tree together (a packet). Camera rays of one pixel's samples, and
//! shadow rays from neighbouring hits to one light, go the same way: a node's boxes and a
//! leaf's triangles are read once for all eight, and each triangle is tested against the eight
//! rays in one vector instead of each ray against four triangles.
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

use super::stack::Stack;
use super::traverse::{EXIT_SCALE, Kernel, STACK_LEVELS, STACK_SIZE, cull_limit, cull_reach};
use super::triangle::{PACK, RayTriangles, Tri4, closer};
use super::wide::{EMPTY, LANES, LEAF_BIT, WIDTH, WideNode, leaf_range};
use super::{Bvh, Hit, PADDING};
use crate::geometry::Ray;

/// Rays per packet.
pub const PACKET: usize = 8;

type F8 = [f32; PACKET];

/// Stack entries: a packet pushes at most every child of a node.
const PACKET_STACK: usize = STACK_SIZE + WIDTH;

/// Eight rays prepared for box and triangle tests. Lanes past the rays given repeat the first
/// ray and are never active.
#[derive(Clone, Copy)]
struct Rays8 {
    /// Bit per lane holding a ray.
    active: u32,
    origin: [F8; 3],
    inv_dir: [F8; 3],
    inv_dir_exit: [F8; 3],
    /// Per axis and lane: the direction is negative (the ray enters a box through its maximum).
    negative: [[bool; PACKET]; 3],
    t_min: F8,
    t_max: F8,
    /// See `cull_reach`.
    reach: F8,
    /// The triangle test's frame per lane: the origin's coordinates along kx, ky, kz, the
    /// shear, and the axes themselves.
    origin_k: [F8; 3],
    shear: [F8; 3],
    axes: [[usize; 3]; PACKET],
    /// The axes when every lane has the same (the common case), for plain broadcasts.
    uniform_axes: Option<[usize; 3]>,
}

impl Rays8 {
    fn new(rays: &[Ray]) -> Self {
        debug_assert!((1..=PACKET).contains(&rays.len()));
        let ray = |i: usize| rays.get(i).unwrap_or(&rays[0]);
        let tri: [RayTriangles; PACKET] = std::array::from_fn(|i| RayTriangles::new(ray(i)));
        let inv: [[f32; 3]; PACKET] = std::array::from_fn(|i| {
            let d = ray(i).dir;
            [1.0 / d.x, 1.0 / d.y, 1.0 / d.z]
        });
        let axes: [[usize; 3]; PACKET] = std::array::from_fn(|i| tri[i].k);
        let uniform_axes = axes[1..rays.len()]
            .iter()
            .all(|k| *k == axes[0])
            .then_some(axes[0]);
        Self {
            active: (1u32 << rays.len()) - 1,
            origin: std::array::from_fn(|a| std::array::from_fn(|i| ray(i).origin[a])),
            inv_dir: std::array::from_fn(|a| std::array::from_fn(|i| inv[i][a])),
            inv_dir_exit: std::array::from_fn(|a| std::array::from_fn(|i| inv[i][a] * EXIT_SCALE)),
            negative: std::array::from_fn(|a| {
                std::array::from_fn(|i| inv[i][a].is_sign_negative())
            }),
            t_min: std::array::from_fn(|i| ray(i).t_min),
            t_max: std::array::from_fn(|i| ray(i).t_max),
            reach: std::array::from_fn(|i| cull_reach(ray(i).origin.to_array(), inv[i])),
            origin_k: std::array::from_fn(|j| std::array::from_fn(|i| tri[i].origin[tri[i].k[j]])),
            shear: std::array::from_fn(|j| std::array::from_fn(|i| tri[i].shear[j])),
            axes,
            uniform_axes,
        }
    }

    /// Which lanes of `lanes` meet child `c`'s box of `node` within `[t_min, limit[lane]]`
    /// (a finite cull limit), and where each enters it (the portable slab test, per lane).
    #[inline(always)]
    fn enter(&self, node: &WideNode, c: usize, limit: &F8, lanes: u32) -> (u32, F8) {
        let (g, l) = (c / LANES, c % LANES);
        let mut near = self.t_min;
        let mut far = *limit;
        for axis in 0..3 {
            let lo = node.bounds[axis][g][l];
            let hi = node.bounds[3 + axis][g][l];
            for i in 0..PACKET {
                let neg = self.negative[axis][i];
                let (np, fp) = if neg { (hi, lo) } else { (lo, hi) };
                let o = self.origin[axis][i];
                let tn = (np - o) * self.inv_dir[axis][i];
                let tf = (fp - o) * self.inv_dir_exit[axis][i];
                // NaN (origin on the plane, zero direction) keeps the other side.
                near[i] = if tn > near[i] { tn } else { near[i] };
                far[i] = if tf < far[i] { tf } else { far[i] };
            }
        }
        (lanes & lane_bits(|i| near[i] <= far[i]), near)
    }

    /// One vertex in every lane's ray frame: (x, y) sheared, z along the ray (the single-ray
    /// test's `frame`).
    #[inline(always)]
    fn frame(&self, p: [f32; 3]) -> [F8; 3] {
        let pick = |j: usize| -> F8 {
            match self.uniform_axes {
                Some(k) => [p[k[j]]; PACKET],
                None => std::array::from_fn(|i| {
                    let k = self.axes[i][j];
                    if k == 0 {
                        p[0]
                    } else if k == 1 {
                        p[1]
                    } else {
                        p[2]
                    }
                }),
            }
        };
        let (px, py, pz) = (pick(0), pick(1), pick(2));
        let mut x = [0.0; PACKET];
        let mut y = [0.0; PACKET];
        let mut z = [0.0; PACKET];
        for i in 0..PACKET {
            z[i] = pz[i] - self.origin_k[2][i];
            x[i] = (px[i] - self.origin_k[0][i]) - self.shear[0][i] * z[i];
            y[i] = (py[i] - self.origin_k[1][i]) - self.shear[1][i] * z[i];
        }
        [x, y, z]
    }

    /// Triangle `j` of `pack` against every lane (the watertight test, as `Tri4::lanes` does
    /// it per triangle): lanes hit with `t` in `[t_min, t_max[lane]]`, and `t`, `u`, `v`.
    #[inline(always)]
    fn triangle(&self, pack: &Tri4, j: usize, t_max: &F8) -> (u32, F8, F8, F8) {
        let vertex = |v: usize| [pack.v[v][0][j], pack.v[v][1][j], pack.v[v][2][j]];
        let [ax, ay, az] = self.frame(vertex(0));
        let [bx, by, bz] = self.frame(vertex(1));
        let [cx, cy, cz] = self.frame(vertex(2));
        let mut t = [0.0; PACKET];
        let mut bu = [0.0; PACKET];
        let mut bv = [0.0; PACKET];
        let mut hit = [false; PACKET];
        for i in 0..PACKET {
            let u = cx[i] * by[i] - cy[i] * bx[i];
            let v = ax[i] * cy[i] - ay[i] * cx[i];
            let w = bx[i] * ay[i] - by[i] * ax[i];
            let negative = u < 0.0 || v < 0.0 || w < 0.0;
            let positive = u > 0.0 || v > 0.0 || w > 0.0;
            let det = u + v + w;
            let t_scaled = self.shear[2][i] * (u * az[i] + v * bz[i] + w * cz[i]);
            let inv_det = 1.0 / det;
            t[i] = t_scaled * inv_det;
            bu[i] = v * inv_det;
            bv[i] = w * inv_det;
            hit[i] =
                det != 0.0 && t[i] >= self.t_min[i] && t[i] <= t_max[i] && !(negative && positive);
        }
        (lane_bits(|i| hit[i]), t, bu, bv)
    }
}

/// Bits of the lanes where `f` holds.
#[inline(always)]
fn lane_bits(f: impl Fn(usize) -> bool) -> u32 {
    let mut bits = 0;
    for i in 0..PACKET {
        bits |= u32::from(f(i)) << i;
    }
    bits
}

#[derive(Clone, Copy)]
struct Entry {
    child: u32,
    lanes: u32,
    t_enter: F8,
}

/// The best hit per lane so far.
struct Best8 {
    t: F8,
    id: [u32; PACKET],
    u: F8,
    v: F8,
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
        if self.kernel == Kernel::Auto && is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, the only feature `closest8_avx2` is compiled for.
            unsafe { self.closest8_avx2(rays, out) };
            return;
        }
        self.closest8(rays, out);
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
        if self.kernel == Kernel::Auto && is_x86_feature_detected!("avx2") {
            // SAFETY: as in `intersect_packet`.
            unsafe { self.any8_avx2(rays, out) };
            return;
        }
        self.any8(rays, out);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn closest8_avx2(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        self.closest8(rays, out);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn any8_avx2(&self, rays: &[Ray], out: &mut [bool]) {
        self.any8(rays, out);
    }

    #[inline(always)]
    fn closest8(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        let r = Rays8::new(rays);
        let mut best = Best8 {
            t: r.t_max,
            id: [u32::MAX; PACKET],
            u: [0.0; PACKET],
            v: [0.0; PACKET],
        };
        let mut cull: F8 = std::array::from_fn(|i| cull_limit(r.t_max[i], r.reach[i]));
        let buf = &mut [MaybeUninit::uninit(); PACKET_STACK];
        let mut stack = Stack::new(buf);
        stack.push(Entry {
            child: 0,
            lanes: r.active,
            t_enter: r.t_min,
        });
        let mut children = [(
            0.0f32,
            Entry {
                child: 0,
                lanes: 0,
                t_enter: [0.0; PACKET],
            },
        ); WIDTH];
        while let Some(e) = stack.pop() {
            // Lanes that found a hit nearer than where they enter this box need not open it.
            let lanes = e.lanes & lane_bits(|i| e.t_enter[i] <= cull[i]);
            if lanes == 0 {
                continue;
            }
            if e.child & LEAF_BIT == 0 {
                let node = &self.nodes[e.child as usize];
                let mut n = 0;
                for c in 0..WIDTH {
                    let child = node.children[c];
                    if child == EMPTY {
                        break;
                    }
                    let (hit, near) = r.enter(node, c, &cull, lanes);
                    if hit != 0 {
                        let key = (0..PACKET)
                            .filter(|&i| hit & (1 << i) != 0)
                            .map(|i| near[i])
                            .fold(f32::INFINITY, f32::min);
                        children[n] = (
                            key,
                            Entry {
                                child,
                                lanes: hit,
                                t_enter: near,
                            },
                        );
                        n += 1;
                    }
                }
                // Nearest on top of the stack.
                let run = &mut children[..n];
                for i in 1..n {
                    let mut j = i;
                    while j > 0 && run[j - 1].0 < run[j].0 {
                        run.swap(j - 1, j);
                        j -= 1;
                    }
                }
                for (_, entry) in run.iter() {
                    stack.push(*entry);
                }
            } else {
                let (first, count) = leaf_range(e.child);
                for pack in &self.triangles[first..first + count] {
                    for j in 0..PACK {
                        let id = pack.ids[j];
                        if id == PADDING {
                            continue;
                        }
                        let (hit, t, u, v) = r.triangle(pack, j, &best.t);
                        let mut hit = hit & lanes;
                        while hit != 0 {
                            let i = hit.trailing_zeros() as usize;
                            hit &= hit - 1;
                            if closer(t[i], id, best.t[i], best.id[i]) {
                                best.t[i] = t[i];
                                best.id[i] = id;
                                best.u[i] = u[i];
                                best.v[i] = v[i];
                                cull[i] = cull_limit(t[i], r.reach[i]);
                            }
                        }
                    }
                }
            }
        }
        for (i, o) in out.iter_mut().enumerate() {
            *o = (best.id[i] != u32::MAX).then(|| Hit {
                t: best.t[i],
                u: best.u[i],
                v: best.v[i],
                prim: best.id[i],
            });
        }
    }

    #[inline(always)]
    fn any8(&self, rays: &[Ray], out: &mut [bool]) {
        let r = Rays8::new(rays);
        let limit: F8 = std::array::from_fn(|i| cull_limit(r.t_max[i], r.reach[i]));
        let mut done = 0u32;
        let buf = &mut [MaybeUninit::uninit(); PACKET_STACK];
        let mut stack: Stack<Entry> = Stack::new(buf);
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
                for c in 0..WIDTH {
                    let child = node.children[c];
                    if child == EMPTY {
                        break;
                    }
                    let (hit, near) = r.enter(node, c, &limit, lanes);
                    if hit != 0 {
                        stack.push(Entry {
                            child,
                            lanes: hit,
                            t_enter: near,
                        });
                    }
                }
            } else {
                let (first, count) = leaf_range(e.child);
                'packs: for pack in &self.triangles[first..first + count] {
                    for j in 0..PACK {
                        if pack.ids[j] == PADDING {
                            continue;
                        }
                        done |= r.triangle(pack, j, &r.t_max).0 & lanes;
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
