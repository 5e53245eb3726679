//! The triangle test shared by the BVH and the brute-force reference: the watertight test of
//! Woop, Benthin and Wald ("Watertight Ray/Triangle Intersection", JCGT 2013), two-sided.
//!
//! Why not Möller–Trumbore: with `>= 0` bounds (and even with 1e-6 slack) it let rays through
//! edge midpoints of a closed `uv_sphere(64)` pass between the thin triangles at the poles. The
//! watertight test moves each vertex into a ray-aligned frame the same way for every triangle
//! sharing it, so a shared edge's edge function is exactly negated between the two triangles
//! and zero counts as inside: a ray through an edge or vertex of a closed mesh always hits.

use glam::Vec3;

use super::Hit;
use crate::geometry::Ray;

/// A triangle's three vertices, as given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Triangle {
    pub v: [Vec3; 3],
}

/// A ray prepared for the watertight test: `kz` is the dominant direction axis, `kx`, `ky` the
/// other two; the shear maps the direction onto the `+kz` unit axis.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RayTriangles {
    origin: Vec3,
    k: [usize; 3],
    shear: [f32; 3],
    t_min: f32,
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
        Self {
            origin: ray.origin,
            k: [kx, ky, kz],
            shear: [d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]],
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
