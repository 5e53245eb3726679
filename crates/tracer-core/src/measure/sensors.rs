//! Measuring grids: each sensor point's illuminance is the mean of independent estimates by the
//! integrator's irradiance estimator, summed exactly (fixed point) with their squares for the
//! standard error.

use super::grid::Grid;
use crate::integrator::{Integrator, IntegratorKind, Sample};
use crate::render::PixelSum;
use crate::sampling::SampleRng;
use crate::scene::{Scene, Setup};
use crate::shading::Prepared;
use glam::Vec3;
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// How to measure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeasureSettings {
    pub integrator: IntegratorKind,
    pub max_bounces: Option<u32>,
    /// Estimates per point (a cap when `time_limit` is set).
    pub samples: u32,
    /// Stop after this long (checked between rounds of samples).
    pub time_limit: Option<Duration>,
}

/// One point's reading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointResult {
    pub i: u32,
    pub j: u32,
    /// Position in the scene unit.
    pub position: Vec3,
    pub illuminance_lx: f64,
    /// Standard error of `illuminance_lx` (lx).
    pub std_error_lx: f64,
}

/// One grid's readings.
#[derive(Clone, Debug, PartialEq)]
pub struct GridResult {
    pub name: String,
    pub normal: Vec3,
    pub points: Vec<PointResult>,
    /// Estimates per point.
    pub samples: u32,
    pub rays: u64,
}

/// Stream keys of sensors: apart from every pixel's (pixel keys are below 2^48).
fn sensor_key(grid: usize, point: usize) -> u64 {
    (1 << 63) | ((grid as u64) << 32) | point as u64
}

/// Samples per round between time checks.
const ROUND: u32 = 16;

/// Measures every grid of `setup` on the current rayon pool. Each estimate depends on (grid,
/// point, sample index) only: the same for any thread count.
pub fn measure_grids(scene: &Scene, setup: &Setup, settings: &MeasureSettings) -> Vec<GridResult> {
    let started = Instant::now();
    let prep = Prepared::new(scene, setup, crate::render::DEFAULT_MAX_DEPTH);
    let integrator = Integrator::new(settings.integrator, prep, settings.max_bounces);
    let points: Vec<(usize, usize, super::SensorPoint)> = setup
        .grids
        .iter()
        .enumerate()
        .flat_map(|(g, grid)| grid.points().enumerate().map(move |(k, p)| (g, k, p)))
        .collect();
    let mut sums = vec![PixelSum::default(); points.len()];
    let mut rays_total = 0u64;
    let cap = settings.samples.max(1);
    let mut done = 0u32;
    while done < cap {
        let end = (done + ROUND).min(cap);
        rays_total += sums
            .par_iter_mut()
            .zip(&points)
            .map(|(sum, (g, k, p))| {
                let mut rays = 0u64;
                for s in done..end {
                    let mut rng = SampleRng::new(sensor_key(*g, *k), s);
                    let (e, r) = integrator.illuminance(p.position, p.normal, &mut rng);
                    rays += u64::from(r);
                    // The luminance of a grey triple is its value: the squared sums are E².
                    sum.add(&Sample {
                        rgb: Vec3::splat(e),
                        illuminance_lx: e,
                        rays: r,
                    });
                }
                rays
            })
            .sum::<u64>();
        done = end;
        if settings
            .time_limit
            .is_some_and(|limit| started.elapsed() >= limit)
        {
            break;
        }
    }
    let mut results: Vec<GridResult> = setup
        .grids
        .iter()
        .map(|g: &Grid| GridResult {
            name: g.name.clone(),
            normal: Vec3::from(g.normal),
            points: Vec::with_capacity(g.point_count()),
            samples: done,
            rays: 0,
        })
        .collect();
    for ((g, _, p), sum) in points.iter().zip(&sums) {
        results[*g].points.push(PointResult {
            i: p.i,
            j: p.j,
            position: p.position,
            illuminance_lx: sum.mean_luminance(),
            std_error_lx: sum.luminance_std_error().unwrap_or(f64::NAN),
        });
    }
    let total_points = points.len().max(1) as u64;
    for r in &mut results {
        r.rays = rays_total * r.points.len() as u64 / total_points;
    }
    results
}

impl GridResult {
    /// Mean illuminance over the points (lx).
    pub fn mean_lx(&self) -> f64 {
        self.points.iter().map(|p| p.illuminance_lx).sum::<f64>() / self.points.len().max(1) as f64
    }
}
