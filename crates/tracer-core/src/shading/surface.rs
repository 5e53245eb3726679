//! The local frame at a ray's hit: the geometric normal, the shading normal interpolated from
//! the vertex normals (smooth shading), and the origin for rays that leave the surface.
//!
//! Two rules keep smooth shading honest on a coarse mesh:
//! - **No light leaks**: light counts only from directions above both the geometric and the
//!   shading surface, and a sampled direction below the geometric surface ends the path (it
//!   would pass through the mesh).
//! - **No black blotches at the shadow terminator**: where the shading normal says "lit" but the
//!   flat triangle itself lies in its neighbour's shadow, rays start from the point lifted onto
//!   the curved surface the vertex normals describe (Hanika, "Hacking the shadow terminator",
//!   Ray Tracing Gems II, 2021): the hit projected onto each corner's tangent plane when it lies
//!   below it, blended with the barycentric weights.

use super::Prepared;
use crate::bvh::Hit;
use glam::Vec3;

/// The frame at a hit, turned towards the side the ray came from.
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    /// The hit point on the triangle.
    pub p: Vec3,
    /// Unit geometric normal on the side the ray came from.
    pub ng: Vec3,
    /// Unit shading normal on the same side (`ng` for flat triangles).
    pub ns: Vec3,
    /// Origin for rays leaving on the `ng` side: the lifted point, offset by epsilon.
    pub origin: Vec3,
}

impl Surface {
    /// The frame at `hit` of a ray travelling along `dir`.
    pub fn at(prep: &Prepared<'_>, hit: &Hit, p: Vec3, dir: Vec3) -> Surface {
        let scene = prep.scene;
        let prim = hit.prim as usize;
        let n = scene.normals[prim];
        let ng = if n.dot(dir) > 0.0 { -n } else { n };
        let corners = scene
            .corner_normals
            .get(prim)
            .filter(|c| c[0] != Vec3::ZERO);
        let Some(c) = corners else {
            return Surface {
                p,
                ng,
                ns: ng,
                origin: p + ng * prep.epsilon,
            };
        };
        let (u, v) = (hit.u, hit.v);
        let w = 1.0 - u - v;
        let interpolated = c[0] * w + c[1] * u + c[2] * v;
        // The vertex normals on the side the ray came from.
        let sign = if interpolated.dot(ng) < 0.0 {
            -1.0
        } else {
            1.0
        };
        let ns = (interpolated * sign).try_normalize().unwrap_or(ng);
        let t = &scene.triangles[prim];
        let lift = |k: usize| {
            let nk = c[k] * sign;
            let below = (p - t[k]).dot(nk).min(0.0);
            p - nk * below
        };
        let lifted = lift(0) * w + lift(1) * u + lift(2) * v;
        let lifted = if lifted.is_finite() { lifted } else { p };
        Surface {
            p,
            ng,
            ns,
            origin: lifted + ng * prep.epsilon,
        }
    }

    /// Whether light arriving along unit `wi` (towards the light) can reach this side: above
    /// both the geometric and the shading surface.
    pub fn lit_from(&self, wi: Vec3) -> bool {
        self.ng.dot(wi) > 0.0 && self.ns.dot(wi) > 0.0
    }

    /// Origin for a ray leaving along `wi`: above the surface when `wi` is on the `ng` side,
    /// else just below the hit (refraction).
    pub fn origin_towards(&self, wi: Vec3, epsilon: f32) -> Vec3 {
        if self.ng.dot(wi) >= 0.0 {
            self.origin
        } else {
            self.p - self.ng * epsilon
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;
    use crate::formats::{MeshDescription, PartDescription, SceneDescription};
    use crate::geometry::Ray;
    use crate::scene::{LengthUnit, Scene, Setup};

    /// A UV sphere of radius 1 about the origin without vertex normals: `rings` × `segments`.
    fn sphere(rings: u32, segments: u32) -> SceneDescription {
        let mut positions = Vec::new();
        for i in 0..=rings {
            let theta = std::f64::consts::PI * f64::from(i) / f64::from(rings);
            for j in 0..segments {
                let phi = 2.0 * std::f64::consts::PI * f64::from(j) / f64::from(segments);
                positions.push([
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                ]);
            }
        }
        let at = |i: u32, j: u32| i * segments + j % segments;
        let mut triangles = Vec::new();
        for i in 0..rings {
            for j in 0..segments {
                let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j), at(i + 1, j + 1));
                if i > 0 {
                    triangles.push([a, b, c]);
                }
                if i + 1 < rings {
                    triangles.push([b, d, c]);
                }
            }
        }
        SceneDescription {
            meshes: vec![MeshDescription {
                name: "sphere".into(),
                positions,
                triangles,
                parts: vec![PartDescription::default()],
                ..MeshDescription::default()
            }],
            ..SceneDescription::default()
        }
    }

    #[test]
    fn smooth_normals_on_a_sphere_match_the_analytic_normal_within_one_degree() {
        let scene = Scene::build(sphere(24, 48), "sphere").expect("sphere");
        assert!(!scene.corner_normals.is_empty());

        let setup = Setup::defaults(&scene, LengthUnit::M);
        let prep = Prepared::new(&scene, &setup, 1);
        let flat = Scene::build_with(sphere(24, 48), "sphere", 0.0).expect("sphere");
        assert!(flat.corner_normals.is_empty());
        let flat_setup = Setup::defaults(&flat, LengthUnit::M);
        let flat_prep = Prepared::new(&flat, &flat_setup, 1);
        let (mut worst, mut worst_flat) = (0.0f32, 0.0f32);
        let mut rng = crate::sampling::SampleRng::new(7, 0);
        for _ in 0..20_000 {
            let (u, v) = rng.next_2d();
            let dir = crate::sampling::uniform_sphere(u, v);
            let ray = Ray::new(dir * 3.0, -dir);
            for (prep, worst) in [(&prep, &mut worst), (&flat_prep, &mut worst_flat)] {
                let hit = prep.closest_visible(&ray).expect("the sphere is hit");
                let p = ray.at(hit.t);
                let s = Surface::at(prep, &hit, p, ray.dir);
                let analytic = p.normalize();
                *worst = worst.max(s.ns.dot(analytic).clamp(-1.0, 1.0).acos().to_degrees());
                // The lifted origin stays outside the sphere's triangles, never inside.
                assert!(s.origin.length() >= p.length() - 1e-5);
            }
        }
        assert!(worst < 1.0, "smooth: {worst}°");
        // The flat normals are several degrees off, so the test can tell the two apart.
        assert!(worst_flat > 3.0, "flat: {worst_flat}°");
    }
}
