//! A placed light of one render: one of the point-like kinds, built from the user's [`Light`]
//! for the scene's unit and handedness.

use super::{
    Emission, GoniometricLight, Incident, Light, LightBounds, LightKind, LightSource,
    LuminaireFrame, PointLight, Receiver, SpotLight, SpotProfile,
};
use glam::Vec3;
use std::sync::Arc;

#[derive(Clone, Debug, PartialEq)]
pub enum PlacedLight {
    Point(PointLight),
    Spot(SpotLight),
    Goniometric(GoniometricLight),
}

impl PlacedLight {
    /// The light `l` (valid) of a scene with `metres_per_unit_sq` and `handedness_sign` (+1
    /// right-handed, −1 left-handed).
    pub fn new(l: &Light, handedness_sign: f32, metres_per_unit_sq: f32) -> Self {
        let position = l.position();
        let tint = l.tint();
        match &l.kind {
            LightKind::Luminaire(lum) => PlacedLight::Goniometric(GoniometricLight {
                position,
                multiplier: lum.multiplier.max(0.0),
                tint,
                luminaire: Arc::clone(&lum.luminaire),
                frame: LuminaireFrame::new(Vec3::from(lum.aim), lum.rotation_deg, handedness_sign),
                metres_per_unit_sq,
                shape: lum.opening(metres_per_unit_sq.sqrt()),
            }),
            LightKind::Spot(s) => PlacedLight::Spot(SpotLight {
                position,
                intensity_cd: s.intensity_cd.max(0.0),
                tint,
                profile: SpotProfile::new(
                    Vec3::from(s.aim),
                    s.cone_deg.to_radians(),
                    s.falloff_deg.to_radians(),
                ),
                metres_per_unit_sq,
            }),
            LightKind::Point { intensity_cd } => PlacedLight::Point(PointLight {
                position,
                intensity_cd: intensity_cd.max(0.0),
                tint,
                metres_per_unit_sq,
            }),
        }
    }

    fn source(&self) -> &dyn LightSource {
        match self {
            PlacedLight::Point(l) => l,
            PlacedLight::Spot(l) => l,
            PlacedLight::Goniometric(l) => l,
        }
    }

    pub fn position(&self) -> Vec3 {
        match self {
            PlacedLight::Point(l) => l.position,
            PlacedLight::Spot(l) => l.position,
            PlacedLight::Goniometric(l) => l.position,
        }
    }

    /// Colour with Rec. 709 luminance 1.
    pub fn tint(&self) -> Vec3 {
        match self {
            PlacedLight::Point(l) => l.tint,
            PlacedLight::Spot(l) => l.tint,
            PlacedLight::Goniometric(l) => l.tint,
        }
    }

    /// Intensity (cd) along unit `dir` leaving the light.
    #[inline]
    pub fn intensity_towards(&self, dir: Vec3) -> f32 {
        match self {
            PlacedLight::Point(l) => l.intensity_cd,
            PlacedLight::Spot(l) => l.intensity_towards(dir),
            PlacedLight::Goniometric(l) => l.intensity_towards(dir),
        }
    }

    /// Whether it emits from a point (the batched direct shading handles no other).
    pub fn is_point(&self) -> bool {
        !self.samples_area()
    }

    /// The intensity (cd) when it is the same in every direction (batched shading skips the
    /// per-direction lookup).
    pub fn uniform_intensity(&self) -> Option<f32> {
        match self {
            PlacedLight::Point(l) => Some(l.intensity_cd),
            _ => None,
        }
    }
}

/// Dispatch by kind. The calls are small; `match` keeps them inlinable where `dyn` would not.
impl LightSource for PlacedLight {
    fn power_lm(&self) -> f64 {
        self.source().power_lm()
    }

    fn bounds(&self) -> LightBounds {
        self.source().bounds()
    }

    fn is_delta(&self) -> bool {
        true
    }

    #[inline]
    fn samples_area(&self) -> bool {
        match self {
            PlacedLight::Goniometric(l) => l.samples_area(),
            _ => false,
        }
    }

    fn area_share(&self, p: Vec3) -> f32 {
        self.source().area_share(p)
    }

    #[inline(always)]
    fn sample_incident(&self, at: Receiver, u: [f32; 2]) -> Option<Incident> {
        match self {
            PlacedLight::Point(l) => l.sample_incident(at, u),
            PlacedLight::Spot(l) => l.sample_incident(at, u),
            PlacedLight::Goniometric(l) => l.sample_incident(at, u),
        }
    }

    fn incident_pdf(&self, origin: Vec3, wi: Vec3, distance: f32) -> f32 {
        self.source().incident_pdf(origin, wi, distance)
    }

    #[inline]
    fn emitted(&self, dir: Vec3) -> Vec3 {
        match self {
            PlacedLight::Point(l) => l.emitted(dir),
            PlacedLight::Spot(l) => l.emitted(dir),
            PlacedLight::Goniometric(l) => l.emitted(dir),
        }
    }

    fn sample_emission(&self, u_point: [f32; 2], u_dir: [f32; 2]) -> Option<Emission> {
        self.source().sample_emission(u_point, u_dir)
    }

    #[inline]
    fn emission_dir_pdf(&self, dir: Vec3) -> f32 {
        match self {
            PlacedLight::Point(l) => l.emission_dir_pdf(dir),
            PlacedLight::Spot(l) => l.emission_dir_pdf(dir),
            PlacedLight::Goniometric(l) => l.emission_dir_pdf(dir),
        }
    }

    fn emission_point_pdf(&self) -> f32 {
        1.0
    }

    fn normal(&self) -> Vec3 {
        Vec3::ZERO
    }

    #[inline]
    fn emission_cosine(&self, n: Vec3, dir: Vec3) -> f32 {
        self.source().emission_cosine(n, dir)
    }
}
