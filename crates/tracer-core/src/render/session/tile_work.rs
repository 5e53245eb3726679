//! What a worker does with one tile of a pass: a coarse preview (one sample per block) or one
//! full sample per pixel, then the result applied to this generation's film under the lock.

use super::super::guides::GuideSum;
use super::super::passes::Pass;
use super::super::pixel::{BATCH_SAMPLES, BatchScratch, FrameSampler};
use super::super::pixel_sum::PixelSum;
use super::super::progressive_film::ProgressiveFilm;
use super::super::sampler::SampleJob;
use super::super::tiles::Tile;
use super::shared::Shared;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Least time between whole-frame refreshes for splats (bidirectional mode), seconds.
const SPLAT_REFRESH_SECS: f64 = 0.5;

/// Pixels (x, y) with (x mod 2, y mod 2) equal to this: a quarter of the frame.
pub(super) type Phase = (u32, u32);

/// The first full pass's quarters in order: after the first, every 2x2 block has a sample
/// (see [`ProgressiveFilm::shown_rgb`]); the second completes the diagonal.
pub(super) const FIRST_PASS_PHASES: [Option<Phase>; 4] =
    [Some((0, 0)), Some((1, 1)), Some((1, 0)), Some((0, 1))];

/// What the status figures are refreshed from after every tile.
pub(super) struct Progress<'a> {
    pub started: Instant,
    /// When the first full pass started.
    pub full_started: Option<Instant>,
    /// Pixels of the running pass done so far.
    pub pixels_done: &'a AtomicU64,
    pub pass_pixels: u64,
}

pub(super) struct PassContext<'a> {
    pub shared: &'a Shared,
    pub generation: u64,
    pub frame: &'a FrameSampler<'a>,
    pub pass: Pass,
    /// Only this quarter of the tile's pixels (the first full pass), else all.
    pub phase: Option<Phase>,
    pub rays: &'a AtomicU64,
    pub progress: Progress<'a>,
    /// An adaptive round's samples: pixel i's are `from[i]..from[i] + extra[i]`.
    pub round: Option<&'a Round>,
}

/// The samples of one adaptive round, per pixel (row-major).
#[derive(Debug, Default)]
pub(super) struct Round {
    pub from: Vec<u32>,
    pub extra: Vec<u32>,
}

impl PassContext<'_> {
    /// Waits while paused; returns false when this generation is stale.
    fn keep_going(&self) -> bool {
        if self.shared.paused.load(Ordering::Acquire) {
            let mut st = self.shared.lock();
            while st.paused && !st.shutdown && self.shared.is_current(self.generation) {
                st = match self.shared.wake.wait(st) {
                    Ok(g) => g,
                    Err(e) => e.into_inner(),
                };
            }
        }
        self.shared.is_current(self.generation)
    }

    pub fn run_tile(&self, tile: &Tile) {
        if !self.keep_going() {
            return;
        }
        match self.pass {
            Pass::Preview { block } => self.preview_tile(tile, block),
            Pass::Full { index } => self.full_tile(tile, index),
            Pass::Adaptive { .. } => self.round_tile(tile),
        }
    }

    fn preview_tile(&self, tile: &Tile, block: u32) {
        let mut blocks = Vec::new();
        let mut rays = 0u64;
        for by in (tile.y0..tile.y1).step_by(block as usize) {
            if !self.shared.is_current(self.generation) {
                return;
            }
            for bx in (tile.x0..tile.x1).step_by(block as usize) {
                let rect = Tile {
                    x0: bx,
                    y0: by,
                    x1: (bx + block).min(tile.x1),
                    y1: (by + block).min(tile.y1),
                };
                let cx = (rect.x0 + rect.x1) as f32 * 0.5;
                let cy = (rect.y0 + rect.y1) as f32 * 0.5;
                let sample = self.frame.preview(cx, cy);
                rays += u64::from(sample.rays);
                blocks.push((rect, sample));
            }
        }
        self.rays.fetch_add(rays, Ordering::Relaxed);
        self.progress
            .pixels_done
            .fetch_add(tile.pixel_count() as u64, Ordering::Relaxed);
        self.commit(tile, |film| {
            for (rect, s) in &blocks {
                film.fill_preview(rect, s);
            }
        });
    }

    fn full_tile(&self, tile: &Tile, index: u32) {
        let n = tile.pixel_count();
        // The pixels of this pass's quarter (all, after the first pass), in row-major order.
        let mut pixels = Vec::with_capacity(n);
        let mut sums = Vec::with_capacity(n);
        let mut missed = Vec::with_capacity(n);
        let mut guides = Vec::new();
        let mut splats = Vec::new();
        let mut rays = 0u64;
        let mut scratch = BatchScratch::default();
        let (mut jobs, mut samples) = (Vec::new(), Vec::new());
        let width = (tile.x1 - tile.x0).max(1);
        let in_phase =
            |x: u32, y: u32| self.phase.is_none_or(|(px, py)| x % 2 == px && y % 2 == py);
        // Whole rows per batch, so staleness is still checked every few rows.
        let rows_per_batch = (BATCH_SAMPLES as u32 / width).max(1);
        for y0 in (tile.y0..tile.y1).step_by(rows_per_batch as usize) {
            if !self.shared.is_current(self.generation) {
                return;
            }
            jobs.clear();
            for y in y0..(y0 + rows_per_batch).min(tile.y1) {
                jobs.extend(
                    (tile.x0..tile.x1)
                        .filter(|&x| in_phase(x, y))
                        .map(|x| SampleJob { x, y, s: index }),
                );
            }
            self.frame
                .sample_batch(&jobs, &mut scratch, &mut splats, &mut samples);
            for (job, sample) in jobs.iter().zip(&samples) {
                rays += u64::from(sample.rays);
                let mut sum = PixelSum::default();
                sum.add(sample);
                pixels.push((job.x, job.y));
                sums.push(sum);
                missed.push(u32::from(sample.missed));
            }
            if self.frame.guides {
                guides.extend(jobs.iter().map(|j| {
                    let mut sum = GuideSum::default();
                    sum.add(&self.frame.guide(j.x, j.y, j.s));
                    sum
                }));
            }
        }
        self.rays.fetch_add(rays, Ordering::Relaxed);
        self.progress
            .pixels_done
            .fetch_add(pixels.len() as u64, Ordering::Relaxed);
        self.commit(tile, |film| {
            film.add_pixels(&pixels, &sums, &missed, &guides);
            film.add_splats(&splats);
        });
        if !splats.is_empty() {
            self.refresh_everywhere_now_and_then();
        }
    }

    /// An adaptive round's samples of the tile's pixels: runs of each pixel's samples, summed
    /// per pixel and batch.
    fn round_tile(&self, tile: &Tile) {
        let Some(round) = self.round else { return };
        let width = self.frame.basis.width as usize;
        let mut pixels = Vec::new();
        let mut sums = Vec::new();
        let mut missed = Vec::new();
        let mut guides = Vec::new();
        let mut splats = Vec::new();
        let mut scratch = BatchScratch::default();
        let mut done = 0u64;
        // The next sample index of the pixel whose runs are arriving (they come in order).
        let mut cursor: Option<((u32, u32), u32)> = None;
        for y in tile.y0..tile.y1 {
            if !self.shared.is_current(self.generation) {
                return;
            }
            let row = (tile.x0..tile.x1).map(|x| {
                let i = y as usize * width + x as usize;
                (x, y, round.from[i]..round.from[i] + round.extra[i])
            });
            let rays = self
                .frame
                .for_each_sample(row, &mut scratch, &mut splats, |x, y, run| {
                    let mut sum = PixelSum::default();
                    sum.add_run(run);
                    pixels.push((x, y));
                    sums.push(sum);
                    missed.push(run.iter().map(|s| u32::from(s.missed)).sum());
                    if self.frame.guides {
                        let start = match cursor {
                            Some((p, next)) if p == (x, y) => next,
                            _ => round.from[y as usize * width + x as usize],
                        };
                        let end = start + run.len() as u32;
                        let mut g = GuideSum::default();
                        for s in start..end {
                            g.add(&self.frame.guide(x, y, s));
                        }
                        guides.push(g);
                        cursor = Some(((x, y), end));
                    }
                });
            self.rays.fetch_add(rays, Ordering::Relaxed);
            done += u64::from(tile.x1 - tile.x0);
        }
        self.progress.pixels_done.fetch_add(done, Ordering::Relaxed);
        self.commit(tile, |film| {
            film.add_pixels(&pixels, &sums, &missed, &guides);
            film.add_splats(&splats);
        });
        if !splats.is_empty() {
            self.refresh_everywhere_now_and_then();
        }
    }

    /// The status figures after a tile (under the lock): elapsed time, rays, the pass's share
    /// done and the time per full sample, so the status bar moves within long passes.
    fn refresh_stats(&self, stats: &mut super::SessionStats) {
        let p = &self.progress;
        stats.elapsed_secs = p.started.elapsed().as_secs_f64();
        stats.rays = self.rays.load(Ordering::Relaxed);
        let done = p.pixels_done.load(Ordering::Relaxed) as f64;
        stats.pass_fraction = (done / p.pass_pixels.max(1) as f64).min(1.0);
        if let (Pass::Full { .. }, Some(t)) = (self.pass, p.full_started) {
            let samples = f64::from(stats.samples_per_pixel) + stats.pass_fraction;
            if samples > 0.0 {
                stats.secs_per_sample = Some(t.elapsed().as_secs_f64() / samples);
            }
        }
    }

    /// Light subpaths land anywhere in the picture: mark the whole frame changed, at most every
    /// [`SPLAT_REFRESH_SECS`] (and at the end of every pass), so the display keeps up without
    /// remapping the whole picture for every tile.
    fn refresh_everywhere_now_and_then(&self) {
        let mut st = self.shared.lock();
        let due = st
            .last_full_refresh
            .is_none_or(|t| t.elapsed().as_secs_f64() >= SPLAT_REFRESH_SECS);
        let shown = st
            .film
            .as_ref()
            .is_some_and(|f| f.generation == self.generation);
        if due && shown && self.shared.is_current(self.generation) {
            st.last_full_refresh = Some(std::time::Instant::now());
            let (w, h) = (self.frame.basis.width, self.frame.basis.height);
            st.dirty.push(Tile {
                x0: 0,
                y0: 0,
                x1: w,
                y1: h,
            });
            drop(st);
            (self.shared.notify)();
        }
    }

    /// Applies a finished tile to this generation's film unless the generation is stale. Until
    /// the first preview pass is complete the new film is kept aside (the consumer keeps showing
    /// the previous picture); after that, the tile is marked dirty and the consumer woken.
    fn commit(&self, tile: &Tile, apply: impl FnOnce(&mut ProgressiveFilm)) {
        let mut st = self.shared.lock();
        // Checked under the lock: `start` bumps the generation under the same lock, so a stale
        // tile can never land in a newer film.
        if !self.shared.is_current(self.generation) {
            return;
        }
        self.refresh_stats(&mut st.stats);
        // Whoever waits on the figures (`RenderSession::wait_for`) sees them move.
        self.shared.wake.notify_all();
        let shown = st
            .film
            .as_ref()
            .is_some_and(|f| f.generation == self.generation);
        if shown {
            if let Some(film) = st.film.as_mut() {
                apply(film);
            }
            st.dirty.push(*tile);
            drop(st);
            (self.shared.notify)();
            return;
        }
        // Before the first preview is complete the tile goes to the pending film, prepared
        // (allocated) by the coordinator outside the lock.
        if let Some(film) = st
            .pending
            .as_mut()
            .filter(|f| f.generation == self.generation)
        {
            apply(film);
        }
    }
}
