//! Radiance along a ray: direct light from point lights with hard shadows, a Lambertian BRDF with
//! a normalised Blinn-Phong highlight, and perfect mirror reflection traced recursively.
//!
//! Physics (photometric SI units):
//! - Illuminance at a surface point from a point light of intensity `I` (cd) at distance `R` (m):
//!   `E = I cos θ / R²` (lx), θ between the shading normal and the direction to the light; zero
//!   when the light is behind the side facing the viewer or a shadow ray finds an occluder.
//! - Luminance leaving towards the viewer (cd/m²):
//!   `L = Σ_lights E · f + Ks · L_reflected`, with `f = Kd / π + Ks (g + 8) / (8π) (n·h)^g`
//!   (the highlight only for glossiness `g > 0`) and `L_reflected` the luminance seen along the
//!   mirror direction, traced up to `max_depth` reflections.
//!
//! The integrator answers "luminance along this ray"; tiles, passes and threads belong to `render`.

mod prepared;

pub use prepared::{Prepared, PreparedLight, PreparedMaterial};

use crate::bvh::Hit;
use crate::geometry::Ray;
use glam::Vec3;

/// What one camera sample sees.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sample {
    /// Linear luminance per RGB channel, cd/m².
    pub rgb: Vec3,
    /// Illuminance (lx) from all point lights on the first surface hit (0 on a miss).
    pub illuminance_lx: f32,
    /// Rays traced for this sample (camera, shadow and mirror rays).
    pub rays: u32,
}

/// Luminance arriving along `ray` (a camera ray: depth 0), with the first hit's illuminance.
pub fn trace(prep: &Prepared<'_>, ray: &Ray) -> Sample {
    let mut sample = Sample::default();
    let mut ray = *ray;
    // Throughput: the product of Ks along the mirror chain so far.
    let mut weight = Vec3::ONE;
    for depth in 0..=prep.max_depth {
        sample.rays += 1;
        let Some(hit) = prep.closest_visible(&ray) else {
            break;
        };
        let p = ray.at(hit.t);
        let n = facing_normal(prep, &hit, ray.dir);
        let slot = prep.scene.triangle_slots[hit.prim as usize] as usize;
        let mat = &prep.materials[slot];
        let view = -ray.dir.normalize();
        let origin = p + n * prep.epsilon;
        let mut direct = Vec3::ZERO;
        let mut e_total = 0.0;
        for light in &prep.lights {
            let to_light = light.position - p;
            let dist2 = to_light.length_squared();
            if dist2 <= 0.0 {
                continue;
            }
            let wi = to_light / dist2.sqrt();
            let cos_theta = n.dot(wi);
            if cos_theta <= 0.0 {
                continue;
            }
            sample.rays += 1;
            if prep.occluded(origin, light.position - origin) {
                continue;
            }
            // E = I cos θ / R², R converted to metres.
            let e = light.intensity_cd * cos_theta / (dist2 * prep.metres_per_unit_sq);
            e_total += e;
            let mut brdf = mat.kd_over_pi;
            if mat.glossiness > 0.0 {
                let h = (wi + view).normalize_or_zero();
                let n_dot_h = n.dot(h).max(0.0);
                brdf += mat.ks * (mat.highlight_norm * n_dot_h.powf(mat.glossiness));
            }
            direct += light.tint * e * brdf;
        }
        if depth == 0 {
            sample.illuminance_lx = e_total;
        }
        sample.rgb += weight * direct;
        weight *= mat.ks;
        if depth == prep.max_depth || weight.max_element() <= 0.0 {
            break;
        }
        let d = ray.dir.normalize();
        let reflected = d - n * (2.0 * d.dot(n));
        ray = Ray::new(origin, reflected);
    }
    sample
}

/// The geometric normal turned to face the incoming ray (surfaces are two-sided).
fn facing_normal(prep: &Prepared<'_>, hit: &Hit, dir: Vec3) -> Vec3 {
    let n = prep.scene.normals[hit.prim as usize];
    if n.dot(dir) > 0.0 { -n } else { n }
}
