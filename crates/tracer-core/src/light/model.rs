//! The lights a user places and edits: the model type the viewer, the sidecar and the readers
//! share. The sidecar has its own serde type (`scene::LightSpec`); a render turns each into a
//! [`super::PlacedLight`].

use super::{Luminaire, LuminaireFrame, SpotProfile, unit_luminance_tint};
use glam::Vec3;
use std::sync::Arc;

/// The kinds of placed light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LightKind {
    /// Isotropic: `intensity_cd` in every direction.
    #[default]
    Point,
    /// `intensity_cd` on the axis `aim`, full out to `cone_deg`, falling smoothly to zero at
    /// `falloff_deg` (see [`SpotProfile`]).
    Spot,
    /// A measured distribution (IES or EULUMDAT file) times `multiplier`, its nadir along `aim`,
    /// turned by `rotation_deg` about it (see [`LuminaireFrame`]).
    Luminaire,
}

/// A light the user places and edits (the model type; the sidecar has its own serde type).
#[derive(Clone, Debug, PartialEq)]
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
    /// Luminaire: turn of the C planes about the aim, degrees.
    pub rotation_deg: f32,
    /// Luminaire: factor applied to the file's intensities (1: as measured).
    pub multiplier: f32,
    /// Luminaire: the distribution (None for points and spots).
    pub luminaire: Option<Arc<Luminaire>>,
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
            rotation_deg: 0.0,
            multiplier: 1.0,
            luminaire: None,
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
            LightKind::Luminaire => {
                finite
                    && self.luminaire.is_some()
                    && self.multiplier.is_finite()
                    && self.multiplier >= 0.0
                    && self.rotation_deg.is_finite()
                    && Vec3::from(self.aim).try_normalize().is_some()
            }
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

    /// The angular profile of a spot, or `None` for other kinds.
    pub fn spot_profile(&self) -> Option<SpotProfile> {
        match self.kind {
            LightKind::Point | LightKind::Luminaire => None,
            LightKind::Spot => Some(SpotProfile::new(
                Vec3::from(self.aim),
                self.cone_deg.to_radians(),
                self.falloff_deg.to_radians(),
            )),
        }
    }

    /// Luminous flux (lm) the light emits: 4π I for a point light, the integral of the profile
    /// for a spot, of the distribution as rendered (times the multiplier) for a luminaire.
    pub fn flux_lm(&self) -> f32 {
        if self.kind == LightKind::Luminaire {
            return self
                .luminaire
                .as_ref()
                .map_or(0.0, |l| (l.flux_lm * f64::from(self.multiplier)) as f32);
        }
        let solid_angle = self
            .spot_profile()
            .map_or(4.0 * std::f32::consts::PI, |p| p.solid_angle_sr());
        self.intensity_cd * solid_angle
    }

    /// The luminaire's photometric frame, for a scene of `handedness_sign` (+1 right-handed,
    /// −1 left-handed).
    pub fn luminaire_frame(&self, handedness_sign: f32) -> LuminaireFrame {
        LuminaireFrame::new(Vec3::from(self.aim), self.rotation_deg, handedness_sign)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;
    use crate::light::luminance;

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
