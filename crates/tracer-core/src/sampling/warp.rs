//! Warps from the unit square to directions and points, with their densities.

use glam::Vec3;
use std::f32::consts::PI;

/// A cosine-weighted direction about +Z in local coordinates (density cos θ / π per sr).
pub fn cosine_hemisphere(u: f32, v: f32) -> Vec3 {
    let r = u.sqrt();
    let phi = 2.0 * PI * v;
    let z = (1.0 - u).max(0.0).sqrt();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A uniform direction on the unit sphere (density 1 / 4π per sr).
pub fn uniform_sphere(u: f32, v: f32) -> Vec3 {
    let z = 1.0 - 2.0 * u;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * v;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Barycentric weights (b1, b2) of a uniform point on a triangle: p = v0 + b1 e1 + b2 e2.
pub fn uniform_triangle_barycentric(u: f32, v: f32) -> (f32, f32) {
    let su = u.sqrt();
    (1.0 - su, v * su)
}

/// An orthonormal tangent pair (t, b) such that (t, b, n) is right-handed (Duff et al. 2017).
pub fn frame_from_normal(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// A local direction (z along `n`) expressed in world coordinates.
pub fn to_world(local: Vec3, n: Vec3) -> Vec3 {
    let (t, b) = frame_from_normal(n);
    t * local.x + b * local.y + n * local.z
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn frames_are_orthonormal() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.5, 0.8).normalize(),
        ] {
            let (t, b) = frame_from_normal(n);
            assert!(t.dot(b).abs() < 1e-6 && t.dot(n).abs() < 1e-6 && b.dot(n).abs() < 1e-6);
            assert!((t.cross(b) - n).length() < 1e-5, "{n}");
        }
    }

    #[test]
    fn cosine_hemisphere_has_mean_cosine_two_thirds() {
        // E[cos θ] under the density cos θ / π is 2/3.
        let n = 256;
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                let d = cosine_hemisphere((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                assert!((d.length() - 1.0).abs() < 1e-5 && d.z >= 0.0);
                sum += d.z;
            }
        }
        let mean = sum / (n * n) as f32;
        assert!((mean - 2.0 / 3.0).abs() < 1e-3, "{mean}");
    }
}
