//! glTF 2.0's metallic-roughness material (the specification's Appendix B), in the local frame
//! where the normal is +Z:
//!
//! - specular_brdf = D · G2 / (4 |n·ωo| |n·ωi|), GGX with α = roughness² ([`Ggx`]);
//! - dielectric = fresnel_mix(F0, base = c / π, layer = specular_brdf), with
//!   F = F0 + (1 − F0)(1 − |ωo·h|)⁵ and F0 = ((1 − ior) / (1 + ior))² (0.04 at ior 1.5);
//! - metal = conductor_fresnel(c, specular_brdf), its F0 the base colour c;
//! - f = mix(dielectric, metal, metallic).
//!
//! `KHR_materials_transmission` (factor T) replaces the dielectric's diffuse base by a
//! transmission of the base colour: thin-walled, as glTF defines it without
//! `KHR_materials_volume`, so the light goes on in its own direction (a delta lobe), weighed by
//! T (1 − metallic) (1 − F(n·ωo)) c. The rough transmission lobe of the extension is drawn
//! smooth (noted by the glTF reader).
//!
//! Sampled as a mixture of a cosine lobe and GGX's visible normals, each chosen with a
//! probability from ωo alone, weighted by the mixture's full density (one-sample MIS); the
//! transmission, when present, is picked first with its own probability from ωo.

use super::microfacet::Ggx;
use crate::light::luminance;
use crate::sampling::cosine_hemisphere;
use glam::Vec3;
use std::f32::consts::PI;

/// A metallic-roughness surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetalRough {
    pub base_color: Vec3,
    pub metallic: f32,
    pub ggx: Ggx,
    /// The dielectric layer's reflectance at normal incidence.
    pub f0: f32,
    /// glTF's transmission factor T (thin-walled, onto the dielectric).
    pub transmission: f32,
    /// Roughness 0: the specular layer is a mirror (direct mode follows it as one).
    pub smooth: bool,
}

/// F0 of a dielectric of refractive index `ior` in air.
pub fn dielectric_f0(ior: f32) -> f32 {
    let r = (1.0 - ior) / (1.0 + ior);
    r * r
}

/// Schlick's weight (1 − cos)⁵.
#[inline]
fn schlick(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

impl MetalRough {
    pub fn new(base_color: Vec3, metallic: f32, roughness: f32, ior: f32) -> Self {
        Self {
            base_color: base_color.clamp(Vec3::ZERO, Vec3::ONE),
            metallic: metallic.clamp(0.0, 1.0),
            ggx: Ggx::from_roughness(roughness),
            f0: dielectric_f0(ior.max(1.0)),
            transmission: 0.0,
            smooth: roughness <= 0.0,
        }
    }

    /// The same surface with glTF's transmission factor `t` (0..=1).
    pub fn with_transmission(mut self, t: f32) -> Self {
        self.transmission = t.clamp(0.0, 1.0);
        self
    }

    /// The dielectric layer's Fresnel reflectance for cos θ = |ωo·h|.
    #[inline]
    fn fresnel_dielectric(&self, cos: f32) -> f32 {
        self.f0 + (1.0 - self.f0) * schlick(cos)
    }

    /// Weight of the diffuse base of the dielectric per channel: c (1 − T).
    #[inline]
    fn base(&self) -> Vec3 {
        self.base_color * (1.0 - self.transmission)
    }

    /// The diffuse base's BRDF alone, c (1 − T) / π (1 − F(|ωo·h|)) (1 − metallic): what direct
    /// mode evaluates for its lights on a smooth surface, whose specular layer it follows as a
    /// mirror.
    pub fn eval_base(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        let h = (wo + wi).normalize_or_zero();
        self.base() / PI
            * ((1.0 - self.fresnel_dielectric(wo.dot(h).abs())) * (1.0 - self.metallic))
    }

    /// Reflectance of the smooth specular layer at cos θo (its mirror weight per channel).
    pub fn mirror_reflectance(&self, cos_o: f32) -> Vec3 {
        let w = schlick(cos_o);
        let metal = self.base_color + (Vec3::ONE - self.base_color) * w;
        Vec3::splat(self.fresnel_dielectric(cos_o)) * (1.0 - self.metallic) + metal * self.metallic
    }

    /// The thin-walled transmission's weight per channel for ωo (zero without transmission).
    #[inline]
    pub fn transmittance(&self, cos_o: f32) -> Vec3 {
        if self.transmission <= 0.0 {
            return Vec3::ZERO;
        }
        self.base_color
            * (self.transmission * (1.0 - self.metallic) * (1.0 - self.fresnel_dielectric(cos_o)))
    }

    /// Probability of picking the transmission for ωo (0 without it).
    #[inline]
    fn transmission_probability(&self, wo: Vec3) -> f32 {
        let t = luminance(self.transmittance(wo.z));
        if t <= 0.0 {
            return 0.0;
        }
        let reflected = luminance(self.mirror_reflectance(wo.z))
            + luminance(self.base()) * (1.0 - self.metallic);
        (t / (t + reflected)).clamp(0.0, 1.0)
    }

    /// f(ωo, ωi) per channel for unit local directions (0 unless both are above the surface).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        let h = (wo + wi).normalize_or_zero();
        let vh = wo.dot(h).abs();
        let specular = self.ggx.d(h) * self.ggx.g2(wo, wi) / (4.0 * wo.z * wi.z);
        let w = schlick(vh);
        let f_dielectric = self.f0 + (1.0 - self.f0) * w;
        let dielectric =
            self.base() / PI * (1.0 - f_dielectric) + Vec3::splat(specular * f_dielectric);
        let f_metal = self.base_color + (Vec3::ONE - self.base_color) * w;
        let metal = f_metal * specular;
        dielectric * (1.0 - self.metallic) + metal * self.metallic
    }

    /// Probability of sampling the specular lobe for `wo`: its Fresnel weight at ωo against
    /// the diffuse base's.
    #[inline]
    fn specular_probability(&self, wo: Vec3) -> f32 {
        let w = schlick(wo.z);
        let f0 = Vec3::splat(self.f0) * (1.0 - self.metallic) + self.base_color * self.metallic;
        let specular = luminance(f0 + (Vec3::ONE - f0) * w);
        let diffuse = (1.0 - self.metallic)
            * luminance(self.base())
            * (1.0 - (self.f0 + (1.0 - self.f0) * w));
        if specular + diffuse > 0.0 {
            (specular / (specular + diffuse)).clamp(0.0, 1.0)
        } else {
            1.0
        }
    }

    /// Density (per sr) with which [`MetalRough::sample`] picks `wi` through its smooth lobes.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let p = self.specular_probability(wo);
        let smooth = 1.0 - self.transmission_probability(wo);
        smooth * (p * self.ggx.reflection_pdf(wo, wi) + (1.0 - p) * wi.z / PI)
    }

    /// An incident direction for `wo` from `pick` and `u`; None below the surface.
    pub fn sample(&self, wo: Vec3, pick: f32, u: [f32; 2]) -> Option<MetalRoughSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let p_t = self.transmission_probability(wo);
        if pick < p_t {
            // Thin-walled transmission: on in the same direction, through the surface.
            return Some(MetalRoughSample::Through(self.transmittance(wo.z) / p_t));
        }
        let pick = (pick - p_t) / (1.0 - p_t);
        let wi = if pick < self.specular_probability(wo) {
            let h = self.ggx.sample_visible_normal(wo, u);
            h * (2.0 * wo.dot(h)) - wo
        } else {
            cosine_hemisphere(u[0], u[1])
        };
        if wi.z <= 0.0 {
            return None;
        }
        let pdf = self.pdf(wo, wi);
        (pdf.is_finite() && pdf > 0.0).then(|| MetalRoughSample::Reflected {
            wi,
            f: self.eval(wo, wi),
            pdf,
        })
    }
}

/// What [`MetalRough::sample`] chose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MetalRoughSample {
    /// A reflected direction with f and the smooth lobes' density.
    Reflected { wi: Vec3, f: Vec3, pdf: f32 },
    /// The delta transmission (ωi = −ωo), with its weight over its probability.
    Through(Vec3),
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;
    use crate::sampling::SampleRng;
    use std::f64::consts::PI as PI64;

    fn dir(theta: f64, phi: f64) -> [f64; 3] {
        [
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        ]
    }

    fn v(w: [f64; 3]) -> Vec3 {
        Vec3::new(w[0] as f32, w[1] as f32, w[2] as f32)
    }

    /// Midpoint quadrature of `f(ωi)` over the upper hemisphere, `q` steps in θ.
    fn over_hemisphere(q: usize, f: impl Fn([f64; 3]) -> f64) -> f64 {
        let (dt, dp) = (0.5 * PI64 / q as f64, PI64 / q as f64);
        let mut sum = 0.0;
        for i in 0..q {
            let t = (i as f64 + 0.5) * dt;
            for j in 0..2 * q {
                sum += f(dir(t, (j as f64 + 0.5) * dp)) * t.sin() * dt * dp;
            }
        }
        sum
    }

    /// Directional albedo A(θo) = ∫ f cos θi dωi by quadrature of `eval` (the sampler must
    /// agree with it: the renders check `eval` against the formulas).
    fn albedo(m: &MetalRough, theta_o: f64) -> f64 {
        let wo = v(dir(theta_o, 0.0));
        over_hemisphere(500, |wi| f64::from(m.eval(wo, v(wi)).y) * wi[2])
    }

    /// f is reciprocal, and the sampled weights average to the quadrature albedo, for a rough
    /// metal (F0 = 1) and a rough dielectric.
    #[test]
    fn sampling_estimates_the_quadrature_albedo_and_f_is_reciprocal() {
        for roughness in [0.3f32, 0.6, 1.0] {
            for (base, metallic) in [(Vec3::ONE, 1.0f32), (Vec3::new(0.8, 0.5, 0.2), 0.0)] {
                let m = MetalRough::new(base, metallic, roughness, 1.5);
                for (to, ti, dphi) in [(0.3, 0.9, 2.0), (1.2, 0.2, 0.5), (0.0, 1.3, 1.0)] {
                    let (a, b) = (v(dir(to, 0.0)), v(dir(ti, dphi)));
                    let (f, back) = (m.eval(a, b), m.eval(b, a));
                    for k in 0..3 {
                        assert!((f[k] / back[k] - 1.0).abs() < 1e-4, "not reciprocal");
                    }
                }
                for theta in [0.0f64, 0.8, 1.3] {
                    let exact = albedo(&m, theta);
                    let wo = v(dir(theta, 0.0));
                    let n = 400_000u32;
                    let mut sum = 0.0f64;
                    for k in 0..n {
                        let mut rng = SampleRng::new(9, k);
                        let pick = rng.next_f32();
                        let (a, b) = rng.next_2d();
                        if let Some(MetalRoughSample::Reflected { wi, f, pdf }) =
                            m.sample(wo, pick, [a, b])
                        {
                            sum += f64::from(f.y * wi.z / pdf);
                        }
                    }
                    let est = sum / f64::from(n);
                    assert!(
                        (est / exact - 1.0).abs() < 0.01,
                        "roughness {roughness} metallic {metallic} θ {theta}: sampled {est} vs \
                         quadrature {exact}"
                    );
                }
            }
        }
    }

    /// The density integrates to 1 over the hemisphere (with what leaves it, which the
    /// sampler discards, at most the GGX lobe's share below the horizon).
    #[test]
    fn the_density_integrates_to_at_most_one() {
        let m = MetalRough::new(Vec3::splat(0.5), 0.5, 0.5, 1.5);
        let wo = v(dir(0.6, 0.0));
        let sum = over_hemisphere(600, |wi| f64::from(m.pdf(wo, v(wi))));
        assert!(sum <= 1.0 + 2e-3 && sum > 0.95, "{sum}");
    }
}
