//! A glowing triangle as a light: a view into the [`EmitterTable`] that holds it. It emits its
//! material's luminance from the sides its [`EmissionSides`] name, uniformly over its area.

use super::emitters::{Emitter, EmitterSample, flux_of, sample_from, solid_angle_pdf};
use super::{Emission, EmissionSides, Incident, LightBounds, LightSource, Receiver};
use crate::sampling::{cosine_hemisphere, to_world, uniform_triangle_barycentric};
use glam::Vec3;
use std::f32::consts::PI;

/// One emissive triangle of a render.
#[derive(Clone, Copy, Debug)]
pub struct TriangleLight<'a> {
    pub(super) emitter: &'a Emitter,
    /// Metres per scene unit (its flux is in lm).
    pub(super) metres_per_unit: f32,
}

impl TriangleLight<'_> {
    /// The scene triangle.
    pub fn triangle(&self) -> u32 {
        self.emitter.triangle
    }

    pub fn sides(&self) -> EmissionSides {
        self.emitter.sides
    }
}

impl LightSource for TriangleLight<'_> {
    /// π L A per emitting side.
    fn power_lm(&self) -> f64 {
        flux_of(self.emitter, self.metres_per_unit)
    }

    fn bounds(&self) -> LightBounds {
        let e = self.emitter;
        let verts = [e.v0, e.v0 + e.e1, e.v0 + e.e2];
        let (normal, two_sided) = match e.sides {
            EmissionSides::Front => (e.front, false),
            EmissionSides::Back => (-e.front, false),
            EmissionSides::Both => (e.front, true),
        };
        LightBounds::surface(&verts, self.power_lm() as f32, normal, two_sided)
    }

    fn is_delta(&self) -> bool {
        false
    }

    /// A uniform point on the triangle, seen from `at.origin`.
    #[inline]
    fn sample_incident(&self, at: Receiver, u: [f32; 2]) -> Option<Incident> {
        sample_from(self.emitter, at.origin, u[0], u[1], 1.0).map(Incident::from)
    }

    #[inline]
    fn incident_pdf(&self, _origin: Vec3, wi: Vec3, distance: f32) -> f32 {
        solid_angle_pdf(self.emitter, 1.0, wi, distance).unwrap_or(0.0)
    }

    #[inline]
    fn emitted(&self, dir: Vec3) -> Vec3 {
        let e = self.emitter;
        if e.sides.emits_towards(e.front, dir) {
            e.radiance
        } else {
            Vec3::ZERO
        }
    }

    /// A uniform point, and a cosine-weighted direction on an emitting side (each side with
    /// probability ½ when both emit).
    fn sample_emission(&self, u_point: [f32; 2], u_dir: [f32; 2]) -> Option<Emission> {
        let e = self.emitter;
        let (b1, b2) = uniform_triangle_barycentric(u_point[0], u_point[1]);
        let [u, v] = u_dir;
        let (side, u) = match e.sides {
            EmissionSides::Front => (1.0, u),
            EmissionSides::Back => (-1.0, u),
            EmissionSides::Both if u < 0.5 => (1.0, u * 2.0),
            EmissionSides::Both => (-1.0, (u - 0.5) * 2.0),
        };
        let dir = to_world(cosine_hemisphere(u.min(0.999_999_9), v), e.front * side);
        Some(Emission {
            p: e.v0 + e.e1 * b1 + e.e2 * b2,
            n: e.front,
            dir,
            pdf_point: 1.0 / e.area,
            pdf_dir: self.emission_dir_pdf(dir),
        })
    }

    fn emission_dir_pdf(&self, dir: Vec3) -> f32 {
        let e = self.emitter;
        let c = e.front.dot(dir);
        match e.sides {
            EmissionSides::Front => c.max(0.0) / PI,
            EmissionSides::Back => (-c).max(0.0) / PI,
            EmissionSides::Both => c.abs() / (2.0 * PI),
        }
    }

    fn emission_point_pdf(&self) -> f32 {
        1.0 / self.emitter.area
    }

    fn normal(&self) -> Vec3 {
        self.emitter.front
    }
}

impl From<EmitterSample> for Incident {
    /// A point on a glowing triangle as incident light: its luminance, its density per sr.
    fn from(s: EmitterSample) -> Self {
        Incident {
            wi: s.wi,
            target: s.point,
            tint: s.radiance,
            level: 1.0,
            pdf: s.pdf_solid_angle,
            delta: false,
            n: Vec3::ZERO,
        }
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;
    use crate::light::{EmissiveTriangle, EmitterTable};

    fn table(sides: EmissionSides) -> EmitterTable {
        // A right triangle of legs 2 and 1 (area 1 unit²) in the plane y = 0, front +Y.
        let t = EmissiveTriangle {
            triangle: 0,
            vertices: [
                Vec3::ZERO,
                Vec3::new(0.0, 0.0, 2.0),
                Vec3::new(1.0, 0.0, 0.0),
            ],
            front: Vec3::Y,
            radiance: Vec3::splat(100.0),
            sides,
        };
        EmitterTable::new(1, &[t])
    }

    /// A light subpath's start estimates the flux: E[L cos θ / (p_A p_ω)] = π L A per emitting
    /// side (A in m²: 1 unit = 0.5 m here, so A = 0.25 m²).
    #[test]
    fn emission_samples_estimate_pi_l_a() {
        for (sides, count) in [(EmissionSides::Front, 1.0), (EmissionSides::Both, 2.0)] {
            let table = table(sides);
            let light = table.light(0, 0.5).unwrap();
            let exact = std::f64::consts::PI * 100.0 * 0.25 * count;
            assert!((light.power_lm() - exact).abs() < 1e-3);
            let k = 64;
            let mut sum = 0.0f64;
            for i in 0..k * k {
                let u = |j: u32| ((i * 7 + j * 13) % (k * k)) as f32 / (k * k) as f32;
                let cell = [(i % k) as f32 + 0.5, (i / k) as f32 + 0.5];
                let e = light
                    .sample_emission([u(1), u(2)], [cell[0] / k as f32, cell[1] / k as f32])
                    .unwrap();
                assert!((light.emission_dir_pdf(e.dir) - e.pdf_dir).abs() < 1e-4);
                let value = light.emitted(e.dir).x * light.emission_cosine(e.n, e.dir);
                sum += f64::from(value / (e.pdf_point * e.pdf_dir));
            }
            // Scene units² to m².
            let flux = sum / f64::from(k * k) * 0.25;
            assert!(
                (flux / exact - 1.0).abs() < 1e-3,
                "{sides:?}: {flux} vs {exact}"
            );
        }
    }

    /// Front-only emission is dark from behind, and the incident density matches the sample's.
    #[test]
    fn incident_sample_and_density_agree() {
        let table = table(EmissionSides::Front);
        let light = table.light(0, 1.0).unwrap();
        let below = Receiver {
            p: Vec3::new(0.3, -1.0, 0.4),
            origin: Vec3::new(0.3, -1.0, 0.4),
        };
        let s = light.sample_incident(below, [0.3, 0.6]).unwrap();
        assert_eq!(s.tint, Vec3::ZERO);
        let above = Receiver {
            p: Vec3::new(0.3, 1.0, 0.4),
            origin: Vec3::new(0.3, 1.0, 0.4),
        };
        let s = light.sample_incident(above, [0.3, 0.6]).unwrap();
        assert_eq!(s.tint, Vec3::splat(100.0));
        let distance = (s.target - above.origin).length();
        let pdf = light.incident_pdf(above.origin, s.wi, distance);
        assert!((pdf / s.pdf - 1.0).abs() < 1e-5);
        assert!(!s.delta && !light.is_delta());
    }
}
