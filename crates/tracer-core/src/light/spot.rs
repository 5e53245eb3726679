//! The spot light: a point whose intensity follows a profile about an axis, full inside the
//! cone, zero outside the falloff angle, and a smoothstep in the angle between them.

use super::point::incident_from_point;
use super::{Emission, Incident, LightBounds, LightSource, Receiver};
use crate::sampling::to_world;
use glam::Vec3;
use std::f32::consts::PI;

/// `intensity_cd` on the axis of `profile`, at `position`.
#[derive(Clone, Debug, PartialEq)]
pub struct SpotLight {
    pub position: Vec3,
    pub intensity_cd: f32,
    /// Colour with Rec. 709 luminance 1.
    pub tint: Vec3,
    pub profile: SpotProfile,
    /// (metres per scene unit)².
    pub metres_per_unit_sq: f32,
}

impl SpotLight {
    /// Intensity (cd) along unit `dir` leaving the light.
    #[inline]
    pub fn intensity_towards(&self, dir: Vec3) -> f32 {
        self.intensity_cd * self.profile.factor(dir)
    }

    /// cos of the falloff angle: emission sampling covers the cone out to it.
    fn cos_max(&self) -> f32 {
        self.profile.falloff.cos()
    }
}

impl LightSource for SpotLight {
    fn power_lm(&self) -> f64 {
        f64::from(self.intensity_cd) * f64::from(self.profile.solid_angle_sr())
    }

    fn bounds(&self) -> LightBounds {
        let p = &self.profile;
        LightBounds::beam(self.position, self.power_lm() as f32, p.axis, p.falloff)
    }

    fn is_delta(&self) -> bool {
        true
    }

    #[inline]
    fn sample_incident(&self, at: Receiver, _u: [f32; 2]) -> Option<Incident> {
        incident_from_point(self.position, self.tint, self.metres_per_unit_sq, at, |d| {
            self.intensity_towards(d)
        })
    }

    fn incident_pdf(&self, _origin: Vec3, _wi: Vec3, _distance: f32) -> f32 {
        0.0
    }

    fn emitted(&self, dir: Vec3) -> Vec3 {
        self.tint * (self.intensity_towards(dir) / self.metres_per_unit_sq)
    }

    /// Uniform over the cone out to the falloff angle.
    fn sample_emission(&self, _u_point: [f32; 2], u_dir: [f32; 2]) -> Option<Emission> {
        let cos_max = self.cos_max();
        let z = 1.0 - u_dir[0] * (1.0 - cos_max);
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = 2.0 * PI * u_dir[1];
        let local = Vec3::new(r * phi.cos(), r * phi.sin(), z);
        let dir = to_world(local, self.profile.axis);
        Some(Emission {
            p: self.position,
            n: Vec3::ZERO,
            dir,
            pdf_point: 1.0,
            pdf_dir: self.emission_dir_pdf(dir),
        })
    }

    fn emission_dir_pdf(&self, dir: Vec3) -> f32 {
        let cos_max = self.cos_max();
        if self.profile.axis.dot(dir) < cos_max || cos_max >= 1.0 {
            0.0
        } else {
            1.0 / (2.0 * PI * (1.0 - cos_max))
        }
    }

    fn emission_point_pdf(&self) -> f32 {
        1.0
    }

    fn normal(&self) -> Vec3 {
        Vec3::ZERO
    }
}

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

    /// Emission sampling is a density over the cone: averaging I(ω) / pdf(ω) gives the flux
    /// I × ∫ factor dω.
    #[test]
    fn emission_samples_estimate_the_flux() {
        let light = SpotLight {
            position: Vec3::ZERO,
            intensity_cd: 50.0,
            tint: Vec3::ONE,
            profile: SpotProfile::new(Vec3::NEG_Y, 20f32.to_radians(), 40f32.to_radians()),
            metres_per_unit_sq: 1.0,
        };
        let k = 256;
        let mut sum = 0.0f64;
        for i in 0..k {
            for j in 0..k {
                let u = [(i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / k as f32];
                let e = light.sample_emission([0.5; 2], u).unwrap();
                assert!((light.emission_dir_pdf(e.dir) - e.pdf_dir).abs() < 1e-4);
                sum += f64::from(light.emitted(e.dir).y / e.pdf_dir);
            }
        }
        let flux = sum / f64::from(k * k);
        assert!((flux / light.power_lm() - 1.0).abs() < 1e-3, "{flux}");
    }
}
