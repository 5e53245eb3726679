//! A library in a side-by-side run: builds and traces behind a trait object so runs can be
//! interleaved (raygine, peer, raygine, peer ...), while the ray loops stay monomorphic.

use anyhow::Context;
use glam::Vec3;
use rayon::ThreadPool;
use tracer_core::Ray;

use crate::peers::Accel;
use crate::report::{Figure, emit};
use crate::stats::median;
use crate::trace::{Workload, timed_build, timed_pass};
use crate::workloads::Workloads;

pub trait Contender {
    fn lib(&self) -> &'static str;
    /// Drops the built structure, then builds a new one; returns milliseconds.
    fn rebuild(&mut self, pool: &ThreadPool, triangles: &[[Vec3; 3]]) -> anyhow::Result<f64>;
    /// One timed pass over `rays`: (Mrays/s, hits).
    fn pass(&self, pool: &ThreadPool, rays: &[Ray], any_hit: bool) -> anyhow::Result<(f64, usize)>;
    fn memory_bytes(&self) -> Option<usize>;
    fn clear(&mut self);
}

/// A contender for library `A`.
#[derive(Debug)]
pub struct Lib<A: Accel>(Option<A>);

impl<A: Accel> Lib<A> {
    pub fn boxed() -> Box<dyn Contender>
    where
        A: 'static,
    {
        Box::new(Self(None))
    }
}

impl<A: Accel> Contender for Lib<A> {
    fn lib(&self) -> &'static str {
        A::NAME
    }

    fn rebuild(&mut self, pool: &ThreadPool, triangles: &[[Vec3; 3]]) -> anyhow::Result<f64> {
        self.0 = None;
        let (accel, ms) = timed_build::<A>(pool, triangles)?;
        self.0 = Some(accel);
        Ok(ms)
    }

    fn pass(&self, pool: &ThreadPool, rays: &[Ray], any_hit: bool) -> anyhow::Result<(f64, usize)> {
        let accel = self.0.as_ref().context("traced before building")?;
        Ok(timed_pass(pool, accel, rays, any_hit))
    }

    fn memory_bytes(&self) -> Option<usize> {
        self.0.as_ref().and_then(A::memory_bytes)
    }

    fn clear(&mut self) {
        self.0 = None;
    }
}

/// Builds and traces one mesh with every contender on `pool`, `runs` interleaved rounds per
/// figure; prints each median as it is known and returns them.
pub fn measure(
    contenders: &mut [Box<dyn Contender>],
    pool: &ThreadPool,
    mesh: &str,
    triangles: &[[Vec3; 3]],
    workloads: &Workloads,
    runs: usize,
) -> anyhow::Result<Vec<Figure>> {
    let threads = pool.current_num_threads();
    let mut figures = Vec::new();
    let mut record = |kind: &str, lib: &str, samples: &[f64]| {
        let f = Figure {
            kind: kind.to_owned(),
            mesh: mesh.to_owned(),
            lib: lib.to_owned(),
            threads,
            value: median(samples),
        };
        emit(&f.line());
        figures.push(f);
    };
    let mut builds = vec![Vec::new(); contenders.len()];
    for _ in 0..runs {
        for (c, times) in contenders.iter_mut().zip(&mut builds) {
            times.push(c.rebuild(pool, triangles)?);
        }
    }
    for (c, times) in contenders.iter().zip(&builds) {
        record("build", c.lib(), times);
    }
    for workload in Workload::ALL {
        let rays = match workload {
            Workload::W1 => &workloads.w1,
            Workload::W2 => &workloads.w2,
            Workload::W3 => &workloads.w3,
        };
        let mut rates = vec![Vec::new(); contenders.len()];
        let mut hits = vec![0usize; contenders.len()];
        for _ in 0..runs {
            for (i, c) in contenders.iter().enumerate() {
                let (mrays, h) = c.pass(pool, rays, workload.any_hit())?;
                rates[i].push(mrays);
                hits[i] = h;
            }
        }
        for (i, c) in contenders.iter().enumerate() {
            record(workload.name(), c.lib(), &rates[i]);
            check_hits(workload, mesh, c.lib(), hits[0], hits[i], rays.len());
        }
    }
    Ok(figures)
}

/// Warns when a library's hit count strays from raygine's (the first contender) by more than
/// what edge cases of different triangle tests explain.
fn check_hits(
    workload: Workload,
    mesh: &str,
    lib: &str,
    reference: usize,
    hits: usize,
    rays: usize,
) {
    let diff = reference.abs_diff(hits) as f64 / rays.max(1) as f64;
    if diff > 1e-3 {
        eprintln!(
            "warning: {} mesh={mesh} lib={lib}: {hits} hits, raygine {reference} of {rays} rays",
            workload.name()
        );
    }
}
