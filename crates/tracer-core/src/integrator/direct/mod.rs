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

use super::Sample;
use crate::geometry::Ray;
use crate::sampling::SampleRng;
use crate::shading::Prepared;
use std::cell::RefCell;

/// Luminance arriving along the camera ray `ray`, with the first hit's direct illuminance.
pub fn trace(prep: &Prepared<'_>, ray: &Ray, rng: &mut SampleRng) -> Sample {
    thread_local! {
        // Working memory reused by single samples (previews, tests), so none allocates.
        static BATCH: RefCell<DirectBatch> = RefCell::new(DirectBatch::default());
    }
    let mut out = [Sample::default()];
    BATCH.with(|batch| {
        let mut batch = batch.borrow_mut();
        trace_batch(prep, &[*ray], |_| rng.clone(), &mut batch, &mut out);
        // Callers that draw more from the stream go on from where the sample left it.
        if let Some(after) = batch.final_rng(0) {
            *rng = after;
        }
    });
    out[0]
}
