//! What the renderer asks of a scene's triangles, by triangle id (the `prim` of a hit): rays
//! through both BVH levels, and each triangle's vertices, normals, texture coordinates and
//! material slot in scene coordinates, whether it is one of the scene's own or an instance's.

use super::geometry::Scene;
use super::instances::Instances;
use crate::bvh::{Bvh, Hit, PACKET};
use crate::geometry::Ray;
use glam::{Vec2, Vec3, Vec4};
use std::ops::Range;

impl Scene {
    /// Triangles in the picture, every instance's counted.
    pub fn triangle_count(&self) -> usize {
        self.own.len() + self.instances.triangle_count()
    }

    /// The scene's own triangles (drawn once): ids `0 .. own_triangle_count()`.
    pub fn own_triangle_count(&self) -> usize {
        self.own.len()
    }

    /// Triangles stored: the scene's own and each reused mesh's once.
    pub fn stored_triangle_count(&self) -> usize {
        self.own.len()
            + self
                .instances
                .prototypes
                .iter()
                .map(|p| p.set.len())
                .sum::<usize>()
    }

    /// Instances of meshes drawn several times (0 without).
    pub fn instance_count(&self) -> usize {
        self.instances.instances.len()
    }

    /// "N triangles", with how many are stored and the instances when meshes are reused
    /// ("69451000 triangles (69451 stored, 1000 instances)").
    pub fn triangles_label(&self) -> String {
        let n = self.triangle_count();
        match self.instance_count() {
            0 => format!("{n} triangles"),
            k => format!(
                "{n} triangles ({} stored, {k} instances)",
                self.stored_triangle_count()
            ),
        }
    }

    /// The BVH over the scene's own triangles (statistics).
    pub fn own_bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// The instances (statistics and the shard hash).
    pub fn instances(&self) -> &Instances {
        &self.instances
    }

    /// Bytes held by triangles, their shading data and the BVHs.
    pub fn geometry_bytes(&self) -> usize {
        self.own.memory_bytes() + self.bvh.memory_bytes() + self.instances.memory_bytes()
    }

    /// Every triangle's vertices in id order, scene coordinates (instances placed).
    pub fn triangles(&self) -> impl Iterator<Item = [Vec3; 3]> + '_ {
        (0..self.triangle_count() as u32).map(|t| self.triangle(t))
    }

    /// Vertices of triangle `prim`, scene coordinates.
    #[inline]
    pub fn triangle(&self, prim: u32) -> [Vec3; 3] {
        let p = prim as usize;
        if p < self.own.len() {
            return self.bvh.triangle(p);
        }
        self.instances.triangle(p - self.own.len())
    }

    /// Unit geometric normal of triangle `prim`, `(v1 - v0) × (v2 - v0)` normalised (zero when
    /// degenerate).
    #[inline]
    pub fn normal(&self, prim: u32) -> Vec3 {
        let p = prim as usize;
        if p < self.own.len() {
            return self.own.normal(p, &self.bvh);
        }
        self.instances.normal(p - self.own.len())
    }

    /// Whether some triangle is shaded smooth.
    #[inline]
    pub fn any_smooth(&self) -> bool {
        !self.own.corner_normals.is_empty()
            || self
                .instances
                .prototypes
                .iter()
                .any(|p| !p.set.corner_normals.is_empty())
    }

    /// The vertex normals of triangle `prim`'s corners (unit) when it is shaded smooth.
    #[inline]
    pub fn smooth_corners(&self, prim: u32) -> Option<[Vec3; 3]> {
        let p = prim as usize;
        if p < self.own.len() {
            return self.own.smooth_corners(p);
        }
        self.instances.smooth_corners(p - self.own.len())
    }

    /// Texture coordinates of triangle `prim`'s corners in UV set `set` (0 or 1), when its
    /// mesh has that set.
    #[inline]
    pub fn corner_uvs(&self, set: usize, prim: u32) -> Option<[Vec2; 3]> {
        let p = prim as usize;
        if p < self.own.len() {
            return self.own.uvs[set].get(p).copied();
        }
        self.instances.uvs(set, p - self.own.len())
    }

    /// Tangents of triangle `prim`'s corners where a normal map needs them.
    #[inline]
    pub fn corner_tangents(&self, prim: u32) -> Option<[Vec4; 3]> {
        let p = prim as usize;
        if p < self.own.len() {
            return self.own.tangents(p);
        }
        self.instances.tangents(p - self.own.len())
    }

    /// Material slot of triangle `prim` (None past the last triangle).
    #[inline]
    pub fn slot_of(&self, prim: u32) -> Option<u32> {
        let p = prim as usize;
        match self.own.slots.get(p) {
            Some(s) => Some(*s),
            None if p < self.triangle_count() => Some(self.instances.slot(p - self.own.len())),
            None => None,
        }
    }

    /// Material slot of triangle `prim` (which must be a triangle of the scene).
    #[inline]
    pub fn slot(&self, prim: u32) -> u32 {
        let p = prim as usize;
        match self.own.slots.get(p) {
            Some(s) => *s,
            None => self.instances.slot(p - self.own.len()),
        }
    }

    /// The triangle ids of brep `brep`.
    pub fn brep_triangles(&self, brep: usize) -> Range<usize> {
        let b = &self.breps[brep];
        match b.instance {
            Some(i) => {
                let r = self.instances.range(i as usize);
                r.start + self.own.len()..r.end + self.own.len()
            }
            None => b.first_triangle..b.first_triangle + b.triangle_count,
        }
    }

    /// The closest hit within `[ray.t_min, ray.t_max]`: the least (t, id), as the BVH decides
    /// ties.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let hit = self.bvh.intersect(ray);
        if self.instances.is_empty() {
            return hit;
        }
        self.instances.intersect(ray, hit, self.own.len() as u32)
    }

    /// Whether a triangle lies within `[ray.t_min, ray.t_max]`.
    #[inline]
    pub fn occluded(&self, ray: &Ray) -> bool {
        self.bvh.occluded(ray) || (!self.instances.is_empty() && self.instances.occluded(ray))
    }

    /// [`Scene::intersect`] of up to [`PACKET`] rays, the own triangles' tree walked by all of
    /// them together.
    pub fn intersect_packet(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        debug_assert!(rays.len() <= PACKET);
        self.bvh.intersect_packet(rays, out);
        if self.instances.is_empty() {
            return;
        }
        let first = self.own.len() as u32;
        for (o, r) in out.iter_mut().zip(rays) {
            *o = self.instances.intersect(r, *o, first);
        }
    }

    /// [`Scene::occluded`] of up to [`PACKET`] rays.
    pub fn occluded_packet(&self, rays: &[Ray], out: &mut [bool]) {
        self.bvh.occluded_packet(rays, out);
        if self.instances.is_empty() {
            return;
        }
        for (o, r) in out.iter_mut().zip(rays) {
            *o = *o || self.instances.occluded(r);
        }
    }
}
