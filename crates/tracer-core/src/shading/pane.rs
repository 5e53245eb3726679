//! A thin glass pane: a window modelled as one polygon. Light meets two parallel interfaces of
//! index n and bounces between them; a pane does not deviate rays (the slab's sideways shift
//! is ignored), so what gets through leaves along the incident direction and what is reflected
//! leaves along the mirror direction.
//!
//! Per polarisation (s, p), with R the Fresnel reflectance of one interface at the angle of
//! incidence θ and τ the internal transmittance of one crossing of the glass,
//!
//! T = (1 − R)² τ / (1 − R² τ²),   R_pane = R + (1 − R)² R τ² / (1 − R² τ²),
//!
//! and the pane's values are the means over s and p. Without absorption (τ = 1) T reduces to
//! (1 − R)/(1 + R): for n = 1.52, 0.9183, 0.9160, 0.9025 and 0.8435 at 0°, 30°, 45° and 60°
//! (LIGHTING.md). The unpolarised shortcut, (1 − R̄)/(1 + R̄) with R̄ the mean reflectance, is
//! wrong at oblique angles (0.8307 at 60°).
//!
//! An absorbing pane is given by its transmittance at normal incidence, T₀: τ₀ solves
//! T₀ = (1 − R₀)² τ₀ / (1 − R₀² τ₀²), and at an angle the path through the glass is longer,
//! τ = τ₀^(1 / cos θ_t), θ_t the refracted angle.

/// A pane's optics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pane {
    /// Refractive index of the glass.
    pub ior: f32,
    /// Internal transmittance of one crossing at normal incidence (1: no absorption).
    tau0: f32,
}

/// Fresnel reflectances (s, p) of one interface from air into index `n` at cos θ = `cos_i`.
fn fresnel_sp(cos_i: f32, n: f32) -> (f32, f32, f32) {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = (1.0 - cos_i * cos_i) / (n * n);
    let cos_t = (1.0 - sin2_t).max(0.0).sqrt();
    let rs = ((cos_i - n * cos_t) / (cos_i + n * cos_t)).powi(2);
    let rp = ((n * cos_i - cos_t) / (n * cos_i + cos_t)).powi(2);
    (rs, rp, cos_t)
}

impl Pane {
    /// A pane of index `ior` (> 1) with normal-incidence transmittance `transmittance` (None: no
    /// absorption), or why not.
    pub fn new(ior: f32, transmittance: Option<f32>) -> Result<Pane, String> {
        if !(ior.is_finite() && ior > 1.0 && ior <= 4.0) {
            return Err(format!("pane: ior = {ior} must be above 1 and at most 4"));
        }
        let (r0, _, _) = fresnel_sp(1.0, ior);
        let clear = (1.0 - r0) / (1.0 + r0);
        let tau0 = match transmittance {
            None => 1.0,
            Some(t) if t.is_finite() && t > 0.0 && t <= clear + 1e-6 => {
                let t = t.min(clear);
                // R₀² T₀ τ² + (1 − R₀)² τ − T₀ = 0, its positive root.
                let (a, b, c) = (r0 * r0 * t, (1.0 - r0).powi(2), -t);
                (-b + (b * b - 4.0 * a * c).sqrt()) / (2.0 * a)
            }
            Some(t) => {
                return Err(format!(
                    "pane: transmittance = {t} must be above 0 and at most {clear:.4}, the \
                     clear pane's at ior {ior}"
                ));
            }
        };
        Ok(Pane {
            ior,
            tau0: tau0.clamp(0.0, 1.0),
        })
    }

    /// (T, R) of the pane for light arriving at cos θ = `cos_i` (either side).
    pub fn transmit_reflect(&self, cos_i: f32) -> (f32, f32) {
        let (rs, rp, cos_t) = fresnel_sp(cos_i.abs(), self.ior);
        let tau = if self.tau0 < 1.0 {
            self.tau0.powf(1.0 / cos_t.max(1e-4))
        } else {
            1.0
        };
        let one = |r: f32| {
            let denom = 1.0 - r * r * tau * tau;
            if denom <= 0.0 {
                // Grazing: R = 1, nothing gets through.
                return (0.0, 1.0);
            }
            let t = (1.0 - r).powi(2) * tau / denom;
            (t, r + (1.0 - r).powi(2) * r * tau * tau / denom)
        };
        let ((ts, r_s), (tp, r_p)) = (one(rs), one(rp));
        (0.5 * (ts + tp), 0.5 * (r_s + r_p))
    }

    /// The pane's transmittance at cos θ = `cos_i`.
    pub fn transmittance(&self, cos_i: f32) -> f32 {
        self.transmit_reflect(cos_i).0
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    /// LIGHTING.md's figures for n = 1.52, and energy: T + R = 1 without absorption.
    #[test]
    fn clear_pane_matches_the_table() {
        let pane = Pane::new(1.52, None).unwrap();
        for (deg, expected) in [
            (0.0f32, 0.9183),
            (30.0, 0.9160),
            (45.0, 0.9025),
            (60.0, 0.8435),
        ] {
            let (t, r) = pane.transmit_reflect(deg.to_radians().cos());
            assert!((t - expected).abs() < 5e-5, "{deg}°: {t} vs {expected}");
            assert!((t + r - 1.0).abs() < 1e-5, "{deg}°: T + R = {}", t + r);
        }
        // The unpolarised shortcut would give 0.8307 at 60°: the pane is not that.
        let (rs, rp, _) = fresnel_sp(0.5, 1.52);
        let r = 0.5 * (rs + rp);
        assert!(((1.0 - r) / (1.0 + r) - 0.8307).abs() < 5e-4);
        assert_eq!(pane.transmittance(0.0), 0.0);
    }

    /// An absorbing pane keeps the normal transmittance it was given, loses more at slant
    /// (a longer path), and absorbs what it neither sends on nor reflects.
    #[test]
    fn absorbing_pane() {
        let pane = Pane::new(1.52, Some(0.80)).unwrap();
        let (t0, r0) = pane.transmit_reflect(1.0);
        assert!((t0 - 0.80).abs() < 1e-5, "{t0}");
        assert!(r0 < 0.0852 && t0 + r0 < 1.0);
        let clear = Pane::new(1.52, None).unwrap();
        let slant = 0.5f32;
        assert!(pane.transmittance(slant) / clear.transmittance(slant) < 0.80 / 0.9183);
        assert!(
            Pane::new(1.52, Some(0.95))
                .unwrap_err()
                .contains("at most 0.9183")
        );
        assert!(Pane::new(1.0, None).is_err());
    }
}
