//! Tracing a workload with one library on a rayon pool of a given size, in chunks of rays, and
//! timing it. Closest-hit and any-hit answers are reduced to hit counts so nothing is optimised
//! away and libraries can be checked against each other.

use std::time::Instant;

use rayon::ThreadPool;
use rayon::prelude::*;
use tracer_core::Ray;

use crate::peers::Accel;
use crate::workloads::PrimaryHit;

/// Rays handed to a worker at a time.
pub const CHUNK: usize = 4096;

/// A workload of BENCHMARK.md.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Workload {
    W1,
    W2,
    W3,
}

impl Workload {
    pub const ALL: [Workload; 3] = [Workload::W1, Workload::W2, Workload::W3];

    pub fn name(self) -> &'static str {
        match self {
            Workload::W1 => "W1",
            Workload::W2 => "W2",
            Workload::W3 => "W3",
        }
    }

    /// W2 asks for any hit; W1 and W3 for the closest.
    pub fn any_hit(self) -> bool {
        self == Workload::W2
    }
}

/// Traces `rays` once; returns the number of rays that hit.
pub fn count_hits<A: Accel>(pool: &ThreadPool, accel: &A, rays: &[Ray], any_hit: bool) -> usize {
    pool.install(|| {
        rays.par_chunks(CHUNK)
            .map(|chunk| {
                if any_hit {
                    chunk.iter().filter(|r| accel.occluded(r)).count()
                } else {
                    chunk.iter().filter(|r| accel.closest(r).is_some()).count()
                }
            })
            .sum()
    })
}

/// One timed pass: (Mrays/s, hits).
pub fn timed_pass<A: Accel>(
    pool: &ThreadPool,
    accel: &A,
    rays: &[Ray],
    any_hit: bool,
) -> (f64, usize) {
    let start = Instant::now();
    let hits = count_hits(pool, accel, rays, any_hit);
    let secs = start.elapsed().as_secs_f64();
    (rays.len() as f64 / secs / 1e6, hits)
}

/// One timed build on `pool`: (structure, milliseconds).
pub fn timed_build<A: Accel>(
    pool: &ThreadPool,
    triangles: &[[glam::Vec3; 3]],
) -> anyhow::Result<(A, f64)> {
    let threads = pool.current_num_threads();
    let start = Instant::now();
    let accel = pool.install(|| A::build(triangles, threads))?;
    Ok((accel, start.elapsed().as_secs_f64() * 1e3))
}

/// The W1 hits that W2 and W3 start from, in ray order.
pub fn primary_hits<A: Accel>(pool: &ThreadPool, accel: &A, rays: &[Ray]) -> Vec<PrimaryHit> {
    pool.install(|| {
        rays.par_iter()
            .filter_map(|ray| {
                accel
                    .closest(ray)
                    .map(|(t, prim)| PrimaryHit { ray: *ray, t, prim })
            })
            .collect()
    })
}

/// A rayon pool of exactly `threads` workers.
pub fn pool(threads: usize) -> anyhow::Result<ThreadPool> {
    Ok(rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|i| format!("raybench-{i}"))
        .build()?)
}

/// The three workloads of a mesh; W2 and W3 start from raygine's W1 hits.
pub fn workloads_for(triangles: &[[glam::Vec3; 3]]) -> anyhow::Result<crate::workloads::Workloads> {
    use crate::peers::raygine::Raygine;
    use crate::workloads::{Frame, W1_SIZE, Workloads, diffuse_rays, primary_rays, shadow_rays};
    let pool = pool(std::thread::available_parallelism().map_or(1, |n| n.get()))?;
    let frame = Frame::of(triangles);
    let (accel, _) = timed_build::<Raygine>(&pool, triangles)?;
    let w1 = primary_rays(&frame, W1_SIZE);
    let hits = primary_hits(&pool, &accel, &w1);
    Ok(Workloads {
        w2: shadow_rays(&frame, triangles, &hits),
        w3: diffuse_rays(&frame, triangles, &hits),
        w1,
    })
}
