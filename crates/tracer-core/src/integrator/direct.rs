//! The coursework's model, extended to every light kind: direct light with hard shadows,
//! `L = Σ E · (Kd/π + Ks (g+8)/(8π) (n·h)^g) + Ks · L_reflected`, mirrors traced to a depth
//! limit, and emissive surfaces seen directly or sampled as lights.
//!
//! - Point and spot lights: `E = I(ω) cos θ / R²`, exact, one shadow ray each.
//! - Emissive triangles: one light sample per shading point (an unbiased estimate of their
//!   direct illuminance), picked by flux.

use super::Sample;
use crate::geometry::Ray;
use crate::sampling::SampleRng;
use crate::shading::{Prepared, PreparedMaterial, Surface};
use glam::Vec3;

/// Luminance arriving along the camera ray `ray`, with the first hit's direct illuminance.
pub fn trace(prep: &Prepared<'_>, ray: &Ray, rng: &mut SampleRng) -> Sample {
    let mut sample = Sample::default();
    let mut ray = *ray;
    // Throughput: the product of Ks along the mirror chain so far.
    let mut weight = Vec3::ONE;
    for depth in 0..=prep.max_depth {
        sample.rays += 1;
        let Some(hit) = prep.closest_visible(&ray) else {
            sample.missed = depth == 0;
            break;
        };
        let p = ray.at(hit.t);
        let surface = Surface::at(prep, &hit, p, ray.dir);
        let n = surface.ns;
        let mat = prep.material_of(hit.prim);
        let view = -ray.dir.normalize();
        if mat.emission.max_element() > 0.0 {
            sample.rgb += weight * prep.emitters.radiance(hit.prim, view);
        }
        let origin = surface.origin;
        let (direct, e_total, rays) = direct_light(prep, mat, &surface, view, rng);
        sample.rays += rays;
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
        if surface.ng.dot(reflected) <= 0.0 {
            // The shading normal bent the mirror direction into the mesh: it ends here.
            break;
        }
        ray = Ray::new(origin, reflected);
    }
    sample
}

/// Reflected direct luminance (cd/m² per channel), illuminance (lx) and rays traced at `p`.
fn direct_light(
    prep: &Prepared<'_>,
    mat: &PreparedMaterial,
    surface: &Surface,
    view: Vec3,
    rng: &mut SampleRng,
) -> (Vec3, f32, u32) {
    let (p, n, origin) = (surface.p, surface.ns, surface.origin);
    let brdf = |wi: Vec3| {
        let mut f = mat.kd_over_pi;
        if mat.glossiness > 0.0 {
            let h = (wi + view).normalize_or_zero();
            let n_dot_h = n.dot(h).max(0.0);
            f += mat.ks * (mat.highlight_norm * n_dot_h.powf(mat.glossiness));
        }
        f
    };
    let mut direct = Vec3::ZERO;
    let mut e_total = 0.0;
    let mut rays = 0;
    for light in &prep.lights {
        // E = I cos θ / R², R converted to metres.
        let Some((wi, e)) = prep.light_at(light, p, n) else {
            continue;
        };
        if !surface.lit_from(wi) {
            continue;
        }
        rays += 1;
        if prep.occluded(origin, light.position - origin) {
            continue;
        }
        e_total += e;
        direct += light.tint * e * brdf(wi);
    }
    if !prep.emitters.is_empty() {
        let u_pick = rng.next_f32();
        let (u, v) = rng.next_2d();
        if let Some(s) = prep.emitters.sample(p, u_pick, u, v) {
            let cos_theta = n.dot(s.wi);
            if surface.lit_from(s.wi) && s.radiance.max_element() > 0.0 {
                rays += 1;
                if !prep.occluded(origin, s.point - origin) {
                    // dE = L cos θ dω: the sample estimates ∫ L cos θ dω over the emitters.
                    let e_rgb = s.radiance * (cos_theta / s.pdf_solid_angle);
                    e_total += crate::light::luminance(e_rgb);
                    direct += e_rgb * brdf(s.wi);
                }
            }
        }
    }
    (direct, e_total, rays)
}
