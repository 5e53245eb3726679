//! What surfaces do with light: per-render material constants ([`Prepared`]) and the
//! scattering model of path mode ([`Bsdf`]: Lambert, normalised Blinn-Phong lobe, mirror).
//! The integrators in [`crate::integrator`] combine them with the lights.

mod bsdf;
mod prepared;

pub use bsdf::{Bsdf, BsdfSample};
pub use prepared::{Prepared, PreparedLight, PreparedMaterial, Profile};

use crate::bvh::Hit;
use glam::Vec3;

/// The geometric normal turned to face the incoming ray (surfaces are two-sided).
pub fn facing_normal(prep: &Prepared<'_>, hit: &Hit, dir: Vec3) -> Vec3 {
    let n = prep.scene.normals[hit.prim as usize];
    if n.dot(dir) > 0.0 { -n } else { n }
}
