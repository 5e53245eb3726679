//! The wavefront: a batch of camera samples walks its mirror chains in lockstep, one stage at a
//! time over every walk still going (closest hits, shading, shadow rays, adding up).

use super::super::Sample;
use super::walk::{Contribution, Walk};
use crate::bvh::Hit;
use crate::geometry::Ray;
use crate::sampling::SampleRng;
use crate::shading::Prepared;

/// Working memory of [`trace_batch`], kept between batches so a render allocates it once per
/// thread.
#[derive(Debug, Default)]
pub struct DirectBatch {
    walks: Vec<Walk>,
    /// Indices of the walks still going.
    active: Vec<u32>,
    /// The active walks' mirror rays (after the first step), and the closest hits.
    rays: Vec<Ray>,
    hits: Vec<Option<Hit>>,
    shadows: Vec<Ray>,
    contributions: Vec<Contribution>,
    blocked: Vec<bool>,
}

impl DirectBatch {
    /// The random stream of walk `i` of the last batch, as the walk left it.
    pub fn final_rng(&self, i: usize) -> SampleRng {
        self.walks[i].rng.clone()
    }
}

/// Traces the camera samples `rays` (each with its random stream, `rngs[i]` for `rays[i]`)
/// and writes what each sees to `out` (as long as `rays`): the same samples, bit for bit, as
/// tracing them one by one.
pub fn trace_batch(
    prep: &Prepared<'_>,
    rays: &[Ray],
    rngs: &[SampleRng],
    batch: &mut DirectBatch,
    out: &mut [Sample],
) {
    debug_assert!(rays.len() == out.len() && rays.len() == rngs.len());
    // Walks are restarted in place, field by field: building each on the stack and copying
    // it in made the CPU read back stores it could not forward (a tenth of a frame).
    batch.walks.truncate(rays.len());
    batch.walks.resize_with(rays.len(), Walk::default);
    for (walk, rng) in batch.walks.iter_mut().zip(rngs) {
        walk.restart(rng);
    }
    batch.active.clear();
    batch.active.extend(0..rays.len() as u32);
    // The camera rays are traced from the caller's slice; mirror rays from `batch.rays`.
    let mut first = true;
    while !batch.active.is_empty() {
        let walks = &mut batch.walks;
        let current: &[Ray] = if first { rays } else { &batch.rays };
        batch.hits.clear();
        batch.hits.resize(current.len(), None);
        prep.closest_visible_many(current, &mut batch.hits);
        batch.shadows.clear();
        batch.contributions.clear();
        for ((&i, &hit), ray) in batch.active.iter().zip(&batch.hits).zip(current) {
            walks[i as usize].shade(prep, ray, hit, &mut batch.shadows, &mut batch.contributions);
        }
        batch.blocked.clear();
        batch.blocked.resize(batch.shadows.len(), false);
        prep.occluded_many(&batch.shadows, &mut batch.blocked);
        batch.active.retain(|&i| {
            let walk = &mut walks[i as usize];
            walk.resolve(&batch.contributions, &batch.blocked);
            walk.advance()
        });
        batch.rays.clear();
        batch
            .rays
            .extend(batch.active.iter().map(|&i| walks[i as usize].next_ray));
        first = false;
    }
    for (o, walk) in out.iter_mut().zip(&batch.walks) {
        *o = walk.sample;
    }
}
