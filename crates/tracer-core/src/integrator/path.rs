//! The path tracer: global illumination, unbiased.
//!
//! - Next-event estimation at every non-delta vertex: one light, placed or glowing triangle,
//!   picked by the light tree for that point (`lit_scene::light_sampler`), one shadow ray;
//!   glowing surfaces are combined with BSDF sampling by multiple importance sampling (power
//!   heuristic), with the tree's probability in both densities. The cost per vertex does not
//!   grow with the number of lights.
//! - Russian roulette instead of a bounce cap: once a path's throughput falls below
//!   [`RR_THRESHOLD`] it survives with probability throughput / threshold and is reweighted, so
//!   the expected value is unchanged. [`MAX_VERTICES`] only guards against lossless enclosures
//!   (reflectance 1), which would never end; a room of reflectance 0.9 reaches it with
//!   probability below 1e-180. Sample 0 of every pixel starts the roulette at once (threshold
//!   1): shorter paths, more noise, the same expected value, so the first full-resolution pass
//!   of the viewer arrives sooner.
//! - `max_bounces` (None: unlimited) counts non-delta scattering events: 1 is direct light
//!   only. Mirror reflections do not count, as in direct mode, whose mirror depth is its own.
//! - Pixel illuminance: the irradiance of the first surface seen, estimated like a sensor (light
//!   sampling with MIS against cosine sampling, and a cosine-sampled path for the rest). On a
//!   purely Lambertian surface the same estimate gives the luminance, `L = Le + Kd/π · E`, so
//!   one path serves both.

use super::{Integrator, IntegratorKind, Sample, Splat, Want};
use crate::geometry::Ray;
use crate::light::Incident;
use crate::light::luminance;
use crate::lit_scene::LitScene;
use crate::sampling::{SampleRng, cosine_hemisphere, to_world};
use crate::scene::CameraBasis;
use crate::shading::{Bsdf, Classic, Scatter, Surface, scatter_at};
use glam::Vec3;
use std::f32::consts::PI;

/// Throughput below which Russian roulette starts.
pub const RR_THRESHOLD: f32 = 0.05;

/// Hard limit on vertices per path (see the module docs).
pub const MAX_VERTICES: u32 = 4096;

/// A surface point a path has reached.
#[derive(Clone, Copy, Debug)]
struct Vertex {
    prim: u32,
    /// Barycentrics (u, v) of the hit on `prim` (textures are read there).
    bary: [f32; 2],
    /// The surface point itself (distances to lights are measured from here).
    point: Vec3,
    /// Origin for rays leaving the facing side.
    origin: Vec3,
    /// Unit shading normal facing `wo`.
    n: Vec3,
    /// Unit geometric normal facing `wo`.
    ng: Vec3,
    /// Unit direction back along the arriving ray.
    wo: Vec3,
}

/// How the ray that arrives at a vertex was chosen, for the MIS weight of emission found there.
#[derive(Clone, Copy, Debug)]
enum Came {
    /// From the camera or a mirror: light sampling could not have produced it.
    Delta,
    /// Sampled with solid-angle density `pdf` at a vertex (shading normal `n`, rays leaving
    /// from the ray's origin) that also sampled the lights.
    Pdf { pdf: f32, n: Vec3 },
}

/// A path tracer over a prepared scene.
#[derive(Clone, Copy, Debug)]
pub struct PathTracer<'p, 'a> {
    pub lit: &'p LitScene<'a>,
    /// Non-delta bounces allowed (u32::MAX: unlimited).
    pub max_bounces: u32,
    /// Throughput below which Russian roulette starts ([`RR_THRESHOLD`]; 1 for the cheaper
    /// first pass, which is just as unbiased).
    pub rr_threshold: f32,
    /// Next-event estimation sums every placed light exactly (the coursework's direct light,
    /// for direct mode's sensors) instead of picking one with the light tree.
    pub every_light: bool,
}

/// Path tracing as an integrator.
#[derive(Debug)]
pub struct PathTracing<'a> {
    pub lit: LitScene<'a>,
    /// Non-delta bounces allowed (None: unlimited).
    pub max_bounces: Option<u32>,
}

impl PathTracing<'_> {
    fn tracer(&self, rr_threshold: f32) -> PathTracer<'_, '_> {
        PathTracer {
            lit: &self.lit,
            max_bounces: self.max_bounces.unwrap_or(u32::MAX),
            rr_threshold,
            every_light: false,
        }
    }
}

impl Integrator for PathTracing<'_> {
    fn kind(&self) -> IntegratorKind {
        IntegratorKind::Path
    }

    fn lit(&self) -> &LitScene<'_> {
        &self.lit
    }

    /// Sample 0 takes the cheaper roulette (see the module docs).
    fn sample_camera(
        &self,
        _basis: &CameraBasis,
        ray: &Ray,
        rng: &mut SampleRng,
        want: Want,
        _splats: &mut Vec<Splat>,
    ) -> Sample {
        let rr = if want.index == 0 { 1.0 } else { RR_THRESHOLD };
        self.tracer(rr).trace(ray, rng, want.illuminance)
    }

    fn preview_camera(
        &self,
        _basis: &CameraBasis,
        ray: &Ray,
        rng: &mut SampleRng,
        illuminance: bool,
    ) -> Sample {
        self.tracer(1.0).trace(ray, rng, illuminance)
    }

    fn illuminance(&self, p: Vec3, n: Vec3, rng: &mut SampleRng) -> (f32, u32) {
        let mut rays = 0;
        let e = self.tracer(RR_THRESHOLD).irradiance(p, n, rng, &mut rays);
        (luminance(e), rays)
    }
}

fn power_heuristic(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 { a2 / (a2 + b2) } else { 0.0 }
}

impl<'p, 'a> PathTracer<'p, 'a> {
    /// Direct light only, as direct mode gives it: one bounce, every placed light exactly,
    /// the roulette as in path mode.
    pub fn direct_only(lit: &'p LitScene<'a>) -> Self {
        PathTracer {
            lit,
            max_bounces: 1,
            rr_threshold: RR_THRESHOLD,
            every_light: true,
        }
    }

    /// Gives `f` the light sampled at a surface point `p` (shading normal `n`, rays from
    /// `origin`): one light from the tree, or every placed light and one glowing triangle.
    #[inline]
    fn incident(
        &self,
        p: Vec3,
        origin: Vec3,
        n: Vec3,
        rng: &mut SampleRng,
        mut f: impl FnMut(Incident),
    ) {
        if self.every_light {
            self.lit.each_incident(p, origin, rng, f);
        } else if let Some(s) = self.lit.sample_incident(p, origin, n, rng) {
            f(s);
        }
    }

    /// Luminance along the camera ray `ray` and, when `illuminance`, the illuminance of the
    /// first surface it meets (free on plain Lambertian surfaces, a path of its own on others,
    /// from a stream of its own: the luminance is the same either way).
    pub fn trace(&self, ray: &Ray, rng: &mut SampleRng, illuminance: bool) -> Sample {
        let mut sample = Sample::default();
        let mut rays = 0u32;
        // Seen through thin panes, everything is weighted by what they let through (the
        // illuminance is the surface's own).
        let (arrival, through) = self.arrive(ray, Came::Delta, rng, &mut rays);
        let Some((v, le)) = arrival else {
            sample.rays = rays;
            match &self.lit.environment {
                // The environment is the background.
                Some(env) if env.background => {
                    sample.rgb = env.radiance(ray.dir.normalize()) * through;
                }
                _ => sample.missed = true,
            }
            return sample;
        };
        let mat = self.lit.material_at(v.prim, v.bary);
        if self.max_bounces == 0 {
            sample.rgb = le * through;
            sample.rays = rays;
            return sample;
        }
        let p = v.point;
        if mat.ks.max_element() <= 0.0
            && mat.kt.max_element() <= 0.0
            && mat.pbr.is_none()
            && mat.pane.is_none()
        {
            let e = self.irradiance_from(p, v.n, v.ng, v.origin, rng, &mut rays);
            sample.rgb = le + mat.kd_over_pi * e;
            sample.illuminance_lx = luminance(e);
        } else {
            let reflected = self.continue_at(v, 0, rng, &mut rays);
            sample.rgb = le + reflected;
            if illuminance {
                let mut own = rng.split(1);
                let e = self.irradiance_from(p, v.n, v.ng, v.origin, &mut own, &mut rays);
                sample.illuminance_lx = luminance(e);
            }
        }
        sample.rgb *= through;
        sample.rays = rays;
        sample
    }

    /// Irradiance (per channel; its luminance is the illuminance in lx) arriving at `p` from
    /// the side of unit normal `n`, counting this point as one bounce. Blocks no light; rays
    /// leave from just above `p` so a surface at `p` does not shadow it.
    pub fn irradiance(&self, p: Vec3, n: Vec3, rng: &mut SampleRng, rays: &mut u32) -> Vec3 {
        let origin = p + n * self.lit.epsilon;
        self.irradiance_from(p, n, n, origin, rng, rays)
    }

    /// [`PathTracer::irradiance`] on a surface with shading normal `n`, geometric normal `ng`
    /// (both facing the same side) and ray origin `origin`.
    fn irradiance_from(
        &self,
        p: Vec3,
        n: Vec3,
        ng: Vec3,
        origin: Vec3,
        rng: &mut SampleRng,
        rays: &mut u32,
    ) -> Vec3 {
        let lit = self.lit;
        let mut e = Vec3::ZERO;
        if self.max_bounces == 0 {
            return e;
        }
        // Lights count by the shading normal (the shadow ray from the lifted origin decides);
        // a sampled continuation must also leave above the triangle.
        let above = |wi: Vec3| ng.dot(wi) > 0.0;
        self.incident(p, origin, n, rng, |s| {
            let cos = n.dot(s.wi);
            if cos > 0.0 && s.tint.max_element() > 0.0 && s.level > 0.0 {
                *rays += 1;
                let through = lit.transmittance(origin, s.target - origin);
                if through > 0.0 {
                    let w = if s.delta {
                        1.0
                    } else {
                        power_heuristic(s.pdf, cos / PI)
                    };
                    e += s.tint * (s.level * cos * w * through / s.pdf);
                }
            }
        });
        let (u, v) = rng.next_2d();
        let wi = to_world(cosine_hemisphere(u, v), n);
        let cos = n.dot(wi);
        if cos > 0.0 && above(wi) {
            // cos θ / pdf = π for cosine sampling.
            let came = Came::Pdf { pdf: cos / PI, n };
            let l_in = self.incoming(&Ray::new(origin, wi), came, 1, rng, rays);
            e += l_in * PI;
        }
        e
    }

    /// Luminance arriving along `ray` (unit direction), which left a vertex after `bounces`
    /// non-delta bounces.
    fn incoming(
        &self,
        ray: &Ray,
        came: Came,
        bounces: u32,
        rng: &mut SampleRng,
        rays: &mut u32,
    ) -> Vec3 {
        match self.arrive(ray, came, rng, rays) {
            (Some((v, le)), w) => (le + self.continue_at(v, bounces, rng, rays)) * w,
            (None, w) => self.escaped(ray.dir.normalize(), came) * w,
        }
    }

    /// The MIS-weighted luminance of the environment seen along unit `dir` by a ray that left
    /// the scene (zero without one).
    fn escaped(&self, dir: Vec3, came: Came) -> Vec3 {
        let Some(env) = &self.lit.environment else {
            return Vec3::ZERO;
        };
        let w = match came {
            Came::Delta => 1.0,
            Came::Pdf { pdf, .. } => {
                power_heuristic(pdf, self.lit.environment_pdf(dir, self.every_light))
            }
        };
        env.radiance(dir) * w
    }

    /// Traces `ray` to the next drawn surface the walk stops at (thin panes on the way may be
    /// passed: `LitScene::closest_through_panes`); returns the vertex and the MIS-weighted
    /// emission seen there, and the weight of the panes passed or stopped at, which multiplies
    /// everything found from here on (the environment too, when the ray leaves).
    fn arrive(
        &self,
        ray: &Ray,
        came: Came,
        rng: &mut SampleRng,
        rays: &mut u32,
    ) -> (Option<(Vertex, Vec3)>, f32) {
        *rays += 1;
        match self.lit.closest_through_panes(ray, rng) {
            (Some(hit), w) => (Some(self.vertex_at(ray, hit, came)), w),
            (None, w) => (None, w),
        }
    }

    /// The vertex `hit` along `ray`, with the MIS-weighted emission seen there.
    fn vertex_at(&self, ray: &Ray, hit: crate::bvh::Hit, came: Came) -> (Vertex, Vec3) {
        let lit = self.lit;
        let dir = ray.dir.normalize();
        let p = ray.at(hit.t);
        let surface = Surface::at(lit, &hit, p, dir);
        let wo = -dir;
        let mat = lit.material_of(hit.prim);
        let mut le = Vec3::ZERO;
        if mat.emission.max_element() > 0.0 {
            let radiance = lit.glow(hit.prim, p, wo);
            let w = match came {
                Came::Delta => 1.0,
                Came::Pdf { pdf, n } => {
                    let distance = hit.t * ray.dir.length();
                    let light_pdf = if self.every_light {
                        lit.each_incident_pdf(hit.prim, dir, distance)
                    } else {
                        lit.emitter_pdf(ray.origin, n, hit.prim, dir, distance)
                    };
                    power_heuristic(pdf, light_pdf)
                }
            };
            le = radiance * w;
        }
        let v = Vertex {
            prim: hit.prim,
            bary: [hit.u, hit.v],
            point: p,
            origin: surface.origin,
            n: surface.ns,
            ng: surface.ng,
            wo,
        };
        (v, le)
    }

    /// Luminance reflected at `v` towards `v.wo`, by a path continued from it; `bounces` is the
    /// number of non-delta bounces before `v`.
    fn continue_at(&self, v: Vertex, bounces: u32, rng: &mut SampleRng, rays: &mut u32) -> Vec3 {
        if self.lit.has_metal_rough() {
            self.continue_with::<Bsdf>(v, bounces, rng, rays)
        } else {
            self.continue_with::<Classic>(v, bounces, rng, rays)
        }
    }

    /// [`PathTracer::continue_at`] with the scattering model `S` (`shading::Scatter`).
    fn continue_with<S: Scatter>(
        &self,
        v: Vertex,
        bounces: u32,
        rng: &mut SampleRng,
        rays: &mut u32,
    ) -> Vec3 {
        let lit = self.lit;
        let mut l = Vec3::ZERO;
        let mut beta = Vec3::ONE;
        let mut v = v;
        let mut bounces = bounces;
        for _ in 0..MAX_VERTICES {
            let bsdf: S = scatter_at(lit, v.prim, v.bary, v.wo, false);
            if bsdf.is_black() {
                break;
            }
            let smooth_allowed = bounces < self.max_bounces;
            if smooth_allowed && bsdf.has_smooth_lobe() {
                l += beta * self.next_event(&bsdf, &v, rng, rays);
            }
            let Some(s) = bsdf.sample(v.n, v.wo, rng) else {
                break;
            };
            if v.ng.dot(s.wi) * v.n.dot(s.wi) < 0.0 {
                // The shading normal sent the path through the mesh: it ends (no leak).
                break;
            }
            if !s.delta {
                if !smooth_allowed {
                    break;
                }
                bounces += 1;
            }
            beta *= s.weight;
            let m = beta.max_element();
            if m.is_nan() || m <= 0.0 || !m.is_finite() {
                break;
            }
            if m < self.rr_threshold {
                let survive = m / self.rr_threshold;
                if rng.next_f32() >= survive {
                    break;
                }
                beta /= survive;
            }
            let came = if s.delta {
                Came::Delta
            } else {
                Came::Pdf { pdf: s.pdf, n: v.n }
            };
            // Refracted rays leave from behind the surface.
            let origin = if v.ng.dot(s.wi) >= 0.0 {
                v.origin
            } else {
                v.point - v.ng * lit.epsilon
            };
            let (arrival, through) = self.arrive(&Ray::new(origin, s.wi), came, rng, rays);
            beta *= through;
            let Some((next, le)) = arrival else {
                l += beta * self.escaped(s.wi.normalize(), came);
                break;
            };
            l += beta * le;
            v = next;
        }
        l
    }

    /// Light sampled at `v` (one light, picked by the light tree) and reflected towards `v.wo`
    /// by the smooth lobes.
    fn next_event<S: Scatter>(
        &self,
        bsdf: &S,
        v: &Vertex,
        rng: &mut SampleRng,
        rays: &mut u32,
    ) -> Vec3 {
        let lit = self.lit;
        let mut l = Vec3::ZERO;
        self.incident(v.point, v.origin, v.n, rng, |s| {
            let cos = v.n.dot(s.wi);
            if cos <= 0.0 || s.value().max_element() <= 0.0 {
                return;
            }
            let f = bsdf.eval(v.n, v.wo, s.wi);
            if f.max_element() <= 0.0 {
                return;
            }
            *rays += 1;
            let through = lit.transmittance(v.origin, s.target - v.origin);
            if through <= 0.0 {
                return;
            }
            let w = if s.delta {
                1.0
            } else {
                power_heuristic(s.pdf, bsdf.pdf(v.n, v.wo, s.wi))
            };
            l += f * s.tint * (s.level * cos * w * through / s.pdf);
        });
        l
    }
}
