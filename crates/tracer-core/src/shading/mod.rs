//! What surfaces do with light: per-render material constants ([`PreparedMaterial`]) and the
//! scattering model of path mode ([`Bsdf`]: Lambert, normalised Blinn-Phong lobe, mirror).
//! The integrators in [`crate::integrator`] combine them with the lights.

mod bsdf;
mod dielectric;
mod material;
mod metal_rough;
mod microfacet;
mod surface;

pub use bsdf::{Bsdf, BsdfSample};
pub use dielectric::{fresnel, refract};
pub use material::PreparedMaterial;
pub use metal_rough::{MetalRough, MetalRoughSample, dielectric_f0};
pub use microfacet::{Ggx, MIN_ALPHA};
pub use surface::Surface;

use crate::lit_scene::LitScene;
use glam::Vec3;

/// The scattering at triangle `prim` for light leaving along unit `wo` (glass knows whether
/// `wo` is outside, in front of the front face, or inside); `importance` for light paths.
pub fn bsdf_at(lit: &LitScene<'_>, prim: u32, wo: Vec3, importance: bool) -> Bsdf {
    let inside = lit.front_normal(prim).dot(wo) < 0.0;
    Bsdf::at(lit.material_of(prim), inside, importance)
}
