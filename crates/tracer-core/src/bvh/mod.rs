//! TEMPORARY brute-force stand-in with the BVH's interface (replaced by the real BVH branch).
use crate::geometry::{Aabb, Ray};
use glam::Vec3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f32,
    pub u: f32,
    pub v: f32,
    pub prim: u32,
}

#[derive(Debug, Default)]
pub struct Bvh {
    tris: Vec<[Vec3; 3]>,
}

impl Bvh {
    pub fn build(triangles: &[[Vec3; 3]]) -> Bvh {
        Bvh {
            tris: triangles.to_vec(),
        }
    }
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut r = *ray;
        for (i, t) in self.tris.iter().enumerate() {
            let e1 = t[1] - t[0];
            let e2 = t[2] - t[0];
            let p = r.dir.cross(e2);
            let det = e1.dot(p);
            if det.abs() < 1e-20 {
                continue;
            }
            let inv = 1.0 / det;
            let s = r.origin - t[0];
            let u = s.dot(p) * inv;
            if !(0.0..=1.0).contains(&u) {
                continue;
            }
            let q = s.cross(e1);
            let v = r.dir.dot(q) * inv;
            if v < 0.0 || u + v > 1.0 {
                continue;
            }
            let tt = e2.dot(q) * inv;
            if tt >= r.t_min && tt <= r.t_max {
                r.t_max = tt;
                best = Some(Hit {
                    t: tt,
                    u,
                    v,
                    prim: i as u32,
                });
            }
        }
        best
    }
    pub fn occluded(&self, ray: &Ray) -> bool {
        self.intersect(ray).is_some()
    }
    pub fn validate(&self) -> Result<(), String> {
        Ok(())
    }
    pub fn bounds(&self) -> Aabb {
        self.tris
            .iter()
            .flatten()
            .fold(Aabb::EMPTY, |b, &p| b.grow(p))
    }
    pub fn triangle_count(&self) -> usize {
        self.tris.len()
    }
    pub fn node_count(&self) -> usize {
        1
    }
    pub fn memory_bytes(&self) -> usize {
        self.tris.len() * 36
    }
}
