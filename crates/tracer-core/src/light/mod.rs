//! Lights behind one type: point and spot lights placed by the user ([`Light`]), and emissive
//! surfaces (materials with an emission luminance), which the renderer samples through an
//! [`EmitterTable`]. Every kind answers the same question: how much light arrives at a point
//! from a sampled position, and how likely that sample was.
//!
//! Photometric SI: intensity in candela, flux in lumen, luminance in cd/m². A light's colour is a
//! tint normalised to Rec. 709 luminance 1, so its intensity stays in candela.

mod emitters;
mod spot;

pub use emitters::{EmissionSides, EmissiveTriangle, EmitterSample, EmitterTable};
pub use spot::SpotProfile;

use glam::Vec3;

/// Rec. 709 / sRGB luminance weights of linear RGB.
pub const LUMINANCE_WEIGHTS: Vec3 = Vec3::new(0.2126, 0.7152, 0.0722);

/// Rec. 709 luminance Y of a linear RGB triple.
pub fn luminance(rgb: Vec3) -> f32 {
    rgb.dot(LUMINANCE_WEIGHTS)
}

/// `rgb` scaled to luminance 1 (white when it is black or invalid).
pub fn unit_luminance_tint(rgb: [f32; 3]) -> Vec3 {
    let c = Vec3::from(rgb).max(Vec3::ZERO);
    let y = luminance(c);
    if y.is_finite() && y > 0.0 {
        c / y
    } else {
        Vec3::ONE
    }
}

/// The kinds of placed light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LightKind {
    /// Isotropic: `intensity_cd` in every direction.
    #[default]
    Point,
    /// `intensity_cd` on the axis `aim`, full out to `cone_deg`, falling smoothly to zero at
    /// `falloff_deg` (see [`SpotProfile`]).
    Spot,
}

/// A light the user places and edits (the model type; the sidecar has its own serde type).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    pub kind: LightKind,
    /// Position in scene coordinates (the file's numbers, scene unit).
    pub position: [f32; 3],
    /// Luminous intensity in candela (cd): in every direction for a point light, on the axis for
    /// a spot.
    pub intensity_cd: f32,
    /// RGB tint; normalised to Rec. 709 luminance 1 when shading, so the intensity stays in cd.
    pub color: [f32; 3],
    /// Spot axis (any length; normalised when rendering). Unused by point lights.
    pub aim: [f32; 3],
    /// Spot: half-angle of full intensity, degrees.
    pub cone_deg: f32,
    /// Spot: half-angle where the intensity reaches zero, degrees (>= `cone_deg`).
    pub falloff_deg: f32,
}

impl Default for Light {
    fn default() -> Self {
        Self {
            kind: LightKind::Point,
            position: [0.0; 3],
            intensity_cd: 100.0,
            color: [1.0; 3],
            aim: [0.0, -1.0, 0.0],
            cone_deg: 30.0,
            falloff_deg: 45.0,
        }
    }
}

impl Light {
    /// An isotropic point light.
    pub fn point(position: [f32; 3], intensity_cd: f32) -> Self {
        Self {
            position,
            intensity_cd,
            ..Self::default()
        }
    }

    pub fn position(&self) -> Vec3 {
        Vec3::from(self.position)
    }

    /// The colour scaled to luminance 1 (white when the colour is black or invalid).
    pub fn tint(&self) -> Vec3 {
        unit_luminance_tint(self.color)
    }

    /// Whether every number is finite and in range (intensity >= 0, spot angles ordered).
    pub fn is_valid(&self) -> bool {
        let finite = self.intensity_cd.is_finite()
            && self.intensity_cd >= 0.0
            && self.position.iter().all(|x| x.is_finite());
        match self.kind {
            LightKind::Point => finite,
            LightKind::Spot => {
                finite
                    && Vec3::from(self.aim).try_normalize().is_some()
                    && self.cone_deg.is_finite()
                    && self.falloff_deg.is_finite()
                    && (0.0..=180.0).contains(&self.cone_deg)
                    && (self.cone_deg..=180.0).contains(&self.falloff_deg)
            }
        }
    }

    /// The angular profile, or `None` for an isotropic light.
    pub fn spot_profile(&self) -> Option<SpotProfile> {
        match self.kind {
            LightKind::Point => None,
            LightKind::Spot => Some(SpotProfile::new(
                Vec3::from(self.aim),
                self.cone_deg.to_radians(),
                self.falloff_deg.to_radians(),
            )),
        }
    }

    /// Luminous flux (lm) the light emits: 4π I for a point light, the integral of the profile
    /// for a spot.
    pub fn flux_lm(&self) -> f32 {
        let solid_angle = self
            .spot_profile()
            .map_or(4.0 * std::f32::consts::PI, |p| p.solid_angle_sr());
        self.intensity_cd * solid_angle
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn tint_has_unit_luminance() {
        let l = Light {
            color: [1.0, 0.5, 0.25],
            ..Light::point([0.0; 3], 10.0)
        };
        assert!((luminance(l.tint()) - 1.0).abs() < 1e-6);
        let black = Light {
            color: [0.0; 3],
            ..l
        };
        assert_eq!(black.tint(), Vec3::ONE);
    }

    #[test]
    fn point_flux_is_four_pi_intensity() {
        let l = Light::point([0.0; 3], 100.0);
        assert!((l.flux_lm() - 400.0 * std::f32::consts::PI).abs() < 1e-3);
    }
}
