//! Lights behind one type: point and spot lights placed by the user ([`Light`]), and emissive
//! surfaces (materials with an emission luminance), which the renderer samples through an
//! [`EmitterTable`]. Every kind answers the same question: how much light arrives at a point
//! from a sampled position, and how likely that sample was.
//!
//! Photometric SI: intensity in candela, flux in lumen, luminance in cd/m². A light's colour is a
//! tint normalised to Rec. 709 luminance 1, so its intensity stays in candela.

mod emitters;
mod goniometric;
mod spot;
mod tree;

pub use emitters::{EmissionSides, EmissiveTriangle, EmitterPoint, EmitterSample, EmitterTable};
pub use goniometric::{Photometry, PhotometryError, Plane, cosine_flux};
pub use spot::SpotProfile;
pub use tree::{LightBounds, LightTree, Picked};

use glam::Vec3;
use std::sync::Arc;

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
    /// A measured distribution (IES or EULUMDAT file) times `multiplier`, its nadir along `aim`,
    /// turned by `rotation_deg` about it (see [`LuminaireFrame`]).
    Luminaire,
}

/// A photometric file as loaded: the distribution and where it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Luminaire {
    pub photometry: Photometry,
    /// The path as the sidecar wrote it (relative to the sidecar, or absolute).
    pub file: std::path::PathBuf,
    /// The file's luminous flux as rendered (lm), integrated once.
    pub flux_lm: f64,
}

impl Luminaire {
    pub fn new(photometry: Photometry, file: std::path::PathBuf) -> Self {
        let flux_lm = photometry.flux_lm();
        Self {
            photometry,
            file,
            flux_lm,
        }
    }
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
    fn luminaire_frame_turns_counter_clockwise_with_rotation() {
        let f = LuminaireFrame::new(Vec3::NEG_Y, 0.0, 1.0);
        assert!((f.c0 - Vec3::X).length() < 1e-6);
        assert!((f.c90 - Vec3::NEG_Z).length() < 1e-6, "{}", f.c90);
        let turned = LuminaireFrame::new(Vec3::NEG_Y, 90.0, 1.0);
        assert!((turned.c0 - f.c90).length() < 1e-6);
        let (c, g) = f.angles_deg(Vec3::new(0.0, -1.0, -1.0).normalize());
        assert!(
            (c - 90.0).abs() < 1e-3 && (g - 45.0).abs() < 1e-3,
            "{c} {g}"
        );
        // Aim along X: C0 along +Z.
        let side = LuminaireFrame::new(Vec3::X, 0.0, 1.0);
        assert!((side.c0 - Vec3::Z).length() < 1e-6);
    }

    #[test]
    fn point_flux_is_four_pi_intensity() {
        let l = Light::point([0.0; 3], 100.0);
        assert!((l.flux_lm() - 400.0 * std::f32::consts::PI).abs() < 1e-3);
    }
}

/// The orientation of a goniometric distribution in the scene: the nadir (γ = 0) along the aim;
/// at rotation 0 the C0 plane contains +X projected perpendicular to the aim (+Z when the aim is
/// parallel to X); C angles increase counter-clockwise in the picture raygine draws, looking
/// along the aim from behind the luminaire (LM-63 type C). As `.shp` scenes are drawn mirrored
/// (left-handed), the C90 direction is `aim × C0` there and `C0 × aim` in right-handed scenes,
/// so a file's C90 lobe lands in the same place on screen in both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LuminaireFrame {
    pub nadir: Vec3,
    pub c0: Vec3,
    pub c90: Vec3,
}

impl LuminaireFrame {
    pub fn new(aim: Vec3, rotation_deg: f32, handedness_sign: f32) -> Self {
        let nadir = aim.try_normalize().unwrap_or(Vec3::NEG_Y);
        let reference = if nadir.cross(Vec3::X).length_squared() < 1e-8 {
            Vec3::Z
        } else {
            Vec3::X
        };
        let c0 = (reference - nadir * nadir.dot(reference)).normalize();
        let c90 = c0.cross(nadir) * handedness_sign.signum();
        // Turn the C planes by the rotation, counter-clockwise as C angles run.
        let (s, c) = rotation_deg.to_radians().sin_cos();
        let c0r = c0 * c + c90 * s;
        let c90r = c90 * c - c0 * s;
        Self {
            nadir,
            c0: c0r,
            c90: c90r,
        }
    }

    /// (C, γ) in degrees of the unit direction `dir` leaving the luminaire.
    pub fn angles_deg(&self, dir: Vec3) -> (f32, f32) {
        let gamma = dir.dot(self.nadir).clamp(-1.0, 1.0).acos().to_degrees();
        let c = dir.dot(self.c90).atan2(dir.dot(self.c0)).to_degrees();
        (c.rem_euclid(360.0), gamma)
    }
}
