//! The denoiser's guide images: per pixel, the albedo and the shading normal of the first
//! surface a camera sample meets that is not a perfect mirror or glass (mirrors and glass are
//! followed, their reflectance or transmittance multiplied in, as Open Image Denoise expects).
//!
//! Guides are summed like the film ([`super::Film`]): each sample's values rounded once to
//! fixed point (2⁻²⁴) and added as integers, so they are the same for any thread count and add
//! exactly across shards. A pixel's guide sum is 56 bytes, kept only while denoising.

use super::fixed_point::round_half_away;
use crate::bvh::Hit;
use crate::geometry::Ray;
use crate::lit_scene::LitScene;
use crate::sampling::SampleRng;
use crate::shading::{Surface, bsdf_at};
use glam::Vec3;

/// Fixed-point units per unit of albedo or normal component (2^24): one sample adds at most
/// 2^24, so 2^39 samples fit in an i64.
pub const GUIDE_SCALE: f64 = 16_777_216.0;

/// Mirrors and glass followed before a guide gives up (and records what it has).
const MAX_DELTA_BOUNCES: u32 = 8;

/// One sample's guide values.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Guide {
    /// Reflectance (0-1 per channel) of the first diffuse or glossy surface, times the mirrors'
    /// and glass's on the way; 0 where the camera sees nothing.
    pub albedo: Vec3,
    /// Unit shading normal (world space) at that surface; 0 where the camera sees nothing.
    pub normal: Vec3,
}

/// The exact sum of some samples' guides of one pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Zeroable)]
pub struct GuideSum {
    pub albedo: [i64; 3],
    pub normal: [i64; 3],
    pub count: u32,
}

#[inline]
fn fixed(v: f32) -> i64 {
    // |v| <= 1 by construction (clamped below): far inside round_half_away's range.
    round_half_away(f64::from(v.clamp(-1.0, 1.0)) * GUIDE_SCALE)
}

impl GuideSum {
    pub fn add(&mut self, g: &Guide) {
        for k in 0..3 {
            self.albedo[k] = self.albedo[k].saturating_add(fixed(g.albedo[k]));
            self.normal[k] = self.normal[k].saturating_add(fixed(g.normal[k]));
        }
        self.count = self.count.saturating_add(1);
    }

    pub fn merge(&mut self, other: &GuideSum) {
        for k in 0..3 {
            self.albedo[k] = self.albedo[k].saturating_add(other.albedo[k]);
            self.normal[k] = self.normal[k].saturating_add(other.normal[k]);
        }
        self.count = self.count.saturating_add(other.count);
    }

    fn mean(sum: &[i64; 3], count: u32) -> Vec3 {
        if count == 0 {
            return Vec3::ZERO;
        }
        let n = f64::from(count) * GUIDE_SCALE;
        Vec3::new(
            (sum[0] as f64 / n) as f32,
            (sum[1] as f64 / n) as f32,
            (sum[2] as f64 / n) as f32,
        )
    }

    pub fn mean_albedo(&self) -> Vec3 {
        Self::mean(&self.albedo, self.count)
    }

    /// The mean of the samples' unit normals (shorter than 1 where they disagree: OIDN takes
    /// it as it is).
    pub fn mean_normal(&self) -> Vec3 {
        Self::mean(&self.normal, self.count)
    }
}

/// Guide sums of a whole image, row-major.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GuideFilm {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<GuideSum>,
}

impl GuideFilm {
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: crate::pages::zeroed_vec_on_huge_pages(width as usize * height as usize),
        }
    }

    /// Adds another guide film of the same image (sizes are checked by the film that owns it).
    pub fn merge(&mut self, other: &GuideFilm) {
        for (a, b) in self.pixels.iter_mut().zip(&other.pixels) {
            a.merge(b);
        }
    }

    /// The albedo image (0-1 per channel).
    pub fn albedo_image(&self) -> Vec<Vec3> {
        self.pixels.iter().map(GuideSum::mean_albedo).collect()
    }

    /// The normal image (components -1 to 1).
    pub fn normal_image(&self) -> Vec<Vec3> {
        self.pixels.iter().map(GuideSum::mean_normal).collect()
    }
}

/// The guide of a camera ray: mirrors and glass are followed (one lobe picked at random, as
/// the integrators do) to the first diffuse or glossy surface.
pub fn trace_guide(lit: &LitScene<'_>, ray: &Ray, rng: &mut SampleRng) -> Guide {
    let mut ray = *ray;
    let mut throughput = Vec3::ONE;
    for _ in 0..=MAX_DELTA_BOUNCES {
        let Some(hit) = lit.closest_visible(&ray) else {
            return Guide::default();
        };
        let (surface, wo) = frame(lit, &hit, &ray);
        let bary = [hit.u, hit.v];
        let bsdf = bsdf_at(lit, hit.prim, bary, wo, false);
        let mat = lit.material_at(hit.prim, bary);
        let guide = |albedo: Vec3| Guide {
            albedo: (throughput * albedo).clamp(Vec3::ZERO, Vec3::ONE),
            normal: surface.ns,
        };
        if bsdf.has_smooth_lobe() || bsdf.is_black() {
            let glossy = if mat.glossiness > 0.0 {
                mat.ks
            } else {
                Vec3::ZERO
            };
            // A metallic-roughness surface: its base colour (glTF's albedo).
            let reflectance = match &mat.pbr {
                Some(pbr) => pbr.base_color,
                None => mat.kd_over_pi * std::f32::consts::PI + glossy,
            };
            // A surface that only glows is its own colour to the denoiser: white.
            let albedo = if reflectance.max_element() <= 0.0 && mat.emission.max_element() > 0.0 {
                Vec3::ONE
            } else {
                reflectance
            };
            return guide(albedo);
        }
        let Some(s) = bsdf.sample(surface.ns, wo, rng) else {
            return guide(Vec3::ZERO);
        };
        throughput = (throughput * s.weight).min(Vec3::ONE);
        ray = Ray::new(surface.origin_towards(s.wi, lit.epsilon), s.wi);
    }
    Guide {
        albedo: Vec3::ZERO,
        normal: Vec3::ZERO,
    }
}

fn frame(lit: &LitScene<'_>, hit: &Hit, ray: &Ray) -> (Surface, Vec3) {
    let dir = ray.dir.normalize();
    let p = ray.at(hit.t);
    (Surface::at(lit, hit, p, dir), -dir)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn guide_sums_are_exact_and_order_free() {
        let guides = [
            Guide {
                albedo: Vec3::new(0.7, 0.1, 0.33),
                normal: Vec3::new(0.0, 1.0, 0.0),
            },
            Guide {
                albedo: Vec3::new(0.2, 0.9, 0.0),
                normal: Vec3::new(0.6, -0.8, 0.0),
            },
            Guide::default(),
        ];
        let mut forward = GuideSum::default();
        guides.iter().for_each(|g| forward.add(g));
        let mut split = GuideSum::default();
        let mut rest = GuideSum::default();
        split.add(&guides[2]);
        rest.add(&guides[1]);
        rest.add(&guides[0]);
        split.merge(&rest);
        assert_eq!(forward, split);
        let a = forward.mean_albedo();
        assert!(
            (a - Vec3::new(0.3, 1.0 / 3.0, 0.11)).abs().max_element() < 1e-6,
            "{a}"
        );
        let n = forward.mean_normal();
        assert!(
            (n - Vec3::new(0.2, 0.2 / 3.0, 0.0)).abs().max_element() < 1e-6,
            "{n}"
        );
        assert_eq!(GuideSum::default().mean_albedo(), Vec3::ZERO);
    }
}
