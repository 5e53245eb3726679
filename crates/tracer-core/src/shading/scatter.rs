//! The scattering interface the bidirectional integrators are generic over, so that a scene
//! without metallic-roughness materials runs the classic lobes' code alone ([`Classic`]: no
//! dispatch, nothing of the other model in its hot loops), and one with them the full
//! [`Bsdf`]. Measured on BENCHMARK.md's E3: the enum alone cost bdpt 1.4 % more instructions
//! and 16 % more instruction-cache misses per sample; path mode, 0.8 % more instructions.

use super::bsdf::{Bsdf, BsdfSample, Classic};
use super::material::PreparedMaterial;
use crate::lit_scene::LitScene;
use crate::sampling::SampleRng;
use glam::Vec3;

/// A surface's scattering at one point, as the integrators use it.
pub trait Scatter: Copy + std::fmt::Debug {
    /// The scattering of `m`, seen from inside its glass when `inside`, for light paths
    /// (importance transport) when `importance`.
    fn at(m: &PreparedMaterial, inside: bool, importance: bool) -> Self;
    fn is_black(&self) -> bool;
    /// Whether any lobe is not a delta (light sampling pays off).
    fn has_smooth_lobe(&self) -> bool;
    /// The non-delta BRDF value for unit `wo`, `wi` (both on the side of unit normal `n`).
    fn eval(&self, n: Vec3, wo: Vec3, wi: Vec3) -> Vec3;
    /// Density (per sr) with which `sample` picks `wi` through a non-delta lobe.
    fn pdf(&self, n: Vec3, wo: Vec3, wi: Vec3) -> f32;
    /// An incident direction for the outgoing unit `wo`, with `n` facing `wo`.
    fn sample(&self, n: Vec3, wo: Vec3, rng: &mut SampleRng) -> Option<BsdfSample>;
}

/// The scattering at barycentrics `bary` of triangle `prim` (textures vary it) for light
/// leaving along unit `wo` (glass knows whether `wo` is outside, in front of the front face,
/// or inside); `importance` for light paths.
#[inline]
pub fn scatter_at<S: Scatter>(
    lit: &LitScene<'_>,
    prim: u32,
    bary: [f32; 2],
    wo: Vec3,
    importance: bool,
) -> S {
    let inside = lit.front_normal(prim).dot(wo) < 0.0;
    S::at(&lit.material_at(prim, bary), inside, importance)
}

impl Scatter for Classic {
    /// Only for scenes without metallic-roughness materials or panes
    /// (`LitScene::has_metal_rough`).
    #[inline]
    fn at(m: &PreparedMaterial, inside: bool, importance: bool) -> Self {
        debug_assert!(
            m.pbr.is_none() && m.pane.is_none(),
            "a metallic-roughness material or a pane in Classic"
        );
        Classic::at(m, inside, importance)
    }
    #[inline]
    fn is_black(&self) -> bool {
        Classic::is_black(self)
    }
    #[inline]
    fn has_smooth_lobe(&self) -> bool {
        Classic::has_smooth_lobe(self)
    }
    #[inline]
    fn eval(&self, n: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
        Classic::eval(self, n, wo, wi)
    }
    #[inline]
    fn pdf(&self, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        Classic::pdf(self, n, wo, wi)
    }
    #[inline]
    fn sample(&self, n: Vec3, wo: Vec3, rng: &mut SampleRng) -> Option<BsdfSample> {
        Classic::sample(self, n, wo, rng)
    }
}

impl Scatter for Bsdf {
    #[inline]
    fn at(m: &PreparedMaterial, inside: bool, importance: bool) -> Self {
        Bsdf::at(m, inside, importance)
    }
    #[inline]
    fn is_black(&self) -> bool {
        Bsdf::is_black(self)
    }
    #[inline]
    fn has_smooth_lobe(&self) -> bool {
        Bsdf::has_smooth_lobe(self)
    }
    #[inline]
    fn eval(&self, n: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
        Bsdf::eval(self, n, wo, wi)
    }
    #[inline]
    fn pdf(&self, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        Bsdf::pdf(self, n, wo, wi)
    }
    #[inline]
    fn sample(&self, n: Vec3, wo: Vec3, rng: &mut SampleRng) -> Option<BsdfSample> {
        Bsdf::sample(self, n, wo, rng)
    }
}
