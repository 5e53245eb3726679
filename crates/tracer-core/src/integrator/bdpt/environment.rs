//! The environment in bidirectional transport. A path that ends in it has two strategies: the
//! eye subpath leaves the scene (s = 0), or an eye vertex samples it (s = 1, in the share
//! `LitScene::environment_pick` of the light choice). They are weighted by the power heuristic
//! over those two, as in path mode. The light tracer also starts light subpaths from it (on
//! the disc across the bounding sphere, picked by the flux through it): their surface vertices
//! are joined to the eye (t = 1), which carries every path whose first surface scatters
//! smoothly; the eye subpath's two strategies carry the rest (the sky seen directly or through
//! mirrors and glass).

use super::vertex::{Kind, Vertex};
use super::walk::Escape;
use super::{Bidirectional, Eye};
use crate::light::{LightSource, Receiver};
use crate::sampling::SampleRng;
use crate::shading::Scatter;
use glam::Vec3;

fn power_heuristic(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 { a2 / (a2 + b2) } else { 0.0 }
}

impl Bidirectional<'_, '_> {
    /// Non-delta scattering vertices of an eye subpath.
    fn eye_bounces<S: Scatter>(eye: &[Vertex<S>]) -> u32 {
        eye.iter()
            .filter(|v| matches!(v.kind, Kind::Surface(_)) && v.connectible())
            .count() as u32
    }

    /// s = 0 on the environment: the eye subpath `eye` left the scene as `e` says.
    pub(super) fn hit_environment<S: Scatter>(&self, eye: &[Vertex<S>], e: &Escape) -> Vec3 {
        let Some(env) = &self.lit.environment else {
            return Vec3::ZERO;
        };
        if e.beta.max_element() <= 0.0 {
            return Vec3::ZERO;
        }
        let from_camera = eye.len() == 1 && matches!(self.eye, Eye::Camera(_));
        if from_camera && !env.background {
            return Vec3::ZERO;
        }
        if self.max_bounces != u32::MAX
            && Self::eye_bounces(&eye[1.min(eye.len())..]) > self.max_bounces
        {
            return Vec3::ZERO;
        }
        // The camera and delta lobes cannot sample the environment; a sensor samples all of
        // it (`sensor_environment`), a surface its share of the light choice.
        let w = if e.pdf_dir <= 0.0 || from_camera {
            1.0
        } else {
            power_heuristic(e.pdf_dir, self.lit.environment_pdf(e.dir, eye.len() == 1))
        };
        e.beta * env.radiance(e.dir) * w
    }

    /// s = 1 at a sensor (eye vertex `eye0`, facing `eye0.n`): a direction of the environment,
    /// against the sensor's own cosine-sampled ray (which `hit_environment` weighs).
    pub(super) fn sensor_environment<S: Scatter>(
        &self,
        eye0: &Vertex<S>,
        rng: &mut SampleRng,
        rays: &mut u32,
    ) -> Vec3 {
        let Some(env) = &self.lit.environment else {
            return Vec3::ZERO;
        };
        let (u, v) = rng.next_2d();
        let origin = eye0.p + eye0.n * self.lit.epsilon;
        let at = Receiver { p: eye0.p, origin };
        let Some(s) = env.sample_incident(at, [u, v]) else {
            return Vec3::ZERO;
        };
        let cos = eye0.n.dot(s.wi);
        if cos <= 0.0 || s.pdf <= 0.0 {
            return Vec3::ZERO;
        }
        *rays += 1;
        let through = self.lit.transmittance(origin, s.target - origin);
        if through <= 0.0 {
            return Vec3::ZERO;
        }
        // Importance 1 over the hemisphere: E = ∫ L cos θ dω.
        s.tint
            * (cos / s.pdf)
            * power_heuristic(s.pdf, super::vertex::cosine_pdf(eye0.n, s.wi))
            * through
    }

    /// s = 1 on the environment: a direction sampled for eye vertex `pt`, the environment
    /// having been chosen with probability `pick`.
    pub(super) fn connect_to_environment<S: Scatter>(
        &self,
        pt: &Vertex<S>,
        pick: f32,
        rng: &mut SampleRng,
        rays: &mut u32,
    ) -> Vec3 {
        let Some(env) = &self.lit.environment else {
            return Vec3::ZERO;
        };
        let (u, v) = rng.next_2d();
        let at = Receiver {
            p: pt.p,
            origin: pt.p,
        };
        let Some(s) = env.sample_incident(at, [u, v]) else {
            return Vec3::ZERO;
        };
        let w = s.wi;
        let pdf = s.pdf * pick;
        if pdf <= 0.0 {
            return Vec3::ZERO;
        }
        // The BSDF (with its shading correction) times the geometric cosine: the shading one.
        let c = pt.beta * pt.f(self, w) * s.tint * (pt.n.dot(w).abs() / pdf);
        if c.max_element() <= 0.0 {
            return Vec3::ZERO;
        }
        // Leave from the lifted origin on the side the subpath arrived on, as `visible` does.
        let origin = if pt.ns.dot(w) * pt.ns.dot(pt.wo) > 0.0 {
            pt.origin
        } else {
            pt.p + pt.facing(w) * self.lit.epsilon
        };
        *rays += 1;
        let through = self.lit.transmittance(origin, s.target - origin);
        if through <= 0.0 {
            return Vec3::ZERO;
        }
        c * power_heuristic(pdf, pt.pdf_dir(self, pt.wo, w)) * through
    }
}
