//! Point lights, photometric.

use glam::Vec3;
use serde::{Deserialize, Serialize};

/// An isotropic point light.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointLight {
    /// Position in scene coordinates (the file's numbers, scene unit).
    pub position: [f32; 3],
    /// Luminous intensity in candela (cd), the same in every direction.
    pub intensity_cd: f32,
    /// RGB tint; normalised to Rec. 709 luminance 1 when shading, so the intensity stays in cd.
    #[serde(default = "white")]
    pub color: [f32; 3],
}

fn white() -> [f32; 3] {
    [1.0; 3]
}

/// Rec. 709 / sRGB luminance weights of linear RGB.
pub const LUMINANCE_WEIGHTS: Vec3 = Vec3::new(0.2126, 0.7152, 0.0722);

/// Rec. 709 luminance Y of a linear RGB triple.
pub fn luminance(rgb: Vec3) -> f32 {
    rgb.dot(LUMINANCE_WEIGHTS)
}

impl PointLight {
    pub fn position(&self) -> Vec3 {
        Vec3::from(self.position)
    }

    /// The colour scaled to luminance 1 (white when the colour is black or invalid).
    pub fn tint(&self) -> Vec3 {
        let c = Vec3::from(self.color).max(Vec3::ZERO);
        let y = luminance(c);
        if y.is_finite() && y > 0.0 {
            c / y
        } else {
            Vec3::ONE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tint_has_unit_luminance() {
        let l = PointLight {
            position: [0.0; 3],
            intensity_cd: 10.0,
            color: [1.0, 0.5, 0.25],
        };
        assert!((luminance(l.tint()) - 1.0).abs() < 1e-6);
        let black = PointLight {
            color: [0.0; 3],
            ..l
        };
        assert_eq!(black.tint(), Vec3::ONE);
    }
}
