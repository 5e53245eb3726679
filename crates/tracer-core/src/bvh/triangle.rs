//! The triangle test shared by the BVH and the brute-force reference: the watertight test of
//! Woop, Benthin and Wald ("Watertight Ray/Triangle Intersection", JCGT 2013), two-sided.
//!
//! Why not Möller–Trumbore: with `>= 0` bounds (and even with 1e-6 slack) it let rays through
//! edge midpoints of a closed `uv_sphere(64)` pass between the thin triangles at the poles. The
//! watertight test moves each vertex into a ray-aligned frame the same way for every triangle
//! sharing it, so a shared edge's edge function is exactly negated between the two triangles
//! and zero counts as inside: a ray through an edge or vertex of a closed mesh always hits.

// Lane loops index several parallel arrays by lane on purpose: that is the shape the compiler
// turns into one vector instruction per step.
#![allow(clippy::needless_range_loop)]

use glam::Vec3;

use super::simd::F4;
use super::{Hit, PADDING};
use crate::geometry::Ray;

/// A triangle's three vertices, as given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Triangle {
    pub v: [Vec3; 3],
}

/// Lanes of a [`Tri4`].
pub(crate) const PACK: usize = 4;

/// Up to four triangles side by side, `v[vertex][axis][lane]`, so one ray is tested against all
/// four with the same instructions, and each lane's index in the caller's slice (kept here, in
/// the cache lines the test has just read, rather than in an array of its own: on large meshes
/// that lookup was one more cache miss per hit). Unused lanes repeat one vertex (a degenerate
/// triangle, never hit) and have the id [`PADDING`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(16))]
pub(crate) struct Tri4 {
    pub v: [[[f32; PACK]; 3]; 3],
    pub ids: [u32; PACK],
}

impl Tri4 {
    /// Packs `tris` (1..=4 of them) with their `ids`; unused lanes become the first triangle's
    /// `v0` thrice, with the id [`PADDING`].
    pub fn new(tris: &[[Vec3; 3]], ids: &[u32]) -> Self {
        let pad = [tris[0][0]; 3];
        let mut v = [[[0.0; PACK]; 3]; 3];
        for lane in 0..PACK {
            let t = tris.get(lane).unwrap_or(&pad);
            for (vertex, p) in t.iter().enumerate() {
                for axis in 0..3 {
                    v[vertex][axis][lane] = p[axis];
                }
            }
        }
        Self {
            v,
            ids: std::array::from_fn(|lane| ids.get(lane).copied().unwrap_or(PADDING)),
        }
    }

    pub fn vertex(&self, lane: usize, vertex: usize) -> Vec3 {
        let p = &self.v[vertex];
        Vec3::new(p[0][lane], p[1][lane], p[2][lane])
    }

    /// Whether `lane` holds the padding (all three vertices equal).
    pub fn is_degenerate(&self, lane: usize) -> bool {
        let a = self.vertex(lane, 0);
        a == self.vertex(lane, 1) && a == self.vertex(lane, 2)
    }

    /// [`Triangle::intersect`] on all four lanes, the same operations in the same order per
    /// lane (so results are bit for bit those of the scalar test). Returns the lanes hit at `t`
    /// in `[t_min, t_max]` as bits, `t` and the unnormalised `v`, `w` and `1 / det`.
    ///
    /// With `EARLY_OUT`, four misses of the edge tests return at once, before the division
    /// (closest hits, where most tests miss; any-hit traversal compiles better without it).
    #[inline(always)]
    fn lanes<const EARLY_OUT: bool>(&self, r: &RayTriangles, t_max: f32) -> (u32, [F4; 4]) {
        let [kx, ky, kz] = r.k;
        let (sx, sy, sz) = (
            F4::splat(r.shear[0]),
            F4::splat(r.shear[1]),
            F4::splat(r.shear[2]),
        );
        let o = r.origin.to_array();
        let (ox, oy, oz) = (F4::splat(o[kx]), F4::splat(o[ky]), F4::splat(o[kz]));
        // Sheared vertex coordinates: x, y in the ray's frame and the unsheared z.
        let frame = |p: &[[f32; PACK]; 3]| {
            let z = F4::load(&p[kz]) - oz;
            (
                (F4::load(&p[kx]) - ox) - sx * z,
                (F4::load(&p[ky]) - oy) - sy * z,
                z,
            )
        };
        let (ax, ay, az) = frame(&self.v[0]);
        let (bx, by, bz) = frame(&self.v[1]);
        let (cx, cy, cz) = frame(&self.v[2]);
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        let zero = F4::splat(0.0);
        let negative = u.lt(zero).or(v.lt(zero)).or(w.lt(zero));
        let positive = u.gt(zero).or(v.gt(zero)).or(w.gt(zero));
        let det = u + v + w;
        let inside = det.ne(zero).and_not(negative.and(positive));
        if EARLY_OUT && inside.bits() == 0 {
            // The ray passes beside all four (most tests): no division, no distances.
            return (0, [zero; 4]);
        }
        let t_scaled = sz * (u * az + v * bz + w * cz);
        let inv_det = F4::splat(1.0) / det;
        let t = t_scaled * inv_det;
        let hit = inside
            .and(t.ge(F4::splat(r.t_min)))
            .and(t.le(F4::splat(t_max)));
        (hit.bits(), [t, v, w, inv_det])
    }

    /// The nearest hit lane with `t` in `[t_min, t_max]`: `(lane, t, u, v)`; of lanes at the
    /// same `t`, the one with the smallest id (see [`closer`]).
    #[inline(always)]
    pub fn intersect(&self, r: &RayTriangles, t_max: f32) -> Option<(usize, f32, f32, f32)> {
        let (mut bits, [t, v, w, inv_det]) = self.lanes::<true>(r, t_max);
        if bits == 0 {
            return None;
        }
        let t = t.to_array();
        let mut best = bits.trailing_zeros() as usize;
        bits &= bits - 1;
        while bits != 0 {
            let lane = bits.trailing_zeros() as usize;
            if closer(t[lane], self.ids[lane], t[best], self.ids[best]) {
                best = lane;
            }
            bits &= bits - 1;
        }
        let inv_det = inv_det.to_array()[best];
        Some((
            best,
            t[best],
            v.to_array()[best] * inv_det,
            w.to_array()[best] * inv_det,
        ))
    }

    /// Whether any lane is hit with `t` in `[t_min, t_max]`.
    #[inline(always)]
    pub fn occludes(&self, r: &RayTriangles, t_max: f32) -> bool {
        self.lanes::<false>(r, t_max).0 != 0
    }
}

/// Whether a hit on triangle `id` at `t` beats the best so far (`best_t`, `best_id`): nearer,
/// or as near with a smaller id. The closest hit is then the least (t, id) of all triangles
/// hit, whatever order they are met in, so single rays, packets and the brute-force reference
/// (which keeps the first of equal hits in index order) agree bit for bit even on ties at
/// shared edges.
#[inline(always)]
pub(crate) fn closer(t: f32, id: u32, best_t: f32, best_id: u32) -> bool {
    t < best_t || (t == best_t && id < best_id)
}

/// A ray prepared for the watertight test: `kz` is the dominant direction axis, `kx`, `ky` the
/// other two; the shear maps the direction onto the `+kz` unit axis.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RayTriangles {
    pub origin: Vec3,
    pub k: [usize; 3],
    pub shear: [f32; 3],
    pub t_min: f32,
}

impl RayTriangles {
    pub fn new(ray: &Ray) -> Self {
        let d = ray.dir.to_array();
        let a = ray.dir.abs();
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        // One division: the shear's rounding differs a little from two more divisions, but it
        // is the same for every triangle the ray meets, which is all watertightness needs.
        let inv_z = 1.0 / d[kz];
        Self {
            origin: ray.origin,
            k: [kx, ky, kz],
            shear: [d[kx] * inv_z, d[ky] * inv_z, inv_z],
            t_min: ray.t_min,
        }
    }
}

impl Triangle {
    pub fn new(v: &[Vec3; 3]) -> Self {
        Self { v: *v }
    }

    /// Returns `(t, u, v)` (barycentrics of `v1` and `v2`) when the ray meets the triangle,
    /// edges and vertices included, at `t` in `[t_min, t_max]`. Rays in the triangle's plane
    /// and degenerate triangles miss.
    #[inline(always)]
    pub fn intersect(&self, r: &RayTriangles, t_max: f32) -> Option<(f32, f32, f32)> {
        let [kx, ky, kz] = r.k;
        let [sx, sy, sz] = r.shear;
        let a = (self.v[0] - r.origin).to_array();
        let b = (self.v[1] - r.origin).to_array();
        let c = (self.v[2] - r.origin).to_array();
        let (ax, ay) = (a[kx] - sx * a[kz], a[ky] - sy * a[kz]);
        let (bx, by) = (b[kx] - sx * b[kz], b[ky] - sy * b[kz]);
        let (cx, cy) = (c[kx] - sx * c[kz], c[ky] - sy * c[kz]);
        // Edge functions: u for edge b-c (weight of v0), v for c-a, w for a-b.
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let t_scaled = sz * (u * a[kz] + v * b[kz] + w * c[kz]);
        let inv_det = 1.0 / det;
        let t = t_scaled * inv_det;
        if !(r.t_min..=t_max).contains(&t) {
            return None;
        }
        Some((t, v * inv_det, w * inv_det))
    }
}

/// Reference closest hit: every triangle, the same test as the BVH.
pub fn intersect_brute_force(triangles: &[[Vec3; 3]], ray: &Ray) -> Option<Hit> {
    let r = RayTriangles::new(ray);
    let mut best: Option<Hit> = None;
    for (prim, v) in triangles.iter().enumerate() {
        let t_max = best.map_or(ray.t_max, |b| b.t);
        if let Some((t, u, v)) = Triangle::new(v).intersect(&r, t_max)
            && best.is_none_or(|b| t < b.t)
        {
            best = Some(Hit {
                t,
                u,
                v,
                prim: prim as u32,
            });
        }
    }
    best
}

/// Reference any hit: every triangle until the first hit, the same test as the BVH.
pub fn occluded_brute_force(triangles: &[[Vec3; 3]], ray: &Ray) -> bool {
    let r = RayTriangles::new(ray);
    triangles
        .iter()
        .any(|v| Triangle::new(v).intersect(&r, ray.t_max).is_some())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_lanes_match_the_scalar_test_bit_for_bit() {
        let tris = [
            [Vec3::ZERO, Vec3::X, Vec3::Y],
            [
                Vec3::new(0.1, 0.3, -0.5),
                Vec3::new(0.9, 0.2, -0.4),
                Vec3::new(0.2, 0.8, -0.6),
            ],
            [
                Vec3::new(-1.0, 0.0, 0.3),
                Vec3::new(1.0, 1.0, 0.1),
                Vec3::new(0.0, -1.0, 0.2),
            ],
        ];
        let pack = Tri4::new(&tris, &[0, 1, 2]);
        assert!(pack.is_degenerate(3) && !pack.is_degenerate(2));
        for (k, dir) in [
            Vec3::NEG_Z,
            Vec3::new(0.1, -0.2, -1.0),
            Vec3::new(-0.7, 0.1, 0.2),
            // Beside all three.
            Vec3::new(3.0, 4.0, -1.0),
        ]
        .into_iter()
        .enumerate()
        {
            let origin = Vec3::new(0.25, 0.2, 1.0) - dir * (k as f32);
            let r = RayTriangles::new(&Ray::new(origin, dir));
            // With and without the early return on four edge-test misses.
            for (hit, [t, v, w, inv]) in [
                pack.lanes::<false>(&r, f32::INFINITY),
                pack.lanes::<true>(&r, f32::INFINITY),
            ] {
                let [t, v, w, inv] = [t, v, w, inv].map(F4::to_array);
                for (lane, tri) in tris.iter().enumerate() {
                    let scalar = Triangle::new(tri).intersect(&r, f32::INFINITY);
                    let wide = (hit >> lane & 1 == 1).then_some((
                        t[lane],
                        v[lane] * inv[lane],
                        w[lane] * inv[lane],
                    ));
                    assert_eq!(scalar.map(|h| h.0.to_bits()), wide.map(|h| h.0.to_bits()));
                    assert_eq!(scalar, wide, "lane {lane} dir {dir}");
                }
                assert_eq!(hit >> 3, 0);
            }
        }
    }

    const TRI: [Vec3; 3] = [Vec3::ZERO, Vec3::X, Vec3::Y];

    fn hit(origin: Vec3, dir: Vec3) -> Option<(f32, f32, f32)> {
        let r = RayTriangles::new(&Ray::new(origin, dir));
        Triangle::new(&TRI).intersect(&r, f32::INFINITY)
    }

    #[test]
    fn hits_both_sides_with_barycentrics_of_v1_and_v2() {
        let front = hit(Vec3::new(0.25, 0.5, 1.0), Vec3::NEG_Z);
        assert_eq!(front, Some((1.0, 0.25, 0.5)));
        let back = hit(Vec3::new(0.25, 0.5, -2.0), Vec3::Z * 2.0);
        assert_eq!(back, Some((1.0, 0.25, 0.5)));
    }

    #[test]
    fn edges_and_vertices_are_inclusive() {
        for p in [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(0.5, 0.0, 0.0)] {
            assert!(hit(p + Vec3::Z, Vec3::NEG_Z).is_some(), "{p}");
        }
        assert!(hit(Vec3::new(0.5, 0.5001, 1.0), Vec3::NEG_Z).is_none());
        assert!(hit(Vec3::new(-0.0001, 0.5, 1.0), Vec3::NEG_Z).is_none());
    }

    #[test]
    fn parallel_and_degenerate_miss() {
        assert!(hit(Vec3::new(-1.0, 0.2, 0.0), Vec3::X).is_none());
        let line = Triangle::new(&[Vec3::ZERO, Vec3::X, Vec3::X * 2.0]);
        let r = RayTriangles::new(&Ray::new(Vec3::new(0.5, 0.0, 1.0), Vec3::NEG_Z));
        assert!(line.intersect(&r, 10.0).is_none());
    }

    #[test]
    fn t_range_is_inclusive() {
        let t = Triangle::new(&TRI);
        let ray = |t_min, t_max| {
            RayTriangles::new(&Ray {
                origin: Vec3::new(0.2, 0.2, 1.0),
                dir: Vec3::NEG_Z,
                t_min,
                t_max,
            })
        };
        assert!(t.intersect(&ray(1.0, 1.0), 1.0).is_some());
        assert!(t.intersect(&ray(0.0, 0.999), 0.999).is_none());
        assert!(t.intersect(&ray(1.001, 5.0), 5.0).is_none());
    }
}
