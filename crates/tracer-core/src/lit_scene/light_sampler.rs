//! One light for a receiving point: a light tree ([`LightTree`]) over every placed light and
//! every glowing triangle picks it, and the light is sampled. Next-event estimation in path mode
//! and bidirectional connections with one light vertex go through here, and the multiple
//! importance sampling weights of glowing surfaces found by chance ask [`LitScene::emitter_pdf`]
//! for the same densities.
//!
//! Light subpaths still start in proportion to flux (`integrator::bdpt::LightPicker`): a start
//! has no receiving point.

use super::LitScene;
use crate::light::{LightBounds, LightTree};
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

/// Light arriving at a receiving point from one sampled light.
#[derive(Clone, Copy, Debug)]
pub struct Incident {
    /// Unit direction from the receiving point towards the light.
    pub wi: Vec3,
    /// The point on the light: shadow rays end there.
    pub target: Vec3,
    /// A placed light: the illuminance at normal incidence per channel, I / R² (lx). A glowing
    /// triangle: its luminance towards the point per channel (cd/m²).
    pub value: Vec3,
    /// The probability of the pick, times the solid-angle density (1/sr) of the point for a
    /// glowing triangle. The estimate is f · value · cos θ / pdf.
    pub pdf: f32,
    /// A placed light is a point: no direction sampled at a surface can find it (no MIS).
    pub delta: bool,
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
    /// glowing triangle.
    #[inline]
    pub fn sample_incident(
        &self,
        p: Vec3,
        origin: Vec3,
        n: Vec3,
        rng: &mut SampleRng,
    ) -> Option<Incident> {
        let (light, pmf) = self.pick_light(origin, n, self.pick_number(rng))?;
        match light {
            TreeLight::Placed(i) => self.placed_incident(i, p, pmf),
            TreeLight::Triangle(t) => {
                let (u, v) = rng.next_2d();
                let index = self.emitters.index_of(t)?;
                let s = self.emitters.sample_on(index, origin, u, v)?;
                Some(Incident {
                    wi: s.wi,
                    target: s.point,
                    value: s.radiance,
                    pdf: pmf * s.pdf_solid_angle,
                    delta: false,
                })
            }
        }
    }

    /// The light of placed light `index` at `p`, as picked with probability `pmf`.
    #[inline]
    fn placed_incident(&self, index: u32, p: Vec3, pmf: f32) -> Option<Incident> {
        let light = self.lights.get(index as usize)?;
        let to_light = light.position - p;
        let dist2 = to_light.length_squared();
        if dist2 <= 0.0 {
            return None;
        }
        let wi = to_light / dist2.sqrt();
        let intensity = light.intensity_towards(-wi);
        Some(Incident {
            wi,
            target: light.position,
            value: light.tint * (intensity / (dist2 * self.metres_per_unit_sq)),
            pdf: pmf,
            delta: true,
        })
    }

    /// The coursework's exact sum instead of one pick: every placed light at `p` (probability
    /// 1 each), then one glowing triangle picked by flux (no tree), each given to `f`. Its MIS
    /// density for glowing surfaces is `emitters.pdf`, not [`LitScene::emitter_pdf`].
    pub fn each_incident(
        &self,
        p: Vec3,
        origin: Vec3,
        rng: &mut SampleRng,
        mut f: impl FnMut(Incident),
    ) {
        for i in 0..self.lights.len() as u32 {
            if let Some(s) = self.placed_incident(i, p, 1.0) {
                f(s);
            }
        }
        if !self.emitters.is_empty() {
            let u_pick = rng.next_f32();
            let (u, v) = rng.next_2d();
            if let Some(s) = self.emitters.sample(origin, u_pick, u, v) {
                f(Incident {
                    wi: s.wi,
                    target: s.point,
                    value: s.radiance,
                    pdf: s.pdf_solid_angle,
                    delta: false,
                });
            }
        }
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
        let pmf = self.light_pmf(origin, n, TreeLight::Triangle(triangle));
        if pmf <= 0.0 {
            return 0.0;
        }
        pmf * self.emitters.pdf_on(triangle, wi, distance)
    }
}
