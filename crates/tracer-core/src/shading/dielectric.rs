//! The smooth dielectric interface: Fresnel reflectance of unpolarised light and Snell's law.

use glam::Vec3;

/// Fresnel reflectance for light meeting the interface at cos θ = `cos_o` (> 0) from the side
/// of index 1 towards index `eta` (the relative index behind / in front); 1 under total
/// internal reflection.
pub fn fresnel(cos_o: f32, eta: f32) -> f32 {
    let cos_o = cos_o.clamp(0.0, 1.0);
    let sin_t2 = (1.0 - cos_o * cos_o) / (eta * eta);
    if sin_t2 >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin_t2).sqrt();
    let r_s = (cos_o - eta * cos_t) / (cos_o + eta * cos_t);
    let r_p = (eta * cos_o - cos_t) / (eta * cos_o + cos_t);
    0.5 * (r_s * r_s + r_p * r_p)
}

/// The refracted direction of unit `wo` (pointing away from the surface, on the side of unit
/// `n`) through an interface of relative index `eta`; None under total internal reflection.
pub fn refract(wo: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_o = n.dot(wo);
    let sin_t2 = (1.0 - cos_o * cos_o).max(0.0) / (eta * eta);
    if sin_t2 >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin_t2).sqrt();
    Some((-wo / eta + n * (cos_o / eta - cos_t)).normalize())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn normal_incidence_gives_the_textbook_reflectance() {
        // ((n - 1) / (n + 1))² = 0.04 for n = 1.5, from either side.
        assert!((fresnel(1.0, 1.5) - 0.04).abs() < 1e-6);
        assert!((fresnel(1.0, 1.0 / 1.5) - 0.04).abs() < 1e-6);
        assert!(fresnel(0.3, 1.0) < 1e-12);
    }

    #[test]
    fn snell_holds_and_total_internal_reflection_is_found() {
        let n = Vec3::Z;
        let theta: f32 = 0.7;
        let wo = Vec3::new(theta.sin(), 0.0, theta.cos());
        let wt = refract(wo, n, 1.5).unwrap();
        assert!(wt.z < 0.0 && wt.x < 0.0, "{wt}");
        let sin_t = (wt.x * wt.x + wt.y * wt.y).sqrt();
        assert!((theta.sin() - 1.5 * sin_t).abs() < 1e-5);
        // From glass at 45 degrees: beyond the critical angle asin(1/1.5) = 41.8 degrees.
        let wo = Vec3::new(0.5f32.sqrt(), 0.0, 0.5f32.sqrt());
        assert!(refract(wo, n, 1.0 / 1.5).is_none());
        assert_eq!(fresnel(wo.z, 1.0 / 1.5), 1.0);
        // Brewster's angle: no p-polarised reflection, R = r_s² / 2.
        let b = 1.5f32.atan();
        let r = fresnel(b.cos(), 1.5);
        let cos_t = (1.0 - (b.sin() / 1.5).powi(2)).sqrt();
        let r_s = (b.cos() - 1.5 * cos_t) / (b.cos() + 1.5 * cos_t);
        assert!((r - 0.5 * r_s * r_s).abs() < 1e-6);
    }
}
