//! The local frame at a ray's hit: the geometric normal, the shading normal interpolated from
//! the vertex normals (smooth shading), and the origin for rays that leave the surface.
//!
//! Two rules keep smooth shading honest on a coarse mesh:
//! - **No black blotches at the shadow terminator**: the shading normal decides whether a light
//!   is in front (as on the smooth surface the normals describe), and shadow rays start from the
//!   hit lifted onto that surface (Hanika, "Hacking the shadow terminator", Ray Tracing Gems II,
//!   2021): the hit projected onto each corner's tangent plane when it lies below it, blended
//!   with the barycentric weights. From the flat triangle itself, a light the shading normal
//!   faces but the triangle does not would be shadowed by the triangle's own plane: a faceted,
//!   blotchy terminator.
//! - **No light leaks**: the shadow ray decides what the light reaches, from that lifted point
//!   on the side the ray came from; a scattered direction that the shading normal sends below
//!   the triangle (or above it for a refraction) ends the path, since it would pass through
//!   the mesh.

use super::LitScene;
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
    /// The frame at `hit` of a ray travelling along `dir`. (Inlined: called, its vector
    /// arguments went through memory in pieces the CPU could not forward to its loads.)
    #[inline(always)]
    pub fn at(lit: &LitScene<'_>, hit: &Hit, p: Vec3, dir: Vec3) -> Surface {
        let scene = lit.scene;
        let n = scene.normal(hit.prim);
        let ng = if n.dot(dir) > 0.0 { -n } else { n };
        let Some(c) = scene.smooth_corners(hit.prim) else {
            let ns = if lit.bends_normals() {
                // The map bends the face's own normal, then it turns to the ray's side.
                let bent = lit.bent_normal(hit.prim, [hit.u, hit.v], n);
                crate::texture::above_surface(if ng == n { bent } else { -bent }, ng)
            } else {
                ng
            };
            return Surface {
                p,
                ng,
                ns,
                origin: p + ng * lit.epsilon,
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
        let mut ns = (interpolated * sign).try_normalize().unwrap_or(ng);
        if lit.bends_normals() {
            // Maps bend the vertex normals' own side (their tangent space), then it turns.
            let bent = lit.bent_normal(hit.prim, [hit.u, hit.v], ns * sign);
            ns = crate::texture::above_surface(bent * sign, ng);
        }
        let t = scene.triangle(hit.prim);
        let lift = |k: usize| {
            let nk = c[k] * sign;
            // `min(0.0)` spelt out: the lanes of the direct wavefront compute it the same way,
            // down to the sign of a zero.
            let d = (p - t[k]).dot(nk);
            let below = if d < 0.0 { d } else { 0.0 };
            p - nk * below
        };
        let lifted = lift(0) * w + lift(1) * u + lift(2) * v;
        let lifted = if lifted.is_finite() { lifted } else { p };
        Surface {
            p,
            ng,
            ns,
            origin: lifted + ng * lit.epsilon,
        }
    }

    /// Whether light arriving along unit `wi` (towards the light) is in front of the surface the
    /// vertex normals describe (the shadow ray from [`Surface::origin`] decides the rest).
    pub fn lit_from(&self, wi: Vec3) -> bool {
        self.ns.dot(wi) > 0.0
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
    use crate::geometry::Ray;
    use crate::scene::{LengthUnit, Scene, Setup};
    use crate::test_scenes::sphere;

    #[test]
    fn smooth_normals_on_a_sphere_match_the_analytic_normal_within_one_degree() {
        let scene = Scene::build(sphere(24, 48), "sphere").expect("sphere");
        assert!(scene.any_smooth());

        let setup = Setup::defaults(&scene, LengthUnit::M);
        let lit = LitScene::new(&scene, &setup, 1);
        let flat = Scene::build_with(sphere(24, 48), "sphere", 0.0).expect("sphere");
        assert!(!flat.any_smooth());
        let flat_setup = Setup::defaults(&flat, LengthUnit::M);
        let flat_prep = LitScene::new(&flat, &flat_setup, 1);
        let (mut worst, mut worst_flat) = (0.0f32, 0.0f32);
        let mut rng = crate::sampling::SampleRng::new(7, 0);
        for _ in 0..20_000 {
            let (u, v) = rng.next_2d();
            let dir = crate::sampling::uniform_sphere(u, v);
            let ray = Ray::new(dir * 3.0, -dir);
            for (lit, worst) in [(&lit, &mut worst), (&flat_prep, &mut worst_flat)] {
                let hit = lit.closest_visible(&ray).expect("the sphere is hit");
                let p = ray.at(hit.t);
                let s = Surface::at(lit, &hit, p, ray.dir);
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

    /// The shadow terminator of a coarse sphere: among points the shading normal turns towards
    /// a distant light (ns·L > 0.05), the fraction whose shadow ray the sphere's own triangles
    /// block. On the smooth sphere none is shadowed: those are the black blotches.
    fn blotches(lifted: bool) -> f64 {
        let scene = Scene::build(sphere(6, 12), "sphere").expect("sphere");
        let setup = Setup::defaults(&scene, LengthUnit::M);
        let lit = LitScene::new(&scene, &setup, 1);
        let light = Vec3::new(1.0, 0.3, 0.2).normalize() * 1000.0;
        let (mut facing, mut blocked) = (0u32, 0u32);
        let mut rng = crate::sampling::SampleRng::new(11, 0);
        for _ in 0..50_000 {
            let (u, v) = rng.next_2d();
            let dir = crate::sampling::uniform_sphere(u, v);
            let ray = Ray::new(dir * 3.0, -dir);
            let hit = lit.closest_visible(&ray).expect("the sphere is hit");
            let p = ray.at(hit.t);
            let s = Surface::at(&lit, &hit, p, ray.dir);
            let wi = (light - p).normalize();
            if !s.lit_from(wi) || s.ns.dot(wi) < 0.05 {
                continue;
            }
            facing += 1;
            let origin = if lifted {
                s.origin
            } else {
                p + s.ng * lit.epsilon
            };
            if lit.occluded(origin, light - origin) {
                blocked += 1;
            }
        }
        f64::from(blocked) / f64::from(facing)
    }

    #[test]
    fn the_lifted_origin_removes_black_blotches_at_the_shadow_terminator() {
        let (without, with) = (blotches(false), blotches(true));
        eprintln!(
            "blocked where shading says lit: {:.2} % unlifted, {:.2} % lifted",
            without * 100.0,
            with * 100.0
        );
        assert!(
            without > 0.01,
            "the test sees no terminator problem to fix: {without}"
        );
        assert!(with < 0.001, "{with}");
    }
}
