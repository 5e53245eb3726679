//! The angular profile of a spot light: full intensity inside the cone, zero outside the falloff
//! angle, and a smoothstep in the angle between them.

use glam::Vec3;

/// A spot's profile about its unit axis. Angles are radians.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotProfile {
    pub axis: Vec3,
    pub cone: f32,
    pub falloff: f32,
    cos_cone: f32,
    cos_falloff: f32,
}

impl SpotProfile {
    /// `axis` need not be unit length (a zero axis points down -Y); `falloff` is raised to
    /// `cone` when smaller.
    pub fn new(axis: Vec3, cone: f32, falloff: f32) -> Self {
        let cone = cone.clamp(0.0, std::f32::consts::PI);
        let falloff = falloff.clamp(cone, std::f32::consts::PI);
        Self {
            axis: axis.try_normalize().unwrap_or(Vec3::NEG_Y),
            cone,
            falloff,
            cos_cone: cone.cos(),
            cos_falloff: falloff.cos(),
        }
    }

    /// The fraction of the axial intensity emitted along unit direction `dir`:
    /// 1 for θ <= cone, 0 for θ >= falloff, else s(t) = t² (3 − 2t) with
    /// t = (falloff − θ) / (falloff − cone).
    pub fn factor(&self, dir: Vec3) -> f32 {
        let c = self.axis.dot(dir);
        if c >= self.cos_cone {
            return 1.0;
        }
        if c <= self.cos_falloff {
            return 0.0;
        }
        let theta = c.clamp(-1.0, 1.0).acos();
        let t = ((self.falloff - theta) / (self.falloff - self.cone)).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    }

    /// ∫ factor dω over the sphere (sr): flux = intensity × this.
    pub fn solid_angle_sr(&self) -> f32 {
        // 2π ∫ factor(θ) sin θ dθ; the cone part exactly, the smooth edge by the midpoint rule.
        let tau = 2.0 * std::f32::consts::PI;
        let mut sum = tau * (1.0 - self.cos_cone);
        let n = 256;
        let width = self.falloff - self.cone;
        if width > 0.0 {
            let h = width / n as f32;
            for i in 0..n {
                let theta = self.cone + (i as f32 + 0.5) * h;
                let t = (self.falloff - theta) / width;
                sum += tau * t * t * (3.0 - 2.0 * t) * theta.sin() * h;
            }
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn profile_is_full_inside_zero_outside_and_half_midway() {
        let p = SpotProfile::new(Vec3::NEG_Y, 20f32.to_radians(), 40f32.to_radians());
        let at = |deg: f32| {
            let r = deg.to_radians();
            p.factor(Vec3::new(r.sin(), -r.cos(), 0.0))
        };
        assert_eq!(at(0.0), 1.0);
        assert_eq!(at(19.9), 1.0);
        assert!((at(30.0) - 0.5).abs() < 1e-4);
        assert_eq!(at(40.1), 0.0);
        assert_eq!(at(180.0), 0.0);
        // A hard-edged cone of half-angle 20 deg covers 2π (1 − cos 20°) sr.
        let hard = SpotProfile::new(Vec3::Y, 20f32.to_radians(), 20f32.to_radians());
        let exact = 2.0 * std::f32::consts::PI * (1.0 - 20f32.to_radians().cos());
        assert!((hard.solid_angle_sr() - exact).abs() < 1e-5);
        // A smooth edge lies between the inner and the outer hard cones.
        let outer = 2.0 * std::f32::consts::PI * (1.0 - 40f32.to_radians().cos());
        assert!(p.solid_angle_sr() > exact && p.solid_angle_sr() < outer);
    }
}
