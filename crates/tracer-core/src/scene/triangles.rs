//! Triangles with what shading reads of them, in one frame: the scene's own triangles in scene
//! coordinates, or a reused mesh's in its local frame (its instances place it). Built mesh by
//! mesh from the neutral description.

use super::error::SceneError;
use crate::formats::{MaterialDescription, MeshDescription};
use glam::{DMat4, Vec2, Vec3, Vec4};

/// Sets of more triangles than this make their face normals when asked instead of keeping
/// them (12 bytes a triangle, 48 MB here): in a big scene traversal dominates and memory is
/// short; in a small one the stored normal saves a few percent of a path's time.
pub const STORED_NORMALS_MAX: usize = 4 << 20;

/// Per-triangle data, all arrays indexed by triangle. The vertices are the build's input: once
/// the BVH over them is built, it holds them ([`crate::bvh::Bvh::triangle`]) and `triangles` is
/// emptied.
#[derive(Clone, Debug, Default)]
pub struct TriangleSet {
    /// Vertices, until the BVH holds them.
    pub triangles: Vec<[Vec3; 3]>,
    /// Unit geometric normal of each triangle ([`face_normal`] of its vertices), kept for sets
    /// of up to [`STORED_NORMALS_MAX`] triangles; empty for larger ones, whose normals are
    /// made from the BVH's vertices when asked (the same numbers).
    pub normals: Vec<Vec3>,
    /// Vertex normals per corner for smooth shading (unit); zero for a triangle shaded flat.
    /// Empty when every triangle is flat.
    pub corner_normals: Vec<[Vec3; 3]>,
    /// Texture coordinates per corner, UV set 0 and set 1 (the image's frame, v = 0 at its
    /// top row); each empty when no mesh has that set.
    pub uvs: [Vec<[Vec2; 3]>; 2],
    /// Tangent (xyz unit, w the handedness: B = w · N × T) per corner where a normal map needs
    /// one; zero elsewhere, empty when no normal map is used.
    pub corner_tangents: Vec<[Vec4; 3]>,
    /// The scene's material slot of each triangle (a reused mesh: its part, which each
    /// instance turns into a slot of its own).
    pub slots: Vec<u32>,
}

impl TriangleSet {
    pub fn len(&self) -> usize {
        self.slots.len()
    }

    pub fn is_empty(&self) -> bool {
        self.slots.is_empty()
    }

    /// The corner normals of triangle `t` when it is shaded smooth.
    #[inline]
    pub fn smooth_corners(&self, t: usize) -> Option<[Vec3; 3]> {
        self.corner_normals
            .get(t)
            .filter(|c| c[0] != Vec3::ZERO)
            .copied()
    }

    /// The corner tangents of triangle `t` where a normal map needs them.
    #[inline]
    pub fn tangents(&self, t: usize) -> Option<[Vec4; 3]> {
        self.corner_tangents
            .get(t)
            .filter(|c| c[0] != Vec4::ZERO)
            .copied()
    }

    /// Appends `mesh`'s triangles placed by `m` (normals through its inverse transpose),
    /// each with slot `first_slot` + its part (parts past `part_count` read the last). Vertex
    /// normals are the file's, else averaged within `smooth_angle_deg`; tangents are computed
    /// where a part's material has a normal map.
    pub fn append_mesh(
        &mut self,
        mesh: &MeshDescription,
        materials: &[MaterialDescription],
        m: DMat4,
        smooth_angle_deg: f32,
        first_slot: u32,
        part_count: u32,
    ) -> Result<(), SceneError> {
        let mut world = Vec::with_capacity(mesh.positions.len());
        for v in &mesh.positions {
            let p = m.transform_point3(glam::DVec3::from(*v)).as_vec3();
            if !p.is_finite() {
                let (path, line) = mesh.placement_source();
                return Err(SceneError::NonFinitePlacement {
                    path,
                    line,
                    brep: mesh.name.clone(),
                });
            }
            world.push(p);
        }
        // Normals go through the inverse transpose of the placement.
        let normal_matrix = glam::DMat3::from_mat4(m).inverse().transpose();
        // Tangents where a part's material has a normal map (in the map's UV set): they need
        // the mesh's corner normals kept; other meshes take them one by one.
        let normal_set = mesh.parts.iter().find_map(|p| {
            let maps = materials.get(p.material?)?.maps.as_ref()?;
            maps.normal.as_ref().map(|n| usize::from(n.set.min(1)))
        });
        let mut mesh_normals = Vec::new();
        let first_triangle = self.triangles.len();
        let corner_normals = &mut self.corner_normals;
        super::smoothing::for_each_corner_normals(mesh, smooth_angle_deg, |t, corners| {
            if normal_set.is_some() {
                mesh_normals.push(corners);
            }
            let face = mesh.triangles[t].map(|i| world.get(i as usize).copied());
            let face_normal = match face {
                [Some(a), Some(b), Some(c)] => (b - a).cross(c - a).normalize_or_zero(),
                _ => Vec3::ZERO,
            };
            let world = corners.and_then(|c| {
                let out = c.map(|n| (normal_matrix * n).normalize_or_zero().as_vec3());
                let usable = out.iter().all(|n| n.is_finite() && *n != Vec3::ZERO);
                // Corners that all lie along the face normal (a plane) are shaded flat: the
                // same picture, without the cost.
                let planar = out.iter().all(|n| n.dot(face_normal).abs() >= 1.0 - 1e-6);
                (usable && !planar).then_some(out)
            });
            if world.is_some() && corner_normals.is_empty() {
                corner_normals.resize(first_triangle, [Vec3::ZERO; 3]);
            }
            if world.is_some() || !corner_normals.is_empty() {
                corner_normals.push(world.unwrap_or([Vec3::ZERO; 3]));
            }
        });
        if let Some(set) = normal_set {
            let local = super::tangents::mesh_tangents(mesh, &mesh_normals, set);
            if !local.is_empty() {
                let linear = glam::DMat3::from_mat4(m);
                let handedness = linear.determinant().signum() as f32;
                self.corner_tangents.resize(first_triangle, [Vec4::ZERO; 3]);
                self.corner_tangents.extend(local.iter().map(|t| {
                    t.map(|c| {
                        let xyz = (linear * c.truncate().as_dvec3()).normalize_or_zero();
                        xyz.as_vec3().extend(c.w * handedness)
                    })
                }));
            }
        }
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let fetch = |i: u32| world.get(i as usize).copied();
            let (Some(a), Some(b), Some(c)) = (fetch(tri[0]), fetch(tri[1]), fetch(tri[2])) else {
                return Err(SceneError::BadIndex {
                    brep: mesh.name.clone(),
                    triangle: t,
                });
            };
            self.triangles.push([a, b, c]);
            for (set, out) in self.uvs.iter_mut().enumerate() {
                let given = &mesh.uvs[set];
                if given.is_empty() && out.is_empty() {
                    continue;
                }
                // Meshes before the first with this set, and corners without, read (0, 0).
                out.resize(self.triangles.len() - 1, [Vec2::ZERO; 3]);
                out.push(tri.map(|i| {
                    given
                        .get(i as usize)
                        .map_or(Vec2::ZERO, |&uv| Vec2::from(uv))
                }));
            }
            let part = mesh
                .triangle_parts
                .get(t)
                .copied()
                .unwrap_or(0)
                .min(part_count - 1);
            self.slots.push(first_slot + part);
        }
        Ok(())
    }

    /// Pads the per-corner arrays to every triangle (the meshes after the last smooth, mapped
    /// or tangent-carrying one).
    pub fn pad(&mut self) {
        let n = self.slots.len();
        if !self.corner_normals.is_empty() {
            self.corner_normals.resize(n, [Vec3::ZERO; 3]);
        }
        for out in &mut self.uvs {
            if !out.is_empty() {
                out.resize(n, [Vec2::ZERO; 3]);
            }
        }
        if !self.corner_tangents.is_empty() {
            self.corner_tangents.resize(n, [Vec4::ZERO; 3]);
        }
        // Arrays grown push by push hold up to twice their length.
        self.corner_normals.shrink_to_fit();
        self.uvs.iter_mut().for_each(Vec::shrink_to_fit);
        self.corner_tangents.shrink_to_fit();
        self.slots.shrink_to_fit();
    }

    /// Builds the BVH over the vertices, which it then holds (the set's copy is freed), and
    /// the face normals of a set small enough to keep them.
    pub fn build_bvh(&mut self) -> crate::bvh::Bvh {
        let mut bvh = crate::bvh::Bvh::build(&self.triangles);
        self.normals = if self.triangles.len() <= STORED_NORMALS_MAX {
            self.triangles.iter().map(|&t| face_normal(t)).collect()
        } else {
            Vec::new()
        };
        self.triangles = Vec::new();
        bvh.index_triangles();
        bvh
    }

    /// The face normal of triangle `t`, whose vertices `bvh` holds.
    #[inline]
    pub fn normal(&self, t: usize, bvh: &crate::bvh::Bvh) -> Vec3 {
        match self.normals.get(t) {
            Some(n) => *n,
            None => face_normal(bvh.triangle(t)),
        }
    }

    /// Bytes held by the arrays.
    pub fn memory_bytes(&self) -> usize {
        self.triangles.capacity() * size_of::<[Vec3; 3]>()
            + self.normals.capacity() * size_of::<Vec3>()
            + self.corner_normals.capacity() * size_of::<[Vec3; 3]>()
            + self
                .uvs
                .iter()
                .map(|u| u.capacity() * size_of::<[Vec2; 3]>())
                .sum::<usize>()
            + self.corner_tangents.capacity() * size_of::<[Vec4; 3]>()
            + self.slots.capacity() * size_of::<u32>()
    }
}

/// The unit geometric normal of a triangle, `(v1 - v0) × (v2 - v0)` normalised (zero when
/// degenerate).
#[inline]
pub fn face_normal([a, b, c]: [Vec3; 3]) -> Vec3 {
    (b - a).cross(c - a).normalize_or_zero()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    /// A set too big to keep its normals makes the same ones, bit for bit, from the BVH.
    #[test]
    fn normals_made_when_asked_equal_the_kept_ones() {
        let mut set = TriangleSet::default();
        for i in 0..300 {
            let f = i as f32 * 0.1;
            set.triangles.push([
                Vec3::new(f.sin(), f.cos(), f),
                Vec3::new(f, 1.0 + f * f, -f),
                Vec3::new(2.0 * f, 0.5, f.sqrt()),
            ]);
            set.slots.push(0);
        }
        let input = set.triangles.clone();
        let bvh = set.build_bvh();
        assert!(set.triangles.is_empty());
        assert_eq!(set.normals.len(), 300);
        let kept: Vec<Vec3> = (0..300).map(|t| set.normal(t, &bvh)).collect();
        set.normals = Vec::new();
        for (t, n) in kept.iter().enumerate() {
            assert_eq!(
                set.normal(t, &bvh).to_array().map(f32::to_bits),
                n.to_array().map(f32::to_bits)
            );
            assert_eq!(*n, face_normal(input[t]));
        }
    }
}
