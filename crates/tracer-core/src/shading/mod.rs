//! What surfaces do with light: per-render material constants ([`Prepared`]) and the
//! scattering model of path mode ([`Bsdf`]: Lambert, normalised Blinn-Phong lobe, mirror).
//! The integrators in [`crate::integrator`] combine them with the lights.

mod bsdf;
mod dielectric;
mod prepared;
mod surface;

pub use bsdf::{Bsdf, BsdfSample};
pub use dielectric::{fresnel, refract};
pub use prepared::{Prepared, PreparedLight, PreparedMaterial, Profile};
pub use surface::Surface;

use glam::Vec3;

/// The scattering at triangle `prim` for light leaving along unit `wo` (glass knows whether
/// `wo` is outside, in front of the front face, or inside).
pub fn bsdf_at(prep: &Prepared<'_>, prim: u32, wo: Vec3) -> Bsdf {
    let bsdf = Bsdf::new(prep.material_of(prim));
    if prep.front_normal(prim).dot(wo) >= 0.0 {
        bsdf
    } else {
        bsdf.from_inside()
    }
}
