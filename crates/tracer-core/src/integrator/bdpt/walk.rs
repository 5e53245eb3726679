//! Random walks: the eye and light subpaths.

use super::emit::{Start, emission_cosine, emitted};
use super::vertex::{Kind, Vertex};
use super::{Bidirectional, MAX_SUBPATH, Subpaths};
use crate::geometry::Ray;
use crate::light::{Emission, LightSource};
use crate::sampling::SampleRng;
use crate::shading::Scatter;
use crate::shading::{Surface, scatter_at};
use glam::Vec3;

impl Bidirectional<'_, '_> {
    /// A light subpath into `paths`: a light picked by flux, a direction, then a walk. Empty
    /// without lights.
    pub fn light_subpath<S: Scatter>(
        &self,
        rng: &mut SampleRng,
        rays: &mut u32,
        paths: &mut Subpaths<S>,
    ) {
        let path = &mut paths.light;
        path.clear();
        let (start, emission) = match self.lights.sample_start(self.lit, rng) {
            Some(Start::Light(start, emission)) => (start, emission),
            Some(Start::Environment(e, probability)) => {
                self.environment_subpath(e, probability, rng, rays, path);
                return;
            }
            None => return,
        };
        if start.pdf_origin <= 0.0 {
            return;
        }
        let beta0 = Vec3::splat(1.0 / start.pdf_origin);
        path.push(Vertex::new(
            Kind::Light(start.light),
            start.p,
            start.n,
            beta0,
            start.pdf_origin,
        ));
        let (dir, pdf_dir) = (emission.dir, emission.pdf_dir);
        if pdf_dir <= 0.0 {
            return;
        }
        let le = emitted(self.lit, start.light, start.p, dir);
        let beta = beta0 * le * (emission_cosine(self.lit, start.light, start.n, dir) / pdf_dir);
        if beta.max_element() <= 0.0 {
            return;
        }
        let origin = if start.n == Vec3::ZERO {
            // A lamp mounted on a surface must not hit that surface at distance 0.
            start.p + dir * self.lit.epsilon
        } else {
            start.p + start.n * (self.lit.epsilon * start.n.dot(dir).signum())
        };
        // (A light subpath that leaves the scene carries nothing further.)
        let _ = self.walk(Ray::new(origin, dir), beta, pdf_dir, true, rng, path, rays);
        if path.len() >= 2 {
            // Once per subpath, for every connection's MIS weight.
            path[1].tree_ratio = self.tree_factor(&path[0], &path[1]);
        }
    }

    /// A light subpath from the environment (the light tracer's): from a point on the disc
    /// across the bounding sphere, along a direction by the map, picked with `probability`.
    /// Its first vertex is not connectible: only its surface vertices are joined to the eye.
    fn environment_subpath<S: Scatter>(
        &self,
        e: Emission,
        probability: f32,
        rng: &mut SampleRng,
        rays: &mut u32,
        path: &mut Vec<Vertex<S>>,
    ) {
        let Some(env) = &self.lit.environment else {
            return;
        };
        let pdf_origin = probability * e.pdf_point;
        if pdf_origin <= 0.0 || e.pdf_dir <= 0.0 {
            return;
        }
        let beta0 = Vec3::splat(1.0 / pdf_origin);
        path.push(Vertex::new(
            Kind::Environment,
            e.p,
            Vec3::ZERO,
            beta0,
            pdf_origin,
        ));
        // The disc faces the direction: no cosine.
        let beta = beta0 * env.emitted(e.dir) / e.pdf_dir;
        if beta.max_element() <= 0.0 {
            return;
        }
        let _ = self.walk(Ray::new(e.p, e.dir), beta, e.pdf_dir, true, rng, path, rays);
    }

    /// Extends `path` from its last vertex along `ray` (unit direction), sampled with density
    /// `pdf_dir` per sr, carrying throughput `beta`. `importance`: a light subpath. Returns how
    /// the subpath left the scene, when it did.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn walk<S: Scatter>(
        &self,
        mut ray: Ray,
        mut beta: Vec3,
        mut pdf_dir: f32,
        importance: bool,
        rng: &mut SampleRng,
        path: &mut Vec<Vertex<S>>,
        rays: &mut u32,
    ) -> Option<Escape> {
        let lit = self.lit;
        let mut relative = Vec3::ONE;
        while path.len() < MAX_SUBPATH {
            *rays += 1;
            // Thin panes on the way are passed or stopped at, weighted (`closest_through_panes`):
            // a passed pane is no vertex, so the densities stay those from the last one.
            let (hit, through) = lit.closest_through_panes(&ray, rng);
            beta *= through;
            let Some(hit) = hit else {
                return Some(Escape {
                    dir: ray.dir.normalize(),
                    beta,
                    pdf_dir,
                });
            };
            let prim = hit.prim;
            let p = ray.at(hit.t);
            let surface = Surface::at(lit, &hit, p, ray.dir);
            // `n` stays the triangle's own normal (emission sides are measured against it).
            let n = lit.scene.normal(prim);
            let mut v = Vertex::new(Kind::Surface(prim), p, n, beta, 0.0);
            v.ns = if surface.ng.dot(n) < 0.0 {
                -surface.ns
            } else {
                surface.ns
            };
            v.origin = surface.origin;
            v.adjoint = importance;
            v.wo = -ray.dir;
            let bsdf = scatter_at::<S>(lit, prim, [hit.u, hit.v], v.wo, importance);
            v.bsdf = Some(bsdf);
            let Some(prev) = path.last() else {
                break;
            };
            v.dist2_prev = (p - prev.p).length_squared();
            v.pdf_fwd = v.density_from(pdf_dir, v.dist2_prev, v.wo);
            path.push(v);
            if path.len() >= MAX_SUBPATH {
                break;
            }
            let nf = v.facing(v.wo);
            let nsf = v.shading_facing(v.wo);
            let Some(s) = bsdf.sample(nsf, v.wo, rng) else {
                break;
            };
            if nf.dot(s.wi) * nsf.dot(s.wi) < 0.0 {
                // The shading normal sent the subpath through the mesh: it ends (no leak).
                break;
            }
            if self.light_tracing && !importance && path.len() == 2 && !s.delta {
                // Light tracing: light vertices joined to the eye carry every path whose first
                // surface scatters smoothly.
                break;
            }
            let k = path.len() - 1;
            let pdf_rev_dir = if s.delta {
                path[k].delta = true;
                pdf_dir = 0.0;
                0.0
            } else {
                pdf_dir = s.pdf;
                bsdf.pdf(v.shading_facing(s.wi), s.wi, v.wo)
            };
            let here = path[k];
            path[k - 1].pdf_rev = path[k - 1].density_from(pdf_rev_dir, here.dist2_prev, here.wo);
            // A light subpath's adjoint BSDF with a shading normal (Veach §5.3):
            // |ns·wo| |ng·wi| / (|ng·wo| |ns·wi|), which goes to 0 as wi grazes the geometric
            // surface. (Written as the ratio of two corrections with a floor under the second,
            // it jumped to 10⁶ there instead: the fireflies of BENCHMARK.md G1, from the
            // Cornell box's smoothed walls.)
            let weight = if importance && nsf != nf && !s.delta {
                s.weight * adjoint_correction(nsf, nf, v.wo, s.wi)
            } else {
                s.weight
            };
            beta *= weight;
            relative *= weight;
            let m = relative.max_element();
            if m.is_nan() || m <= 0.0 || !m.is_finite() {
                break;
            }
            // No roulette at mirrors and glass: refraction's (η_o / η_i)² is not a loss.
            if !s.delta && m < self.rr_threshold {
                let survive = m / self.rr_threshold;
                if rng.next_f32() >= survive {
                    break;
                }
                beta /= survive;
                relative /= survive;
            }
            let origin = if nf.dot(s.wi) >= 0.0 {
                v.origin
            } else {
                p - nf * lit.epsilon
            };
            ray = Ray::new(origin, s.wi);
        }
        None
    }
}

/// A subpath that left the scene: along unit `dir`, with throughput `beta`, sampled with
/// density `pdf_dir` per sr at its last vertex (0 after a delta lobe).
#[derive(Clone, Copy, Debug)]
pub(super) struct Escape {
    pub dir: Vec3,
    pub beta: Vec3,
    pub pdf_dir: f32,
}

/// The factor Veach's adjoint BSDF (§5.3) puts on a light subpath's sampled weight at a
/// surface with shading normal `ns` and geometric normal `ng`, for light arriving from `wo` and
/// leaving along `wi`: |ns·wo| |ng·wi| / (|ng·wo| |ns·wi|); 0 when the denominator vanishes.
pub(super) fn adjoint_correction(ns: Vec3, ng: Vec3, wo: Vec3, wi: Vec3) -> f32 {
    let den = ng.dot(wo).abs() * ns.dot(wi).abs();
    if den > 0.0 {
        ns.dot(wo).abs() * ng.dot(wi).abs() / den
    } else {
        0.0
    }
}
