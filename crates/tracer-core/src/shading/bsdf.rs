//! The scattering model of the path and bidirectional integrators, per material: a Lambertian
//! lobe (Kd), either a glossy normalised Blinn-Phong lobe (Ks with glossiness g > 0) or a perfect
//! mirror (Ks with g = 0), and a smooth dielectric interface (Kt, see [`super::dielectric`]).
//!
//! `f(wo, wi) = Kd / π + Ks (g + 8)/(8π) (n·h)^g` for the non-delta part, the same lobe the
//! direct mode uses for highlights; the mirror and the glass are delta lobes. One lobe is chosen
//! per sample in proportion to the luminance of Kd, Ks and Kt; non-delta samples are weighted by
//! `f cos / pdf` with the mixture's full density (one-sample MIS over the lobes), so the estimate
//! stays unbiased whichever lobe was picked.
//!
//! A metallic-roughness material ([`MetalRough`]: GGX over a Lambertian base, glTF 2.0) is
//! one smooth lobe instead, evaluated and sampled in the normal's frame. A thin pane
//! ([`Pane`]) is its mirror lobe R(θ) here; what it lets through, T(θ), the walks pass along
//! their rays.
//!
//! The non-delta part is symmetric in (wo, wi), so light paths use the same `eval` and `pdf`.
//! Refraction is not symmetric: camera paths (radiance) scale a refracted sample by
//! (η_wo / η_wi)², light paths (importance, [`Bsdf::at`]) do not.

use super::dielectric::{fresnel, refract};
use super::material::PreparedMaterial;
use super::{MetalRough, MetalRoughSample, Pane};
use crate::light::luminance;
use crate::sampling::{SampleRng, cosine_hemisphere, frame_from_normal, to_world};
use glam::Vec3;
use std::f32::consts::PI;

/// A sampled incident direction.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    /// Unit direction towards where the light comes from (for light paths: where it goes).
    pub wi: Vec3,
    /// `f cos θ / pdf` per channel (for a delta lobe: its weight over its probability).
    pub weight: Vec3,
    /// Density in solid angle of the non-delta mixture at `wi` (0 for a delta sample).
    pub pdf: f32,
    /// Whether a delta lobe (mirror, glass) was sampled: no light sampling can reach `wi`.
    pub delta: bool,
}

/// A material's scattering at one surface point: the coursework's lobes or metallic-roughness.
/// An enum, so that a vertex holding one stays as small as the larger model.
#[derive(Clone, Copy, Debug)]
pub enum Bsdf {
    Classic(Classic),
    MetalRough(MetalRough),
    Pane(Pane),
}

/// Lambert, Blinn-Phong or mirror, and glass, with lobe selection probabilities.
#[derive(Clone, Copy, Debug)]
pub struct Classic {
    kd: Vec3,
    ks: Vec3,
    kt: Vec3,
    glossiness: f32,
    highlight_norm: f32,
    /// Probability of picking the diffuse lobe, and the diffuse or the Ks lobe.
    p_diffuse: f32,
    p_reflective: f32,
    /// Refractive index behind the surface over the one in front (the side of `wo`).
    eta: f32,
    /// Light paths (importance): no (η_wo / η_wi)² on refraction.
    importance: bool,
}

/// Unit `n`'s frame: `w` in it, and back.
#[inline]
fn local(n: Vec3, w: Vec3) -> Vec3 {
    let (t, b) = frame_from_normal(n);
    Vec3::new(w.dot(t), w.dot(b), w.dot(n))
}

impl Bsdf {
    /// The scattering of `m` seen from outside (from the front face, or `m` has no glass).
    pub fn new(m: &PreparedMaterial) -> Self {
        Self::at(m, false, false)
    }

    /// The scattering of `m` seen from inside its glass (from behind the front face) when
    /// `inside`, for light paths (importance transport) when `importance`. Built in place:
    /// bdpt builds one per vertex.
    #[inline]
    pub fn at(m: &PreparedMaterial, inside: bool, importance: bool) -> Self {
        if let Some(pane) = m.pane {
            // A pane does not deviate what it lets through: nothing to scale.
            return Bsdf::Pane(pane);
        }
        match m.pbr {
            // Metallic-roughness is symmetric and has no refraction.
            Some(pbr) => Bsdf::MetalRough(pbr),
            None => Bsdf::Classic(Classic::at(m, inside, importance)),
        }
    }

    pub fn is_black(&self) -> bool {
        match self {
            Bsdf::Classic(c) => c.is_black(),
            Bsdf::MetalRough(_) | Bsdf::Pane(_) => false,
        }
    }

    /// Whether any lobe is not a delta (light sampling pays off).
    pub fn has_smooth_lobe(&self) -> bool {
        match self {
            Bsdf::Classic(c) => c.has_smooth_lobe(),
            Bsdf::MetalRough(_) => true,
            Bsdf::Pane(_) => false,
        }
    }

    /// The non-delta BRDF value for unit `wo`, `wi` (both on the side of unit normal `n`).
    #[inline]
    pub fn eval(&self, n: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
        match self {
            Bsdf::Classic(c) => c.eval(n, wo, wi),
            Bsdf::MetalRough(m) => metal_rough_eval(m, n, wo, wi),
            Bsdf::Pane(_) => Vec3::ZERO,
        }
    }

    /// Density (per steradian) with which [`Bsdf::sample`] picks `wi` through a non-delta lobe.
    #[inline]
    pub fn pdf(&self, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        match self {
            Bsdf::Classic(c) => c.pdf(n, wo, wi),
            Bsdf::MetalRough(m) => metal_rough_pdf(m, n, wo, wi),
            Bsdf::Pane(_) => 0.0,
        }
    }

    /// Samples an incident direction for the outgoing unit `wo`, with `n` facing `wo`.
    pub fn sample(&self, n: Vec3, wo: Vec3, rng: &mut SampleRng) -> Option<BsdfSample> {
        match self {
            Bsdf::Classic(c) => c.sample(n, wo, rng),
            Bsdf::MetalRough(m) => metal_rough_sample(m, n, wo, rng),
            Bsdf::Pane(p) => pane_sample(p, n, wo),
        }
    }
}

/// The mirror direction with the pane's reflectance R(θ). What a pane lets through is not
/// scattered here: the walks pass it along their rays
/// (`crate::lit_scene::LitScene::closest_through_panes`), and shadow rays through it
/// (`LitScene::transmittance`).
#[inline(never)]
#[cold]
fn pane_sample(p: &Pane, n: Vec3, wo: Vec3) -> Option<BsdfSample> {
    let cos_o = n.dot(wo);
    let (_, r) = p.transmit_reflect(cos_o);
    (r > 0.0).then(|| BsdfSample {
        wi: n * (2.0 * cos_o) - wo,
        weight: Vec3::splat(r),
        pdf: 0.0,
        delta: true,
    })
}

// The metallic-roughness arms stay out of line and cold, so the classic lobes' hot loops keep
// their size. The bidirectional integrators go further: scenes without this model run on
// `Classic` alone (`super::scatter`).

#[inline(never)]
#[cold]
fn metal_rough_eval(m: &MetalRough, n: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
    if n.dot(wi) <= 0.0 || n.dot(wo) <= 0.0 {
        return Vec3::ZERO;
    }
    m.eval(local(n, wo), local(n, wi))
}

#[inline(never)]
#[cold]
fn metal_rough_pdf(m: &MetalRough, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
    if n.dot(wi) <= 0.0 || n.dot(wo) <= 0.0 {
        return 0.0;
    }
    m.pdf(local(n, wo), local(n, wi))
}

#[inline(never)]
#[cold]
fn metal_rough_sample(
    m: &MetalRough,
    n: Vec3,
    wo: Vec3,
    rng: &mut SampleRng,
) -> Option<BsdfSample> {
    let pick = rng.next_f32();
    let (u, v) = rng.next_2d();
    let (t, b) = frame_from_normal(n);
    let lo = Vec3::new(wo.dot(t), wo.dot(b), wo.dot(n));
    Some(match m.sample(lo, pick, [u, v])? {
        MetalRoughSample::Reflected { wi: li, f, pdf } => BsdfSample {
            wi: t * li.x + b * li.y + n * li.z,
            weight: f * (li.z / pdf),
            pdf,
            delta: false,
        },
        MetalRoughSample::Through(weight) => BsdfSample {
            wi: -wo,
            weight,
            pdf: 0.0,
            delta: true,
        },
    })
}

impl Classic {
    /// The lobes of `m`, seen from inside its glass when `inside`, for light paths when
    /// `importance`.
    #[inline]
    pub fn at(m: &PreparedMaterial, inside: bool, importance: bool) -> Self {
        let kd = m.kd_over_pi * PI;
        let (yd, ys, yt) = (luminance(kd), luminance(m.ks), luminance(m.kt));
        let total = yd + ys + yt;
        let (p_diffuse, p_reflective) = if total > 0.0 {
            (yd / total, (yd + ys) / total)
        } else {
            (1.0, 1.0)
        };
        Self {
            kd,
            ks: m.ks,
            kt: m.kt,
            glossiness: m.glossiness,
            highlight_norm: m.highlight_norm,
            p_diffuse,
            p_reflective,
            eta: if inside { 1.0 / m.ior } else { m.ior },
            importance,
        }
    }

    pub fn is_black(&self) -> bool {
        self.kd.max_element() <= 0.0 && self.ks.max_element() <= 0.0 && self.kt.max_element() <= 0.0
    }

    /// Whether any lobe is not a delta (light sampling pays off).
    pub fn has_smooth_lobe(&self) -> bool {
        self.kd.max_element() > 0.0 || (self.glossiness > 0.0 && self.ks.max_element() > 0.0)
    }

    fn is_mirror(&self) -> bool {
        self.glossiness <= 0.0
    }

    /// The non-delta BRDF value for unit `wo`, `wi` (both on the side of unit normal `n`).
    #[inline]
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

    /// Density (per steradian) with which [`Classic::sample`] picks `wi` through a non-delta
    /// lobe.
    #[inline]
    pub fn pdf(&self, n: Vec3, wo: Vec3, wi: Vec3) -> f32 {
        let cos_i = n.dot(wi);
        if cos_i <= 0.0 || n.dot(wo) <= 0.0 {
            return 0.0;
        }
        let mut pdf = self.p_diffuse * cos_i / PI;
        let p_glossy = self.p_reflective - self.p_diffuse;
        if !self.is_mirror() && p_glossy > 0.0 {
            let h = (wi + wo).normalize_or_zero();
            let n_dot_h = n.dot(h).max(0.0);
            let o_dot_h = wo.dot(h);
            if o_dot_h > 0.0 {
                let pdf_h = (self.glossiness + 1.0) / (2.0 * PI) * n_dot_h.powf(self.glossiness);
                pdf += p_glossy * pdf_h / (4.0 * o_dot_h);
            }
        }
        pdf
    }

    /// Samples an incident direction for the outgoing unit `wo`, with `n` facing `wo`.
    pub fn sample(&self, n: Vec3, wo: Vec3, rng: &mut SampleRng) -> Option<BsdfSample> {
        if self.is_black() {
            return None;
        }
        let pick = rng.next_f32();
        let (u, v) = rng.next_2d();
        if pick >= self.p_reflective {
            return self.sample_glass(n, wo, u);
        }
        let p_ks = self.p_reflective - self.p_diffuse;
        if pick >= self.p_diffuse && self.is_mirror() {
            let wi = n * (2.0 * n.dot(wo)) - wo;
            return Some(BsdfSample {
                wi,
                weight: self.ks / p_ks,
                pdf: 0.0,
                delta: true,
            });
        }
        let wi = if pick < self.p_diffuse {
            to_world(cosine_hemisphere(u, v), n)
        } else {
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
        // With a mirror Ks the only non-delta lobe is the diffuse one.
        let f = if self.is_mirror() {
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

    /// The glass lobe: reflection with probability R(θ), else refraction.
    fn sample_glass(&self, n: Vec3, wo: Vec3, u: f32) -> Option<BsdfSample> {
        let p_glass = 1.0 - self.p_reflective;
        if p_glass <= 0.0 {
            return None;
        }
        let cos_o = n.dot(wo);
        let r = fresnel(cos_o, self.eta);
        let weight = self.kt / p_glass;
        if u < r {
            return Some(BsdfSample {
                wi: n * (2.0 * cos_o) - wo,
                weight,
                pdf: 0.0,
                delta: true,
            });
        }
        let wi = refract(wo, n, self.eta)?;
        let scale = if self.importance {
            1.0
        } else {
            1.0 / (self.eta * self.eta)
        };
        Some(BsdfSample {
            wi,
            weight: weight * scale,
            pdf: 0.0,
            delta: true,
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
            kt: Vec3::ZERO,
            ior: 1.5,
            emission: Vec3::ZERO,
            pbr: None,
            pane: None,
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
