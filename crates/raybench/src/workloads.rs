//! The ray workloads of BENCHMARK.md, generated once per mesh so every library traces exactly
//! the same rays.
//!
//! - W1 primary: 1024x1024, one ray per pixel centre from eye = c + (0, 0, r / sin 22.5°), looking
//!   down -Z, +Y up, vertical field of view 45°. Closest hit.
//! - W2 shadow: from every W1 hit, offset 1e-4 * 2r along the geometric normal turned to face the
//!   ray, an any-hit ray towards the light at c + (r, 2r, 2r), ending just short of it.
//! - W3 diffuse: from the same offset points, one cosine-weighted direction about that normal,
//!   from a fixed-seed generator. Closest hit.
//!
//! c is the centre of the mesh's bounding box and r half its diagonal.

use glam::Vec3;
use tracer_core::{Aabb, Ray};

use crate::rng::{SplitMix64, cosine_direction};

/// Image size of W1.
pub const W1_SIZE: u32 = 1024;
/// Vertical field of view of W1, degrees.
pub const W1_FOV_DEG: f32 = 45.0;
/// Offset of secondary ray origins, as a fraction of the bounding box diagonal (2r).
pub const OFFSET_FRACTION: f32 = 1e-4;
/// Seed of the W3 direction generator.
pub const W3_SEED: u64 = 0x5EED_0003;

/// Where the workloads of one mesh are placed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Centre of the bounding box.
    pub centre: Vec3,
    /// Half the bounding box diagonal.
    pub radius: f32,
}

impl Frame {
    pub fn of(triangles: &[[Vec3; 3]]) -> Frame {
        let bounds = triangles
            .iter()
            .flatten()
            .fold(Aabb::EMPTY, |b, &p| b.grow(p));
        Frame {
            centre: bounds.center(),
            radius: bounds.radius(),
        }
    }

    /// W1's eye: on +Z at the distance where the bounding sphere fills the 45° view.
    pub fn eye(&self) -> Vec3 {
        let half_fov = (W1_FOV_DEG * 0.5).to_radians();
        self.centre + Vec3::new(0.0, 0.0, self.radius / half_fov.sin())
    }

    pub fn light(&self) -> Vec3 {
        self.centre + Vec3::new(self.radius, 2.0 * self.radius, 2.0 * self.radius)
    }

    /// Offset of secondary ray origins along the facing normal.
    pub fn offset(&self) -> f32 {
        OFFSET_FRACTION * 2.0 * self.radius
    }
}

/// W1: `size * size` unit-direction rays, row by row from the top-left pixel.
pub fn primary_rays(frame: &Frame, size: u32) -> Vec<Ray> {
    let eye = frame.eye();
    let tan_half = (W1_FOV_DEG * 0.5).to_radians().tan();
    let s = size as f32;
    let mut rays = Vec::with_capacity(size as usize * size as usize);
    for y in 0..size {
        for x in 0..size {
            let px = ((x as f32 + 0.5) / s * 2.0 - 1.0) * tan_half;
            let py = (1.0 - (y as f32 + 0.5) / s * 2.0) * tan_half;
            rays.push(Ray::new(eye, Vec3::new(px, py, -1.0).normalize()));
        }
    }
    rays
}

/// A W1 hit: the primary ray, its closest `t` and the triangle hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimaryHit {
    pub ray: Ray,
    pub t: f32,
    pub prim: u32,
}

/// The hit point lifted off the surface along the geometric normal turned towards the ray, and
/// that normal.
fn lifted(frame: &Frame, triangles: &[[Vec3; 3]], hit: &PrimaryHit) -> (Vec3, Vec3) {
    let [a, b, c] = triangles[hit.prim as usize];
    let mut n = (b - a).cross(c - a).normalize_or_zero();
    if n.dot(hit.ray.dir) > 0.0 {
        n = -n;
    }
    (hit.ray.at(hit.t) + n * frame.offset(), n)
}

/// W2: one shadow ray per hit towards the light, unit direction, ending just short of the light.
pub fn shadow_rays(frame: &Frame, triangles: &[[Vec3; 3]], hits: &[PrimaryHit]) -> Vec<Ray> {
    let light = frame.light();
    hits.iter()
        .map(|h| {
            let (p, _) = lifted(frame, triangles, h);
            let to_light = light - p;
            let dist = to_light.length();
            let mut ray = Ray::new(p, to_light / dist);
            ray.t_max = dist * (1.0 - 1e-4);
            ray
        })
        .collect()
}

/// W3: one cosine-weighted ray per hit about the facing normal (fixed seed, in hit order).
pub fn diffuse_rays(frame: &Frame, triangles: &[[Vec3; 3]], hits: &[PrimaryHit]) -> Vec<Ray> {
    let mut rng = SplitMix64::new(W3_SEED);
    hits.iter()
        .map(|h| {
            let (p, n) = lifted(frame, triangles, h);
            let d = cosine_direction(n, rng.next_f32(), rng.next_f32());
            Ray::new(p, d)
        })
        .collect()
}

/// All three workloads of one mesh.
#[derive(Clone, Debug)]
pub struct Workloads {
    pub w1: Vec<Ray>,
    pub w2: Vec<Ray>,
    pub w3: Vec<Ray>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_frame() -> Frame {
        Frame {
            centre: Vec3::ZERO,
            radius: 1.0,
        }
    }

    #[test]
    fn w1_has_one_ray_per_pixel_of_1024_squared() {
        let rays = primary_rays(&unit_frame(), W1_SIZE);
        assert_eq!(rays.len(), 1024 * 1024);
        assert!(rays.iter().all(|r| r.dir.z < 0.0));
        assert!(rays.iter().all(|r| (r.dir.length() - 1.0).abs() < 1e-5));
    }

    #[test]
    fn w1_corner_rays_span_45_degrees() {
        let rays = primary_rays(&unit_frame(), 2);
        // Pixel centres of a 2x2 image sit at half the half-height: tan(angle) = tan(22.5°) / 2.
        let d = rays[0].dir;
        assert!((d.y / -d.z - (22.5f32).to_radians().tan() * 0.5).abs() < 1e-6);
        assert!(d.x < 0.0 && d.y > 0.0, "first ray goes to the top-left");
    }

    #[test]
    fn sphere_frame_puts_the_eye_on_z_and_the_light_up_right() {
        let sphere = tracer_core::bvh::uv_sphere(64);
        let frame = Frame::of(&sphere);
        assert!(frame.centre.length() < 1e-5);
        // The unit sphere's box is [-1,1]^3: r = sqrt(3).
        assert!((frame.radius - 3f32.sqrt()).abs() < 1e-5);
        let eye = frame.eye();
        let expected = 3f32.sqrt() / (22.5f32).to_radians().sin();
        assert!(eye.x.abs() < 1e-5 && eye.y.abs() < 1e-5);
        assert!((eye.z - expected).abs() < 1e-4, "{eye}");
        let light = frame.light();
        assert!((light - Vec3::new(1.0, 2.0, 2.0) * 3f32.sqrt()).length() < 1e-4);
    }

    #[test]
    fn secondary_rays_leave_the_facing_side() {
        let tri = [[
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ]];
        let frame = Frame {
            centre: Vec3::ZERO,
            radius: 1.0,
        };
        let hit = PrimaryHit {
            ray: Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z),
            t: 5.0,
            prim: 0,
        };
        let w2 = shadow_rays(&frame, &tri, &[hit]);
        let w3 = diffuse_rays(&frame, &tri, &[hit]);
        assert_eq!(w2.len(), 1);
        assert!((w2[0].origin.z - 2e-4).abs() < 1e-7);
        assert!(w2[0].at(w2[0].t_max).distance(frame.light()) < 1e-3);
        assert!(w3[0].dir.z > 0.0);
    }
}
