//! The scattering model of path mode, per material: a Lambertian lobe (Kd), and either a glossy
//! normalised Blinn-Phong lobe (Ks with glossiness g > 0) or a perfect mirror (Ks with g = 0).
//!
//! `f(wo, wi) = Kd / π + Ks (g + 8)/(8π) (n·h)^g` for the non-delta part, the same lobe the
//! direct mode uses for highlights; the mirror is a delta lobe of weight Ks. One lobe is chosen
//! per sample in proportion to the luminance of Kd and Ks; non-delta samples are weighted by
//! `f cos / pdf` with the mixture's full density (one-sample MIS over the lobes), so the estimate
//! stays unbiased whichever lobe was picked.

use super::prepared::PreparedMaterial;
use crate::light::luminance;
use crate::sampling::{SampleRng, cosine_hemisphere, to_world};
use glam::Vec3;
use std::f32::consts::PI;

/// A sampled incident direction.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    /// Unit direction towards where the light comes from.
    pub wi: Vec3,
    /// `f cos θ / pdf` per channel (for a delta lobe: its reflectance over its probability).
    pub weight: Vec3,
    /// Density in solid angle of the non-delta mixture at `wi` (0 for a delta sample).
    pub pdf: f32,
    /// Whether the mirror lobe was sampled (no light sampling can reach this direction).
    pub delta: bool,
}

/// A material's scattering at one surface point, with lobe selection probabilities.
#[derive(Clone, Copy, Debug)]
pub struct Bsdf {
    kd: Vec3,
    ks: Vec3,
    glossiness: f32,
    highlight_norm: f32,
    /// Probability of sampling the Lambertian lobe (else the Ks lobe).
    p_diffuse: f32,
}

impl Bsdf {
    pub fn new(m: &PreparedMaterial) -> Self {
        let kd = m.kd_over_pi * PI;
        let (yd, ys) = (luminance(kd), luminance(m.ks));
        let p_diffuse = if yd + ys > 0.0 { yd / (yd + ys) } else { 1.0 };
        Self {
            kd,
            ks: m.ks,
            glossiness: m.glossiness,
            highlight_norm: m.highlight_norm,
            p_diffuse,
        }
    }

    /// Whether the surface reflects nothing.
    pub fn is_black(&self) -> bool {
        self.kd.max_element() <= 0.0 && self.ks.max_element() <= 0.0
    }

    /// Whether light sampling can find any light this surface reflects (it has a non-delta lobe).
    pub fn has_smooth_lobe(&self) -> bool {
        self.kd.max_element() > 0.0 || (self.glossiness > 0.0 && self.ks.max_element() > 0.0)
    }

    fn is_mirror(&self) -> bool {
        self.glossiness <= 0.0
    }

    /// The non-delta part of f (1/sr) for unit `wo`, `wi` on the side of the unit normal `n`.
    pub fn eval(&self, n: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
        if n.dot(wi) <= 0.0 || n.dot(wo) <= 0.0 {
            return Vec3::ZERO;
        }
        let mut f = self.kd / PI;
        if !self.is_mirror() {
            let h = (wi + wo).normalize_or_zero();
            let n_dot_h = n.dot(h).max(0.0);
            f += self.ks * (self.highlight_norm * n_dot_h.powf(self.glossiness));
        }
        f
    }

    /// Density (1/sr) with which [`Bsdf::sample`] returns the non-delta direction `wi`.
    pub fn pdf(&self, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        let cos_i = n.dot(wi);
        if cos_i <= 0.0 || n.dot(wo) <= 0.0 {
            return 0.0;
        }
        let mut pdf = self.p_diffuse * cos_i / PI;
        if !self.is_mirror() && self.p_diffuse < 1.0 {
            let h = (wi + wo).normalize_or_zero();
            let n_dot_h = n.dot(h).max(0.0);
            let o_dot_h = wo.dot(h);
            if o_dot_h > 0.0 {
                let pdf_h = (self.glossiness + 1.0) / (2.0 * PI) * n_dot_h.powf(self.glossiness);
                pdf += (1.0 - self.p_diffuse) * pdf_h / (4.0 * o_dot_h);
            }
        }
        pdf
    }

    /// Samples an incident direction for outgoing `wo` (both unit, `n` facing `wo`). None when
    /// the sample carries no light (below the surface, or a black surface).
    pub fn sample(&self, n: Vec3, wo: Vec3, rng: &mut SampleRng) -> Option<BsdfSample> {
        if self.is_black() {
            return None;
        }
        let pick = rng.next_f32();
        let (u, v) = rng.next_2d();
        if pick >= self.p_diffuse && self.is_mirror() {
            let wi = n * (2.0 * n.dot(wo)) - wo;
            return Some(BsdfSample {
                wi,
                weight: self.ks / (1.0 - self.p_diffuse),
                pdf: 0.0,
                delta: true,
            });
        }
        let wi = if pick < self.p_diffuse {
            to_world(cosine_hemisphere(u, v), n)
        } else {
            // Half vector with density (g + 1)/(2π) (n·h)^g, reflected about it.
            let cos_h = u.powf(1.0 / (self.glossiness + 1.0));
            let sin_h = (1.0 - cos_h * cos_h).max(0.0).sqrt();
            let phi = 2.0 * PI * v;
            let h = to_world(Vec3::new(sin_h * phi.cos(), sin_h * phi.sin(), cos_h), n);
            h * (2.0 * wo.dot(h)) - wo
        };
        let cos_i = n.dot(wi);
        if cos_i <= 0.0 {
            return None;
        }
        let pdf = self.pdf(n, wo, wi);
        if pdf.is_nan() || pdf <= 0.0 {
            return None;
        }
        let f = if self.is_mirror() {
            // The mirror is not part of the smooth lobe; with a mirror the smooth part is Kd only.
            self.kd / PI
        } else {
            self.eval(n, wo, wi)
        };
        Some(BsdfSample {
            wi,
            weight: f * (cos_i / pdf),
            pdf,
            delta: false,
        })
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    fn material(kd: f32, ks: f32, g: f32) -> PreparedMaterial {
        PreparedMaterial {
            kd_over_pi: Vec3::splat(kd / PI),
            ks: Vec3::splat(ks),
            glossiness: g,
            highlight_norm: (g + 8.0) / (8.0 * PI),
            emission: Vec3::ZERO,
        }
    }

    /// The sampled weights average to the lobe's albedo ∫ f cos dω, computed here by midpoint
    /// quadrature over the hemisphere (independent of the sampling code).
    #[test]
    fn sampling_estimates_the_quadrature_albedo() {
        let n = Vec3::Z;
        for (kd, ks, g) in [
            (0.6, 0.0, 0.0),
            (0.3, 0.5, 20.0),
            (0.0, 0.8, 5.0),
            (0.2, 0.0, 1.0),
        ] {
            let bsdf = Bsdf::new(&material(kd, ks, g));
            let t: f32 = 0.6;
            let wo = Vec3::new(t.sin(), 0.0, t.cos());
            let q = 600;
            let mut albedo = 0.0f64;
            for i in 0..q {
                let th = (i as f32 + 0.5) / q as f32 * PI / 2.0;
                for j in 0..2 * q {
                    let ph = (j as f32 + 0.5) / (2 * q) as f32 * 2.0 * PI;
                    let wi = Vec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos());
                    let d_omega = th.sin() * (PI / 2.0 / q as f32) * (PI / q as f32);
                    albedo += f64::from(bsdf.eval(n, wo, wi).x * wi.z * d_omega);
                }
            }
            let m = 200_000;
            let mut sum = 0.0f64;
            for s in 0..m {
                let mut rng = SampleRng::new(11, s);
                if let Some(b) = bsdf.sample(n, wo, &mut rng) {
                    sum += f64::from(b.weight.x);
                }
            }
            let est = sum / f64::from(m);
            assert!(
                (est - albedo).abs() < 0.01 * albedo.max(0.05),
                "kd {kd} ks {ks} g {g}: sampled {est} vs quadrature {albedo}"
            );
        }
    }
}
