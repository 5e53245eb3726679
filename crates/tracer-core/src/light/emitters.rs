//! Emissive surfaces as lights: every triangle whose material has an emission luminance, in a
//! table that picks one in proportion to its flux and a uniform point on it.

use crate::sampling::uniform_triangle_barycentric;
use glam::Vec3;
use serde::{Deserialize, Serialize};

/// Which faces of an emissive surface emit. "Front" is the side the front normal points to:
/// (v1 − v0) × (v2 − v0) in right-handed scenes, its negation in left-handed ones.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum EmissionSides {
    #[default]
    Both,
    Front,
    Back,
}

impl EmissionSides {
    /// Whether light leaves along `dir` from a surface with unit front normal `front`.
    pub fn emits_towards(self, front: Vec3, dir: Vec3) -> bool {
        match self {
            EmissionSides::Both => true,
            EmissionSides::Front => front.dot(dir) > 0.0,
            EmissionSides::Back => front.dot(dir) < 0.0,
        }
    }

    pub fn count(self) -> f32 {
        match self {
            EmissionSides::Both => 2.0,
            _ => 1.0,
        }
    }
}

/// One emissive triangle.
#[derive(Clone, Copy, Debug)]
pub(super) struct Emitter {
    pub(super) triangle: u32,
    pub(super) v0: Vec3,
    pub(super) e1: Vec3,
    pub(super) e2: Vec3,
    pub(super) front: Vec3,
    /// Area in scene units².
    pub(super) area: f32,
    /// Emitted luminance per channel (cd/m²): L × tint.
    pub(super) radiance: Vec3,
    pub(super) sides: EmissionSides,
}

/// A point sampled on an emitter, seen from a shading point.
#[derive(Clone, Copy, Debug)]
pub struct EmitterSample {
    /// The scene triangle the point lies on.
    pub triangle: u32,
    pub point: Vec3,
    /// Unit direction from the shading point to `point`.
    pub wi: Vec3,
    /// Distance from the shading point, scene units.
    pub distance: f32,
    /// Luminance per channel arriving along `-wi` (zero when that side does not emit).
    pub radiance: Vec3,
    /// Density of this sample in solid angle at the shading point (1/sr).
    pub pdf_solid_angle: f32,
}

/// Every emissive triangle with a flux-proportional selection table.
#[derive(Clone, Debug, Default)]
pub struct EmitterTable {
    emitters: Vec<Emitter>,
    /// Running sums of the selection weights (flux ∝ L × area × sides).
    cdf: Vec<f64>,
    total: f64,
    /// Index into `emitters` of each scene triangle, `u32::MAX` when it does not emit.
    of_triangle: Vec<u32>,
}

/// What the table needs to know about one emissive triangle.
#[derive(Clone, Copy, Debug)]
pub struct EmissiveTriangle {
    pub triangle: u32,
    pub vertices: [Vec3; 3],
    /// Unit front normal.
    pub front: Vec3,
    /// Emission luminance per channel, cd/m².
    pub radiance: Vec3,
    pub sides: EmissionSides,
}

impl EmitterTable {
    /// The table of `triangles` (those with zero area or no emission are left out);
    /// `triangle_count` is the number of triangles in the scene.
    pub fn new(triangle_count: usize, triangles: &[EmissiveTriangle]) -> Self {
        let mut table = EmitterTable {
            of_triangle: vec![u32::MAX; triangle_count],
            ..EmitterTable::default()
        };
        for t in triangles {
            let [v0, v1, v2] = t.vertices;
            let (e1, e2) = (v1 - v0, v2 - v0);
            let area = 0.5 * e1.cross(e2).length();
            let power = super::luminance(t.radiance) * area * t.sides.count();
            if !(area > 0.0 && power > 0.0 && power.is_finite()) {
                continue;
            }
            table.total += f64::from(power);
            table.cdf.push(table.total);
            if let Some(slot) = table.of_triangle.get_mut(t.triangle as usize) {
                *slot = table.emitters.len() as u32;
            }
            table.emitters.push(Emitter {
                triangle: t.triangle,
                v0,
                e1,
                e2,
                front: t.front,
                area,
                radiance: t.radiance,
                sides: t.sides,
            });
        }
        table
    }

    pub fn is_empty(&self) -> bool {
        self.emitters.is_empty()
    }

    pub fn len(&self) -> usize {
        self.emitters.len()
    }

    /// Total luminous flux emitted (lm), with `metres_per_unit` converting areas: Φ = π L A per
    /// emitting face.
    pub fn flux_lm(&self, metres_per_unit: f32) -> f64 {
        self.emitters
            .iter()
            .map(|e| flux_of(e, metres_per_unit))
            .sum()
    }

    /// Whether triangle `triangle` emits at all.
    pub fn emits(&self, triangle: u32) -> bool {
        self.get(triangle).is_some()
    }

    fn get(&self, triangle: u32) -> Option<&Emitter> {
        let i = *self.of_triangle.get(triangle as usize)?;
        self.emitters.get(i as usize)
    }

    /// Picks an emitter by flux with `u_pick` and a uniform point on it with (`u`, `v`), as seen
    /// from `from`. None when the table is empty or the point coincides with `from`.
    pub fn sample(&self, from: Vec3, u_pick: f32, u: f32, v: f32) -> Option<EmitterSample> {
        let last = *self.cdf.last()?;
        let target = f64::from(u_pick) * last;
        let i = self
            .cdf
            .partition_point(|&c| c <= target)
            .min(self.emitters.len() - 1);
        let pick = self.pick_probability(&self.emitters[i]);
        sample_from(&self.emitters[i], from, u, v, pick)
    }

    /// Every emitter's bounds for a light tree, in table order, with its flux in lm
    /// (`metres_per_unit` converting areas).
    pub fn light_bounds(&self, metres_per_unit: f32) -> Vec<super::LightBounds> {
        use super::LightSource;
        (0..self.emitters.len() as u32)
            .filter_map(|i| self.light(i, metres_per_unit))
            .map(|l| l.bounds())
            .collect()
    }

    /// Emitter `index` (in table order) as a light, in a scene of `metres_per_unit`.
    #[inline]
    pub fn light(&self, index: u32, metres_per_unit: f32) -> Option<super::TriangleLight<'_>> {
        Some(super::TriangleLight {
            emitter: self.emitters.get(index as usize)?,
            metres_per_unit,
        })
    }

    /// The table index of `triangle`'s emitter.
    pub fn index_of(&self, triangle: u32) -> Option<u32> {
        let i = *self.of_triangle.get(triangle as usize)?;
        (i != u32::MAX).then_some(i)
    }

    /// The scene triangle of emitter `index`.
    pub fn triangle_of(&self, index: u32) -> Option<u32> {
        self.emitters.get(index as usize).map(|e| e.triangle)
    }

    fn pick_probability(&self, e: &Emitter) -> f32 {
        if self.total <= 0.0 {
            return 0.0;
        }
        let power = f64::from(super::luminance(e.radiance) * e.area * e.sides.count());
        (power / self.total) as f32
    }

    /// Density (1/sr) with which [`EmitterTable::sample`] from some point picks the direction
    /// `wi` that reaches triangle `triangle` at `distance`.
    pub fn pdf(&self, triangle: u32, wi: Vec3, distance: f32) -> f32 {
        self.get(triangle)
            .and_then(|e| self.pdf_of(e, wi, distance))
            .unwrap_or(0.0)
    }

    fn pdf_of(&self, e: &Emitter, wi: Vec3, distance: f32) -> Option<f32> {
        if self.total <= 0.0 {
            return None;
        }
        solid_angle_pdf(e, self.pick_probability(e), wi, distance)
    }

    /// The triangle index of every emitter (for tests and statistics).
    pub fn triangles(&self) -> impl Iterator<Item = u32> + '_ {
        self.emitters.iter().map(|e| e.triangle)
    }
}

/// Φ = π L A per emitting face (lm), `metres_per_unit` converting the area.
pub(super) fn flux_of(e: &Emitter, metres_per_unit: f32) -> f64 {
    std::f64::consts::PI
        * f64::from(super::luminance(e.radiance))
        * f64::from(e.area)
        * f64::from(metres_per_unit).powi(2)
        * f64::from(e.sides.count())
}

/// A uniform point on `e`, picked with probability `pick`, seen from `from`.
pub(super) fn sample_from(
    e: &Emitter,
    from: Vec3,
    u: f32,
    v: f32,
    pick: f32,
) -> Option<EmitterSample> {
    let (b1, b2) = uniform_triangle_barycentric(u, v);
    let point = e.v0 + e.e1 * b1 + e.e2 * b2;
    let to = point - from;
    let distance = to.length();
    if distance.is_nan() || distance <= 0.0 {
        return None;
    }
    let wi = to / distance;
    let pdf = solid_angle_pdf(e, pick, wi, distance)?;
    let radiance = if e.sides.emits_towards(e.front, -wi) {
        e.radiance
    } else {
        Vec3::ZERO
    };
    Some(EmitterSample {
        triangle: e.triangle,
        point,
        wi,
        distance,
        radiance,
        pdf_solid_angle: pdf,
    })
}

/// Density (1/sr) of a uniform point on `e`, picked with probability `pick`, seen along unit
/// `wi` at `distance`.
pub(super) fn solid_angle_pdf(e: &Emitter, pick: f32, wi: Vec3, distance: f32) -> Option<f32> {
    let cos = e.front.dot(wi).abs();
    if cos <= 0.0 {
        return None;
    }
    Some(pick / e.area * distance * distance / cos)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    fn quad(radiance: f32) -> Vec<EmissiveTriangle> {
        // A 2 x 2 square in the plane y = 1, facing down.
        let a = Vec3::new(-1.0, 1.0, -1.0);
        let b = Vec3::new(1.0, 1.0, -1.0);
        let c = Vec3::new(1.0, 1.0, 1.0);
        let d = Vec3::new(-1.0, 1.0, 1.0);
        [[a, b, c], [a, c, d]]
            .iter()
            .enumerate()
            .map(|(i, v)| EmissiveTriangle {
                triangle: i as u32,
                vertices: *v,
                front: Vec3::NEG_Y,
                radiance: Vec3::splat(radiance),
                sides: EmissionSides::Front,
            })
            .collect()
    }

    /// Light sampling estimates the irradiance under a square emitter: E = π L F, and for a
    /// point on the axis at distance h under a square of half-side a, four corner rectangles of
    /// X = Y = a/h give F = 4 · (1/2π) · 2 · X/√(1+X²) · atan(X/√(1+X²)).
    #[test]
    fn sampled_irradiance_matches_the_form_factor() {
        let table = EmitterTable::new(2, &quad(1000.0));
        let p = Vec3::ZERO;
        let n = Vec3::Y;
        let k = 200;
        let mut sum = 0.0f64;
        for i in 0..k {
            for j in 0..k {
                let u = (i as f32 + 0.5) / k as f32;
                let v = (j as f32 + 0.5) / k as f32;
                let pick = crate::sampling::SampleRng::new(i * k + j, 0).next_f32();
                let s = table.sample(p, pick, u, v);
                let s = s.expect("sample");
                sum += f64::from(s.radiance.x * n.dot(s.wi) / s.pdf_solid_angle);
            }
        }
        let e = sum / (k * k) as f64;
        // Square of half-side a = 1 at height h = 1: X = 1.
        let s = 1.0f64 / 2f64.sqrt();
        let f = 4.0 / (2.0 * std::f64::consts::PI) * 2.0 * s * s.atan();
        let exact = std::f64::consts::PI * 1000.0 * f;
        assert!((e / exact - 1.0).abs() < 2e-3, "{e} vs {exact}");
        // Seen from above, the front (downward) face does not emit.
        let above = table
            .sample(Vec3::new(0.0, 2.0, 0.0), 0.3, 0.4, 0.5)
            .expect("sample");
        assert_eq!(above.radiance, Vec3::ZERO);
        assert!((table.flux_lm(1.0) - std::f64::consts::PI * 1000.0 * 4.0).abs() < 1e-2);
    }
}
