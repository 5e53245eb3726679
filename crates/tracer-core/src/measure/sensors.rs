//! Measuring grids: each sensor point's illuminance is the mean of independent estimates by the
//! integrator's irradiance estimator, summed exactly (fixed point) with their squares for the
//! standard error.

use super::grid::{Grid, SensorPoint};
use super::sensor_sum::SensorSum;
use crate::integrator::{Integrator, IntegratorKind, IntegratorSettings};
use crate::lit_scene::LitScene;
use crate::sampling::SampleRng;
use crate::scene::{Scene, Setup};
use glam::Vec3;
use rayon::prelude::*;
use std::ops::Range;
use std::time::{Duration, Instant};

/// How to measure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeasureSettings {
    pub integrator: IntegratorKind,
    pub max_bounces: Option<u32>,
    /// Estimates per point (a cap when `time_limit` or `target_error` is set).
    pub samples: u32,
    /// Stop after this long (checked between rounds of samples).
    pub time_limit: Option<Duration>,
    /// Stop once every point's standard error is at most this fraction of
    /// max(E_i, 0.1 × Eavg of its grid), after at least [`TARGET_MIN_SAMPLES`].
    pub target_error: Option<f64>,
}

/// Samples every point takes before `target_error` may stop a measurement.
pub const TARGET_MIN_SAMPLES: u32 = 64;

/// Progress of a measurement, for progress bars.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeasureProgress {
    pub samples_done: u32,
    pub samples_cap: u32,
    pub elapsed_secs: f64,
    /// The largest standard error relative to its point's target scale (1 = at the target).
    pub worst_relative_error: Option<f64>,
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
    /// Inside or under an object (see [`super::is_buried`]): left out of the statistics.
    pub buried: bool,
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
    measure_grids_with_progress(scene, setup, settings, &mut |_| true)
}

type Points = Vec<(usize, usize, SensorPoint)>;

/// Every point of every grid in measuring order: (grid, point index, point).
fn sensor_points(grids: &[Grid]) -> Points {
    grids
        .iter()
        .enumerate()
        .flat_map(|(g, grid)| grid.points().enumerate().map(move |(k, p)| (g, k, p)))
        .collect()
}

fn integrator_for<'a>(
    scene: &'a Scene,
    setup: &Setup,
    settings: &MeasureSettings,
) -> Box<dyn Integrator + 'a> {
    let lit = LitScene::new(scene, setup, crate::render::DEFAULT_MAX_DEPTH);
    let integrator = IntegratorSettings {
        max_bounces: settings.max_bounces,
    };
    crate::integrator::build(settings.integrator, lit, integrator)
}

/// Adds sample indices `samples` of every point to its sum; returns the rays traced.
fn add_samples(
    integrator: &dyn Integrator,
    points: &Points,
    sums: &mut [SensorSum],
    samples: Range<u32>,
) -> u64 {
    sums.par_iter_mut()
        .zip(points)
        .map(|(sum, (g, k, p))| {
            let mut rays = 0u64;
            for s in samples.clone() {
                let mut rng = SampleRng::new(sensor_key(*g, *k), s);
                let (e, r) = integrator.illuminance(p.position, p.normal, &mut rng);
                rays += u64::from(r);
                sum.add(e);
            }
            rays
        })
        .sum::<u64>()
}

/// Measures sample indices `samples` of every point of every grid of `setup` (one shard of a
/// measurement): the exact sums, one per point in grid order, and the rays traced. Sums of
/// disjoint ranges added point by point equal the sums of their union, bit for bit.
pub fn measure_samples(
    scene: &Scene,
    setup: &Setup,
    settings: &MeasureSettings,
    samples: Range<u32>,
) -> (Vec<SensorSum>, u64) {
    let integrator = integrator_for(scene, setup, settings);
    let points = sensor_points(&setup.grids);
    let mut sums = vec![SensorSum::default(); points.len()];
    let rays = add_samples(integrator.as_ref(), &points, &mut sums, samples);
    (sums, rays)
}

/// [`measure_grids`], calling `progress` after every round of samples; when it returns false
/// the measurement stops there (the results hold the samples done so far).
pub fn measure_grids_with_progress(
    scene: &Scene,
    setup: &Setup,
    settings: &MeasureSettings,
    progress: &mut dyn FnMut(MeasureProgress) -> bool,
) -> Vec<GridResult> {
    let started = Instant::now();
    let integrator = integrator_for(scene, setup, settings);
    let points = sensor_points(&setup.grids);
    let mut sums = vec![SensorSum::default(); points.len()];
    let mut rays_total = 0u64;
    let cap = settings.samples.max(1);
    let mut done = 0u32;
    while done < cap {
        let end = (done + ROUND).min(cap);
        rays_total += add_samples(integrator.as_ref(), &points, &mut sums, done..end);
        done = end;
        let worst = settings
            .target_error
            .map(|target| worst_relative_error(&sums, &points, setup.grids.len()) / target);
        let go_on = progress(MeasureProgress {
            samples_done: done,
            samples_cap: cap,
            elapsed_secs: started.elapsed().as_secs_f64(),
            worst_relative_error: worst,
        });
        if !go_on {
            break;
        }
        if settings
            .time_limit
            .is_some_and(|limit| started.elapsed() >= limit)
        {
            break;
        }
        if done >= TARGET_MIN_SAMPLES && worst.is_some_and(|w| w <= 1.0) {
            break;
        }
    }
    let mut results = grid_results(&setup.grids, &sums, done, rays_total);
    super::buried::mark_buried(&mut results, scene, setup);
    results
}

/// The readings of `grids` from their points' exact sums (in the order [`measure_samples`]
/// returns them) after `samples` samples a point; `rays` is shared out by point count.
pub fn grid_results(
    grids: &[Grid],
    sums: &[SensorSum],
    samples: u32,
    rays: u64,
) -> Vec<GridResult> {
    let points = sensor_points(grids);
    let mut results: Vec<GridResult> = grids
        .iter()
        .map(|g: &Grid| GridResult {
            name: g.name.clone(),
            normal: Vec3::from(g.normal),
            points: Vec::with_capacity(g.point_count()),
            samples,
            rays: 0,
        })
        .collect();
    for ((g, _, p), sum) in points.iter().zip(sums) {
        results[*g].points.push(PointResult {
            i: p.i,
            j: p.j,
            position: p.position,
            illuminance_lx: sum.mean(),
            std_error_lx: sum.std_error().unwrap_or(f64::NAN),
            buried: false,
        });
    }
    let total_points = points.len().max(1) as u64;
    for r in &mut results {
        r.rays = rays * r.points.len() as u64 / total_points;
    }
    results
}

/// The largest standard error over max(E_i, 0.1 × Eavg of its grid), over all points.
fn worst_relative_error(sums: &[SensorSum], points: &Points, grids: usize) -> f64 {
    let mut total = vec![(0.0f64, 0usize); grids];
    for ((g, _, _), s) in points.iter().zip(sums) {
        total[*g].0 += s.mean();
        total[*g].1 += 1;
    }
    let mut worst = 0.0f64;
    for ((g, _, _), s) in points.iter().zip(sums) {
        let avg = total[*g].0 / total[*g].1.max(1) as f64;
        let scale = s.mean().max(0.1 * avg);
        let se = s.std_error().unwrap_or(f64::INFINITY);
        worst = worst.max(crate::render::relative_error(se, scale));
    }
    worst
}

/// A grid's statistics (lx), maintained values when a maintenance factor applies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridStatistics {
    pub e_min_lx: f64,
    pub e_avg_lx: f64,
    pub e_max_lx: f64,
    /// Uniformity U0 = Emin / Eavg (0 when Eavg is 0).
    pub u0: f64,
    /// Emin / Emax (0 when Emax is 0).
    pub emin_over_emax: f64,
}

impl GridResult {
    /// How many points sit inside or under objects (left out of the statistics).
    pub fn buried_count(&self) -> usize {
        self.points.iter().filter(|p| p.buried).count()
    }

    /// Mean illuminance over the points (lx).
    pub fn mean_lx(&self) -> f64 {
        self.points.iter().map(|p| p.illuminance_lx).sum::<f64>() / self.points.len().max(1) as f64
    }

    /// Emin, Eavg, Emax, U0 and Emin/Emax of the points' illuminance.
    /// Points inside or under objects are left out (see [`GridResult::buried_count`]).
    pub fn statistics(&self) -> GridStatistics {
        let measured = || self.points.iter().filter(|p| !p.buried);
        let n = measured().count().max(1) as f64;
        let (mut lo, mut hi, mut sum) = (f64::INFINITY, f64::NEG_INFINITY, 0.0);
        for p in measured() {
            lo = lo.min(p.illuminance_lx);
            hi = hi.max(p.illuminance_lx);
            sum += p.illuminance_lx;
        }
        if measured().next().is_none() {
            (lo, hi) = (0.0, 0.0);
        }
        let avg = sum / n;
        GridStatistics {
            e_min_lx: lo,
            e_avg_lx: avg,
            e_max_lx: hi,
            u0: if avg > 0.0 { lo / avg } else { 0.0 },
            emin_over_emax: if hi > 0.0 { lo / hi } else { 0.0 },
        }
    }

    /// The standard errors of Emin, Eavg and Emax (lx): the minimum's and the maximum's
    /// points' own, and the mean's from the points' (independent) errors.
    pub fn statistics_std_errors(&self) -> [f64; 3] {
        let measured: Vec<&PointResult> = self.points.iter().filter(|p| !p.buried).collect();
        if measured.is_empty() {
            return [0.0; 3];
        }
        let pick = |better: fn(f64, f64) -> bool| {
            measured
                .iter()
                .copied()
                .reduce(|a, b| {
                    if better(b.illuminance_lx, a.illuminance_lx) {
                        b
                    } else {
                        a
                    }
                })
                .map_or(0.0, |p| p.std_error_lx)
        };
        let n = measured.len() as f64;
        let avg = measured
            .iter()
            .map(|p| p.std_error_lx.powi(2))
            .sum::<f64>()
            .sqrt()
            / n;
        [pick(|b, a| b < a), avg, pick(|b, a| b > a)]
    }

    /// The readings times `factor` (a maintenance factor: maintained illuminance).
    pub fn scaled(mut self, factor: f64) -> GridResult {
        for p in &mut self.points {
            p.illuminance_lx *= factor;
            p.std_error_lx *= factor;
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_match_hand_computed_values() {
        let point = |e: f64| PointResult {
            i: 0,
            j: 0,
            position: Vec3::ZERO,
            illuminance_lx: e,
            std_error_lx: 0.0,
            buried: false,
        };
        let r = GridResult {
            name: "g".into(),
            normal: Vec3::Y,
            points: [100.0, 200.0, 300.0, 400.0].map(point).to_vec(),
            samples: 1,
            rays: 0,
        };
        let s = r.statistics();
        assert_eq!((s.e_min_lx, s.e_avg_lx, s.e_max_lx), (100.0, 250.0, 400.0));
        assert!((s.u0 - 0.4).abs() < 1e-12 && (s.emin_over_emax - 0.25).abs() < 1e-12);
        let m = r.scaled(0.8).statistics();
        assert!((m.e_avg_lx - 200.0).abs() < 1e-9 && (m.u0 - 0.4).abs() < 1e-12);
    }
}
