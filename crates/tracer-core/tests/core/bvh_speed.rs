//! Build time and W1 throughput (BENCHMARK.md), run by hand in release:
//! `cargo test --release -p tracer-core --test bvh_speed -- --ignored --nocapture`

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::Instant;

use crate::bvh_support::{bounds_of, shared_meshes, w1_rays};
use glam::Vec3;
use rayon::prelude::*;
use tracer_core::bvh::{Bvh, uv_sphere};

const RUNS: usize = 5;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn build_ms(triangles: &[[Vec3; 3]]) -> (Bvh, f64) {
    let mut times = Vec::new();
    let mut bvh = Bvh::default();
    for _ in 0..RUNS {
        let start = Instant::now();
        bvh = Bvh::build(triangles);
        times.push(start.elapsed().as_secs_f64() * 1e3);
    }
    (bvh, median(times))
}

fn w1_mrays(bvh: &Bvh, triangles: &[[Vec3; 3]]) -> (f64, usize) {
    let rays = w1_rays(&bounds_of(triangles));
    let mut rates = Vec::new();
    let mut hits = 0;
    for _ in 0..RUNS {
        let start = Instant::now();
        hits = rays
            .par_chunks(4096)
            .map(|c| c.iter().filter(|r| bvh.intersect(r).is_some()).count())
            .sum();
        rates.push(rays.len() as f64 / start.elapsed().as_secs_f64() / 1e6);
    }
    (median(rates), hits)
}

fn report(name: &str, triangles: &[[Vec3; 3]]) {
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let (bvh, ms) = build_ms(triangles);
            bvh.validate().unwrap();
            let (mrays, hits) = w1_mrays(&bvh, triangles);
            println!(
                "mesh={name} threads={threads} tris={} nodes={} depth={} mem_mb={:.1} build_ms={ms:.1} W1_mrays_per_s={mrays:.2} hits={hits}",
                bvh.triangle_count(),
                bvh.node_count(),
                bvh.depth(),
                bvh.memory_bytes() as f64 / 1e6
            );
        });
    }
}

#[test]
#[ignore = "timing; run in release by hand"]
fn bvh_speed() {
    report("sphere-1000", &uv_sphere(1000));
    for (name, triangles) in shared_meshes() {
        report(&name, &triangles);
    }
}
