//! Textured materials and alpha at a hit: the material a hit's texture coordinates make, and
//! whether a ray passes through an alpha-cut surface there.
//!
//! Alpha is tested on every ray that asks what it sees or whether it is blocked, camera,
//! scattered and shadow rays alike, so a cut-out leaf lets light through its holes. MASK cuts
//! where alpha < cutoff. BLEND (and MTL `map_d`) keeps the surface with probability alpha
//! (stochastic transparency): the expected picture is the blend, and no estimator changes.
//! The random number is a hash of the ray and the triangle, so a render stays reproducible
//! with any number of threads.

use super::LitScene;
use crate::bvh::Hit;
use crate::geometry::Ray;
use crate::shading::PreparedMaterial;
use crate::texture::AlphaMode;
use crate::texture::SurfaceDerivatives;
use glam::{Vec2, Vec3};
use std::borrow::Cow;

/// At most this many alpha-cut surfaces are passed along one ray (then it stops there).
const MAX_CUTS: usize = 64;

/// Per-slot texture facts of a render.
#[derive(Debug, Default)]
pub(super) struct SlotMaps {
    /// Per slot: the texture set whose maps change its shading (empty: none does).
    pub shading: Vec<Option<u32>>,
    /// Per slot: the texture set that cuts it (empty: none does).
    pub cutting: Vec<Option<u32>>,
    /// Per slot: the texture set that bends its normals (empty: none does).
    pub bending: Vec<Option<u32>>,
    /// Per slot: the texture set whose map varies its emission (empty: none does).
    pub glowing: Vec<Option<u32>>,
    /// Per slot: the clamped material the maps multiply (empty without shading maps).
    pub factors: Vec<crate::scene::Material>,
}

impl SlotMaps {
    pub fn new(scene: &crate::scene::Scene, materials: &[crate::scene::Material]) -> Self {
        use crate::texture::TextureSet;
        // Per slot, the set that does `what`; empty when no slot's does.
        let slots_where = |what: fn(&TextureSet) -> bool| -> Vec<Option<u32>> {
            let per_slot: Vec<Option<u32>> = materials
                .iter()
                .map(|m| {
                    m.textures
                        .filter(|&s| scene.texture_sets.get(s as usize).is_some_and(what))
                })
                .collect();
            if per_slot.iter().any(Option::is_some) {
                per_slot
            } else {
                Vec::new()
            }
        };
        let shading = slots_where(TextureSet::shades);
        SlotMaps {
            factors: if shading.is_empty() {
                Vec::new()
            } else {
                materials.to_vec()
            },
            shading,
            cutting: slots_where(TextureSet::cuts),
            bending: slots_where(TextureSet::bends),
            glowing: slots_where(TextureSet::glows),
        }
    }
}

/// A uniform number in [0, 1) from the bits of `words` (a 32-bit avalanche mix per word).
fn hash01(words: &[u32]) -> f32 {
    let mut h: u32 = 0x9e37_79b9;
    for &w in words {
        h ^= w;
        h = h.wrapping_mul(0x85eb_ca6b);
        h ^= h >> 13;
        h = h.wrapping_mul(0xc2b2_ae35);
        h ^= h >> 16;
    }
    (h >> 8) as f32 / (1u32 << 24) as f32
}

impl LitScene<'_> {
    /// Texture coordinates (set 0, set 1) at barycentrics `bary` = (u, v) of triangle `prim`.
    #[inline]
    pub fn uv_at(&self, prim: u32, bary: [f32; 2]) -> [Vec2; 2] {
        let [u, v] = bary;
        let w = 1.0 - u - v;
        let at = |set: usize| {
            self.scene
                .corner_uvs(set, prim)
                .map_or(Vec2::ZERO, |c| c[0] * w + c[1] * u + c[2] * v)
        };
        [at(0), at(1)]
    }

    /// The material at barycentrics `bary` of triangle `prim`: its slot's, with the slot's
    /// maps applied when it has any.
    #[inline]
    pub fn material_at(&self, prim: u32, bary: [f32; 2]) -> Cow<'_, PreparedMaterial> {
        let slot = self.scene.slot(prim) as usize;
        if !self.maps.shading.is_empty()
            && let Some(Some(set)) = self.maps.shading.get(slot)
        {
            return Cow::Owned(self.textured(prim, slot, *set, bary));
        }
        Cow::Borrowed(&self.materials[slot])
    }

    #[cold]
    #[inline(never)]
    fn textured(&self, prim: u32, slot: usize, set: u32, bary: [f32; 2]) -> PreparedMaterial {
        let scene = self.scene;
        let (Some(maps), Some(factors)) = (
            scene.texture_sets.get(set as usize),
            self.maps.factors.get(slot),
        ) else {
            return self.materials[slot];
        };
        let m = maps.apply(&scene.textures, self.uv_at(prim, bary), factors);
        PreparedMaterial::new(&m)
    }

    /// Whether maps vary the shading or the normals of material slot `slot`.
    #[inline]
    pub fn is_textured(&self, slot: usize) -> bool {
        self.maps.shading.get(slot).is_some_and(Option::is_some)
            || self.maps.bending.get(slot).is_some_and(Option::is_some)
    }

    /// Whether some material bends its shading normals (normal or bump maps).
    #[inline(always)]
    pub fn bends_normals(&self) -> bool {
        !self.maps.bending.is_empty()
    }

    /// The unit normal `n` (on the side the mesh's normals face) at barycentrics `bary` of
    /// triangle `prim`, bent by its material's normal and bump maps (`n` itself without).
    #[cold]
    #[inline(never)]
    pub fn bent_normal(&self, prim: u32, bary: [f32; 2], n: Vec3) -> Vec3 {
        let scene = self.scene;
        let slot = scene.slot(prim) as usize;
        let Some(Some(set)) = self.maps.bending.get(slot) else {
            return n;
        };
        let Some(maps) = scene.texture_sets.get(*set as usize) else {
            return n;
        };
        let uv_set = usize::from(maps.normal.or(maps.bump).map_or(0, |m| m.set.min(1)));
        let Some(corner_uvs) = scene.corner_uvs(uv_set, prim) else {
            return n;
        };
        let Some((dp_du, dp_dv)) =
            SurfaceDerivatives::of_triangle(scene.triangle(prim), corner_uvs)
        else {
            return n;
        };
        let [u, v] = bary;
        let tangent = scene
            .corner_tangents(prim)
            .map(|t| t[0] * (1.0 - u - v) + t[1] * u + t[2] * v)
            .filter(|t| t.truncate().length_squared() > 1e-12);
        let d = SurfaceDerivatives {
            dp_du,
            dp_dv,
            tangent,
        };
        maps.bend(&scene.textures, self.uv_at(prim, bary), n, &d)
    }

    /// What an emissive map multiplies triangle `prim`'s emission by at its point `p` (1 per
    /// channel without one). Light sampling picks triangles by their factor's flux and points
    /// uniformly, so every estimate stays unbiased with the map applied where the point is.
    #[inline]
    pub fn emission_factor(&self, prim: u32, p: Vec3) -> Vec3 {
        if self.maps.glowing.is_empty() {
            return Vec3::ONE;
        }
        self.textured_emission(prim, p)
    }

    #[cold]
    #[inline(never)]
    fn textured_emission(&self, prim: u32, p: Vec3) -> Vec3 {
        let scene = self.scene;
        let Some(slot) = scene.slot_of(prim) else {
            return Vec3::ONE;
        };
        let Some(Some(set)) = self.maps.glowing.get(slot as usize) else {
            return Vec3::ONE;
        };
        let Some(map) = scene
            .texture_sets
            .get(*set as usize)
            .and_then(|s| s.emissive)
        else {
            return Vec3::ONE;
        };
        // The point's barycentrics on its triangle.
        let [a, b, c] = scene.triangle(prim);
        let (e1, e2, d) = (b - a, c - a, p - a);
        let (d00, d01, d11) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let (d20, d21) = (d.dot(e1), d.dot(e2));
        let den = d00 * d11 - d01 * d01;
        if den.abs() < 1e-30 || !den.is_finite() {
            return Vec3::ONE;
        }
        let u = (d11 * d20 - d01 * d21) / den;
        let v = (d00 * d21 - d01 * d20) / den;
        map.read(
            &scene.textures,
            self.uv_at(prim, [u, v]),
            crate::texture::Encoding::Srgb,
        )
        .truncate()
    }

    /// Whether some surface is alpha-cut (rays then test alpha at every hit).
    #[inline]
    pub(super) fn any_cutout(&self) -> bool {
        !self.maps.cutting.is_empty()
    }

    /// Whether `ray` passes through the surface at `hit` (an alpha-cut one, where alpha says
    /// it is not there).
    fn passes(&self, hit: &Hit, ray: &Ray) -> bool {
        let slot = self.scene.slot(hit.prim) as usize;
        let Some(Some(set)) = self.maps.cutting.get(slot) else {
            return false;
        };
        let Some(maps) = self.scene.texture_sets.get(*set as usize) else {
            return false;
        };
        let alpha = maps.alpha(&self.scene.textures, self.uv_at(hit.prim, [hit.u, hit.v]));
        match maps.alpha_mode {
            AlphaMode::Opaque => false,
            AlphaMode::Mask { cutoff } => alpha < cutoff,
            AlphaMode::Blend => {
                let o = ray.origin.to_array().map(f32::to_bits);
                let d = ray.dir.to_array().map(f32::to_bits);
                let u = hash01(&[
                    o[0],
                    o[1],
                    o[2],
                    d[0],
                    d[1],
                    d[2],
                    hit.prim,
                    hit.t.to_bits(),
                ]);
                u >= alpha
            }
        }
    }

    /// The closest hit along `ray` that alpha does not cut away (`closest` finds hits).
    pub(super) fn closest_uncut(
        &self,
        ray: &Ray,
        closest: impl Fn(&Ray) -> Option<Hit>,
    ) -> Option<Hit> {
        let mut r = *ray;
        let step = self.epsilon / ray.dir.length().max(1e-20);
        for _ in 0..MAX_CUTS {
            let hit = closest(&r)?;
            if !self.passes(&hit, &r) {
                return Some(hit);
            }
            r.t_min = hit.t + step;
            if r.t_min >= r.t_max {
                return None;
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hash_is_uniform_enough_to_blend_by() {
        let n = 100_000u32;
        let mut below = [0u32; 10];
        for i in 0..n {
            let x = hash01(&[i, 7, i.wrapping_mul(31)]);
            assert!((0.0..1.0).contains(&x));
            below[(x * 10.0) as usize] += 1;
        }
        for b in below {
            assert!(
                (f64::from(b) / f64::from(n) - 0.1).abs() < 0.005,
                "{below:?}"
            );
        }
    }
}
