//! Adaptive sampling: once every pixel has [`MIN_SAMPLES`], further samples go where the
//! relative standard error is highest.
//!
//! **Where samples go.** A pixel's error is predicted from its neighbours within 3 pixels, never
//! from its own samples: their variance of one sample, averaged, over the pixel's own count.
//! Choosing a pixel's count from its own samples biases its mean (a pixel whose first samples
//! missed a rare bright path looks converged, stops, and stays dark); its neighbours' samples
//! come from streams of their own, independent of its samples, so its count tells nothing about
//! its values and its mean stays unbiased. (Splats and the neighbours' counts tie pixels
//! together weakly; `tests/core/adaptive.rs` measures what is left.) A window of 7x7 rather than
//! 3x3 because one sample's variance is heavy-tailed: a single bright path in a neighbour would
//! otherwise pull hundreds of samples to its surroundings.
//!
//! **Judged against what.** Under a time limit (and in the viewer) a pixel's standard error is
//! judged against the picture's mean luminance Ȳ, which is what BENCHMARK.md's G1 error
//! averages: measured on G1 and E3 (README), judging it against the pixel's own luminance
//! (max(Y, 0.1 Ȳ) or max(Y, Ȳ)) sent samples to dark corners and made the picture's error
//! 4-20 % worse than uniform sampling. `--target-error` judges every pixel against max(Y,
//! 0.1 Ȳ), the figure it promises.
//!
//! **How many.** Each round gives every pixel whose predicted error is above a threshold the
//! samples that bring it to the threshold, at most doubling its count and never past twice the
//! picture's mean count; the threshold is the target error, or found by bisection so that the
//! round fits its budget of samples.
//!
//! **Splats** (bidirectional and light tracing) are divided by the light subpaths traced per
//! pixel of the whole film, never by the receiving pixel's count ([`Film::splat_paths`]).
//!
//! Every choice is made from the film's exact integer sums, in a fixed order, and each sample
//! depends on (pixel, sample index) only: the film does not depend on the number of threads.

use super::film::Film;
use super::pixel::FrameSampler;
use super::pixel_sum::relative_error;
use super::{RenderSettings, RenderStats, render_pixel_ranges_into};
use crate::scene::{Scene, Setup};
use std::time::{Duration, Instant};

/// Samples every pixel gets before any goes by error.
pub const MIN_SAMPLES: u32 = 16;

/// The relative error's denominator is max(Y, FLOOR × Ȳ), Ȳ the image's mean luminance without
/// its 0.5 % brightest pixels: as for grids' target error, so that black and near-black pixels
/// (whose relative error is endless) are judged against the picture's level.
pub const FLOOR: f64 = 0.1;

/// Neighbours within this many pixels (a square window) predict a pixel's error.
pub const WINDOW_RADIUS: usize = 3;

/// No pixel gets more than this many times the picture's mean count (measured on G1 and E3:
/// 2 did best of 2, 4 and 8; more lets a few pixels of heavy-tailed variance take the round).
pub const MAX_OVER_MEAN: f64 = 2.0;

/// What a pixel's standard error is judged against.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scale {
    /// The picture's mean luminance Ȳ (without its 0.5 % brightest pixels): the picture's
    /// error, as BENCHMARK.md's G1 measures it.
    Picture,
    /// max(Y, [`FLOOR`] × Ȳ): each pixel's own relative error, as `--target-error` promises.
    Pixel,
}

/// Longest a round is planned to take, seconds: progress is reported at least this often.
const ROUND_SECS: f64 = 2.0;

/// When an adaptive render stops (besides `samples_per_pixel`, the cap of every pixel).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stop {
    pub time_limit: Option<Duration>,
    /// Stop once every pixel's standard error is within this share (0.02: 2 %) of max(Y,
    /// [`FLOOR`] × Ȳ), leaving out the 0.5 % brightest pixels (a lamp's hot spot).
    pub target_error: Option<f64>,
    /// Stop once the picture has this many samples per pixel on average (the viewer's
    /// target).
    pub mean_samples: Option<f64>,
}

/// The image's mean luminance without its 0.5 % brightest pixels (G1's rule), cd/m².
fn level(film: &Film) -> f64 {
    let mut y: Vec<f64> = (0..film.len()).map(|i| film.mean_luminance(i)).collect();
    if y.is_empty() {
        return 0.0;
    }
    let keep = y.len() - y.len() / 200;
    y.select_nth_unstable_by(keep - 1, f64::total_cmp);
    y[..keep].iter().sum::<f64>() / keep as f64
}

/// The largest relative standard error of the pixels, leaving out the 0.5 % brightest: the
/// figure `--target-error` compares with. Infinite before two samples in every pixel.
pub fn worst_relative_error(film: &Film) -> f64 {
    let n = film.len();
    if n == 0 {
        return 0.0;
    }
    let floor = FLOOR * level(film);
    let mut y: Vec<f64> = (0..n).map(|i| film.mean_luminance(i)).collect();
    let keep = n - n / 200;
    let cut = *y.select_nth_unstable_by(keep - 1, f64::total_cmp).1;
    let mut worst = 0.0f64;
    let mut kept = 0;
    for i in 0..n {
        let yi = film.mean_luminance(i);
        if yi > cut || kept >= keep {
            continue;
        }
        kept += 1;
        let Some(se) = film.luminance_std_error(i) else {
            return f64::INFINITY;
        };
        let scale = yi.max(floor);
        worst = worst.max(relative_error(se, scale));
    }
    worst
}

/// Each pixel's predicted squared relative error under `scale`: its neighbours' (within
/// [`WINDOW_RADIUS`]) relative variance of one sample, averaged, over its own count. 0 where
/// nothing can be said (no neighbour with two samples).
pub fn predicted_errors(film: &Film, scale: Scale) -> Vec<f64> {
    let level = level(film);
    let per_sample: Vec<f64> = (0..film.len())
        .map(|i| {
            let Some(var) = film.pixel(i).own_luminance_variance() else {
                return f64::NAN;
            };
            let s = match scale {
                Scale::Picture => level,
                Scale::Pixel => film.mean_luminance(i).max(FLOOR * level),
            };
            if s > 0.0 { var / (s * s) } else { 0.0 }
        })
        .collect();
    let (w, h) = (film.width as usize, film.height as usize);
    let r = WINDOW_RADIUS;
    // Window sums by rows, then by columns (finite values and their count).
    let mut rows = vec![(0.0f64, 0u32); w * h];
    for y in 0..h {
        for x in 0..w {
            let mut acc = (0.0, 0);
            for v in &per_sample[y * w + x.saturating_sub(r)..y * w + (x + r + 1).min(w)] {
                if v.is_finite() {
                    acc = (acc.0 + v, acc.1 + 1);
                }
            }
            rows[y * w + x] = acc;
        }
    }
    let mut out = vec![0.0; w * h];
    for y in 0..h {
        for x in 0..w {
            let (mut sum, mut n) = (0.0, 0u32);
            for ny in y.saturating_sub(r)..(y + r + 1).min(h) {
                let (s, c) = rows[ny * w + x];
                sum += s;
                n += c;
            }
            // Without the pixel itself.
            let own = per_sample[y * w + x];
            if own.is_finite() {
                sum -= own;
                n -= 1;
            }
            let count = film.count(y * w + x);
            if n > 0 && count > 0 {
                out[y * w + x] = sum.max(0.0) / f64::from(n) / f64::from(count);
            }
        }
    }
    out
}

/// Samples each pixel gets to bring its predicted squared error `errors[i]` down to `t2`, at
/// most doubling its count and never past `cap`.
fn extra_for(errors: &[f64], film: &Film, t2: f64, cap: u32) -> impl Iterator<Item = u32> {
    errors.iter().zip(film.counts()).map(move |(&e2, n)| {
        let room = cap.saturating_sub(n).min(n.max(1));
        if e2 <= t2 || room == 0 {
            return 0;
        }
        let want = (f64::from(n) * (e2 / t2 - 1.0)).ceil();
        if want >= f64::from(room) {
            room
        } else {
            want as u32
        }
    })
}

/// The extra samples of each pixel for one round: those that bring every pixel's predicted
/// error (judged against `scale`) to `target` (when given), else to the lowest threshold whose
/// samples fit in `budget`; no pixel past `cap`, nor past [`MAX_OVER_MEAN`] × the mean count.
pub fn allocate(film: &Film, scale: Scale, budget: u64, target: Option<f64>, cap: u32) -> Vec<u32> {
    let errors = predicted_errors(film, scale);
    let total_count: u64 = film.counts().map(u64::from).sum();
    let mean = total_count as f64 / film.len().max(1) as f64;
    let cap = cap.min((MAX_OVER_MEAN * mean).ceil().min(f64::from(u32::MAX)) as u32);
    let total = |t2: f64| -> u64 { extra_for(&errors, film, t2, cap).map(u64::from).sum() };
    let t2 = match target {
        Some(t) => (t * t).max(f64::MIN_POSITIVE),
        None => {
            let hi = errors.iter().copied().fold(0.0f64, f64::max);
            if hi <= 0.0 {
                return vec![0; errors.len()];
            }
            // Bisection in log space: the lowest threshold whose round fits the budget.
            let (mut lo, mut hi) = (hi * 1e-12, hi);
            if total(lo) <= budget {
                lo
            } else {
                for _ in 0..60 {
                    let mid = (lo * hi).sqrt();
                    if total(mid) <= budget {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                hi
            }
        }
    };
    extra_for(&errors, film, t2, cap).collect()
}

/// A round toward `target`: every pixel predicted above the threshold gets what brings it
/// there (within `budget`, else the budget goes to the highest errors). The threshold starts
/// at the target, tightened by how far the worst pixel's own error is from it: the neighbours
/// may call a pixel done that its own samples do not (its count still never comes from its
/// own samples, only this one figure of the whole picture does). Halved until some pixel
/// gets samples; empty when none can (every pixel at the cap, or no error left).
fn toward_target(film: &Film, target: f64, budget: u64, cap: u32) -> Vec<u32> {
    let worst = worst_relative_error(film);
    let mut t = if worst.is_finite() && worst > target {
        target * target / worst
    } else {
        target
    };
    for _ in 0..40 {
        let extra = allocate(film, Scale::Pixel, u64::MAX, Some(t), cap);
        let total: u64 = extra.iter().map(|&m| u64::from(m)).sum();
        if total > budget {
            return allocate(film, Scale::Pixel, budget, None, cap);
        }
        if total > 0 {
            return extra;
        }
        t *= 0.5;
    }
    vec![0; film.len()]
}

/// Renders `settings` adaptively until `stop` or every pixel has `settings.samples_per_pixel`
/// (the cap): [`MIN_SAMPLES`] in every pixel first (fewer when the time is up), then rounds
/// by error. `progress` is called after each round.
pub fn render_adaptive(
    scene: &Scene,
    setup: &Setup,
    settings: &RenderSettings,
    stop: Stop,
    progress: &mut dyn FnMut(&RenderStats),
) -> (Film, RenderStats) {
    let started = Instant::now();
    let frame = &FrameSampler::new(scene, setup, settings);
    let cap = settings.samples_per_pixel.max(1);
    let pixels = film_pixels(settings);
    let mut film = super::new_film(settings);
    let mut rays = 0u64;
    let mut total = 0u64;
    let time_left = || {
        stop.time_limit
            .map(|l| l.as_secs_f64() - started.elapsed().as_secs_f64())
    };
    let stats = |film: &Film, rays, total: u64| RenderStats {
        rays,
        elapsed_secs: started.elapsed().as_secs_f64(),
        samples_per_pixel: film.min_samples(),
        mean_samples_per_pixel: total as f64 / pixels.max(1) as f64,
    };
    loop {
        let uniform = film.min_samples().min(cap);
        let secs_per_sample = started.elapsed().as_secs_f64() / total.max(1) as f64;
        // Samples that fit in the round's time (and the time left).
        let mut fit = ROUND_SECS / secs_per_sample.max(1e-12);
        if let Some(left) = time_left() {
            fit = fit.min(left / secs_per_sample.max(1e-12));
        }
        // Samples left to the mean asked for.
        let left = stop
            .mean_samples
            .map(|m| (m * pixels as f64).ceil() as u64)
            .map(|all| all.saturating_sub(total));
        if left == Some(0) {
            break;
        }
        let extra: Vec<u32> = if uniform < MIN_SAMPLES.min(cap) {
            // Uniform passes: one, then as many as fit, up to MIN_SAMPLES.
            let passes = if total == 0 {
                1
            } else {
                ((fit / pixels as f64).floor() as u32)
                    .clamp(1, MIN_SAMPLES.min(cap) - uniform)
                    .min(uniform.max(1) * 2)
            };
            vec![passes; pixels]
        } else {
            let mut budget = (total / 2).max(pixels as u64);
            // Rounds sized by time only under a time limit: otherwise the film depends on the
            // samples alone, never on the machine's speed.
            if stop.time_limit.is_some() {
                budget = budget.min(fit.max(1.0) as u64);
            }
            budget = budget.min(left.unwrap_or(u64::MAX));
            let extra = match stop.target_error {
                Some(target) => toward_target(&film, target, budget, cap),
                None => allocate(&film, Scale::Picture, budget, None, cap),
            };
            if extra.iter().all(|&m| m == 0) {
                break; // every pixel at the cap, or nothing left to improve
            }
            extra
        };
        let counts: Vec<u32> = film.counts().collect();
        let ranges = |i: usize| counts[i]..counts[i] + extra[i];
        // Added in place: an overflow is counted as rejected samples.
        let part_rays = render_pixel_ranges_into(frame, settings, &ranges, &mut film);
        film.count_splat_paths();
        rays += part_rays;
        total += extra.iter().map(|&m| u64::from(m)).sum::<u64>();
        progress(&stats(&film, rays, total));
        if time_left().is_some_and(|t| t <= 0.0) || film.min_samples() >= cap {
            break;
        }
        if let Some(target) = stop.target_error
            && film.min_samples() >= MIN_SAMPLES.min(cap)
            && worst_relative_error(&film) <= target
        {
            break;
        }
    }
    let s = stats(&film, rays, total);
    (film, s)
}

fn film_pixels(settings: &RenderSettings) -> usize {
    settings.width as usize * settings.height as usize
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;
    use crate::integrator::Sample;
    use glam::Vec3;

    /// A 12x4 film: the left half's samples alternate 0 and 2 (noisy), the right half's are 1.
    fn half_noisy(count: u32) -> Film {
        let mut film = Film::new(12, 4);
        for y in 0..4 {
            for x in 0..12 {
                let i = film.index(x, y);
                let mut p = crate::render::PixelSum::default();
                for s in 0..count {
                    let v = if x < 6 { 2.0 * (s % 2) as f32 } else { 1.0 };
                    p.add(&Sample {
                        rgb: Vec3::splat(v),
                        ..Sample::default()
                    });
                }
                film.set_pixel(i, &p);
            }
        }
        film
    }

    #[test]
    fn samples_go_to_the_noisy_half_within_the_budget_and_at_most_double() {
        let film = half_noisy(16);
        let extra = allocate(&film, Scale::Picture, 200, None, 1000);
        let total: u32 = extra.iter().sum();
        assert!(total <= 200 && total > 150, "{total}");
        for y in 0..4 {
            for x in 0..12 {
                let m = extra[film.index(x, y)];
                assert!(m <= 16, "at most doubling");
                // Up to x = 8 a noisy pixel is within the window; further right none is.
                if x > 8 {
                    assert_eq!(m, 0, "({x}, {y})");
                }
            }
        }
        assert!(extra[film.index(2, 1)] > 0);
        // A target: only the pixels predicted above it, up to the cap.
        let capped = allocate(&film, Scale::Pixel, 0, Some(0.01), 20);
        assert!(capped.iter().all(|&m| m <= 4));
        assert_eq!(capped[film.index(2, 1)], 4);
        assert_eq!(capped[film.index(9, 1)], 0);
    }

    #[test]
    fn the_worst_error_leaves_out_the_brightest_and_judges_black_against_the_level() {
        let film = half_noisy(16);
        // Noisy half: σ = 1 (alternating 0 and 2, n/(n−1) corrected), mean 1, n = 16.
        let expected = (16.0f64 / 15.0).sqrt() / 4.0;
        assert!((worst_relative_error(&film) - expected).abs() < 1e-9);
        assert_eq!(worst_relative_error(&Film::new(3, 3)), f64::INFINITY);
    }
}
