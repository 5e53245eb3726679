//! The maps one material carries, and the material they make at a hit.

use super::{Encoding, Texture, TextureRef};
use crate::scene::Material;
use glam::{Vec2, Vec3};

/// How a material's alpha (base colour alpha times its factor, or an MTL `map_d`) cuts it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum AlphaMode {
    /// Alpha is ignored.
    #[default]
    Opaque,
    /// Where alpha is below the cutoff the surface is not there, for every ray.
    Mask { cutoff: f32 },
    /// The surface is there with probability alpha (stochastic transparency: unbiased, the
    /// expected picture is the blend).
    Blend,
}

/// The maps of one material, with the scene's textures by index.
pub type TextureSet = Maps<TextureRef>;

/// The maps of one material (all optional), each a `T`: a [`TextureRef`] in a scene, a
/// reference to an image file in a scene description.
#[derive(Clone, Debug, PartialEq)]
pub struct Maps<T> {
    /// The material's name, for the user.
    pub material: String,
    /// Multiplies the diffuse reflectance (classic) or base colour (metallic-roughness); its
    /// alpha is glTF's alpha. sRGB.
    pub base_color: Option<T>,
    /// glTF `metallicRoughnessTexture`: roughness in G, metallic in B, times the factors.
    pub metal_rough: Option<T>,
    /// MTL `map_Ks`: multiplies the specular reflectance. sRGB.
    pub specular: Option<T>,
    /// MTL `map_Pr`, `map_Pm`: roughness and metallic (their red channel), times the factors.
    pub roughness: Option<T>,
    pub metallic: Option<T>,
    /// MTL `map_d`: alpha from the image's alpha channel, or its red channel when it has none.
    pub alpha_map: Option<T>,
    /// A tangent-space normal map (glTF `normalTexture`, MTL `norm`): RGB = (x, y, z) · ½ + ½,
    /// x along the tangent (increasing u), y up the image, z out of the surface; x and y times
    /// `normal_scale`.
    pub normal: Option<T>,
    pub normal_scale: f32,
    /// A height map (MTL `bump` / `map_Bump`, red channel, linear) in scene units times
    /// `bump_scale` (`-bm`).
    pub bump: Option<T>,
    pub bump_scale: f32,
    /// Multiplies the emission (glTF `emissiveTexture`, MTL `map_Ke`). sRGB.
    pub emissive: Option<T>,
    /// glTF's base colour factor alpha (1 for OBJ).
    pub alpha_factor: f32,
    pub alpha_mode: AlphaMode,
}

impl<T> Default for Maps<T> {
    fn default() -> Self {
        Self {
            material: String::new(),
            base_color: None,
            metal_rough: None,
            specular: None,
            roughness: None,
            metallic: None,
            alpha_map: None,
            normal: None,
            normal_scale: 1.0,
            bump: None,
            bump_scale: 1.0,
            emissive: None,
            alpha_factor: 1.0,
            alpha_mode: AlphaMode::Opaque,
        }
    }
}

impl<T> Maps<T> {
    /// Whether the maps change anything a BSDF reads (as opposed to alpha only).
    pub fn shades(&self) -> bool {
        self.base_color.is_some()
            || self.metal_rough.is_some()
            || self.specular.is_some()
            || self.roughness.is_some()
            || self.metallic.is_some()
    }

    /// Whether the material cuts holes (alpha mask or blend).
    pub fn cuts(&self) -> bool {
        self.alpha_mode != AlphaMode::Opaque
    }

    /// Each map turned into a `U` by `f` (which names the map: `base_color`, ...); a map `f`
    /// returns None for is dropped.
    pub fn try_map<U>(&self, mut f: impl FnMut(&str, &T) -> Option<U>) -> Maps<U> {
        let mut one = |name: &str, t: &Option<T>| t.as_ref().and_then(|t| f(name, t));
        Maps {
            material: self.material.clone(),
            base_color: one("base colour", &self.base_color),
            metal_rough: one("metallic-roughness", &self.metal_rough),
            specular: one("specular", &self.specular),
            roughness: one("roughness", &self.roughness),
            metallic: one("metallic", &self.metallic),
            alpha_map: one("alpha", &self.alpha_map),
            normal: one("normal", &self.normal),
            normal_scale: self.normal_scale,
            bump: one("bump", &self.bump),
            bump_scale: self.bump_scale,
            emissive: one("emissive", &self.emissive),
            alpha_factor: self.alpha_factor,
            alpha_mode: self.alpha_mode,
        }
    }

    /// Each map present, named (`base colour`, `normal`, ...), in a fixed order.
    pub fn named(&self) -> Vec<(&'static str, &T)> {
        [
            ("base colour", &self.base_color),
            ("metallic-roughness", &self.metal_rough),
            ("specular", &self.specular),
            ("roughness", &self.roughness),
            ("metallic", &self.metallic),
            ("alpha", &self.alpha_map),
            ("normal", &self.normal),
            ("bump", &self.bump),
            ("emissive", &self.emissive),
        ]
        .into_iter()
        .filter_map(|(name, t)| t.as_ref().map(|t| (name, t)))
        .collect()
    }

    /// Whether the maps bend the shading normal (normal or bump map).
    pub fn bends(&self) -> bool {
        self.normal.is_some() || self.bump.is_some()
    }

    /// Whether a map varies the emission.
    pub fn glows(&self) -> bool {
        self.emissive.is_some()
    }

    /// Whether the set has no map and no alpha.
    pub fn is_empty(&self) -> bool {
        !self.shades() && !self.bends() && !self.glows() && self.alpha_map.is_none() && !self.cuts()
    }
}

impl TextureSet {
    /// The alpha at a hit with UV sets `uv` (1 when the set has none).
    pub fn alpha(&self, textures: &[Texture], uv: [Vec2; 2]) -> f32 {
        let mut a = self.alpha_factor;
        if let Some(t) = &self.base_color {
            a *= t.read(textures, uv, Encoding::Srgb).w;
        }
        if let Some(t) = &self.alpha_map {
            let has_alpha = textures
                .get(t.texture as usize)
                .is_some_and(Texture::has_alpha);
            let v = t.read(textures, uv, Encoding::Linear);
            a *= if has_alpha { v.w } else { v.x };
        }
        a
    }

    /// The material `factors` makes at a hit with UV sets `uv`: each map multiplies its factor.
    pub fn apply(&self, textures: &[Texture], uv: [Vec2; 2], factors: &Material) -> Material {
        let mut m = *factors;
        let colour = self
            .base_color
            .map(|t| t.read(textures, uv, Encoding::Srgb).truncate());
        if let Some(pbr) = &mut m.pbr {
            if let Some(c) = colour {
                pbr.base_color = (Vec3::from(pbr.base_color) * c).to_array();
            }
            if let Some(t) = &self.metal_rough {
                let v = t.read(textures, uv, Encoding::Linear);
                pbr.roughness *= v.y;
                pbr.metallic *= v.z;
            }
            if let Some(t) = &self.roughness {
                pbr.roughness *= t.read(textures, uv, Encoding::Linear).x;
            }
            if let Some(t) = &self.metallic {
                pbr.metallic *= t.read(textures, uv, Encoding::Linear).x;
            }
        } else {
            if let Some(c) = colour {
                m.kd = (Vec3::from(m.kd) * c).to_array();
            }
            if let Some(t) = &self.specular {
                let c = t.read(textures, uv, Encoding::Srgb).truncate();
                m.ks = (Vec3::from(m.ks) * c).to_array();
            }
        }
        m
    }
}
