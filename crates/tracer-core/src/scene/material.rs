//! Surface materials: Lambertian diffuse plus a mirror with a normalised Blinn-Phong highlight,
//! and a smooth dielectric (glass) interface.

use crate::light::EmissionSides;
use glam::Vec3;
use serde::{Deserialize, Serialize};

/// Reflectances are RGB tints in 0..=1 (dimensionless).
///
/// BRDF for a point light, with `n` the shading normal, `h` the half vector:
/// `f = Kd / π + Ks · (g + 8) / (8π) · (n·h)^g` (the highlight only when `glossiness > 0`),
/// and the mirror term `Ks · L_reflected` traced recursively. `Kd + Ks <= 1` per channel keeps
/// the surface from creating energy; [`Material::clamped`] enforces it.
///
/// Glass: `kt` weights a smooth dielectric interface of refractive index `ior` (inside behind
/// the front face, outside 1): Fresnel reflection R(θ) and refraction 1 − R by Snell's law, with
/// total internal reflection, both times `kt`. `Kd + Ks + Kt <= 1` per channel. The direct
/// (coursework) integrator does not trace glass: there `kt` is absorbed.
///
/// Pane (`kind = "pane"`): a window as one polygon, see `crate::shading::Pane`; it has no other
/// lobe, and the direct (coursework) integrator lets light through it to shadow rays only.
///
/// Metallic-roughness (glTF 2.0 Appendix B): [`Material::pbr`] replaces Kd, Ks and glossiness
/// with a base colour, metallic and roughness (see `crate::shading::MetalRough`); `ior` then sets
/// the dielectric layer's F0.
///
/// The sidecar's keys are those of `super::material_keys::MaterialKeys`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "super::material_keys::MaterialKeys")]
#[serde(into = "super::material_keys::MaterialKeys")]
pub struct Material {
    /// Diffuse reflectance Kd per channel.
    pub kd: [f32; 3],
    /// Mirror reflectance Ks per channel.
    pub ks: [f32; 3],
    /// Blinn-Phong exponent g of the highlight of point lights (0: no highlight, mirror only).
    pub glossiness: f32,
    /// Weight Kt of the smooth dielectric interface (glass) per channel.
    pub kt: [f32; 3],
    /// Refractive index of the inside (behind the front face) when `kt` > 0; of the dielectric
    /// layer of a metallic-roughness material.
    pub ior: f32,
    /// Luminance the surface emits as a Lambertian emitter, cd/m² (0: not a light).
    pub emission_cd_m2: f32,
    /// RGB tint of the emission, normalised to luminance 1 (so `emission_cd_m2` stays cd/m²).
    pub emission_color: [f32; 3],
    /// Which faces emit: both (default), front or back.
    pub emission_sides: EmissionSides,
    /// Metallic-roughness instead of Kd, Ks and glossiness.
    pub pbr: Option<Pbr>,
    /// A thin glass pane (a window as one polygon) of index `ior` instead of every lobe.
    pub pane: Option<Glazing>,
    /// The file's image textures and alpha for this material: an index into the scene's
    /// `texture_sets` (the maps multiply the factors above). The sidecar does not write it and
    /// its materials keep the slot's.
    pub textures: Option<u32>,
}

/// A thin pane's glazing (see `crate::shading::Pane`): its index is the material's `ior`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Glazing {
    /// Transmittance at normal incidence of an absorbing pane (None: clear glass).
    pub transmittance: Option<f32>,
}

/// A pane's refractive index unless given: soda-lime float glass.
pub const PANE_IOR: f32 = 1.52;

/// glTF's metallic-roughness parameters (its defaults: white, metallic 1, roughness 1, no
/// transmission).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pbr {
    pub base_color: [f32; 3],
    pub metallic: f32,
    pub roughness: f32,
    /// `KHR_materials_transmission`'s factor: thin-walled transmission of the dielectric.
    pub transmission: f32,
}

impl Default for Pbr {
    fn default() -> Self {
        Self {
            base_color: [1.0; 3],
            metallic: 1.0,
            roughness: 1.0,
            transmission: 0.0,
        }
    }
}

/// Default refractive index: crown glass.
pub const GLASS_IOR: f32 = 1.5;

impl Default for Material {
    /// Neutral grey diffuse: Kd 0.7, Ks 0.
    fn default() -> Self {
        Self {
            kd: [0.7; 3],
            ks: [0.0; 3],
            glossiness: 0.0,
            kt: [0.0; 3],
            ior: GLASS_IOR,
            emission_cd_m2: 0.0,
            emission_color: [1.0; 3],
            emission_sides: EmissionSides::Both,
            pbr: None,
            pane: None,
            textures: None,
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

    pub fn kt(&self) -> Vec3 {
        Vec3::from(self.kt)
    }

    /// Emitted luminance per channel (cd/m²): `emission_cd_m2` times the unit-luminance tint.
    pub fn emission(&self) -> Vec3 {
        if self.emission_cd_m2 > 0.0 && self.emission_cd_m2.is_finite() {
            crate::light::unit_luminance_tint(self.emission_color) * self.emission_cd_m2
        } else {
            Vec3::ZERO
        }
    }

    /// Clamps every value into its physical range (0..=1 reflectances, Kd + Ks + Kt <= 1 per
    /// channel by scaling all down, glossiness >= 0, ior in 1..=4). Returns the clamped material and whether anything
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
        let mut kt = self.kt.map(fix);
        for c in 0..3 {
            let sum = kd[c] + ks[c] + kt[c];
            if sum > 1.0 {
                kd[c] /= sum;
                ks[c] /= sum;
                kt[c] /= sum;
            }
        }
        let ior = if self.ior.is_finite() {
            self.ior.clamp(1.0, 4.0)
        } else {
            GLASS_IOR
        };
        let glossiness = if self.glossiness.is_finite() {
            self.glossiness.clamp(0.0, 1.0e5)
        } else {
            0.0
        };
        let emission_cd_m2 = if self.emission_cd_m2.is_finite() {
            self.emission_cd_m2.max(0.0)
        } else {
            0.0
        };
        let emission_color = self
            .emission_color
            .map(|c| if c.is_finite() { c.max(0.0) } else { 0.0 });
        let unit = |x: f32| {
            if x.is_finite() {
                x.clamp(0.0, 1.0)
            } else {
                1.0
            }
        };
        let pbr = self.pbr.map(|p| Pbr {
            base_color: p.base_color.map(fix),
            metallic: unit(p.metallic),
            roughness: unit(p.roughness),
            transmission: fix(p.transmission),
        });
        let out = Material {
            kd,
            ks,
            glossiness,
            kt,
            ior,
            emission_cd_m2,
            emission_color,
            emission_sides: self.emission_sides,
            pbr,
            pane: self.pane.map(|g| Glazing {
                transmittance: g
                    .transmittance
                    .filter(|t| t.is_finite())
                    .map(|t| t.clamp(1e-4, 1.0)),
            }),
            textures: self.textures,
        };
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
            ..Material::default()
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
