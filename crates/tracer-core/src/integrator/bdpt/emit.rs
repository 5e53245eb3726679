//! Where light subpaths start: a light picked in proportion to its flux, a point on it and a
//! direction, with the densities multiple importance sampling needs. Connections with one light
//! vertex (s = 1) pick theirs with the light tree instead, for the eye vertex they join.
//!
//! Emission is expressed in the scene's own unit: a point light's intensity becomes
//! I / (metres per unit)², so that a subpath's throughput is cd/m² × (scene unit)² everywhere and
//! a connection's geometry term (per squared scene unit) turns it into lx or cd/m².

use super::vertex::{Kind, Vertex};
use crate::light::EmissionSides;
use crate::lit_scene::{LitScene, Profile, TreeLight};
use crate::sampling::{SampleRng, cosine_hemisphere, to_world, uniform_sphere};
use glam::Vec3;
use std::f32::consts::PI;

/// One light to pick: a point-like light (point, spot, luminaire) or all glowing surfaces.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Entry {
    Point(u32),
    Surfaces,
}

/// The start of a light subpath or a light sample for next-event estimation.
#[derive(Clone, Copy, Debug)]
pub struct LightPoint {
    /// Point light index, or the emitting triangle (`Light::Area`).
    pub light: LightRef,
    pub p: Vec3,
    /// Unit front normal of an emitting triangle (zero for point lights).
    pub n: Vec3,
    /// Density of having picked this point: light choice × area density (1 for a point's
    /// position).
    pub pdf_origin: f32,
}

/// Which light a light vertex is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightRef {
    Point(u32),
    Area(u32),
}

/// Lights in proportion to their flux.
#[derive(Clone, Debug, Default)]
pub struct LightPicker {
    entries: Vec<Entry>,
    /// Cumulative flux (lm).
    cdf: Vec<f64>,
    probability: Vec<f32>,
    surfaces_probability: f32,
}

impl LightPicker {
    pub fn new(lit: &LitScene<'_>) -> Self {
        let mut picker = LightPicker::default();
        let mut total = 0.0f64;
        let mut fluxes = Vec::new();
        for (i, light) in lit.lights.iter().enumerate() {
            let flux = light.flux_lm();
            if flux > 0.0 && flux.is_finite() {
                picker.entries.push(Entry::Point(i as u32));
                fluxes.push(flux);
            }
        }
        let mpu = lit.metres_per_unit_sq.sqrt();
        let surfaces = lit.emitters.flux_lm(mpu);
        if surfaces > 0.0 && surfaces.is_finite() {
            picker.entries.push(Entry::Surfaces);
            fluxes.push(surfaces);
        }
        for f in &fluxes {
            total += f;
            picker.cdf.push(total);
        }
        picker.probability = fluxes.iter().map(|f| (f / total) as f32).collect();
        picker.surfaces_probability = picker
            .entries
            .iter()
            .zip(&picker.probability)
            .find(|(e, _)| **e == Entry::Surfaces)
            .map_or(0.0, |(_, p)| *p);
        picker
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Picks a light and a point on it.
    pub fn sample(&self, lit: &LitScene<'_>, rng: &mut SampleRng) -> Option<LightPoint> {
        let last = *self.cdf.last()?;
        let u_pick = rng.next_f32();
        let (u, v) = rng.next_2d();
        let target = f64::from(u_pick) * last;
        let i = self
            .cdf
            .partition_point(|&c| c <= target)
            .min(self.entries.len() - 1);
        match self.entries[i] {
            Entry::Point(index) => Some(LightPoint {
                light: LightRef::Point(index),
                p: lit.lights[index as usize].position,
                n: Vec3::ZERO,
                pdf_origin: self.probability[i],
            }),
            Entry::Surfaces => {
                // Reuse u_pick's position inside this entry's interval for the triangle choice.
                let lo = if i == 0 { 0.0 } else { self.cdf[i - 1] };
                let inner = ((target - lo) / (self.cdf[i] - lo)).clamp(0.0, 1.0) as f32;
                let e = lit.emitters.sample_point(inner.min(0.999_999_9), u, v)?;
                Some(LightPoint {
                    light: LightRef::Area(e.triangle),
                    p: e.point,
                    n: e.front,
                    pdf_origin: self.surfaces_probability * e.pdf_area,
                })
            }
        }
    }

    /// Density of picking this light's position (see [`LightPoint::pdf_origin`]).
    pub fn pdf_origin(&self, lit: &LitScene<'_>, light: LightRef) -> f32 {
        match light {
            LightRef::Point(index) => self
                .entries
                .iter()
                .position(|e| *e == Entry::Point(index))
                .map_or(0.0, |i| self.probability[i]),
            LightRef::Area(t) => self.surfaces_probability * lit.emitters.pdf_area(t),
        }
    }
}

/// What a light vertex sends along unit `dir`: for a point light its intensity in the scene's
/// unit (cd / (m per unit)²) per channel, for a glowing triangle its luminance (cd/m²).
pub fn emitted(lit: &LitScene<'_>, light: LightRef, dir: Vec3) -> Vec3 {
    match light {
        LightRef::Point(i) => {
            let l = &lit.lights[i as usize];
            l.tint * (l.intensity_towards(dir) / lit.metres_per_unit_sq)
        }
        LightRef::Area(t) => lit.emitters.radiance(t, dir),
    }
}

/// The cosine a glowing triangle's emission carries along `dir` (1 for point lights).
pub fn emission_cosine(light: LightRef, n: Vec3, dir: Vec3) -> f32 {
    match light {
        LightRef::Point(_) => 1.0,
        LightRef::Area(_) => n.dot(dir).abs(),
    }
}

/// Samples the direction a light subpath leaves in; returns it with its density per sr.
pub fn sample_direction(
    lit: &LitScene<'_>,
    start: &LightPoint,
    rng: &mut SampleRng,
) -> Option<(Vec3, f32)> {
    let (u, v) = rng.next_2d();
    match start.light {
        LightRef::Point(i) => match &lit.lights[i as usize].profile {
            Profile::Spot(s) => {
                let cos_max = s.falloff.cos();
                let z = 1.0 - u * (1.0 - cos_max);
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = 2.0 * PI * v;
                let local = Vec3::new(r * phi.cos(), r * phi.sin(), z);
                let dir = to_world(local, s.axis);
                Some((dir, direction_pdf(lit, start.light, start.n, dir)))
            }
            _ => Some((uniform_sphere(u, v), 1.0 / (4.0 * PI))),
        },
        LightRef::Area(t) => {
            let (_, sides) = lit.emitters.orientation(t)?;
            let (side, u) = match sides {
                EmissionSides::Front => (1.0, u),
                EmissionSides::Back => (-1.0, u),
                EmissionSides::Both if u < 0.5 => (1.0, u * 2.0),
                EmissionSides::Both => (-1.0, (u - 0.5) * 2.0),
            };
            let dir = to_world(cosine_hemisphere(u.min(0.999_999_9), v), start.n * side);
            Some((dir, direction_pdf(lit, start.light, start.n, dir)))
        }
    }
}

/// Density per sr of [`sample_direction`] leaving along unit `dir`.
pub fn direction_pdf(lit: &LitScene<'_>, light: LightRef, n: Vec3, dir: Vec3) -> f32 {
    match light {
        LightRef::Point(i) => match &lit.lights[i as usize].profile {
            Profile::Spot(s) => {
                let cos_max = s.falloff.cos();
                if s.axis.dot(dir) < cos_max || cos_max >= 1.0 {
                    0.0
                } else {
                    1.0 / (2.0 * PI * (1.0 - cos_max))
                }
            }
            _ => 1.0 / (4.0 * PI),
        },
        LightRef::Area(t) => {
            let Some((_, sides)) = lit.emitters.orientation(t) else {
                return 0.0;
            };
            let c = n.dot(dir);
            match sides {
                EmissionSides::Front => c.max(0.0) / PI,
                EmissionSides::Back => (-c).max(0.0) / PI,
                EmissionSides::Both => c.abs() / (2.0 * PI),
            }
        }
    }
}

impl super::Bidirectional<'_, '_> {
    /// Strategy s = 1: a light picked by the light tree for eye vertex `pt`, and a point on it
    /// (uniform on a glowing triangle). Its `pdf_origin` is the tree's probability times the
    /// area density.
    pub(super) fn sample_light_for(&self, pt: &Vertex, rng: &mut SampleRng) -> Option<LightPoint> {
        let lit = self.lit;
        let (light, pmf) = lit.pick_light(pt.p, pt.n, lit.pick_number(rng))?;
        match light {
            TreeLight::Placed(i) => Some(LightPoint {
                light: LightRef::Point(i),
                p: lit.lights.get(i as usize)?.position,
                n: Vec3::ZERO,
                pdf_origin: pmf,
            }),
            TreeLight::Triangle(t) => {
                let (u, v) = rng.next_2d();
                let index = lit.emitters.index_of(t)?;
                let s = lit.emitters.sample_on(index, pt.p, u, v)?;
                let (front, _) = lit.emitters.orientation(t)?;
                Some(LightPoint {
                    light: LightRef::Area(t),
                    p: s.point,
                    n: front,
                    pdf_origin: pmf * lit.emitters.area_pdf_on(t),
                })
            }
        }
    }

    /// How much likelier strategy s = 1 makes light vertex `x0` when it joins it to `x1` (the
    /// tree's choice at `x1`) than a light subpath's start does (by flux):
    /// p_tree(x0 | x1) / p_flux(x0).
    pub(super) fn tree_factor(&self, x0: &Vertex, x1: &Vertex) -> f32 {
        let light = match x0.kind {
            Kind::Light(l) => l,
            Kind::Surface(prim) => LightRef::Area(prim),
            Kind::Eye => return 1.0,
        };
        let flux = self.lights.pdf_origin(self.lit, light);
        if flux <= 0.0 {
            return 1.0;
        }
        let (tree_light, area) = match light {
            LightRef::Point(i) => (TreeLight::Placed(i), 1.0),
            LightRef::Area(t) => (TreeLight::Triangle(t), self.lit.emitters.area_pdf_on(t)),
        };
        self.lit.light_pmf(x1.p, x1.n, tree_light) * area / flux
    }
}
