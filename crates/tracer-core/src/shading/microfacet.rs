//! The GGX (Trowbridge-Reitz) microfacet distribution, isotropic, with height-correlated Smith
//! masking-shadowing, sampled by its distribution of visible normals (Heitz 2018, "Sampling the
//! GGX Distribution of Visible Normals"). Written from the formulas, in the local frame where the
//! macro-surface normal is +Z.
//!
//! - D(h) = α² / (π ((h·n)² (α² − 1) + 1)²)
//! - Λ(ω) = (−1 + √(1 + α² tan² θ)) / 2, G1(ω) = 1 / (1 + Λ(ω))
//! - G2(ωo, ωi) = 1 / (1 + Λ(ωo) + Λ(ωi)) (height-correlated)
//! - visible normals: D_ωo(h) = G1(ωo) max(0, ωo·h) D(h) / (ωo·n)

use glam::Vec3;
use std::f32::consts::PI;

/// The smallest α: below it the lobe is too narrow for 32-bit floats (roughness ≈ 0.03).
pub const MIN_ALPHA: f32 = 1.0e-3;

/// An isotropic GGX distribution of roughness α (glTF's roughness squared).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx {
    pub alpha: f32,
}

impl Ggx {
    /// The distribution of glTF's perceptual `roughness` (α = roughness², at least
    /// [`MIN_ALPHA`]).
    pub fn from_roughness(roughness: f32) -> Self {
        let r = if roughness.is_finite() {
            roughness.clamp(0.0, 1.0)
        } else {
            1.0
        };
        Self {
            alpha: (r * r).max(MIN_ALPHA),
        }
    }

    /// D(h) for the unit local micro-normal `h` (per sr of micro-normals, projected).
    #[inline]
    pub fn d(&self, h: Vec3) -> f32 {
        if h.z <= 0.0 {
            return 0.0;
        }
        let a2 = self.alpha * self.alpha;
        let t = h.z * h.z * (a2 - 1.0) + 1.0;
        a2 / (PI * t * t)
    }

    /// Smith's Λ(ω) for the unit local direction `w`.
    #[inline]
    pub fn lambda(&self, w: Vec3) -> f32 {
        let cos2 = w.z * w.z;
        if cos2 <= 0.0 {
            return f32::INFINITY;
        }
        let tan2 = ((1.0 - cos2) / cos2).max(0.0);
        (-1.0 + (1.0 + self.alpha * self.alpha * tan2).sqrt()) * 0.5
    }

    /// G1(ω): the share of micro-normals visible from `w`.
    #[inline]
    pub fn g1(&self, w: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Height-correlated G2(ωo, ωi).
    #[inline]
    pub fn g2(&self, wo: Vec3, wi: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// A micro-normal visible from unit local `wo` (wo.z > 0), from `u` in [0, 1)².
    pub fn sample_visible_normal(&self, wo: Vec3, u: [f32; 2]) -> Vec3 {
        let a = self.alpha;
        // The view direction in the hemisphere configuration (α = 1).
        let v = Vec3::new(a * wo.x, a * wo.y, wo.z).normalize();
        let len2 = v.x * v.x + v.y * v.y;
        let t1 = if len2 > 0.0 {
            Vec3::new(-v.y, v.x, 0.0) / len2.sqrt()
        } else {
            Vec3::X
        };
        let t2 = v.cross(t1);
        // A point on the projected disc, its far half squeezed by the view's tilt.
        let r = u[0].sqrt();
        let phi = 2.0 * PI * u[1];
        let p1 = r * phi.cos();
        let s = 0.5 * (1.0 + v.z);
        let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
        let nh = t1 * p1 + t2 * p2 + v * (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
        // Back to the ellipsoid configuration.
        Vec3::new(a * nh.x, a * nh.y, nh.z.max(1e-7)).normalize()
    }

    /// Density (per sr of micro-normals) of [`Ggx::sample_visible_normal`] at `h`.
    #[inline]
    pub fn visible_normal_pdf(&self, wo: Vec3, h: Vec3) -> f32 {
        if wo.z <= 0.0 {
            return 0.0;
        }
        self.g1(wo) * wo.dot(h).max(0.0) * self.d(h) / wo.z
    }

    /// Density (per sr) of the reflected direction `wi` when the micro-normal is sampled from
    /// `wo` by [`Ggx::sample_visible_normal`]: D_ωo(h) / (4 ωo·h) = G1(ωo) D(h) / (4 ωo·n).
    #[inline]
    pub fn reflection_pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let h = (wo + wi).normalize_or_zero();
        self.g1(wo) * self.d(h) / (4.0 * wo.z)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    /// The midpoint rule's directions over the upper hemisphere, `q` steps in θ, each with
    /// its solid angle.
    fn each_direction(q: usize, mut f: impl FnMut(Vec3, f64)) {
        let (dt, dp) = (
            0.5 * std::f64::consts::PI / q as f64,
            std::f64::consts::PI / q as f64,
        );
        for i in 0..q {
            let t = (i as f64 + 0.5) * dt;
            for j in 0..2 * q {
                let p = (j as f64 + 0.5) * dp;
                let w = Vec3::new(
                    (t.sin() * p.cos()) as f32,
                    (t.sin() * p.sin()) as f32,
                    t.cos() as f32,
                );
                f(w, t.sin() * dt * dp);
            }
        }
    }

    /// Midpoint quadrature of `f(ω)` over the upper hemisphere.
    fn hemisphere(q: usize, mut f: impl FnMut(Vec3) -> f64) -> f64 {
        let mut sum = 0.0;
        each_direction(q, |w, d_omega| sum += f(w) * d_omega);
        sum
    }

    /// ∫ D(h) (h·n) dh = 1, and the visible normals integrate to 1 from every direction.
    #[test]
    fn distributions_are_normalised() {
        for roughness in [0.3f32, 0.6, 1.0] {
            let ggx = Ggx::from_roughness(roughness);
            let projected = hemisphere(800, |h| f64::from(ggx.d(h) * h.z));
            assert!(
                (projected - 1.0).abs() < 2e-3,
                "α {}: {projected}",
                ggx.alpha
            );
            for theta in [0.0f32, 0.7, 1.3] {
                let wo = Vec3::new(theta.sin(), 0.0, theta.cos());
                let visible = hemisphere(800, |h| f64::from(ggx.visible_normal_pdf(wo, h)));
                assert!(
                    (visible - 1.0).abs() < 3e-3,
                    "α {} θ {theta}: {visible}",
                    ggx.alpha
                );
            }
        }
    }

    /// Sampled visible normals follow their density: a histogram over cells of cos θ × φ against
    /// the density's integral over each cell (a χ² test, 10 x 20 cells).
    #[test]
    fn visible_normal_samples_pass_a_chi_square_test() {
        for (roughness, theta) in [(0.3f32, 0.4f32), (0.6, 1.1), (1.0, 0.0), (0.45, 1.4)] {
            let ggx = Ggx::from_roughness(roughness);
            let wo = Vec3::new(theta.sin(), 0.0, theta.cos());
            let (nt, np) = (10usize, 20usize);
            let cell = |h: Vec3| {
                let ct = ((1.0 - h.z.clamp(0.0, 1.0)) * nt as f32).min(nt as f32 - 1.0) as usize;
                let phi = h.y.atan2(h.x).rem_euclid(2.0 * PI);
                let cp = (phi / (2.0 * PI) * np as f32).min(np as f32 - 1.0) as usize;
                ct * np + cp
            };
            let n = 200_000u32;
            let mut observed = vec![0.0f64; nt * np];
            for k in 0..n {
                let mut rng = crate::sampling::SampleRng::new(5, k);
                let (a, b) = rng.next_2d();
                observed[cell(ggx.sample_visible_normal(wo, [a, b]))] += 1.0;
            }
            // Expected counts: the density integrated over each cell, fine quadrature.
            let mut expected = vec![0.0f64; nt * np];
            each_direction(1200, |h, d_omega| {
                expected[cell(h)] +=
                    f64::from(ggx.visible_normal_pdf(wo, h)) * d_omega * f64::from(n);
            });
            let mut chi2 = 0.0;
            let mut dof = 0;
            for (o, e) in observed.iter().zip(&expected) {
                if *e > 5.0 {
                    chi2 += (o - e) * (o - e) / e;
                    dof += 1;
                }
            }
            // The 99.9th percentile of χ² with ~200 degrees of freedom is about 1.3 × dof.
            assert!(
                chi2 < 1.35 * f64::from(dof),
                "roughness {roughness} θ {theta}: χ² {chi2:.1} over {dof} cells"
            );
        }
    }
}
