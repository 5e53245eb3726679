//! Where light subpaths start: a light picked in proportion to its flux, then a point on it and
//! a direction from the light itself ([`LightSource::sample_emission`]). Connections with one
//! light vertex (s = 1) pick theirs with the light tree instead, for the eye vertex they join.
//!
//! Emission is expressed in the scene's own unit: a point light's intensity becomes
//! I / (metres per unit)², so that a subpath's throughput is cd/m² × (scene unit)² everywhere and
//! a connection's geometry term (per squared scene unit) turns it into lx or cd/m².

use super::vertex::{Kind, Vertex};
use crate::light::{Emission, LightSource, Receiver};
use crate::lit_scene::{LitScene, TreeLight};
use crate::sampling::SampleRng;
use crate::shading::Scatter;
use glam::Vec3;

/// A point on a light: the start of a light subpath, or the light vertex of a connection.
#[derive(Clone, Copy, Debug)]
pub struct LightPoint {
    pub light: TreeLight,
    pub p: Vec3,
    /// Unit front normal of an area light (zero for point-like lights).
    pub n: Vec3,
    /// Density of having picked this point: light choice × area density (1 for a point's
    /// position).
    pub pdf_origin: f32,
}

/// Lights in proportion to their flux, in [`LitScene::light_count`]'s order; for the light
/// tracer, the environment too (last, by the flux through its disc).
#[derive(Clone, Debug, Default)]
pub struct LightPicker {
    /// Cumulative flux (lm), one entry per light.
    cdf: Vec<f64>,
    /// Probability of each light.
    probability: Vec<f32>,
    /// Total flux including the environment's (lm).
    total: f64,
    /// Probability of the environment.
    environment: f32,
}

/// The start of a light subpath.
#[derive(Clone, Copy, Debug)]
pub enum Start {
    Light(LightPoint, Emission),
    /// A point on the disc across the scene's bounding sphere, and a direction into the scene,
    /// picked with `probability`.
    Environment(Emission, f32),
}

impl LightPicker {
    /// Light subpaths from the environment too (the light tracer's: bidirectional transport
    /// reaches the environment by its eye subpaths, which escape or sample it).
    pub fn with_environment(lit: &LitScene<'_>) -> Self {
        let mut picker = Self::new(lit);
        let env_flux = lit
            .environment
            .as_ref()
            .map_or(0.0, |e| e.power_lm())
            .max(0.0);
        if !(env_flux.is_finite() && env_flux > 0.0) {
            return picker;
        }
        let lights = picker.cdf.last().copied().unwrap_or(0.0);
        let total = lights + env_flux;
        picker
            .probability
            .iter_mut()
            .for_each(|p| *p = (f64::from(*p) * lights / total) as f32);
        picker.total = total;
        picker.environment = (env_flux / total) as f32;
        picker
    }

    pub fn new(lit: &LitScene<'_>) -> Self {
        let fluxes: Vec<f64> = (0..lit.light_count())
            .map(|i| {
                let flux = lit
                    .light_id(i)
                    .and_then(|id| lit.light(id))
                    .map_or(0.0, |l| l.power_lm());
                if flux > 0.0 && flux.is_finite() {
                    flux
                } else {
                    0.0
                }
            })
            .collect();
        let mut total = 0.0f64;
        let cdf: Vec<f64> = fluxes
            .iter()
            .map(|f| {
                total += f;
                total
            })
            .collect();
        if total <= 0.0 {
            return LightPicker::default();
        }
        LightPicker {
            cdf,
            probability: fluxes.iter().map(|f| (f / total) as f32).collect(),
            total,
            environment: 0.0,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.cdf.is_empty() && self.environment <= 0.0
    }

    /// Picks the environment or a light by flux, then a point and a direction.
    pub fn sample_start(&self, lit: &LitScene<'_>, rng: &mut SampleRng) -> Option<Start> {
        if self.environment > 0.0 {
            let u_pick = rng.next_f32();
            let (u, v) = rng.next_2d();
            let (du, dv) = rng.next_2d();
            let lights = self.cdf.last().copied().unwrap_or(0.0);
            if f64::from(u_pick) * self.total >= lights {
                let e = lit
                    .environment
                    .as_ref()?
                    .sample_emission([u, v], [du, dv])?;
                return Some(Start::Environment(e, self.environment));
            }
            let target = f64::from(u_pick) * self.total;
            return self
                .pick(lit, target, [u, v], [du, dv])
                .map(|(p, e)| Start::Light(p, e));
        }
        self.sample(lit, rng).map(|(p, e)| Start::Light(p, e))
    }

    /// The light whose share of the cumulative flux holds `target` (lm), a point on it and a
    /// direction.
    fn pick(
        &self,
        lit: &LitScene<'_>,
        target: f64,
        u_point: [f32; 2],
        u_dir: [f32; 2],
    ) -> Option<(LightPoint, Emission)> {
        let i = self
            .cdf
            .partition_point(|&c| c <= target)
            .min(self.cdf.len().checked_sub(1)?);
        let id = lit.light_id(i as u32)?;
        let e = lit.light(id)?.sample_emission(u_point, u_dir)?;
        let start = LightPoint {
            light: id,
            p: e.p,
            n: e.n,
            pdf_origin: self.probability[i] * e.pdf_point,
        };
        Some((start, e))
    }

    /// Picks a light by flux, then a point on it and a direction: the start and the direction
    /// with its density per sr.
    pub fn sample(
        &self,
        lit: &LitScene<'_>,
        rng: &mut SampleRng,
    ) -> Option<(LightPoint, Emission)> {
        let last = *self.cdf.last()?;
        let u_pick = rng.next_f32();
        let (u, v) = rng.next_2d();
        let (du, dv) = rng.next_2d();
        self.pick(lit, f64::from(u_pick) * last, [u, v], [du, dv])
    }

    /// Density of picking this light's position (see [`LightPoint::pdf_origin`]).
    pub fn pdf_origin(&self, lit: &LitScene<'_>, light: TreeLight) -> f32 {
        let Some(p) = lit
            .light_index(light)
            .and_then(|i| self.probability.get(i as usize))
        else {
            return 0.0;
        };
        lit.light(light).map_or(0.0, |l| p * l.emission_point_pdf())
    }
}

/// What light `light` sends along unit `dir` from its point `p` (see
/// [`LightSource::emitted`]; an emissive map varies it over a glowing triangle).
#[inline]
pub fn emitted(lit: &LitScene<'_>, light: TreeLight, p: Vec3, dir: Vec3) -> Vec3 {
    let le = lit.light(light).map_or(Vec3::ZERO, |l| l.emitted(dir));
    match light {
        TreeLight::Triangle(t) => le * lit.emission_factor(t, p),
        TreeLight::Placed(_) => le,
    }
}

/// The cosine a light vertex's emission carries along `dir` from a point with normal `n` (1 for
/// point-like lights; see [`LightSource::emission_cosine`]).
#[inline]
pub fn emission_cosine(lit: &LitScene<'_>, light: TreeLight, n: Vec3, dir: Vec3) -> f32 {
    match light {
        TreeLight::Placed(_) if n == Vec3::ZERO => 1.0,
        TreeLight::Placed(_) => lit.light(light).map_or(0.0, |l| l.emission_cosine(n, dir)),
        TreeLight::Triangle(_) => n.dot(dir).abs(),
    }
}

/// Density per sr of a light subpath leaving `light` along unit `dir`.
#[inline]
pub fn direction_pdf(lit: &LitScene<'_>, light: TreeLight, dir: Vec3) -> f32 {
    lit.light(light).map_or(0.0, |l| l.emission_dir_pdf(dir))
}

impl super::Bidirectional<'_, '_> {
    /// Strategy s = 1: a light picked by the light tree for eye vertex `pt`, and a point on it
    /// (uniform on a glowing triangle). Its `pdf_origin` is the tree's probability times the
    /// area density.
    pub(super) fn sample_light_for<S: Scatter>(
        &self,
        pt: &Vertex<S>,
        rng: &mut SampleRng,
    ) -> Option<LightPoint> {
        let lit = self.lit;
        let (id, pmf) = lit.pick_light(pt.p, pt.n, lit.pick_number(rng))?;
        let light = lit.light(id)?;
        let u = if !light.samples_area() {
            [0.5; 2]
        } else {
            let (u, v) = rng.next_2d();
            [u, v]
        };
        let at = Receiver {
            p: pt.p,
            origin: pt.p,
        };
        let s = light.sample_incident(at, u)?;
        Some(LightPoint {
            light: id,
            p: s.target,
            // A luminous body's face, a glowing triangle's front, or zero.
            n: if s.n == Vec3::ZERO {
                light.normal()
            } else {
                s.n
            },
            // (The rest of the choice went to the environment: see `connect_to_light`. A
            // luminous body drew from its faces towards `pt` alone.)
            pdf_origin: pmf * (1.0 - lit.environment_pick()) * light.emission_point_pdf()
                / light.area_share(pt.p),
        })
    }

    /// How much likelier strategy s = 1 makes light vertex `x0` when it joins it to `x1` (the
    /// tree's choice at `x1`) than a light subpath's start does (by flux):
    /// p_tree(x0 | x1) / p_flux(x0).
    pub(super) fn tree_factor<S: Scatter>(&self, x0: &Vertex<S>, x1: &Vertex<S>) -> f32 {
        let light = match x0.kind {
            Kind::Light(l) => l,
            Kind::Surface(prim) => TreeLight::Triangle(prim),
            Kind::Eye | Kind::Environment => return 1.0,
        };
        let flux = self.lights.pdf_origin(self.lit, light);
        if flux <= 0.0 {
            return 1.0;
        }
        let area = self
            .lit
            .light(light)
            .map_or(0.0, |l| l.emission_point_pdf());
        let tree_share = 1.0 - self.lit.environment_pick();
        // A luminous body's s = 1 draws from the faces towards x1 alone (`sample_light_for`).
        let faces = self.lit.light(light).map_or(1.0, |l| l.area_share(x1.p));
        if faces <= 0.0 {
            // Inside the body: s = 1 cannot reach it from x1.
            return 0.0;
        }
        self.lit.light_pmf(x1.p, x1.n, light) * tree_share * area / (flux * faces)
    }
}
