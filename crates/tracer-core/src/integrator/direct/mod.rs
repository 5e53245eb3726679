//! The coursework's model, extended to every light kind: direct light with hard shadows,
//! `L = Σ E · (Kd/π + Ks (g+8)/(8π) (n·h)^g) + Ks · L_reflected`, mirrors traced to a depth
//! limit, and emissive surfaces seen directly or sampled as lights.
//!
//! - Point and spot lights: `E = I(ω) cos θ / R²`, exact, one shadow ray each.
//! - Emissive triangles: one light sample per shading point (an unbiased estimate of their
//!   direct illuminance), picked by flux.
//!
//! Rays are traced as a wavefront ([`trace_batch`]): every camera ray of a batch finds its
//! hit, every hit is shaded and asks for its shadow rays, all shadow rays are traced, and the
//! answers are added in the order a single ray would add them. Independent rays side by side
//! keep the CPU busy where one ray's chain of divisions, square roots and tree steps would
//! stall it, and give the tree rays to trace together. Samples that end at their first hit
//! (a miss, or a surface that neither glows, nor has a highlight, nor mirrors) are shaded
//! eight at a time in vector lanes (`matte`); the others walk. One ray ([`trace`]) is a batch
//! of one, so both give the same samples bit for bit.

mod batch;
mod matte;
mod walk;

pub use batch::{DirectBatch, trace_batch};

use super::{Integrator, IntegratorKind, PathTracer, Sample, Splat, Want};
use crate::geometry::Ray;
use crate::lit_scene::LitScene;
use crate::sampling::SampleRng;
use crate::scene::CameraBasis;
use glam::Vec3;
use std::cell::RefCell;

/// The coursework's model as an integrator.
///
/// Named substitution: a sensor (a grid point) is measured by the path tracer's irradiance
/// estimator cut after its first bounce ([`PathTracer::direct_only`]): the same light as a
/// camera sample's illuminance here (point-like lights exactly, glowing surfaces sampled with
/// MIS), estimated at a point with no surface of its own.
#[derive(Debug)]
pub struct DirectLighting<'a> {
    pub lit: LitScene<'a>,
}

impl Integrator for DirectLighting<'_> {
    fn kind(&self) -> IntegratorKind {
        IntegratorKind::Direct
    }

    fn lit(&self) -> &LitScene<'_> {
        &self.lit
    }

    fn sample_camera(
        &self,
        _basis: &CameraBasis,
        ray: &Ray,
        rng: &mut SampleRng,
        _want: Want,
        _splats: &mut Vec<Splat>,
    ) -> Sample {
        trace(&self.lit, ray, rng)
    }

    fn preview_camera(
        &self,
        _basis: &CameraBasis,
        ray: &Ray,
        rng: &mut SampleRng,
        _illuminance: bool,
    ) -> Sample {
        trace(&self.lit, ray, rng)
    }

    fn illuminance(&self, p: Vec3, n: Vec3, rng: &mut SampleRng) -> (f32, u32) {
        let mut rays = 0;
        let e = PathTracer::direct_only(&self.lit).irradiance(p, n, rng, &mut rays);
        (crate::light::luminance(e), rays)
    }
}

/// Luminance arriving along the camera ray `ray`, with the first hit's direct illuminance.
pub fn trace(lit: &LitScene<'_>, ray: &Ray, rng: &mut SampleRng) -> Sample {
    thread_local! {
        // Working memory reused by single samples (previews, tests), so none allocates.
        static BATCH: RefCell<DirectBatch> = RefCell::new(DirectBatch::default());
    }
    let mut out = [Sample::default()];
    BATCH.with(|batch| {
        let mut batch = batch.borrow_mut();
        trace_batch(lit, &[*ray], |_| rng.clone(), &mut batch, &mut out);
        // Callers that draw more from the stream go on from where the sample left it.
        if let Some(after) = batch.final_rng(0) {
            *rng = after;
        }
    });
    out[0]
}
