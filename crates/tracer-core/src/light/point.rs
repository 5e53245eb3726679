//! The isotropic point light, and what every point-like light (point, spot, luminaire) shares:
//! light reaching a receiver from one position, E = I(ω) cos θ / R².

use super::{Emission, Incident, LightBounds, LightSource, Receiver};
use crate::sampling::uniform_sphere;
use glam::Vec3;
use std::f32::consts::PI;

/// `intensity_cd` in every direction from `position`.
#[derive(Clone, Debug, PartialEq)]
pub struct PointLight {
    pub position: Vec3,
    pub intensity_cd: f32,
    /// Colour with Rec. 709 luminance 1.
    pub tint: Vec3,
    /// (metres per scene unit)².
    pub metres_per_unit_sq: f32,
}

impl LightSource for PointLight {
    fn power_lm(&self) -> f64 {
        f64::from(self.intensity_cd) * 4.0 * std::f64::consts::PI
    }

    fn bounds(&self) -> LightBounds {
        LightBounds::point(self.position, self.power_lm() as f32)
    }

    fn is_delta(&self) -> bool {
        true
    }

    #[inline(always)]
    fn sample_incident(&self, at: Receiver, _u: [f32; 2]) -> Option<Incident> {
        incident_from_point(
            self.position,
            self.tint,
            self.metres_per_unit_sq,
            at,
            |_| self.intensity_cd,
        )
    }

    fn incident_pdf(&self, _origin: Vec3, _wi: Vec3, _distance: f32) -> f32 {
        0.0
    }

    fn emitted(&self, _dir: Vec3) -> Vec3 {
        self.tint * (self.intensity_cd / self.metres_per_unit_sq)
    }

    fn sample_emission(&self, _u_point: [f32; 2], u_dir: [f32; 2]) -> Option<Emission> {
        Some(uniform_emission(self.position, u_dir))
    }

    fn emission_dir_pdf(&self, _dir: Vec3) -> f32 {
        UNIFORM_SPHERE_PDF
    }

    fn emission_point_pdf(&self) -> f32 {
        1.0
    }

    fn normal(&self) -> Vec3 {
        Vec3::ZERO
    }
}

/// A light subpath's start at a point, in a uniform direction (density [`UNIFORM_SPHERE_PDF`]).
pub(super) fn uniform_emission(position: Vec3, u_dir: [f32; 2]) -> Emission {
    Emission {
        p: position,
        n: Vec3::ZERO,
        dir: uniform_sphere(u_dir[0], u_dir[1]),
        pdf_point: 1.0,
        pdf_dir: UNIFORM_SPHERE_PDF,
    }
}

/// Density per sr of a uniform direction.
pub(super) const UNIFORM_SPHERE_PDF: f32 = 1.0 / (4.0 * PI);

/// Light from a point at `position` reaching `at.p`, with intensity `intensity(ω)` (cd) along
/// the unit direction ω leaving the light. Its `pdf` is R² in m², so that value · cos θ / pdf
/// is the illuminance. None when `at.p` is the light's position.
#[inline(always)]
pub(super) fn incident_from_point(
    position: Vec3,
    tint: Vec3,
    metres_per_unit_sq: f32,
    at: Receiver,
    intensity: impl Fn(Vec3) -> f32,
) -> Option<Incident> {
    let to_light = position - at.p;
    let dist2 = to_light.length_squared();
    if dist2 <= 0.0 {
        return None;
    }
    let wi = to_light / dist2.sqrt();
    Some(Incident {
        wi,
        target: position,
        tint,
        level: intensity(-wi),
        pdf: dist2 * metres_per_unit_sq,
        delta: true,
        n: Vec3::ZERO,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    /// E = I cos θ / R² with R in metres: 100 cd, 2 units of 0.5 m below, at 60° incidence.
    #[test]
    fn incident_gives_inverse_square_illuminance() {
        let light = PointLight {
            position: Vec3::new(0.0, 2.0, 0.0),
            intensity_cd: 100.0,
            tint: Vec3::ONE,
            metres_per_unit_sq: 0.25,
        };
        let n = Vec3::new(60f32.to_radians().sin(), 60f32.to_radians().cos(), 0.0);
        let at = Receiver {
            p: Vec3::ZERO,
            origin: Vec3::ZERO,
        };
        let s = light.sample_incident(at, [0.5; 2]).unwrap();
        let e = s.level * n.dot(s.wi) / s.pdf;
        assert!((e - 100.0 * 0.5 / 1.0).abs() < 1e-4, "{e}");
        assert!(s.delta && light.incident_pdf(Vec3::ZERO, s.wi, 2.0) == 0.0);
        // The flux is 4π I, and a light subpath's emission integrates to it: ∫ I dω = 4π I.
        assert!((light.power_lm() - 400.0 * std::f64::consts::PI).abs() < 1e-3);
        let em = light.sample_emission([0.1, 0.2], [0.3, 0.4]).unwrap();
        let flux = light.emitted(em.dir).x * light.metres_per_unit_sq / em.pdf_dir;
        assert!((f64::from(flux) - light.power_lm()).abs() < 1e-2);
    }
}
