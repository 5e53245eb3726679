//! The placed lights of a render and the emitter table, with the direct light a point-like light
//! gives at a surface point.

use super::LitScene;
use crate::light::LightKind;
use crate::light::{
    EmissiveTriangle, EmitterTable, Light, LightBounds, Luminaire, LuminaireFrame, SpotProfile,
};
use crate::scene::Scene;
use crate::shading::PreparedMaterial;
use glam::Vec3;
use std::sync::Arc;

#[derive(Clone, Debug)]
pub struct PreparedLight {
    pub position: Vec3,
    pub intensity_cd: f32,
    /// Colour with Rec. 709 luminance 1.
    pub tint: Vec3,
    /// How the intensity depends on direction.
    pub profile: Profile,
}

/// The angular dependence of a light's intensity.
#[derive(Clone, Debug)]
pub enum Profile {
    Isotropic,
    Spot(SpotProfile),
    /// A measured distribution (cd, already times the multiplier) in its frame.
    Goniometric(Arc<Luminaire>, LuminaireFrame),
}

impl PreparedLight {
    /// The light `l` (valid) of a scene whose handedness gives `handedness_sign`.
    pub fn new(l: &Light, handedness_sign: f32) -> Self {
        let (intensity_cd, profile) = match (l.kind, &l.luminaire) {
            (LightKind::Luminaire, Some(lum)) => (
                l.multiplier,
                Profile::Goniometric(Arc::clone(lum), l.luminaire_frame(handedness_sign)),
            ),
            (LightKind::Spot, _) => (
                l.intensity_cd,
                l.spot_profile().map_or(Profile::Isotropic, Profile::Spot),
            ),
            _ => (l.intensity_cd, Profile::Isotropic),
        };
        PreparedLight {
            position: l.position(),
            intensity_cd: intensity_cd.max(0.0),
            tint: l.tint(),
            profile,
        }
    }

    /// Luminous flux (lm): the intensity over the sphere.
    pub fn flux_lm(&self) -> f64 {
        let solid_angle = match &self.profile {
            Profile::Isotropic => 4.0 * std::f64::consts::PI,
            Profile::Spot(s) => f64::from(s.solid_angle_sr()),
            // The file's flux; `intensity_cd` is the multiplier.
            Profile::Goniometric(table, _) => table.flux_lm,
        };
        f64::from(self.intensity_cd) * solid_angle
    }

    /// Its bounds for the light tree: a point emitting everywhere, or a spot's beam.
    pub fn bounds(&self) -> LightBounds {
        let power = self.flux_lm() as f32;
        match &self.profile {
            Profile::Spot(s) => LightBounds::beam(self.position, power, s.axis, s.falloff),
            Profile::Isotropic | Profile::Goniometric(..) => {
                LightBounds::point(self.position, power)
            }
        }
    }

    /// Intensity (cd) towards unit direction `dir` (from the light).
    pub fn intensity_towards(&self, dir: Vec3) -> f32 {
        match &self.profile {
            Profile::Isotropic => self.intensity_cd,
            Profile::Spot(p) => self.intensity_cd * p.factor(dir),
            Profile::Goniometric(table, frame) => {
                let (c, gamma) = frame.angles_deg(dir);
                self.intensity_cd * table.photometry.intensity(c, gamma)
            }
        }
    }
}

impl LitScene<'_> {
    /// Direct light from the point-like `light` at `p` on a surface of unit normal `n`: the unit
    /// direction to the light and the illuminance it gives there, E = I(ω) cos θ / R² in lx
    /// (R in metres), before shadowing. None when it gives none (behind the surface, no
    /// intensity that way, or the light at `p`).
    pub fn light_at(&self, light: &PreparedLight, p: Vec3, n: Vec3) -> Option<(Vec3, f32)> {
        let to_light = light.position - p;
        let dist2 = to_light.length_squared();
        if dist2 <= 0.0 {
            return None;
        }
        let wi = to_light / dist2.sqrt();
        let cos_theta = n.dot(wi);
        if cos_theta <= 0.0 {
            return None;
        }
        let intensity = light.intensity_towards(-wi);
        if intensity <= 0.0 {
            return None;
        }
        Some((
            wi,
            intensity * cos_theta / (dist2 * self.metres_per_unit_sq),
        ))
    }
}

/// The emitter table of every drawn triangle whose material emits.
pub(super) fn emitter_table(
    scene: &Scene,
    models: &[crate::scene::Material],
    materials: &[PreparedMaterial],
    hidden: &[bool],
    front_sign: f32,
) -> EmitterTable {
    let emissive = |slot: usize| materials[slot].emission.max_element() > 0.0 && !hidden[slot];
    if !(0..materials.len()).any(emissive) {
        return EmitterTable::default();
    }
    let triangles: Vec<EmissiveTriangle> = scene
        .triangle_slots
        .iter()
        .enumerate()
        .filter(|(_, slot)| emissive(**slot as usize))
        .map(|(t, &slot)| EmissiveTriangle {
            triangle: t as u32,
            vertices: scene.triangles[t],
            front: scene.normals[t] * front_sign,
            radiance: materials[slot as usize].emission,
            sides: models[slot as usize].emission_sides,
        })
        .collect();
    EmitterTable::new(scene.triangles.len(), &triangles)
}
