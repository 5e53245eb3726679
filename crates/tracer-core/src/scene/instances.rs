//! Meshes placed more than once: each is stored once in its own frame with its own BVH (a
//! prototype), and each placement (an instance) is a transform and a brep of its own, so it has
//! its own material slots. A tree over the instances' boxes is the top level of a two-level
//! BVH; rays go into a prototype's frame by the instance's inverse transform (the ray parameter
//! `t` is the same in both frames, directions are not renormalised).
//!
//! Triangle ids: an instance's triangles follow the scene's own ones, instance after instance,
//! so a hit names one triangle of the picture by one `u32`, as for a scene without instances.
//! [`Instances`] answers the per-triangle questions (vertices, normals, slot) for those ids,
//! counted from the first instanced triangle.

use super::triangles::{TriangleSet, face_normal};
use crate::bvh::{BoxTree, Bvh, Hit};
use crate::geometry::{Aabb, Ray};
use glam::{Affine3A, DMat4, Mat3A, Vec2, Vec3, Vec4};

/// Meshes of up to this many triangles get an instance box from their placed vertices; larger
/// ones from their BVH's top boxes.
const EXACT_BOUNDS_MAX: usize = 4096;

/// A mesh stored once: its triangles in its local frame (slots hold parts) and their BVH.
#[derive(Clone, Debug, Default)]
pub struct Prototype {
    pub set: TriangleSet,
    pub bvh: Bvh,
}

/// One placement of a prototype.
#[derive(Clone, Debug)]
pub struct Instance {
    pub prototype: u32,
    /// The brep it draws as (its name and slots).
    pub brep: u32,
    /// Its first triangle id, counted from the first instanced triangle.
    pub first: u32,
    /// The slot of its part 0.
    pub first_slot: u32,
    pub world_from_local: Affine3A,
    pub local_from_world: Affine3A,
    /// The inverse transpose of the linear part (normals).
    pub normal_matrix: Mat3A,
    /// The sign of the linear part's determinant (a mirror flips tangents' handedness).
    pub handedness: f32,
    /// Whether the transform is the identity (lookups then skip it: such an instance draws
    /// bit for bit what the mesh drawn directly would).
    pub identity: bool,
    /// Its triangles' box in scene coordinates.
    pub bounds: Aabb,
}

impl Instance {
    /// The instance of `prototype` placed by `m`, or None when `m` is not finite or not
    /// invertible.
    pub fn new(
        prototype: u32,
        proto: &Prototype,
        m: DMat4,
        brep: u32,
        first_slot: u32,
    ) -> Option<Self> {
        let world_from_local = Affine3A::from_mat4(m.as_mat4());
        let det = world_from_local.matrix3.determinant();
        if !world_from_local.is_finite() || det == 0.0 || !det.is_finite() {
            return None;
        }
        let local_from_world = world_from_local.inverse();
        if !local_from_world.is_finite() {
            return None;
        }
        let identity = world_from_local == Affine3A::IDENTITY;
        // A small mesh's vertices placed; a big one's top boxes (its tree's first two levels)
        // placed by their corners: a close box for a turned copy, where the turned box of the
        // whole mesh is loose.
        let bounds = if identity {
            proto.bvh.bounds()
        } else if proto.set.len() <= EXACT_BOUNDS_MAX {
            (0..proto.set.len())
                .flat_map(|t| proto.bvh.triangle(t))
                .fold(Aabb::EMPTY, |acc, p| {
                    acc.grow(world_from_local.transform_point3(p))
                })
        } else {
            let corners = |b: Aabb| {
                (0..8).map(move |corner: usize| {
                    let pick =
                        |bit: usize, lo: f32, hi: f32| if corner & bit != 0 { hi } else { lo };
                    Vec3::new(
                        pick(1, b.min.x, b.max.x),
                        pick(2, b.min.y, b.max.y),
                        pick(4, b.min.z, b.max.z),
                    )
                })
            };
            proto
                .bvh
                .cover_boxes()
                .into_iter()
                .flat_map(corners)
                .fold(Aabb::EMPTY, |acc, p| {
                    acc.grow(world_from_local.transform_point3(p))
                })
        };
        // Corners transformed in f32 can land an ulp inside the exact box: pad it so rays
        // grazing an instance's edge still reach its tree.
        let pad = (bounds.extent() + bounds.min.abs().max(bounds.max.abs())) * 4.0 * f32::EPSILON;
        let bounds = if identity {
            bounds
        } else {
            Aabb {
                min: bounds.min - pad,
                max: bounds.max + pad,
            }
        };
        Some(Instance {
            prototype,
            brep,
            first: 0,
            first_slot,
            world_from_local,
            local_from_world,
            normal_matrix: world_from_local.matrix3.inverse().transpose(),
            handedness: det.signum(),
            identity,
            bounds,
        })
    }

    /// `ray` in the prototype's frame (same `t`).
    #[inline]
    fn local_ray(&self, ray: &Ray) -> Ray {
        if self.identity {
            return *ray;
        }
        Ray {
            origin: self.local_from_world.transform_point3(ray.origin),
            dir: self.local_from_world.transform_vector3(ray.dir),
            t_min: ray.t_min,
            t_max: ray.t_max,
        }
    }
}

/// The scene's prototypes and instances, and the tree over the instances.
#[derive(Clone, Debug, Default)]
pub struct Instances {
    pub prototypes: Vec<Prototype>,
    /// In triangle-id order.
    pub instances: Vec<Instance>,
    tree: BoxTree,
    /// Triangles of all instances together.
    triangle_count: usize,
}

impl Instances {
    /// Numbers the instances' triangles and builds the tree over them. None when they would
    /// need more than `room` ids.
    pub fn new(
        prototypes: Vec<Prototype>,
        mut instances: Vec<Instance>,
        room: usize,
    ) -> Option<Self> {
        let mut next = 0usize;
        for i in &mut instances {
            i.first = u32::try_from(next).ok()?;
            next += prototypes[i.prototype as usize].set.len();
        }
        if next > room {
            return None;
        }
        let boxes: Vec<Aabb> = instances.iter().map(|i| i.bounds).collect();
        Some(Instances {
            tree: BoxTree::build(&boxes),
            prototypes,
            instances,
            triangle_count: next,
        })
    }

    pub fn is_empty(&self) -> bool {
        self.instances.is_empty()
    }

    pub fn triangle_count(&self) -> usize {
        self.triangle_count
    }

    pub fn bounds(&self) -> Aabb {
        self.tree.bounds()
    }

    /// The instance that triangle `id` belongs to, and the triangle in its prototype.
    #[inline]
    fn locate(&self, id: usize) -> (&Instance, &Prototype, usize) {
        let at = self
            .instances
            .partition_point(|i| i.first as usize <= id)
            .saturating_sub(1);
        let instance = &self.instances[at];
        let proto = &self.prototypes[instance.prototype as usize];
        (instance, proto, id - instance.first as usize)
    }

    /// Vertices of triangle `id`, scene coordinates.
    #[inline(never)]
    pub fn triangle(&self, id: usize) -> [Vec3; 3] {
        let (i, p, t) = self.locate(id);
        let local = p.bvh.triangle(t);
        if i.identity {
            return local;
        }
        local.map(|v| i.world_from_local.transform_point3(v))
    }

    /// Unit geometric normal of triangle `id`, from its vertices in scene coordinates (as the
    /// scene's own triangles have it: a mirror turns it with the winding).
    #[inline(never)]
    pub fn normal(&self, id: usize) -> Vec3 {
        let (i, p, t) = self.locate(id);
        if i.identity {
            return p.set.normal(t, &p.bvh);
        }
        face_normal(
            p.bvh
                .triangle(t)
                .map(|v| i.world_from_local.transform_point3(v)),
        )
    }

    /// Corner normals of triangle `id` when it is shaded smooth.
    #[inline(never)]
    pub fn smooth_corners(&self, id: usize) -> Option<[Vec3; 3]> {
        let (i, p, t) = self.locate(id);
        let c = p.set.smooth_corners(t)?;
        if i.identity {
            return Some(c);
        }
        Some(c.map(|n| (i.normal_matrix * n).normalize_or_zero()))
    }

    /// Texture coordinates of triangle `id`'s corners in UV set `set`, when the prototype has
    /// that set.
    #[inline(never)]
    pub fn uvs(&self, set: usize, id: usize) -> Option<[Vec2; 3]> {
        let (_, p, t) = self.locate(id);
        p.set.uvs[set].get(t).copied()
    }

    /// Corner tangents of triangle `id` where a normal map needs them.
    #[inline(never)]
    pub fn tangents(&self, id: usize) -> Option<[Vec4; 3]> {
        let (i, p, t) = self.locate(id);
        let c = p.set.tangents(t)?;
        if i.identity {
            return Some(c);
        }
        Some(c.map(|c| {
            let xyz = i
                .world_from_local
                .transform_vector3(c.truncate())
                .normalize_or_zero();
            xyz.extend(c.w * i.handedness)
        }))
    }

    /// Material slot of triangle `id`.
    #[inline(never)]
    pub fn slot(&self, id: usize) -> u32 {
        let (i, p, t) = self.locate(id);
        i.first_slot + p.set.slots[t]
    }

    /// Triangle ids of instance `instance`.
    pub fn range(&self, instance: usize) -> std::ops::Range<usize> {
        let i = &self.instances[instance];
        let n = self.prototypes[i.prototype as usize].set.len();
        i.first as usize..i.first as usize + n
    }

    /// The closest hit on an instance, or `best` (ids offset by `first_id`) when that is
    /// nearer: the least (t, id), as the triangle tree decides ties.
    #[inline(never)]
    pub fn intersect(&self, ray: &Ray, mut best: Option<Hit>, first_id: u32) -> Option<Hit> {
        if self.instances.is_empty() {
            return best;
        }
        let limit = best.map_or(ray.t_max, |h| h.t.min(ray.t_max));
        self.tree.walk(ray, limit, |k, t_max| {
            let instance = &self.instances[k as usize];
            let mut local = instance.local_ray(ray);
            local.t_max = t_max;
            let proto = &self.prototypes[instance.prototype as usize];
            if let Some(mut hit) = proto.bvh.intersect(&local) {
                hit.prim += first_id + instance.first;
                let better =
                    best.is_none_or(|b| hit.t < b.t || (hit.t == b.t && hit.prim < b.prim));
                if better {
                    best = Some(hit);
                    return hit.t;
                }
            }
            t_max
        });
        best
    }

    /// Whether an instance has a triangle within `[ray.t_min, ray.t_max]`.
    #[inline(never)]
    pub fn occluded(&self, ray: &Ray) -> bool {
        self.tree.any(ray, |k| {
            let instance = &self.instances[k as usize];
            let proto = &self.prototypes[instance.prototype as usize];
            proto.bvh.occluded(&instance.local_ray(ray))
        })
    }

    /// Bytes held: prototypes (triangles, shading data, BVHs) and instances.
    pub fn memory_bytes(&self) -> usize {
        self.prototypes
            .iter()
            .map(|p| p.set.memory_bytes() + p.bvh.memory_bytes())
            .sum::<usize>()
            + self.instances.capacity() * size_of::<Instance>()
    }
}
