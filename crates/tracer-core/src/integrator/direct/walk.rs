//! One camera sample's walk along its mirror chain, in steps a wavefront can interleave:
//! [`Walk::shade`] at a hit asks for shadow rays and keeps each light's contribution aside,
//! [`Walk::resolve`] adds those whose shadow ray was free, [`Walk::advance`] turns to the mirror
//! direction. The arithmetic and its order are the model's, whatever the batch.

use super::super::Sample;
use crate::bvh::Hit;
use crate::geometry::Ray;
use crate::lit_scene::LitScene;
use crate::sampling::{SampleRng, frame_from_normal};
use crate::shading::{PreparedMaterial, Surface};
use glam::Vec3;

/// What one light adds at a hit when its shadow ray is free: illuminance (lx) and reflected
/// luminance per channel (before the mirror chain's weight).
#[derive(Clone, Copy, Debug)]
pub struct Contribution {
    pub illuminance_lx: f32,
    pub rgb: Vec3,
}

/// One camera sample on its way (kept small: a batch holds hundreds, rewritten every batch).
#[derive(Clone, Debug)]
pub struct Walk {
    pub rng: SampleRng,
    pub sample: Sample,
    /// Throughput: the product of Ks along the mirror chain so far.
    weight: Vec3,
    /// The mirror ray to follow after this hit and its weight there (when `continues`).
    pub next_ray: Ray,
    next_weight: Vec3,
    continues: bool,
    depth: u32,
    /// Thin panes passed since the last hit that counted as a step of the chain, and whether
    /// the ray to follow goes on through one.
    panes_passed: u8,
    passing: bool,
    /// The contributions of the current hit: `pending .. pending + pending_len` of the batch's
    /// shadow rays.
    pub pending: u32,
    pub pending_len: u32,
}

impl Default for Walk {
    fn default() -> Self {
        Self {
            rng: SampleRng::new(0, 0),
            sample: Sample::default(),
            weight: Vec3::ONE,
            next_ray: Ray::new(Vec3::ZERO, Vec3::Z),
            next_weight: Vec3::ZERO,
            continues: false,
            depth: 0,
            panes_passed: 0,
            passing: false,
            pending: 0,
            pending_len: 0,
        }
    }
}

impl Walk {
    /// Starts this walk over as a camera sample with the random stream `rng` (its ray is the
    /// batch's).
    #[inline(always)]
    pub fn restart(&mut self, rng: SampleRng) {
        self.rng = rng;
        self.sample = Sample::default();
        self.weight = Vec3::ONE;
        self.depth = 0;
        self.panes_passed = 0;
        self.passing = false;
    }

    /// Shades the closest hit `hit` of the walk's current ray `ray` (None: a miss): emission
    /// seen, the lights' shadow rays pushed to `shadows` with their contributions to
    /// `contributions`, and the mirror ray to follow. (Inlined: out of line, its vector
    /// arguments and the frame went through memory, +5 % on a mirror box.)
    #[inline(always)]
    pub fn shade(
        &mut self,
        lit: &LitScene<'_>,
        ray: &Ray,
        hit: Option<Hit>,
        shadows: &mut Vec<Ray>,
        contributions: &mut Vec<Contribution>,
    ) {
        self.pending = shadows.len() as u32;
        self.pending_len = 0;
        self.continues = false;
        self.sample.rays += 1;
        let Some(hit) = hit else {
            // The environment: the background seen from the camera (unless the backdrop is
            // kept), and always in mirrors.
            match &lit.environment {
                Some(env) if self.depth > 0 || env.background => {
                    self.sample.rgb += self.weight * env.radiance(ray.dir.normalize());
                }
                _ => self.sample.missed = self.depth == 0,
            }
            return;
        };
        let ray = *ray;
        let p = ray.at(hit.t);
        let surface = Surface::at(lit, &hit, p, ray.dir);
        let n = surface.ns;
        let mat = lit.material_at(hit.prim, [hit.u, hit.v]);
        if let Some(pane) = &mat.pane {
            // A window is looked through: the ray goes on along its line, weighted by T(θ),
            // without counting as a step of the mirror chain (direct mode leaves the pane's
            // reflection out).
            let length = ray.dir.length();
            let t = pane.transmittance(surface.ng.dot(ray.dir).abs() / length);
            let weight = self.weight * t;
            if weight.max_element() > 0.0 && self.panes_passed < 32 {
                self.next_ray = Ray {
                    t_min: hit.t + lit.epsilon / length,
                    ..ray
                };
                self.next_weight = weight;
                self.continues = true;
                self.panes_passed += 1;
                self.passing = true;
            }
            return;
        }
        // Towards the viewer; only emission and highlights need it (a square root and a
        // division per hit saved on matte surfaces).
        let view = || -ray.dir.normalize();
        if mat.emission.max_element() > 0.0 {
            self.sample.rgb += self.weight * lit.glow(hit.prim, p, view());
        }
        let before = shadows.len();
        direct_light(
            lit,
            &mat,
            &surface,
            view,
            &mut self.rng,
            shadows,
            contributions,
        );
        self.pending_len = (shadows.len() - before) as u32;
        self.sample.rays += self.pending_len;
        if self.depth == lit.max_depth {
            return;
        }
        let d = ray.dir.normalize();
        // The mirror: Ks, or a smooth metallic-roughness surface's specular layer.
        let reflectance = match &mat.pbr {
            None => mat.ks,
            Some(m) if m.smooth => m.mirror_reflectance(-d.dot(n)),
            Some(_) => Vec3::ZERO,
        };
        let weight = self.weight * reflectance;
        if weight.max_element() <= 0.0 {
            return;
        }
        let reflected = d - n * (2.0 * d.dot(n));
        if surface.ng.dot(reflected) <= 0.0 {
            // The shading normal bent the mirror direction into the mesh: it ends here.
            return;
        }
        self.next_ray = Ray::new(surface.origin, reflected);
        self.next_weight = weight;
        self.continues = true;
    }

    /// Adds the contributions of the current hit whose shadow rays were not `blocked`, times
    /// what thin panes let `through` (all indexed like the batch's shadow rays), in the order
    /// the lights were visited.
    pub fn resolve(&mut self, contributions: &[Contribution], blocked: &[bool], through: &[f32]) {
        let range = self.pending as usize..(self.pending + self.pending_len) as usize;
        let mut direct = Vec3::ZERO;
        let mut e_total = 0.0;
        let passes = blocked[range.clone()].iter().zip(&through[range.clone()]);
        for (c, (&b, &t)) in contributions[range].iter().zip(passes) {
            if !b {
                e_total += c.illuminance_lx * t;
                direct += c.rgb * t;
            }
        }
        if self.depth == 0 {
            self.sample.illuminance_lx = e_total;
        }
        self.sample.rgb += self.weight * direct;
    }

    /// Turns to the mirror ray ([`Walk::next_ray`]) after [`Walk::resolve`]; false when the
    /// walk has ended.
    pub fn advance(&mut self) -> bool {
        if !self.continues {
            return false;
        }
        self.weight = self.next_weight;
        if self.passing {
            // Through a pane: the same step of the chain.
            self.passing = false;
        } else {
            self.depth += 1;
            self.panes_passed = 0;
        }
        true
    }
}

/// The lights' shadow rays at a hit and what each adds when free: point-like lights in order,
/// then one sample of the emissive triangles.
#[inline(always)]
fn direct_light(
    lit: &LitScene<'_>,
    mat: &PreparedMaterial,
    surface: &Surface,
    view: impl Fn() -> Vec3,
    rng: &mut SampleRng,
    shadows: &mut Vec<Ray>,
    contributions: &mut Vec<Contribution>,
) {
    let (p, n, origin) = (surface.p, surface.ns, surface.origin);
    let view = (mat.glossiness > 0.0 || mat.pbr.is_some()).then(view);
    // A metallic-roughness surface evaluates its BSDF (glTF's model) for every light, in the
    // normal's frame; a smooth one only its diffuse base (its mirror is followed as a ray).
    let metal_rough = mat.pbr.zip(view.as_ref()).map(|(m, view)| {
        let (t, b) = frame_from_normal(n);
        let local = move |w: Vec3| Vec3::new(w.dot(t), w.dot(b), w.dot(n));
        (m, local(*view), local)
    });
    let brdf = |wi: Vec3| {
        if let Some((m, wo, local)) = &metal_rough {
            let wi = local(wi);
            return if m.smooth {
                m.eval_base(*wo, wi)
            } else {
                m.eval(*wo, wi)
            };
        }
        let mut f = mat.kd_over_pi;
        if let Some(view) = view {
            let h = (wi + view).normalize_or_zero();
            let n_dot_h = n.dot(h).max(0.0);
            f += mat.ks * (mat.highlight_norm * n_dot_h.powf(mat.glossiness));
        }
        f
    };
    // Every placed light, then one glowing triangle, all seen from `p`.
    lit.each_incident(p, p, rng, |s| {
        let cos_theta = n.dot(s.wi);
        if s.delta {
            // E = I cos θ / R², R in metres (the incident's pdf is R²).
            if cos_theta <= 0.0 || s.level <= 0.0 || !surface.lit_from(s.wi) {
                return;
            }
            let e = s.level * cos_theta / s.pdf;
            shadows.push(LitScene::shadow_ray(origin, s.target - origin));
            contributions.push(Contribution {
                illuminance_lx: e,
                rgb: s.tint * e * brdf(s.wi),
            });
        } else if surface.lit_from(s.wi) && s.tint.max_element() > 0.0 {
            // dE = L cos θ dω: the sample estimates ∫ L cos θ dω over the emitters.
            let e_rgb = s.tint * (cos_theta / s.pdf);
            shadows.push(LitScene::shadow_ray(origin, s.target - origin));
            contributions.push(Contribution {
                illuminance_lx: crate::light::luminance(e_rgb),
                rgb: e_rgb * brdf(s.wi),
            });
        }
    });
}
