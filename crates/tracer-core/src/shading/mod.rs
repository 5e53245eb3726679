//! What surfaces do with light: per-render material constants ([`PreparedMaterial`]) and the
//! scattering model of path mode ([`Bsdf`]: Lambert, normalised Blinn-Phong lobe, mirror).
//! The integrators in [`crate::integrator`] combine them with the lights.

mod bsdf;
mod dielectric;
mod material;
mod metal_rough;
mod microfacet;
mod pane;
mod scatter;
mod surface;

pub use bsdf::{Bsdf, BsdfSample, Classic};
pub use dielectric::{fresnel, refract};
pub use material::PreparedMaterial;
pub use metal_rough::{MetalRough, MetalRoughSample, dielectric_f0};
pub use microfacet::{Ggx, MIN_ALPHA};
pub use pane::Pane;
pub use scatter::{Scatter, scatter_at};
pub use surface::Surface;

use crate::lit_scene::LitScene;
use glam::Vec3;

/// The scattering at barycentrics `bary` of triangle `prim` for light leaving along unit `wo`
/// ([`scatter_at`] with the full model).
#[inline]
pub fn bsdf_at(lit: &LitScene<'_>, prim: u32, bary: [f32; 2], wo: Vec3, importance: bool) -> Bsdf {
    scatter_at(lit, prim, bary, wo, importance)
}
