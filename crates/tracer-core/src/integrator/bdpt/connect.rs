//! Connecting eye and light subpaths, and the multiple importance sampling weight of each
//! strategy (s light vertices, t eye vertices).

use super::vertex::{Kind, Vertex};
use super::{Bidirectional, Eye, Splat};
use crate::lit_scene::TreeLight;
use crate::sampling::SampleRng;
use crate::shading::Scatter;
use glam::Vec3;

/// The segment of a connection, from its light-side vertex to its eye-side one.
#[derive(Clone, Copy, Debug)]
struct Link {
    /// Unit direction from the light side to the eye side.
    w: Vec3,
    dist2: f32,
}

impl Link {
    fn between<S: Scatter>(a: &Vertex<S>, b: &Vertex<S>) -> Option<Self> {
        let d = b.p - a.p;
        let dist2 = d.length_squared();
        (dist2 > 0.0).then(|| Self {
            w: d / dist2.sqrt(),
            dist2,
        })
    }
}

/// Zero densities (delta vertices) count as 1 in ratios.
fn remap0(x: f32) -> f32 {
    if x != 0.0 { x } else { 1.0 }
}

impl Bidirectional<'_, '_> {
    /// Whether strategy (s, t) takes part: the chosen set, without the camera's t = 1 when
    /// there is no film to splat to (the remaining weights then add up to 1 over the rest).
    fn allowed(&self, s: usize, t: usize) -> bool {
        // The orthographic camera's importance is a delta in direction: no light vertex can be
        // joined to it, and the other strategies share its paths.
        let (splat, eye_point) = match self.eye {
            Eye::Camera(b) => (t == 1, b.has_eye_point()),
            Eye::Sensor => (false, true),
        };
        self.strategies.allowed(s, t) && ((self.splats && eye_point) || !splat)
    }

    /// Sum over every allowed strategy of the weighted contribution to this eye sample; splats
    /// for the camera's t = 1 strategies.
    pub(super) fn connect_all<S: Scatter>(
        &self,
        eye: &[Vertex<S>],
        light: &[Vertex<S>],
        rng: &mut SampleRng,
        splats: &mut Vec<Splat>,
        rays: &mut u32,
    ) -> Vec3 {
        let mut total = Vec3::ZERO;
        // Light tracing: past t = 1 only paths that a delta lobe scattered at the first
        // surface, whose strategies joining at or before that surface are impossible (so the
        // remaining weights add up to 1 over t ≥ 3). t = 2 joins at the first surface's smooth
        // part, which t = 1 carries.
        let eye_strategies = if !self.light_tracing || eye.get(1).is_some_and(|v| v.delta) {
            eye.len()
        } else {
            1
        };
        // A light subpath from the environment (the light tracer's) is joined to the eye by
        // t = 1 alone; every other path that ends in the environment is the eye subpath's
        // (s = 0 and s = 1, weighed over those two: see `environment.rs`).
        let from_environment = light
            .first()
            .is_some_and(|v| matches!(v.kind, Kind::Environment));
        for t in 1..=eye_strategies {
            if self.light_tracing && t == 2 {
                continue;
            }
            // (s = 1 samples a light of its own: it runs even when the light subpath is empty,
            // as in a scene lit by the environment alone.)
            for s in 0..=light.len().max(1) {
                if s + t < 2 || !self.allowed(s, t) {
                    continue;
                }
                if from_environment && s >= 2 && !(self.light_tracing && t == 1) {
                    continue;
                }
                if self.max_bounces != u32::MAX && self.bounces(eye, light, s, t) > self.max_bounces
                {
                    continue;
                }
                if t == 1 {
                    if s > light.len() {
                        continue;
                    }
                    if let Some(splat) = self.connect_to_eye(eye, light, s, rays) {
                        match self.eye {
                            Eye::Camera(_) => splats.push(splat),
                            Eye::Sensor => total += splat.rgb,
                        }
                    }
                    continue;
                }
                total += match s {
                    0 => self.hit_light(eye, t),
                    1 => self.connect_to_light(eye, light, t, rng, rays),
                    _ => self.connect_inner(eye, light, s, t, rays),
                };
            }
        }
        total
    }

    /// Non-delta scattering vertices of the path of strategy (s, t).
    fn bounces<S: Scatter>(
        &self,
        eye: &[Vertex<S>],
        light: &[Vertex<S>],
        s: usize,
        t: usize,
    ) -> u32 {
        let count = |vs: &[Vertex<S>]| {
            vs.iter()
                .filter(|v| matches!(v.kind, Kind::Surface(_)) && v.connectible())
                .count() as u32
        };
        let eye_part = if s == 0 {
            // The last eye vertex is the glowing surface itself.
            count(&eye[1..t.saturating_sub(1).max(1)])
        } else {
            count(&eye[1..t])
        };
        eye_part + count(light.get(1.min(s)..s).unwrap_or(&[]))
    }

    /// s = 0: the eye subpath found a glowing surface.
    fn hit_light<S: Scatter>(&self, eye: &[Vertex<S>], t: usize) -> Vec3 {
        let pt = &eye[t - 1];
        let le = pt.emission(self);
        if le.max_element() <= 0.0 {
            return Vec3::ZERO;
        }
        let c = pt.beta * le;
        c * self.mis_weight(eye, &[], None, 0, t, None)
    }

    /// The share of light that crosses the segment between two vertices: 0 when it is blocked,
    /// the thin panes' transmittance on it, 1 when it is clear.
    fn visible<S: Scatter>(&self, a: &Vertex<S>, b: &Vertex<S>, rays: &mut u32) -> f32 {
        let d = b.p - a.p;
        let lift = |v: &Vertex<S>, towards: Vec3| match v.kind {
            // Towards the side the subpath arrived on, by the shading normal (as next-event
            // estimation decides): from the lifted origin.
            Kind::Surface(_) if v.ns.dot(towards) * v.ns.dot(v.wo) > 0.0 => v.origin,
            Kind::Surface(_) | Kind::Light(TreeLight::Triangle(_)) => {
                v.p + v.facing(towards) * self.lit.epsilon
            }
            Kind::Eye if v.n != Vec3::ZERO && matches!(self.eye, Eye::Sensor) => {
                v.p + v.n * self.lit.epsilon
            }
            _ => v.p,
        };
        let on_a = lift(a, d);
        let on_b = lift(b, -d);
        *rays += 1;
        // From the eye side towards the light side, like next-event estimation: a point light
        // on a surface (a lamp on the ceiling) does not shadow itself, since the ray stops
        // short of its end.
        self.lit.transmittance(on_b, on_a - on_b)
    }

    /// The unweighted contribution of joining light-side `a` to eye-side `b` over `link`
    /// (without visibility): a.β f_a G f_b b.β.
    #[inline(always)]
    fn join<S: Scatter>(&self, a: &Vertex<S>, b: &Vertex<S>, link: Link) -> Vec3 {
        let w = link.w;
        let g = a.cosine(self, w) * b.cosine(self, -w) / link.dist2;
        if g <= 0.0 {
            return Vec3::ZERO;
        }
        a.beta * a.f(self, w) * b.f(self, -w) * b.beta * g
    }

    /// t = 1: light vertex s − 1 seen by the eye (a splat for the camera).
    fn connect_to_eye<S: Scatter>(
        &self,
        eye: &[Vertex<S>],
        light: &[Vertex<S>],
        s: usize,
        rays: &mut u32,
    ) -> Option<Splat> {
        let qs = &light[s - 1];
        if !qs.connectible() {
            return None;
        }
        let e = &eye[0];
        if matches!(self.eye, Eye::Camera(_)) && qs.is_delta_light() {
            return None;
        }
        let mut pixel = (0, 0);
        if let Eye::Camera(b) = self.eye {
            let (x, y) = self.film_position((qs.p - e.p).normalize_or_zero())?;
            pixel = (
                (x as u32).min(b.width.saturating_sub(1)),
                (y as u32).min(b.height.saturating_sub(1)),
            );
        }
        let link = Link::between(qs, e)?;
        let mut c = self.join(qs, e, link);
        if c.max_element() <= 0.0 {
            return None;
        }
        let through = self.visible(qs, e, rays);
        if through <= 0.0 {
            return None;
        }
        c *= through;
        let w = if self.light_tracing {
            1.0
        } else {
            self.mis_weight(eye, light, None, s, 1, Some(link))
        };
        Some(Splat {
            x: pixel.0,
            y: pixel.1,
            rgb: c * w,
        })
    }

    /// s = 1: a light sampled anew for eye vertex t − 1.
    fn connect_to_light<S: Scatter>(
        &self,
        eye: &[Vertex<S>],
        light: &[Vertex<S>],
        t: usize,
        rng: &mut SampleRng,
        rays: &mut u32,
    ) -> Vec3 {
        let pt = &eye[t - 1];
        if !pt.connectible() {
            return Vec3::ZERO;
        }
        let env_pick = self.lit.environment_pick();
        if env_pick > 0.0 && rng.next_f32() < env_pick {
            return if self.light_tracing {
                Vec3::ZERO
            } else {
                self.connect_to_environment(pt, env_pick, rng, rays)
            };
        }
        let Some(start) = self.sample_light_for(pt, rng) else {
            return Vec3::ZERO;
        };
        if start.pdf_origin <= 0.0 {
            return Vec3::ZERO;
        }
        let sampled = Vertex::new(
            Kind::Light(start.light),
            start.p,
            start.n,
            Vec3::splat(1.0 / start.pdf_origin),
            start.pdf_origin,
        );
        let Some(link) = Link::between(&sampled, pt) else {
            return Vec3::ZERO;
        };
        let c = self.join(&sampled, pt, link);
        if c.max_element() <= 0.0 {
            return Vec3::ZERO;
        }
        let through = self.visible(&sampled, pt, rays);
        if through <= 0.0 {
            return Vec3::ZERO;
        }
        let c = c * through;
        c * self.mis_weight(eye, light, Some(&sampled), 1, t, Some(link))
    }

    /// s, t ≥ 2: light vertex s − 1 joined to eye vertex t − 1.
    fn connect_inner<S: Scatter>(
        &self,
        eye: &[Vertex<S>],
        light: &[Vertex<S>],
        s: usize,
        t: usize,
        rays: &mut u32,
    ) -> Vec3 {
        let (qs, pt) = (&light[s - 1], &eye[t - 1]);
        if !qs.connectible() || !pt.connectible() {
            return Vec3::ZERO;
        }
        let Some(link) = Link::between(qs, pt) else {
            return Vec3::ZERO;
        };
        let c = self.join(qs, pt, link);
        if c.max_element() <= 0.0 {
            return Vec3::ZERO;
        }
        let through = self.visible(qs, pt, rays);
        if through <= 0.0 {
            return Vec3::ZERO;
        }
        let c = c * through;
        c * self.mis_weight(eye, light, None, s, t, Some(link))
    }

    /// The power-heuristic weight of strategy (s, t) among the allowed strategies for the same
    /// path, joined over `link` (s ≥ 1). `sampled` stands in for light vertex 0 when s = 1.
    /// Nothing is written: the four densities the connection changes are passed to the ratio
    /// loops as overrides. Each is a direction density at one end of the link or next to it,
    /// turned per area with the link's length or the stored one to the vertex's predecessor.
    #[allow(clippy::too_many_arguments)]
    fn mis_weight<S: Scatter>(
        &self,
        eye: &[Vertex<S>],
        light: &[Vertex<S>],
        sampled: Option<&Vertex<S>>,
        s: usize,
        t: usize,
        link: Option<Link>,
    ) -> f32 {
        let light_at = |i: usize| -> &Vertex<S> {
            match (i, sampled) {
                (0, Some(v)) => v,
                _ => &light[i],
            }
        };
        let pt = &eye[t - 1];
        let pt_minus = (t >= 2).then(|| &eye[t - 2]);
        let qs = (s >= 1).then(|| light_at(s - 1));
        let qs_minus = (s >= 2).then(|| light_at(s - 2));
        // Reverse densities of the vertices next to the connection.
        let (pt_rev, pt_minus_rev, qs_rev, qs_minus_rev) = match (qs, link) {
            (Some(q), Some(l)) => (
                pt.density_from(q.pdf_dir(self, q.wo, l.w), l.dist2, l.w),
                pt_minus
                    .map(|pm| pm.density_from(pt.pdf_dir(self, -l.w, pt.wo), pt.dist2_prev, pt.wo)),
                Some(q.density_from(pt.pdf_dir(self, pt.wo, -l.w), l.dist2, l.w)),
                qs_minus.map(|qm| qm.density_from(q.pdf_dir(self, l.w, q.wo), q.dist2_prev, q.wo)),
            ),
            _ => (
                pt.pdf_light_origin(self),
                pt_minus.map(|pm| pt.pdf_light_back(self, pm)),
                None,
                None,
            ),
        };
        let eye_rev = |i: usize| {
            if i + 1 == t {
                pt_rev
            } else if i + 2 == t {
                pt_minus_rev.unwrap_or(eye[i].pdf_rev)
            } else {
                eye[i].pdf_rev
            }
        };
        // The connection vertices count as non-delta whatever lobe their walk sampled.
        let eye_delta = |i: usize| i + 1 != t && eye[i].delta;
        let light_rev = |i: usize| {
            if i + 1 == s {
                qs_rev.unwrap_or(0.0)
            } else if i + 2 == s {
                qs_minus_rev.unwrap_or(0.0)
            } else {
                light[i].pdf_rev
            }
        };
        let light_delta = |i: usize| i + 1 != s && light_at(i).delta;
        // Strategy s = 1 with t ≥ 2 picks its light with the tree at the vertex it joins (x1),
        // the others start light subpaths by flux: its density is theirs times
        // `tree_factor` = p_tree(x0 | x1) / p_flux(x0). The ratios below are written with the
        // flux density throughout and corrected where strategy 1 appears.
        let tree_factor = if s + t < 3 {
            1.0
        } else {
            match s {
                0 => self.tree_factor(pt, &eye[t - 2]),
                // The tree picked the sampled light for `pt`: its density is the tree's.
                1 => {
                    let q = light_at(0);
                    let flux = q.pdf_light_origin(self);
                    if flux > 0.0 { q.pdf_fwd / flux } else { 1.0 }
                }
                _ => light_at(1).tree_ratio,
            }
        };
        let mut sum = 0.0f32;
        // With s = 1 the path's own density is the tree's: the others' are relative to it.
        let mut ri = if s == 1 && t >= 2 {
            1.0 / tree_factor
        } else {
            1.0
        };
        for i in (1..t).rev() {
            ri *= remap0(eye_rev(i)) / remap0(eye[i].pdf_fwd);
            if !eye_delta(i) && !eye_delta(i - 1) && self.allowed(s + t - i, i) {
                let r = if s + t - i == 1 { ri * tree_factor } else { ri };
                sum += r * r;
            }
        }
        ri = 1.0;
        for i in (0..s).rev() {
            ri *= remap0(light_rev(i)) / remap0(light_at(i).pdf_fwd);
            let before_delta = if i > 0 {
                light_delta(i - 1)
            } else {
                light_at(0).is_delta_light()
            };
            if !light_delta(i) && !before_delta && self.allowed(i, s + t - i) {
                let r = if i == 1 && s >= 2 {
                    ri * tree_factor
                } else {
                    ri
                };
                sum += r * r;
            }
        }
        if !sum.is_finite() {
            return 0.0;
        }
        1.0 / (1.0 + sum)
    }
}
