//! Independent batches of a glare image's samples: a standard error that holds when the pixels'
//! estimates are correlated.
//!
//! The figures' first-order error ([`super::figures`]) treats the pixels' means as independent.
//! That holds for direct and path tracing, where each sample lands in its own pixel. In
//! bidirectional and light tracing a light subpath splats into many pixels, so their errors move
//! together, and that error understated the spread of independent runs by about 1.7 times
//! (docs/glare.md). Batches of disjoint sample indices are independent of each other (every
//! sample depends on its pixel and its index only), so the spread of a figure's linearisation
//! across them measures its error whatever the pixels share:
//!
//! X_b = Σ_j (∂F/∂L_j) L_j⁽ᵇ⁾, SE(F)² = Σ_b n_b (X_b − X̄)² / ((K − 1) N),
//!
//! over K batches of n_b samples a pixel, N in all, X̄ = Σ n_b X_b / N. It has K − 1 degrees of
//! freedom (about 27 % relative spread of its own at K = 8).

use super::sun::SUN_SAMPLES;
use crate::render::{
    Film, FrameSampler, RenderSettings, RenderStats, render_pixel_ranges, render_samples,
    render_with_progress_mapped,
};
use crate::scene::{Scene, Setup};
use std::ops::Range;
use std::time::{Duration, Instant};

/// Batches a splatting render is split into by [`render_in_batches`].
pub const BATCHES: u32 = 8;

/// Each batch's mean luminance per pixel, with its samples a pixel.
#[derive(Clone, Debug, Default)]
pub struct SampleBatches {
    /// Samples a pixel in each batch.
    pub samples: Vec<u32>,
    /// Each batch's mean luminance (cd/m²) per pixel, row-major as the film.
    pub luminance: Vec<Vec<f32>>,
}

impl SampleBatches {
    /// Adds `film`, rendered from sample indices no other batch has, as a batch.
    pub fn push(&mut self, film: &Film) {
        let samples = film.min_samples();
        self.luminance.push(
            (0..film.len())
                .map(|i| film.mean_luminance(i) as f32)
                .collect(),
        );
        self.samples.push(samples);
    }

    /// [`SampleBatches::push`], then, above `max` batches, [`SampleBatches::merge_pairs`]:
    /// independent batches in bounded memory.
    pub fn push_capped(&mut self, film: &Film, max: usize) {
        self.push(film);
        if self.len() > max.max(2) {
            self.merge_pairs();
        }
    }

    /// Merges neighbouring batches in pairs (their sample-weighted mean); an odd last one stays.
    pub fn merge_pairs(&mut self) {
        let samples = std::mem::take(&mut self.samples);
        let luminance = std::mem::take(&mut self.luminance);
        for (n, l) in samples.chunks(2).zip(luminance.chunks(2)) {
            if let ([n0, n1], [l0, l1]) = (n, l) {
                let (w0, w1) = (*n0 as f32, *n1 as f32);
                let total = (w0 + w1).max(1.0);
                let mean = l0.iter().zip(l1).map(|(a, b)| (a * w0 + b * w1) / total);
                self.luminance.push(mean.collect());
                self.samples.push(n0 + n1);
            } else {
                self.samples.extend_from_slice(n);
                self.luminance.extend_from_slice(l);
            }
        }
    }

    pub fn len(&self) -> usize {
        self.samples.len()
    }

    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
    }

    /// The standard error of the linear figure Σ_j `gradient`[j] L_j of all the samples, from
    /// its values in each batch (see the module); None with fewer than two batches or when
    /// `gradient` is not one per pixel.
    pub fn std_error_of(&self, gradient: &[f64]) -> Option<f64> {
        if self.len() < 2 || self.luminance.iter().any(|l| l.len() != gradient.len()) {
            return None;
        }
        let values: Vec<f64> = self
            .luminance
            .iter()
            .map(|l| {
                l.iter()
                    .zip(gradient)
                    .filter(|&(_, &g)| g != 0.0)
                    .map(|(&l, &g)| g * f64::from(l))
                    .sum()
            })
            .collect();
        let n: Vec<f64> = self.samples.iter().map(|&s| f64::from(s)).collect();
        let total: f64 = n.iter().sum();
        if total <= 0.0 {
            return None;
        }
        let mean = values.iter().zip(&n).map(|(x, n)| x * n).sum::<f64>() / total;
        let squares: f64 = values
            .iter()
            .zip(&n)
            .map(|(x, n)| n * (x - mean) * (x - mean))
            .sum();
        Some((squares / ((self.len() - 1) as f64 * total)).sqrt())
    }
}

/// `0..total` cut into `count` consecutive ranges whose lengths differ by at most one (fewer
/// when `total` < `count`).
pub fn batch_ranges(total: u32, count: u32) -> Vec<Range<u32>> {
    let count = count.clamp(1, total.max(1));
    (0..count)
        .map(|b| {
            let start = (u64::from(total) * u64::from(b) / u64::from(count)) as u32;
            let end = (u64::from(total) * u64::from(b + 1) / u64::from(count)) as u32;
            start..end
        })
        .filter(|r| !r.is_empty())
        .collect()
}

/// Renders the fisheye for glare. For an integrator that splats, in [`BATCHES`] batches of
/// consecutive sample indices, kept as [`SampleBatches`]; else as
/// [`crate::render::render_with_progress`] does. The film is the same as one render's (exact
/// sums). Pixels marked in `sun` (one flag a pixel, or
/// none) get [`SUN_SAMPLES`] times the samples, in every pass. Stops after the pass in which
/// `time_limit` passes; `progress` hears after each pass.
pub fn render_in_batches(
    scene: &Scene,
    setup: &Setup,
    settings: &RenderSettings,
    sun: &[bool],
    time_limit: Option<Duration>,
    progress: &mut dyn FnMut(&RenderStats),
) -> (Film, Option<SampleBatches>, RenderStats) {
    let map = |i: usize, range: &Range<u32>| samples_of(i, range, sun);
    if !settings.integrator.splats() {
        let (film, stats) =
            render_with_progress_mapped(scene, setup, settings, time_limit, &map, progress);
        return (film, None, stats);
    }
    let started = Instant::now();
    let frame = FrameSampler::new(scene, setup, settings);
    let mut batches = SampleBatches::default();
    let mut film: Option<Film> = None;
    let mut stats = RenderStats::default();
    for range in batch_ranges(settings.samples_per_pixel.max(1), BATCHES) {
        let (mut part, rays) = render_pixel_ranges(&frame, settings, &|i| map(i, &range));
        part.count_splat_paths();
        batches.push(&part);
        match &mut film {
            // Disjoint ranges of the same settings always merge; were one refused, the film
            // would not be the batches' sum, so stop with what agrees.
            Some(f) => {
                if f.merge(&part).is_err() {
                    batches.samples.pop();
                    batches.luminance.pop();
                    break;
                }
            }
            None => film = Some(part),
        }
        stats.rays += rays;
        stats.samples_per_pixel = range.end;
        stats.elapsed_secs = started.elapsed().as_secs_f64();
        if let Some(f) = &film {
            let added: u64 = f.counts().map(u64::from).sum();
            stats.mean_samples_per_pixel = added as f64 / f.len().max(1) as f64;
        }
        progress(&stats);
        if time_limit.is_some_and(|l| started.elapsed() >= l) {
            break;
        }
    }
    let mut film = film.unwrap_or_else(|| render_samples(scene, setup, settings, 0..1).0);
    film.count_splat_paths();
    (film, Some(batches), stats)
}

/// The sample indices pixel `i` takes in the batch of `range`: those, or [`SUN_SAMPLES`] times
/// as many of its own where the sun may show.
pub fn samples_of(i: usize, range: &Range<u32>, sun: &[bool]) -> Range<u32> {
    if sun.get(i).copied().unwrap_or(false) {
        range.start.saturating_mul(SUN_SAMPLES)..range.end.saturating_mul(SUN_SAMPLES)
    } else {
        range.clone()
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn ranges_cover_the_samples_once_in_near_equal_parts() {
        assert_eq!(batch_ranges(16, 8)[3], 6..8);
        assert_eq!(batch_ranges(3, 8), vec![0..1, 1..2, 2..3]);
        let r = batch_ranges(13, 4);
        assert_eq!(r.first().unwrap().start, 0);
        assert_eq!(r.last().unwrap().end, 13);
        assert!(r.windows(2).all(|w| w[0].end == w[1].start));
        assert!(r.iter().all(|r| r.len() == 3 || r.len() == 4));
    }

    #[test]
    fn merged_pairs_keep_the_sample_weighted_mean() {
        let mut b = SampleBatches {
            samples: vec![1, 3, 2, 2, 5],
            luminance: vec![vec![4.0], vec![8.0], vec![1.0], vec![3.0], vec![7.0]],
        };
        b.merge_pairs();
        assert_eq!(b.samples, vec![4, 4, 5]);
        assert_eq!(b.luminance, vec![vec![7.0], vec![2.0], vec![7.0]]);
    }

    /// Batches whose figure values are known: the error is the formula's.
    #[test]
    fn the_error_is_the_spread_of_the_batch_values() {
        let batches = SampleBatches {
            samples: vec![2, 2, 4],
            luminance: vec![vec![1.0, 3.0], vec![2.0, 2.0], vec![4.0, 0.0]],
        };
        // X_b with gradient [1, 0.5]: 2.5, 3, 4; mean (5 + 6 + 16) / 8 = 3.375.
        let x = [2.5, 3.0, 4.0];
        let n = [2.0, 2.0, 4.0];
        let squares: f64 = x
            .iter()
            .zip(n)
            .map(|(x, n)| n * (x - 3.375f64).powi(2))
            .sum();
        let want = (squares / (2.0 * 8.0)).sqrt();
        let got = batches.std_error_of(&[1.0, 0.5]).unwrap();
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        assert_eq!(batches.std_error_of(&[1.0]), None);
        let one = SampleBatches {
            samples: vec![4],
            luminance: vec![vec![1.0]],
        };
        assert_eq!(one.std_error_of(&[1.0]), None);
    }
}
