//! Tangents for normal maps: the file's (glTF `TANGENT`) where it gives them, else MikkTSpace's
//! (the `mikktspace` crate, the tangent basis glTF and Blender bake normal maps in), computed
//! with v up the image so that B = w · N × T points up it.

use crate::formats::MeshDescription;
use glam::{DVec3, Vec4};

/// One mesh for `mikktspace`: its triangles, corner normals, one UV set, and the tangents out.
struct Mikk<'m> {
    mesh: &'m MeshDescription,
    normals: &'m [Option<[DVec3; 3]>],
    set: usize,
    out: Vec<[Vec4; 3]>,
}

impl Mikk<'_> {
    fn corner(&self, face: usize, vert: usize) -> usize {
        self.mesh
            .triangles
            .get(face)
            .map_or(0, |t| t[vert.min(2)] as usize)
    }

    fn face_normal(&self, face: usize) -> DVec3 {
        let p = |k: usize| {
            self.mesh
                .positions
                .get(self.corner(face, k))
                .map_or(DVec3::ZERO, |&p| DVec3::from(p))
        };
        (p(1) - p(0)).cross(p(2) - p(0)).normalize_or_zero()
    }
}

impl mikktspace::Geometry for Mikk<'_> {
    fn num_faces(&self) -> usize {
        self.mesh.triangles.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh
            .positions
            .get(self.corner(face, vert))
            .map_or([0.0; 3], |p| p.map(|x| x as f32))
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        let n = match self.normals.get(face).copied().flatten() {
            Some(c) => c[vert.min(2)],
            None => self.face_normal(face),
        };
        n.as_vec3().to_array()
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        let [u, v] = self.mesh.uvs[self.set]
            .get(self.corner(face, vert))
            .copied()
            .unwrap_or([0.0; 2]);
        // v up the image: MikkTSpace's bitangent then points up it.
        [u, 1.0 - v]
    }

    fn set_tangent_encoded(&mut self, tangent: [f32; 4], face: usize, vert: usize) {
        if let Some(t) = self.out.get_mut(face) {
            t[vert.min(2)] = Vec4::from(tangent);
        }
    }
}

/// The tangent (xyz, handedness w) at each triangle corner of `mesh` in its local coordinates,
/// from UV set `set` and the corner normals `normals` (None: flat); empty when the mesh has no
/// such UVs or MikkTSpace fails.
pub fn mesh_tangents(
    mesh: &MeshDescription,
    normals: &[Option<[DVec3; 3]>],
    set: usize,
) -> Vec<[Vec4; 3]> {
    if mesh.tangents.len() == mesh.positions.len() && !mesh.tangents.is_empty() {
        return mesh
            .triangles
            .iter()
            .map(|t| {
                t.map(|i| {
                    mesh.tangents
                        .get(i as usize)
                        .map_or(Vec4::ZERO, |&x| Vec4::from(x))
                })
            })
            .collect();
    }
    if mesh
        .uvs
        .get(set)
        .is_none_or(|u| u.len() != mesh.positions.len())
    {
        return Vec::new();
    }
    let mut m = Mikk {
        mesh,
        normals,
        set,
        out: vec![[Vec4::ZERO; 3]; mesh.triangles.len()],
    };
    if mikktspace::generate_tangents(&mut m) {
        m.out
    } else {
        Vec::new()
    }
}
