//! The sun as a disc of uniform luminance at infinity, part of the environment light: a cone
//! of half-angle α = 0.2665° around its direction, sampled uniformly by solid angle, so that
//! shadows get penumbrae of the right width.
//!
//! Its luminance is L = E_n / (π sin² α), with E_n its illuminance on a plane facing it
//! (∫ L cos θ dω over the cone is exactly L π sin² α). The cone's solid angle is
//! Ω = 2π (1 − cos α) = 4π sin²(α/2); both are kept in f64 and stored as f32, since 1 − cos α
//! (1.08e-5) is near f32's resolution about 1. Whether a direction lies inside is judged by
//! |w × s|² ≤ sin² α, which stays accurate at such small angles where w · s would not.

use crate::sampling::frame_from_normal;
use glam::Vec3;
use std::f32::consts::PI;

/// A directional light at infinity a scene file designs (USD's DistantLight): a disc of
/// uniform luminance, as the daylight sun is, in a fixed direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistantSun {
    /// Scene direction towards the light (any length).
    pub direction: [f32; 3],
    /// The disc's angular diameter, degrees (> 0).
    pub diameter_deg: f32,
    /// Its illuminance on a plane facing it, lx.
    pub normal_illuminance_lx: f32,
}

impl DistantSun {
    /// The disc it draws (None when its numbers cannot draw one).
    pub fn disc(&self) -> Option<SunDisc> {
        let dir = Vec3::from(self.direction);
        let ok = dir.is_finite()
            && dir.length_squared() > 0.0
            && self.diameter_deg.is_finite()
            && self.diameter_deg > 0.0
            && self.diameter_deg < 180.0
            && self.normal_illuminance_lx.is_finite()
            && self.normal_illuminance_lx > 0.0;
        ok.then(|| {
            SunDisc::new(
                dir,
                f64::from(self.diameter_deg),
                f64::from(self.normal_illuminance_lx),
            )
        })
    }
}

#[derive(Clone, Debug)]
pub struct SunDisc {
    /// Unit scene direction towards the sun.
    dir: Vec3,
    /// Frame around `dir`.
    frame: (Vec3, Vec3),
    /// sin² α.
    sin2_alpha: f32,
    /// 1 − cos α.
    one_minus_cos: f32,
    /// 1 / Ω (1/sr).
    pdf: f32,
    /// Luminance (cd/m²), white.
    luminance: f32,
    /// Ω L: its normal illuminance, near enough (lx).
    integral: f64,
}

impl SunDisc {
    /// The sun towards unit `dir`, `diameter_deg` across, giving `normal_illuminance_lx` on a
    /// plane facing it.
    pub fn new(dir: Vec3, diameter_deg: f64, normal_illuminance_lx: f64) -> Self {
        let alpha = (diameter_deg * 0.5).to_radians();
        let sin2 = alpha.sin().powi(2);
        let one_minus_cos = 2.0 * (alpha * 0.5).sin().powi(2);
        let omega = 2.0 * std::f64::consts::PI * one_minus_cos;
        let luminance = normal_illuminance_lx.max(0.0) / (std::f64::consts::PI * sin2);
        let dir = dir.normalize();
        SunDisc {
            dir,
            frame: frame_from_normal(dir),
            sin2_alpha: sin2 as f32,
            one_minus_cos: one_minus_cos as f32,
            pdf: (1.0 / omega) as f32,
            luminance: luminance as f32,
            integral: luminance * omega,
        }
    }

    /// Whether unit `w` points into the disc.
    #[inline]
    pub fn contains(&self, w: Vec3) -> bool {
        w.dot(self.dir) > 0.0 && w.cross(self.dir).length_squared() <= self.sin2_alpha
    }

    /// Luminance arriving along unit `w` (0 outside the disc).
    #[inline]
    pub fn radiance(&self, w: Vec3) -> f32 {
        if self.contains(w) {
            self.luminance
        } else {
            0.0
        }
    }

    /// Density (1/sr) of [`SunDisc::sample`] giving unit `w`.
    #[inline]
    pub fn pdf(&self, w: Vec3) -> f32 {
        if self.contains(w) { self.pdf } else { 0.0 }
    }

    /// A direction uniformly within the disc from `u`.
    pub fn sample(&self, u: [f32; 2]) -> Vec3 {
        // 1 − cos θ uniform in [0, 1 − cos α]; sin θ from it without cancellation.
        let t = u[0] * self.one_minus_cos;
        let sin_t = (t * (2.0 - t)).sqrt();
        let phi = 2.0 * PI * u[1];
        let (b1, b2) = self.frame;
        (self.dir * (1.0 - t) + (b1 * phi.cos() + b2 * phi.sin()) * sin_t).normalize()
    }

    /// ∫ L dω over the disc (cd/m² sr).
    pub fn integral(&self) -> f64 {
        self.integral
    }

    pub fn luminance(&self) -> f32 {
        self.luminance
    }

    pub fn direction(&self) -> Vec3 {
        self.dir
    }

    /// The disc's angular radius α (rad).
    pub fn angular_radius(&self) -> f64 {
        f64::from(self.sin2_alpha).sqrt().asin()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The disc is 0.533° across, its samples fall inside it, and its normal illuminance is the
    /// one asked for: a midpoint integral of L cos θ over a fine grid of directions around it.
    #[test]
    fn disc_samples_and_illuminance() {
        let dir = Vec3::new(0.3, 0.8, -0.52).normalize();
        let sun = SunDisc::new(dir, 0.533, 80_000.0);
        // 80000 / (π sin² 0.2665°) = 1.1770e9 cd/m².
        assert!(
            (sun.luminance() / 1.0e6 - 1_177.0).abs() < 1.0,
            "{}",
            sun.luminance()
        );
        let mut max_angle = 0.0f32;
        for k in 0..4000 {
            let u = [(k as f32 + 0.5) / 4000.0, (k as f32 * 0.618_034).fract()];
            let w = sun.sample(u);
            assert!(sun.contains(w), "{u:?}");
            max_angle = max_angle.max(w.cross(dir).length().asin().to_degrees());
        }
        assert!((max_angle - 0.2665).abs() < 1e-3, "{max_angle}");
        // E_n = ∫ L cos θ dω over a 1° square of directions around the sun, 400 x 400.
        let (b1, b2) = frame_from_normal(dir);
        let (n, half) = (400, 0.5f64.to_radians());
        let step = 2.0 * half / n as f64;
        let mut e = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let x = -half + (i as f64 + 0.5) * step;
                let y = -half + (j as f64 + 0.5) * step;
                let w = (dir.as_dvec3() + b1.as_dvec3() * x.tan() + b2.as_dvec3() * y.tan())
                    .normalize();
                // The cell's solid angle is step² sec² x sec² y cos³ θ: step² within 1e-4
                // this close to the axis.
                let cos = w.dot(dir.as_dvec3());
                e += f64::from(sun.radiance(w.as_vec3())) * cos * step * step;
            }
        }
        assert!((e / 80_000.0 - 1.0).abs() < 5e-3, "{e}");
    }
}
