//! The lights a user places and edits: the model type the viewer, the sidecar and the readers
//! share, with data per kind. The sidecar has its own serde type (`scene::LightSpec`); a render
//! turns each into a [`super::PlacedLight`].

use super::{Luminaire, LuminaireFrame, LuminousShape, SpotProfile, unit_luminance_tint};
use glam::Vec3;
use serde::Serialize;
use std::sync::Arc;

/// A light the user places and edits: where it is, its colour and what kind it is.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// Position in scene coordinates (the file's numbers, scene unit).
    pub position: [f32; 3],
    /// RGB tint; normalised to Rec. 709 luminance 1 when shading, so intensities stay in cd.
    pub color: [f32; 3],
    pub kind: LightKind,
}

/// What a placed light is, with the data of that kind.
#[derive(Clone, Debug, PartialEq)]
pub enum LightKind {
    /// Isotropic: the same luminous intensity (cd) in every direction.
    Point {
        intensity_cd: f32,
    },
    Spot(Spot),
    Luminaire(LuminairePlacement),
}

/// `intensity_cd` on the axis `aim`, full out to `cone_deg`, falling smoothly to zero at
/// `falloff_deg` (see [`SpotProfile`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spot {
    pub intensity_cd: f32,
    /// The axis (any length; normalised when rendering).
    pub aim: [f32; 3],
    /// Half-angle of full intensity, degrees.
    pub cone_deg: f32,
    /// Half-angle where the intensity reaches zero, degrees (>= `cone_deg`).
    pub falloff_deg: f32,
}

impl Default for Spot {
    fn default() -> Self {
        Self {
            intensity_cd: 100.0,
            aim: [0.0, -1.0, 0.0],
            cone_deg: 30.0,
            falloff_deg: 45.0,
        }
    }
}

/// A measured distribution (IES or EULUMDAT file) times `multiplier`, its nadir along `aim`,
/// turned by `rotation_deg` about it (see [`LuminaireFrame`]).
#[derive(Clone, Debug, PartialEq)]
pub struct LuminairePlacement {
    pub luminaire: Arc<Luminaire>,
    /// The photometric nadir (any length).
    pub aim: [f32; 3],
    /// Turn of the C planes about the aim, degrees.
    pub rotation_deg: f32,
    /// Factor applied to the file's intensities (1: as measured).
    pub multiplier: f32,
    /// Its luminous opening.
    pub shape: ShapeChoice,
}

/// Which luminous opening a luminaire emits from.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum ShapeChoice {
    /// The file's opening (a point when the file gives none or one raygine does not draw).
    #[default]
    File,
    /// A shape given by the user, its sizes in the scene unit; `LuminousShape::Point` is the
    /// point (far-field) model.
    Explicit(LuminousShape),
}

impl LuminairePlacement {
    /// `luminaire` as measured, aimed down −Y, with the file's opening.
    pub fn new(luminaire: Arc<Luminaire>) -> Self {
        Self {
            luminaire,
            aim: [0.0, -1.0, 0.0],
            rotation_deg: 0.0,
            multiplier: 1.0,
            shape: ShapeChoice::File,
        }
    }

    /// The opening it emits from, sizes in the scene unit of a scene with `metres_per_unit`.
    pub fn opening(&self, metres_per_unit: f32) -> LuminousShape {
        match self.shape {
            ShapeChoice::File => self
                .luminaire
                .photometry
                .shape
                .scaled(1.0 / metres_per_unit),
            ShapeChoice::Explicit(shape) => shape,
        }
    }

    /// The largest intensity it emits (cd), for labels.
    pub fn max_cd(&self) -> f32 {
        self.luminaire.photometry.max_cd() * self.multiplier
    }
}

/// The kind of a light without its data, for menus and counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KindTag {
    Point,
    Spot,
    Luminaire,
}

impl KindTag {
    pub fn name(self) -> &'static str {
        match self {
            KindTag::Point => "point",
            KindTag::Spot => "spot",
            KindTag::Luminaire => "luminaire",
        }
    }
}

impl Default for Light {
    fn default() -> Self {
        Light::point([0.0; 3], 100.0)
    }
}

impl Light {
    /// An isotropic point light, white.
    pub fn point(position: [f32; 3], intensity_cd: f32) -> Self {
        Self {
            position,
            color: [1.0; 3],
            kind: LightKind::Point { intensity_cd },
        }
    }

    /// A white spot.
    pub fn spot(position: [f32; 3], spot: Spot) -> Self {
        Self {
            position,
            color: [1.0; 3],
            kind: LightKind::Spot(spot),
        }
    }

    /// A white luminaire.
    pub fn luminaire(position: [f32; 3], placement: LuminairePlacement) -> Self {
        Self {
            position,
            color: [1.0; 3],
            kind: LightKind::Luminaire(placement),
        }
    }

    pub fn tag(&self) -> KindTag {
        match self.kind {
            LightKind::Point { .. } => KindTag::Point,
            LightKind::Spot(_) => KindTag::Spot,
            LightKind::Luminaire(_) => KindTag::Luminaire,
        }
    }

    pub fn position(&self) -> Vec3 {
        Vec3::from(self.position)
    }

    /// The colour scaled to luminance 1 (white when the colour is black or invalid).
    pub fn tint(&self) -> Vec3 {
        unit_luminance_tint(self.color)
    }

    /// The intensity a point or spot is given in (cd; on the axis for a spot), or `None` for a
    /// luminaire, whose intensities come from its file.
    pub fn intensity_cd(&self) -> Option<f32> {
        match &self.kind {
            LightKind::Point { intensity_cd } => Some(*intensity_cd),
            LightKind::Spot(s) => Some(s.intensity_cd),
            LightKind::Luminaire(_) => None,
        }
    }

    /// The intensity of a point or spot, to edit (`None` for a luminaire).
    pub fn intensity_cd_mut(&mut self) -> Option<&mut f32> {
        match &mut self.kind {
            LightKind::Point { intensity_cd } => Some(intensity_cd),
            LightKind::Spot(s) => Some(&mut s.intensity_cd),
            LightKind::Luminaire(_) => None,
        }
    }

    /// The largest intensity it emits (cd), for labels and sizes on screen.
    pub fn peak_cd(&self) -> f32 {
        match &self.kind {
            LightKind::Luminaire(l) => l.max_cd(),
            _ => self.intensity_cd().unwrap_or(0.0),
        }
    }

    /// Every field of the light that a report or a dump shows, by kind (see [`LightSummary`]).
    pub fn summary(&self) -> LightSummary {
        let mut s = LightSummary {
            kind: self.tag().name(),
            position: self.position,
            color: self.color,
            intensity_cd: self.peak_cd(),
            flux_lm: self.flux_lm(),
            aim: self.aim(),
            cone_deg: None,
            falloff_deg: None,
            rotation_deg: None,
            multiplier: None,
            file: None,
            shape: None,
        };
        match &self.kind {
            LightKind::Point { .. } => {}
            LightKind::Spot(spot) => {
                s.cone_deg = Some(spot.cone_deg);
                s.falloff_deg = Some(spot.falloff_deg);
            }
            LightKind::Luminaire(l) => {
                s.rotation_deg = Some(l.rotation_deg);
                s.multiplier = Some(l.multiplier);
                s.file = Some(l.luminaire.file.display().to_string());
                s.shape = Some(match l.shape {
                    ShapeChoice::File => "file",
                    ShapeChoice::Explicit(shape) => shape.name(),
                });
            }
        }
        s
    }

    /// The axis of a spot or luminaire (`None` for a point light).
    pub fn aim(&self) -> Option<[f32; 3]> {
        match &self.kind {
            LightKind::Point { .. } => None,
            LightKind::Spot(s) => Some(s.aim),
            LightKind::Luminaire(l) => Some(l.aim),
        }
    }

    /// The same light turned into a point or a spot (`tag` Luminaire leaves it as it is): the
    /// intensity is kept, a new spot gets the default cone, aimed down −Y.
    pub fn with_kind(&self, tag: KindTag) -> Light {
        let intensity_cd = self.intensity_cd().unwrap_or_else(|| self.peak_cd());
        let kind = match (tag, &self.kind) {
            (KindTag::Point, _) => LightKind::Point { intensity_cd },
            (KindTag::Spot, LightKind::Spot(s)) => LightKind::Spot(*s),
            (KindTag::Spot, other) => LightKind::Spot(Spot {
                intensity_cd,
                aim: match other {
                    LightKind::Luminaire(l) => l.aim,
                    _ => Spot::default().aim,
                },
                ..Spot::default()
            }),
            (KindTag::Luminaire, _) => self.kind.clone(),
        };
        Light {
            kind,
            ..self.clone()
        }
    }

    /// Whether every number is finite and in range (intensity >= 0, spot angles ordered).
    pub fn is_valid(&self) -> bool {
        let aimed = |aim: [f32; 3]| Vec3::from(aim).try_normalize().is_some();
        let cd_ok = |cd: f32| cd.is_finite() && cd >= 0.0;
        self.position.iter().all(|x| x.is_finite())
            && match &self.kind {
                LightKind::Point { intensity_cd } => cd_ok(*intensity_cd),
                LightKind::Spot(s) => {
                    cd_ok(s.intensity_cd)
                        && aimed(s.aim)
                        && s.cone_deg.is_finite()
                        && s.falloff_deg.is_finite()
                        && (0.0..=180.0).contains(&s.cone_deg)
                        && (s.cone_deg..=180.0).contains(&s.falloff_deg)
                }
                LightKind::Luminaire(l) => {
                    let sized = match l.shape {
                        ShapeChoice::File => true,
                        ShapeChoice::Explicit(shape) => {
                            shape.size().iter().all(|s| s.is_finite() && *s > 0.0)
                        }
                    };
                    cd_ok(l.multiplier) && l.rotation_deg.is_finite() && aimed(l.aim) && sized
                }
            }
    }

    /// The angular profile of a spot, or `None` for other kinds.
    pub fn spot_profile(&self) -> Option<SpotProfile> {
        match &self.kind {
            LightKind::Spot(s) => Some(SpotProfile::new(
                Vec3::from(s.aim),
                s.cone_deg.to_radians(),
                s.falloff_deg.to_radians(),
            )),
            _ => None,
        }
    }

    /// Luminous flux (lm) the light emits: 4π I for a point light, the integral of the profile
    /// for a spot, of the distribution as rendered (times the multiplier) for a luminaire.
    pub fn flux_lm(&self) -> f32 {
        match &self.kind {
            LightKind::Point { intensity_cd } => intensity_cd * (4.0 * std::f32::consts::PI),
            LightKind::Spot(s) => {
                s.intensity_cd * self.spot_profile().map_or(0.0, |p| p.solid_angle_sr())
            }
            LightKind::Luminaire(l) => (l.luminaire.flux_lm * f64::from(l.multiplier)) as f32,
        }
    }

    /// A luminaire's photometric frame, for a scene of `handedness_sign` (+1 right-handed,
    /// −1 left-handed); `None` for other kinds.
    pub fn luminaire_frame(&self, handedness_sign: f32) -> Option<LuminaireFrame> {
        match &self.kind {
            LightKind::Luminaire(l) => Some(LuminaireFrame::new(
                Vec3::from(l.aim),
                l.rotation_deg,
                handedness_sign,
            )),
            _ => None,
        }
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

/// A light as `raygine info` and raybench's scene dump write it: the fields every kind has,
/// then those of its kind (absent for other kinds).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LightSummary {
    pub kind: &'static str,
    pub position: [f32; 3],
    pub color: [f32; 3],
    /// The intensity of a point or spot; a luminaire's peak, multiplier included.
    pub intensity_cd: f32,
    pub flux_lm: f32,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aim: Option<[f32; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cone_deg: Option<f32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub falloff_deg: Option<f32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rotation_deg: Option<f32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub multiplier: Option<f32>,
    /// A luminaire's photometric file.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// A luminaire's luminous opening: "file" or the shape's name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shape: Option<&'static str>,
}
