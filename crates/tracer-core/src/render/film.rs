//! The HDR film: per-pixel sums of linear luminance (cd/m² per channel), of the first hit's
//! illuminance (lx) and of the squared luminance, with a sample count, so the mean and its
//! standard error converge as samples accumulate.
//!
//! Sums are exact: each sample is rounded once to fixed point and added as an integer, so a
//! pixel's sum does not depend on the order its samples arrive in. Images are therefore
//! bit-identical for any thread count, after restarts, and when sample ranges computed
//! separately (in other processes, on other machines) are added with [`Film::merge`].
//!
//! Scales: luminance and illuminance in units of 2⁻³² cd/m² (lx), squared luminance in units of
//! 2⁻⁴⁸ (cd/m²)². One sample may be at most 2⁶² cd/m² (lx) and its luminance at most 2³⁹ cd/m²;
//! a sample beyond that, or not a finite number, is not added: it is counted in
//! [`PixelSum::rejected`] and the film reports it ([`Film::rejected_samples`]).
//!
//! Storage: 48 bytes a pixel, 88 once light subpaths splat into it, and full-width sums for
//! the few pixels that need them ([`super::film_cells`]).

use super::film_cells::{Band, FilmPixels};
use super::guides::GuideFilm;
use super::pixel_sum::PixelSum;
use super::tiles::Tile;
use crate::integrator::Sample;
use glam::Vec3;
use rayon::prelude::*;

#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    pub width: u32,
    pub height: u32,
    /// Row-major, top row first.
    pixels: FilmPixels,
    /// The denoiser's albedo and normal guides of the same samples, when asked for
    /// ([`super::RenderSettings::guides`]); None otherwise.
    pub guides: Option<GuideFilm>,
    /// The first sample index whose illuminance the sums hold (0: every sample's; a session
    /// starts measuring it when it is first shown, see `FrameSampler::illuminance_from`).
    /// Every pixel's samples are indices 0, 1, …, so its illuminance mean is over its samples
    /// past this one.
    pub illuminance_from: u32,
    /// Light subpaths per pixel whose splats the sums hold (total samples over pixels), when
    /// the pixels' counts differ (adaptive sampling, [`super::adaptive`]): the splats are
    /// divided by it, never by the receiving pixel's own count. None: every pixel has the same
    /// count, which is that number.
    pub splat_paths: Option<f64>,
}

impl Drop for Film {
    fn drop(&mut self) {
        super::film_buffers::give(self.pixels.take_cells());
    }
}

/// Why two films cannot be added.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FilmError {
    #[error("films of {0}x{1} and {2}x{3} pixels cannot be added")]
    SizeMismatch(u32, u32, u32, u32),
    #[error("pixel ({x}, {y}): the sum exceeds the film's fixed-point range")]
    Overflow { x: u32, y: u32 },
    #[error("the films measured the illuminance from different samples on")]
    IlluminanceMismatch,
}

impl Film {
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: FilmPixels::from_cells(super::film_buffers::take(
                width as usize * height as usize,
            )),
            guides: None,
            illuminance_from: 0,
            splat_paths: None,
        }
    }

    /// A film that also sums the denoiser's guides.
    pub fn with_guides(width: u32, height: u32) -> Self {
        let mut film = Film::new(width, height);
        film.guides = Some(GuideFilm::new(width, height));
        film
    }

    /// Pixels: width × height.
    pub fn len(&self) -> usize {
        self.pixels.len()
    }

    /// True for a film of no pixels.
    pub fn is_empty(&self) -> bool {
        self.pixels.is_empty()
    }

    /// The sums of pixel `i` (row-major).
    pub fn pixel(&self, i: usize) -> PixelSum {
        self.pixels.get(i)
    }

    /// Every pixel's sums, row-major.
    pub fn pixels(&self) -> impl ExactSizeIterator<Item = PixelSum> + '_ {
        (0..self.len()).map(|i| self.pixels.get(i))
    }

    /// Pixel `i`'s sample count.
    pub fn count(&self, i: usize) -> u32 {
        self.pixels.count(i)
    }

    /// Every pixel's sample count, row-major.
    pub fn counts(&self) -> impl ExactSizeIterator<Item = u32> + '_ {
        (0..self.len()).map(|i| self.pixels.count(i))
    }

    /// Adds `sum` to pixel `i`; false when the result would overflow (the samples are then
    /// counted as rejected).
    pub fn merge_pixel(&mut self, i: usize, sum: &PixelSum) -> bool {
        self.pixels.merge(i, sum)
    }

    /// Empties every pixel (keeping the memory of the cells), in parallel on the current
    /// rayon pool.
    pub fn clear(&mut self) {
        self.pixels.clear();
    }

    /// Replaces pixel `i`'s sums.
    pub fn set_pixel(&mut self, i: usize, sum: &PixelSum) {
        self.pixels.set(i, sum);
    }

    /// Bytes the pixel sums hold (the guides apart), and how many pixels outgrew their
    /// cells (own samples, splats).
    pub fn memory(&self) -> (usize, (usize, usize)) {
        (self.pixels.bytes(), self.pixels.moved_pixels())
    }

    /// Runs `f` on bands of `band_len` pixels in parallel ([`FilmPixels::par_bands`]).
    pub(super) fn par_bands<R: Send>(
        &mut self,
        band_len: usize,
        f: impl Fn(usize, &mut Band<'_>) -> R + Sync,
    ) -> Vec<R> {
        let (w, h) = (self.width, self.height);
        self.pixels.par_bands(band_len, w, h, f)
    }

    pub fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    /// Adds a tile's sums (in the tile's row-major pixel order).
    pub fn add_tile(&mut self, tile: &Tile, sums: &[PixelSum]) {
        for ((x, y), s) in tile.pixels().zip(sums) {
            let i = self.index(x, y);
            self.pixels.merge(i, s);
        }
    }

    /// Adds light-subpath splats (bidirectional mode): each is everything one light subpath
    /// sent to its pixel ([`crate::integrator::Splat`]). Exact and order-independent like
    /// samples.
    pub fn add_splats(&mut self, splats: &[crate::integrator::Splat]) {
        self.pixels.add_splats(self.width, self.height, splats);
    }

    /// Adds every pixel of `other` (samples of the same image rendered separately). Exact: the
    /// result does not depend on the order films are added in.
    pub fn merge(&mut self, other: &Film) -> Result<(), FilmError> {
        if (self.width, self.height) != (other.width, other.height) {
            return Err(FilmError::SizeMismatch(
                self.width,
                self.height,
                other.width,
                other.height,
            ));
        }
        if self.illuminance_from != other.illuminance_from {
            return Err(FilmError::IlluminanceMismatch);
        }
        for i in 0..self.len() {
            if !self.pixels.merge(i, &other.pixels.get(i)) {
                let w = self.width.max(1) as usize;
                return Err(FilmError::Overflow {
                    x: (i % w) as u32,
                    y: (i / w) as u32,
                });
            }
        }
        if self.splat_paths.is_some() || other.splat_paths.is_some() {
            self.count_splat_paths();
        }
        // Guides of only some of the samples would not describe the sum: kept only when both
        // films have them.
        match (&mut self.guides, &other.guides) {
            (Some(a), Some(b)) => a.merge(b),
            (Some(_), None) => self.guides = None,
            _ => {}
        }
        Ok(())
    }

    /// Sets [`Film::splat_paths`] from the pixels' counts: None when they are all equal.
    pub fn count_splat_paths(&mut self) {
        let first = if self.is_empty() { 0 } else { self.count(0) };
        let total: u64 = self.counts().map(u64::from).sum();
        let uniform = self.counts().all(|c| c == first);
        self.splat_paths = (!uniform).then(|| total as f64 / self.len().max(1) as f64);
    }

    /// Mean linear luminance per channel (cd/m²); black where no sample landed yet.
    pub fn mean_rgb(&self, i: usize) -> Vec3 {
        self.pixels.get(i).mean_rgb_over(self.splat_paths)
    }

    /// Mean Rec. 709 luminance of pixel `i` (cd/m²), in f64.
    pub fn mean_luminance(&self, i: usize) -> f64 {
        self.pixels.get(i).mean_luminance_over(self.splat_paths)
    }

    /// Standard error of pixel `i`'s mean luminance (cd/m²); None before two samples.
    pub fn luminance_std_error(&self, i: usize) -> Option<f64> {
        self.pixels
            .get(i)
            .luminance_std_error_over(self.splat_paths)
    }

    /// Mean illuminance (lx) on the surface seen in pixel `i`.
    pub fn mean_illuminance(&self, i: usize) -> f32 {
        self.pixels
            .get(i)
            .mean_illuminance_after(self.illuminance_from)
    }

    /// All mean colours, row-major.
    pub fn mean_rgb_all(&self) -> Vec<Vec3> {
        let m = self.splat_paths;
        (0..self.len())
            .into_par_iter()
            .map(|i| self.pixels.get(i).mean_rgb_over(m))
            .collect()
    }

    /// The fewest samples any pixel has.
    pub fn min_samples(&self) -> u32 {
        self.counts().min().unwrap_or(0)
    }

    /// Samples refused anywhere (non-finite or out of range); should be 0.
    pub fn rejected_samples(&self) -> u64 {
        self.pixels.rejected()
    }

    /// The remaining noise of the image: the root-mean-square standard error of the pixels'
    /// luminance over their mean luminance, leaving out the 0.5 % brightest pixels (a light's
    /// hot spot would otherwise stand for the whole picture, as in BENCHMARK.md's G1). Relative;
    /// None before two samples per pixel or for a black image.
    pub fn relative_noise(&self) -> Option<f64> {
        if self.is_empty() || self.counts().any(|c| c < 2) {
            return None;
        }
        let m = self.splat_paths;
        let mut means: Vec<f64> = self.pixels().map(|p| p.mean_luminance_over(m)).collect();
        let drop = means.len() / 200;
        let keep = means.len() - drop;
        let cut = *means.select_nth_unstable_by(keep - 1, f64::total_cmp).1;
        let (mut se2, mut sum, mut n) = (0.0f64, 0.0f64, 0usize);
        for p in self.pixels() {
            let y = p.mean_luminance_over(m);
            if y <= cut && n < keep {
                se2 += p.luminance_std_error_over(m)?.powi(2);
                sum += y;
                n += 1;
            }
        }
        let n = n.max(1) as f64;
        let mean = sum / n;
        (mean > 0.0).then(|| (se2 / n).sqrt() / mean)
    }

    /// A film whose pixel `i` holds one sample of `rgb[i]` and `lx[i]` (for display mapping of
    /// values that were not accumulated here).
    pub fn from_values(width: u32, height: u32, rgb: &[Vec3], lx: &[f32]) -> Film {
        let mut film = Film::new(width, height);
        for i in 0..film.len() {
            let mut p = PixelSum::default();
            p.add(&Sample {
                rgb: rgb.get(i).copied().unwrap_or_default(),
                illuminance_lx: lx.get(i).copied().unwrap_or_default(),
                rays: 0,
                missed: false,
            });
            film.pixels.merge(i, &p);
        }
        film
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn the_film_reports_rejected_samples() {
        let mut p = PixelSum::default();
        assert!(!p.add(&Sample {
            rgb: Vec3::splat(f32::NAN),
            ..Sample::default()
        }));
        let mut film = Film::new(1, 1);
        film.set_pixel(0, &p);
        assert_eq!(film.rejected_samples(), 1);
    }
}
