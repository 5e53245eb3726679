//! One light for a receiving point: a light tree ([`LightTree`]) over every placed light and
//! every glowing triangle picks it, and the light is sampled. Next-event estimation in path mode
//! and bidirectional connections with one light vertex go through here, and the multiple
//! importance sampling weights of glowing surfaces found by chance ask [`LitScene::emitter_pdf`]
//! for the same densities.
//!
//! Light subpaths still start in proportion to flux (`integrator::bdpt::LightPicker`): a start
//! has no receiving point.

use super::LitScene;
use crate::light::{Incident, LightBounds, LightSource, LightTree, Receiver};
use crate::sampling::SampleRng;
use glam::Vec3;

/// A light of the tree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TreeLight {
    /// A placed light (point, spot, luminaire), by its index in [`LitScene::lights`].
    Placed(u32),
    /// A glowing triangle, by its scene index.
    Triangle(u32),
}

/// The tree over a render's lights: placed lights first, then the emitter table's triangles.
#[derive(Clone, Debug, Default)]
pub struct LightSampler {
    tree: LightTree,
    placed: u32,
}

impl LightSampler {
    pub(super) fn new(placed: Vec<LightBounds>, emitters: Vec<LightBounds>) -> Self {
        let count = placed.len() as u32;
        let mut all = placed;
        all.extend(emitters);
        Self {
            tree: LightTree::new(&all),
            placed: count,
        }
    }

    fn light_of(&self, lit: &LitScene<'_>, item: u32) -> Option<TreeLight> {
        if item < self.placed {
            Some(TreeLight::Placed(item))
        } else {
            lit.emitters
                .triangle_of(item - self.placed)
                .map(TreeLight::Triangle)
        }
    }

    fn item_of(&self, lit: &LitScene<'_>, light: TreeLight) -> Option<u32> {
        match light {
            TreeLight::Placed(i) => (i < self.placed).then_some(i),
            TreeLight::Triangle(t) => lit.emitters.index_of(t).map(|i| i + self.placed),
        }
    }
}

impl LitScene<'_> {
    /// The number of lights: placed lights, then glowing triangles in emitter-table order.
    pub fn light_count(&self) -> u32 {
        self.lights.len() as u32 + self.emitters.len() as u32
    }

    /// Light `index` of [`LitScene::light_count`]'s order.
    #[inline]
    pub fn light_id(&self, index: u32) -> Option<TreeLight> {
        self.light_sampler.light_of(self, index)
    }

    /// The index of `light` in [`LitScene::light_count`]'s order.
    #[inline]
    pub fn light_index(&self, light: TreeLight) -> Option<u32> {
        self.light_sampler.item_of(self, light)
    }

    /// The number [`LitScene::pick_light`] needs, drawn from `rng` (none when there is one
    /// light to pick: a scene with one lamp pays nothing for the tree).
    #[inline]
    pub fn pick_number(&self, rng: &mut SampleRng) -> f32 {
        if self.light_sampler.tree.is_single() {
            0.5
        } else {
            rng.next_f32()
        }
    }

    /// Picks a light for point `p` (unit normal `n`, or zero) with `u`: the light and the
    /// probability of the pick. None when no light can reach `p`.
    #[inline]
    pub fn pick_light(&self, p: Vec3, n: Vec3, u: f32) -> Option<(TreeLight, f32)> {
        let sampler = &self.light_sampler;
        let picked = sampler.tree.sample(p, n, u)?;
        Some((sampler.light_of(self, picked.light)?, picked.pmf))
    }

    /// The probability with which [`LitScene::pick_light`] at (`p`, `n`) picks `light`.
    pub fn light_pmf(&self, p: Vec3, n: Vec3, light: TreeLight) -> f32 {
        let sampler = &self.light_sampler;
        sampler
            .item_of(self, light)
            .map_or(0.0, |item| sampler.tree.pmf(p, n, item))
    }

    /// One light sampled for a surface point `p` with unit normal `n` whose rays leave from
    /// `origin` (the tree and glowing triangles see the point from there, placed lights from
    /// `p`). Draws one number for the pick (none with one light), and two for the point on a
    /// glowing triangle. The incident's `pdf` includes the pick's probability.
    #[inline]
    pub fn sample_incident(
        &self,
        p: Vec3,
        origin: Vec3,
        n: Vec3,
        rng: &mut SampleRng,
    ) -> Option<Incident> {
        let env_pick = self.environment_pick();
        if env_pick > 0.0 && rng.next_f32() < env_pick {
            let env = self.environment.as_ref()?;
            let (u, v) = rng.next_2d();
            let mut s = env.sample_incident(Receiver { p, origin }, [u, v])?;
            s.pdf *= env_pick;
            return Some(s);
        }
        let (id, pmf) = self.pick_light(origin, n, self.pick_number(rng))?;
        let light = self.light(id)?;
        let u = if !light.samples_area() {
            [0.5; 2]
        } else {
            let (u, v) = rng.next_2d();
            [u, v]
        };
        let mut s = light.sample_incident(Receiver { p, origin }, u)?;
        s.pdf *= pmf * (1.0 - env_pick);
        if let TreeLight::Triangle(t) = id {
            s.tint *= self.emission_factor(t, s.target);
        }
        Some(s)
    }

    /// The probability with which [`LitScene::sample_incident`] samples the environment
    /// instead of a light of the tree: none without one, all without other lights, else half
    /// (it has no position for the tree to weigh).
    #[inline]
    pub fn environment_pick(&self) -> f32 {
        match (&self.environment, self.light_sampler.tree.is_empty()) {
            (None, _) => 0.0,
            (Some(_), true) => 1.0,
            (Some(_), false) => 0.5,
        }
    }

    /// Density (1/sr) with which [`LitScene::sample_incident`] reaches the environment along
    /// unit `wi` (`every_light`: [`LitScene::each_incident`]'s).
    pub fn environment_pdf(&self, wi: Vec3, every_light: bool) -> f32 {
        let Some(env) = &self.environment else {
            return 0.0;
        };
        let pick = if every_light {
            1.0
        } else {
            self.environment_pick()
        };
        pick * env.dir_pdf(wi)
    }

    /// The coursework's exact sum instead of one pick: every placed light at `p` (probability
    /// 1 each), then one glowing triangle picked by flux (no tree) and one direction of the
    /// environment, each given to `f`. Its MIS
    /// density for glowing surfaces is [`LitScene::each_incident_pdf`].
    pub fn each_incident(
        &self,
        p: Vec3,
        origin: Vec3,
        rng: &mut SampleRng,
        mut f: impl FnMut(Incident),
    ) {
        let at = Receiver { p, origin };
        for light in &self.lights {
            let u = if light.samples_area() {
                let (u, v) = rng.next_2d();
                [u, v]
            } else {
                [0.5; 2]
            };
            if let Some(s) = light.sample_incident(at, u) {
                f(s);
            }
        }
        if !self.emitters.is_empty() {
            let u_pick = rng.next_f32();
            let (u, v) = rng.next_2d();
            if let Some(s) = self.emitters.sample(origin, u_pick, u, v) {
                let factor = self.emission_factor(s.triangle, s.point);
                let mut incident = Incident::from(s);
                incident.tint *= factor;
                f(incident);
            }
        }
        if let Some(env) = &self.environment {
            let (u, v) = rng.next_2d();
            if let Some(s) = env.sample_incident(at, [u, v]) {
                f(s);
            }
        }
    }

    /// Luminance glowing triangle `prim` sends along unit `dir` from its point `p` (0 when it
    /// does not glow).
    #[inline]
    pub fn glow(&self, prim: u32, p: Vec3, dir: Vec3) -> Vec3 {
        self.light(TreeLight::Triangle(prim))
            .map_or(Vec3::ZERO, |l| l.emitted(dir))
            * self.emission_factor(prim, p)
    }

    /// Density (1/sr) with which [`LitScene::each_incident`] from `origin` reaches glowing
    /// triangle `triangle` along unit `wi` at `distance`.
    pub fn each_incident_pdf(&self, triangle: u32, wi: Vec3, distance: f32) -> f32 {
        self.emitters.pdf(triangle, wi, distance)
    }

    /// Density (1/sr) with which [`LitScene::sample_incident`] from `origin` (normal `n`)
    /// reaches glowing triangle `triangle` along unit `wi` at `distance`.
    pub fn emitter_pdf(
        &self,
        origin: Vec3,
        n: Vec3,
        triangle: u32,
        wi: Vec3,
        distance: f32,
    ) -> f32 {
        let id = TreeLight::Triangle(triangle);
        let pmf = self.light_pmf(origin, n, id) * (1.0 - self.environment_pick());
        if pmf <= 0.0 {
            return 0.0;
        }
        self.light(id)
            .map_or(0.0, |l| pmf * l.incident_pdf(origin, wi, distance))
    }
}
