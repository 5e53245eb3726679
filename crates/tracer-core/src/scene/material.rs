//! Surface materials: Lambertian diffuse plus a mirror with a normalised Blinn-Phong highlight.

use glam::Vec3;
use serde::{Deserialize, Serialize};

/// Reflectances are RGB tints in 0..=1 (dimensionless).
///
/// BRDF for a point light, with `n` the shading normal, `h` the half vector:
/// `f = Kd / π + Ks · (g + 8) / (8π) · (n·h)^g` (the highlight only when `glossiness > 0`),
/// and the mirror term `Ks · L_reflected` traced recursively. `Kd + Ks <= 1` per channel keeps
/// the surface from creating energy; [`Material::clamped`] enforces it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Diffuse reflectance Kd per channel.
    pub kd: [f32; 3],
    /// Mirror reflectance Ks per channel.
    #[serde(default)]
    pub ks: [f32; 3],
    /// Blinn-Phong exponent g of the highlight of point lights (0: no highlight, mirror only).
    #[serde(default)]
    pub glossiness: f32,
}

impl Default for Material {
    /// Neutral grey diffuse: Kd 0.7, Ks 0.
    fn default() -> Self {
        Self {
            kd: [0.7; 3],
            ks: [0.0; 3],
            glossiness: 0.0,
        }
    }
}

impl Material {
    pub fn kd(&self) -> Vec3 {
        Vec3::from(self.kd)
    }

    pub fn ks(&self) -> Vec3 {
        Vec3::from(self.ks)
    }

    /// Clamps every value into its physical range (0..=1 reflectances, Kd + Ks <= 1 per channel
    /// by scaling both down, glossiness >= 0). Returns the clamped material and whether anything
    /// changed, so callers can warn.
    pub fn clamped(&self) -> (Material, bool) {
        let fix = |x: f32| {
            if x.is_finite() {
                x.clamp(0.0, 1.0)
            } else {
                0.0
            }
        };
        let mut kd = self.kd.map(fix);
        let mut ks = self.ks.map(fix);
        for c in 0..3 {
            let sum = kd[c] + ks[c];
            if sum > 1.0 {
                kd[c] /= sum;
                ks[c] /= sum;
            }
        }
        let glossiness = if self.glossiness.is_finite() {
            self.glossiness.clamp(0.0, 1.0e5)
        } else {
            0.0
        };
        let out = Material { kd, ks, glossiness };
        (out, out != *self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamping_keeps_kd_plus_ks_at_most_one() {
        let m = Material {
            kd: [0.8, 0.5, 2.0],
            ks: [0.4, 0.5, -1.0],
            glossiness: -3.0,
        };
        let (c, changed) = m.clamped();
        assert!(changed);
        for i in 0..3 {
            assert!(c.kd[i] + c.ks[i] <= 1.0 + 1e-6);
        }
        assert!((c.kd[0] - 0.8 / 1.2).abs() < 1e-6);
        assert_eq!(c.kd[2], 1.0);
        assert_eq!(c.ks[2], 0.0);
        assert_eq!(c.glossiness, 0.0);
        assert!(!Material::default().clamped().1);
    }
}
