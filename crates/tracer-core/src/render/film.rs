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
//! 2⁻¹⁶ (cd/m²)². One sample may be at most 2⁶² cd/m² (lx) and its luminance at most 2³⁹ cd/m²;
//! a sample beyond that, or not a finite number, is not added: it is counted in
//! [`PixelSum::rejected`] and the film reports it ([`Film::rejected_samples`]).

use super::guides::GuideFilm;
use super::run_sums::{RUN_SAMPLES, run_sums, wide_run_sums};
use super::tiles::Tile;
use crate::integrator::Sample;
use crate::light::LUMINANCE_WEIGHTS;
use glam::Vec3;
use rayon::prelude::*;

/// Fixed-point units per cd/m² (and per lx).
pub const VALUE_SCALE: f64 = 4_294_967_296.0; // 2^32
/// Fixed-point units per (cd/m²)² of the squared-luminance sums.
pub const SQUARE_SCALE: f64 = 65_536.0; // 2^16
/// Largest fixed-point magnitude one sample may contribute (2^94): 2^33 samples fit in i128.
const SAMPLE_LIMIT: f64 = 19_807_040_628_566_084_398_385_987_584.0;

/// A sample's five values in fixed point: r, g, b and illuminance in units of 2⁻³², luminance
/// squared in units of 2⁻¹⁶; None when one of them cannot be represented.
/// (All five converted before any is tested: one branch, not five.)
#[inline(always)]
fn fixed_values(s: &Sample) -> Option<[i128; 5]> {
    let y = f64::from(s.rgb.dot(LUMINANCE_WEIGHTS));
    let fixed = (
        to_fixed(f64::from(s.rgb.x), VALUE_SCALE),
        to_fixed(f64::from(s.rgb.y), VALUE_SCALE),
        to_fixed(f64::from(s.rgb.z), VALUE_SCALE),
        to_fixed(f64::from(s.illuminance_lx), VALUE_SCALE),
        to_fixed(y * y, SQUARE_SCALE),
    );
    let (Some(r), Some(g), Some(b), Some(e), Some(q)) = fixed else {
        return None;
    };
    Some([r, g, b, e, q])
}

fn to_fixed(v: f64, scale: f64) -> Option<i128> {
    let x = v * scale;
    if x.abs() < FAST_LIMIT {
        return Some(i128::from(round_half_away(x)));
    }
    let x = x.round();
    (x.is_finite() && x.abs() < SAMPLE_LIMIT).then_some(x as i128)
}

/// Below 2^62 a scaled value rounds through i64 (one instruction each way) instead of libm's
/// `round` and the soft 128-bit conversions, which took a tenth of a direct-light frame.
const FAST_LIMIT: f64 = 4_611_686_018_427_387_904.0; // 2^62

/// `x.round() as i64` for |x| < 2^62, bit for bit: truncate, then step away from zero when the
/// remainder is at least one half. `x - trunc(x)` is exact: below 2^52 by Sterbenz's lemma
/// (or x itself when |x| < 1), above it x is whole and the remainder 0.
#[inline(always)]
pub(super) fn round_half_away(x: f64) -> i64 {
    debug_assert!(x.abs() < FAST_LIMIT);
    // SAFETY: |x| < 2^62 (the caller's test, false for NaN): finite and in range, so the
    // truncation is exact; unlike `as`, no saturation checks.
    let i: i64 = unsafe { x.to_int_unchecked() };
    let frac = x - i as f64;
    // Without branches: which way a sample's remainder falls is a coin toss the branch
    // predictor loses half the time.
    i + i64::from(frac >= 0.5) - i64::from(frac <= -0.5)
}

#[inline(always)]
fn from_fixed(x: i128, scale: f64) -> f64 {
    // i64 to f64 rounds to nearest like i128 to f64, without the soft 128-bit conversion.
    match i64::try_from(x) {
        Ok(small) => small as f64 / scale,
        Err(_) => from_fixed_wide(x, scale),
    }
}

/// The soft 128-bit conversion, out of line: inlined, the compiler computed it on every call
/// and only then picked the i64 result (a fifth of `raygine render`'s time went to it).
#[cold]
#[inline(never)]
fn from_fixed_wide(x: i128, scale: f64) -> f64 {
    x as f64 / scale
}

/// The exact sum of some samples of one pixel. All zero bits is the empty sum (`Zeroable`): a
/// large film's memory comes zeroed from the system, and is touched first by the render.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Zeroable)]
pub struct PixelSum {
    /// Σ luminance per channel, units of 2⁻³² cd/m².
    pub rgb: [i128; 3],
    /// Σ illuminance, units of 2⁻³² lx.
    pub illuminance: i128,
    /// Σ (Rec. 709 luminance)², units of 2⁻¹⁶ (cd/m²)².
    pub luminance_sq: i128,
    /// Σ luminance per channel that light subpaths of every pixel's samples splatted here
    /// (bidirectional mode), units of 2⁻³² cd/m²; divided by this pixel's count like its own.
    pub splat_rgb: [i128; 3],
    /// Σ over light subpaths of the squared Rec. 709 luminance each splatted here (all of one
    /// subpath's splats into this pixel count as one value), units of 2⁻¹⁶ (cd/m²)²: the
    /// variance the splats add to the pixel's mean (see [`PixelSum::luminance_std_error`]).
    pub splat_luminance_sq: i128,
    /// Samples added.
    pub count: u32,
    /// Samples refused (not finite, or beyond the fixed-point range).
    pub rejected: u32,
}

impl PixelSum {
    /// Adds one sample; returns false (and counts it as rejected) when it cannot be represented.
    pub fn add(&mut self, s: &Sample) -> bool {
        let Some([r, g, b, e, q]) = fixed_values(s) else {
            self.rejected = self.rejected.saturating_add(1);
            return false;
        };
        // The five sums a sample adds to, without the splat sums `merge` would add zeros to.
        let sums = (|| {
            Some((
                self.rgb[0].checked_add(r)?,
                self.rgb[1].checked_add(g)?,
                self.rgb[2].checked_add(b)?,
                self.illuminance.checked_add(e)?,
                self.luminance_sq.checked_add(q)?,
                self.count.checked_add(1)?,
            ))
        })();
        let Some((r, g, b, e, q, count)) = sums else {
            self.rejected = self.rejected.saturating_add(1);
            return false;
        };
        self.rgb = [r, g, b];
        self.illuminance = e;
        self.luminance_sq = q;
        self.count = count;
        true
    }

    /// Adds `samples` (all of this pixel), with the same result as [`PixelSum::add`] one by
    /// one (integer sums do not care about order), but summing in 64 bits first: one 128-bit
    /// addition per run instead of five per sample. Returns how many were rejected.
    ///
    /// The run's sums come from [`run_sums`] (in vector lanes where the CPU has them); a run
    /// with a value out of range (large, NaN or infinite: rare) is added one by one through
    /// the exact path instead.
    pub fn add_run(&mut self, samples: &[Sample]) -> u32 {
        let mut rejected = 0;
        for run in samples.chunks(RUN_SAMPLES) {
            let Some(sums) = run_sums(run) else {
                rejected += self.add_wide_run(run);
                continue;
            };
            let sum = PixelSum {
                rgb: [
                    i128::from(sums[0]),
                    i128::from(sums[1]),
                    i128::from(sums[2]),
                ],
                illuminance: i128::from(sums[3]),
                luminance_sq: i128::from(sums[4]),
                splat_rgb: [0; 3],
                splat_luminance_sq: 0,
                count: run.len() as u32,
                rejected: 0,
            };
            if !self.merge(&sum) {
                rejected += run.len() as u32;
            }
        }
        rejected
    }

    /// [`PixelSum::add_run`] for a run with a value past the 64-bit sums (very bright
    /// pixels: a lamp a few millimetres away gives millions of lux): the same fixed-point
    /// values summed as whole parts and remainders ([`wide_run_sums`]), added once. A run with
    /// a value beyond even those (NaN, infinite, or near the fixed-point limit) goes sample by
    /// sample through [`PixelSum::add`], which rejects what cannot be represented.
    fn add_wide_run(&mut self, run: &[Sample]) -> u32 {
        let Some(sums) = wide_run_sums(run) else {
            return run.iter().map(|s| u32::from(!self.add(s))).sum();
        };
        let sum = PixelSum {
            rgb: [sums[0], sums[1], sums[2]],
            illuminance: sums[3],
            luminance_sq: sums[4],
            splat_rgb: [0; 3],
            splat_luminance_sq: 0,
            count: run.len() as u32,
            rejected: 0,
        };
        if self.merge(&sum) {
            0
        } else {
            run.len() as u32
        }
    }

    /// Adds a splat (luminance per channel: everything one light subpath splatted into this
    /// pixel); false (and counted as rejected) when it cannot be represented.
    pub fn add_splat(&mut self, rgb: Vec3) -> bool {
        let y = f64::from(rgb.dot(LUMINANCE_WEIGHTS));
        let fixed = (
            to_fixed(f64::from(rgb.x), VALUE_SCALE),
            to_fixed(f64::from(rgb.y), VALUE_SCALE),
            to_fixed(f64::from(rgb.z), VALUE_SCALE),
            to_fixed(y * y, SQUARE_SCALE),
        );
        let (Some(r), Some(g), Some(b), Some(q)) = fixed else {
            self.rejected = self.rejected.saturating_add(1);
            return false;
        };
        let sums = (|| {
            Some((
                self.splat_rgb[0].checked_add(r)?,
                self.splat_rgb[1].checked_add(g)?,
                self.splat_rgb[2].checked_add(b)?,
                self.splat_luminance_sq.checked_add(q)?,
            ))
        })();
        let Some((r, g, b, q)) = sums else {
            self.rejected = self.rejected.saturating_add(1);
            return false;
        };
        self.splat_rgb = [r, g, b];
        self.splat_luminance_sq = q;
        true
    }

    /// Adds another sum of the same pixel; false when the result would overflow (the sum is
    /// then unchanged and `other`'s samples are counted as rejected).
    pub fn merge(&mut self, other: &PixelSum) -> bool {
        let sum = (|| {
            Some(PixelSum {
                rgb: [
                    self.rgb[0].checked_add(other.rgb[0])?,
                    self.rgb[1].checked_add(other.rgb[1])?,
                    self.rgb[2].checked_add(other.rgb[2])?,
                ],
                illuminance: self.illuminance.checked_add(other.illuminance)?,
                luminance_sq: self.luminance_sq.checked_add(other.luminance_sq)?,
                splat_rgb: [
                    self.splat_rgb[0].checked_add(other.splat_rgb[0])?,
                    self.splat_rgb[1].checked_add(other.splat_rgb[1])?,
                    self.splat_rgb[2].checked_add(other.splat_rgb[2])?,
                ],
                splat_luminance_sq: self
                    .splat_luminance_sq
                    .checked_add(other.splat_luminance_sq)?,
                count: self.count.checked_add(other.count)?,
                rejected: self.rejected.saturating_add(other.rejected),
            })
        })();
        match sum {
            Some(s) => {
                *self = s;
                true
            }
            None => {
                self.rejected = self
                    .rejected
                    .saturating_add(other.count)
                    .saturating_add(other.rejected);
                false
            }
        }
    }

    /// Mean luminance per channel (cd/m²); black without samples.
    pub fn mean_rgb(&self) -> Vec3 {
        if self.count == 0 {
            return Vec3::ZERO;
        }
        let n = f64::from(self.count);
        let channel = |c: usize| {
            (from_fixed(self.rgb[c].saturating_add(self.splat_rgb[c]), VALUE_SCALE) / n) as f32
        };
        Vec3::new(channel(0), channel(1), channel(2))
    }

    /// Mean luminance per channel (cd/m²) with the splats divided by `light_paths_per_pixel`
    /// instead of this pixel's own count: while a progressive pass is under way, splats from
    /// the whole picture's finished samples have arrived, whatever this pixel's own count.
    pub fn mean_rgb_splats_over(&self, light_paths_per_pixel: f64) -> Vec3 {
        if self.count == 0 {
            return Vec3::ZERO;
        }
        let n = f64::from(self.count);
        let m = light_paths_per_pixel.max(1e-9);
        let channel = |c: usize| {
            (from_fixed(self.rgb[c], VALUE_SCALE) / n
                + from_fixed(self.splat_rgb[c], VALUE_SCALE) / m) as f32
        };
        Vec3::new(channel(0), channel(1), channel(2))
    }

    /// Mean illuminance (lx).
    pub fn mean_illuminance(&self) -> f32 {
        if self.count == 0 {
            return 0.0;
        }
        (from_fixed(self.illuminance, VALUE_SCALE) / f64::from(self.count)) as f32
    }

    /// Mean Rec. 709 luminance (cd/m²), splats included, in f64.
    pub fn mean_luminance(&self) -> f64 {
        if self.count == 0 {
            return 0.0;
        }
        let w = LUMINANCE_WEIGHTS.as_dvec3();
        let total =
            |c: usize| from_fixed(self.rgb[c].saturating_add(self.splat_rgb[c]), VALUE_SCALE);
        (w.x * total(0) + w.y * total(1) + w.z * total(2)) / f64::from(self.count)
    }

    /// Mean Rec. 709 luminance of the pixel's own samples (without splats), in f64.
    fn own_mean_luminance(&self) -> f64 {
        if self.count == 0 {
            return 0.0;
        }
        let w = LUMINANCE_WEIGHTS.as_dvec3();
        let sum = w.x * from_fixed(self.rgb[0], VALUE_SCALE)
            + w.y * from_fixed(self.rgb[1], VALUE_SCALE)
            + w.z * from_fixed(self.rgb[2], VALUE_SCALE);
        sum / f64::from(self.count)
    }

    /// Standard error of the mean luminance (cd/m²), splats included; None with fewer than two
    /// samples.
    ///
    /// The mean is (Σ own samples + Σ splats) / n. The n own samples are independent and alike,
    /// so their part contributes their sample variance / n. The splats come from the light
    /// subpaths of every pixel's samples: independent and alike too, each adding a value c_j
    /// (zero for most), so their part of the variance of the mean is Σ_j Var(c_j) / n², which
    /// Σ_j c_j² / n² estimates. It leaves out −Σ_j E[c_j]² / n², which is the squared mean of
    /// the splats over the number of light subpaths (the image's samples): negligible, and it
    /// errs on the side of a larger error. A light subpath also lights its own pixel's sample
    /// through other connections; that correlation is ignored (a subpath rarely splats into
    /// its own pixel).
    pub fn luminance_std_error(&self) -> Option<f64> {
        if self.count < 2 {
            return None;
        }
        let n = f64::from(self.count);
        let mean = self.own_mean_luminance();
        let mean_sq = from_fixed(self.luminance_sq, SQUARE_SCALE) / n;
        let var = (mean_sq - mean * mean).max(0.0) * n / (n - 1.0);
        let splat_var = from_fixed(self.splat_luminance_sq, SQUARE_SCALE) / (n * n);
        Some((var / n + splat_var).sqrt())
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    pub width: u32,
    pub height: u32,
    /// Row-major, top row first.
    pub pixels: Vec<PixelSum>,
    /// The denoiser's albedo and normal guides of the same samples, when asked for
    /// ([`super::RenderSettings::guides`]); None otherwise.
    pub guides: Option<GuideFilm>,
}

impl Drop for Film {
    fn drop(&mut self) {
        super::film_buffers::give(std::mem::take(&mut self.pixels));
    }
}

/// Why two films cannot be added.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FilmError {
    #[error("films of {0}x{1} and {2}x{3} pixels cannot be added")]
    SizeMismatch(u32, u32, u32, u32),
    #[error("pixel ({x}, {y}): the sum exceeds the film's fixed-point range")]
    Overflow { x: u32, y: u32 },
}

impl Film {
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: super::film_buffers::take(width as usize * height as usize),
            guides: None,
        }
    }

    /// A film that also sums the denoiser's guides.
    pub fn with_guides(width: u32, height: u32) -> Self {
        let mut film = Film::new(width, height);
        film.guides = Some(GuideFilm::new(width, height));
        film
    }

    pub fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    /// Adds a tile's sums (in the tile's row-major pixel order).
    pub fn add_tile(&mut self, tile: &Tile, sums: &[PixelSum]) {
        for ((x, y), s) in tile.pixels().zip(sums) {
            let i = self.index(x, y);
            self.pixels[i].merge(s);
        }
    }

    /// Adds light-subpath splats (bidirectional mode): each is everything one light subpath
    /// sent to its pixel ([`crate::integrator::Splat`]). Exact and order-independent like
    /// samples.
    pub fn add_splats(&mut self, splats: &[crate::integrator::Splat]) {
        for s in splats {
            if s.x < self.width && s.y < self.height {
                let i = self.index(s.x, s.y);
                self.pixels[i].add_splat(s.rgb);
            }
        }
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
        for (i, (a, b)) in self.pixels.iter_mut().zip(&other.pixels).enumerate() {
            if !a.merge(b) {
                let w = self.width.max(1) as usize;
                return Err(FilmError::Overflow {
                    x: (i % w) as u32,
                    y: (i / w) as u32,
                });
            }
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

    /// Mean linear luminance per channel (cd/m²); black where no sample landed yet.
    pub fn mean_rgb(&self, i: usize) -> Vec3 {
        self.pixels[i].mean_rgb()
    }

    /// Mean illuminance (lx) on the surface seen in pixel `i`.
    pub fn mean_illuminance(&self, i: usize) -> f32 {
        self.pixels[i].mean_illuminance()
    }

    /// All mean colours, row-major.
    pub fn mean_rgb_all(&self) -> Vec<Vec3> {
        self.pixels.iter().map(PixelSum::mean_rgb).collect()
    }

    /// The fewest samples any pixel has.
    pub fn min_samples(&self) -> u32 {
        self.pixels.iter().map(|p| p.count).min().unwrap_or(0)
    }

    /// Samples refused anywhere (non-finite or out of range); should be 0.
    pub fn rejected_samples(&self) -> u64 {
        self.pixels.par_iter().map(|p| u64::from(p.rejected)).sum()
    }

    /// The remaining noise of the image: the root-mean-square standard error of the pixels'
    /// luminance over their mean luminance, leaving out the 0.5 % brightest pixels (a light's
    /// hot spot would otherwise stand for the whole picture, as in BENCHMARK.md's G1). Relative;
    /// None before two samples per pixel or for a black image.
    pub fn relative_noise(&self) -> Option<f64> {
        if self.pixels.is_empty() || self.pixels.iter().any(|p| p.count < 2) {
            return None;
        }
        let mut means: Vec<f64> = self.pixels.iter().map(PixelSum::mean_luminance).collect();
        let drop = means.len() / 200;
        let keep = means.len() - drop;
        let cut = *means.select_nth_unstable_by(keep - 1, f64::total_cmp).1;
        let (mut se2, mut sum, mut n) = (0.0f64, 0.0f64, 0usize);
        for p in &self.pixels {
            let y = p.mean_luminance();
            if y <= cut && n < keep {
                se2 += p.luminance_std_error()?.powi(2);
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
        for (i, p) in film.pixels.iter_mut().enumerate() {
            p.add(&Sample {
                rgb: rgb.get(i).copied().unwrap_or_default(),
                illuminance_lx: lx.get(i).copied().unwrap_or_default(),
                rays: 0,
                missed: false,
            });
        }
        film
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]

    #[test]
    fn the_fast_fixed_point_conversions_agree_bit_for_bit_with_round_and_i128() {
        let slow_to = |v: f64, scale: f64| {
            let x = (v * scale).round();
            (x.is_finite() && x.abs() < SAMPLE_LIMIT).then_some(x as i128)
        };
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            0.49999999999999994,
            -0.49999999999999994,
            4_503_599_627_370_495.5,
            4_503_599_627_370_496.0,
            -4_503_599_627_370_497.0,
            FAST_LIMIT,
            -FAST_LIMIT,
            FAST_LIMIT * 4.0,
            1e300,
            f64::INFINITY,
            f64::NAN,
        ];
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..200_000 {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let bits = state >> 12;
            // Magnitudes from 1e-12 to 1e12, either sign, and exact halves.
            let mag = 10f64.powf((bits % 24_000) as f64 / 1000.0 - 12.0);
            let sign = if state & 1 == 0 { 1.0 } else { -1.0 };
            values.push(sign * mag);
            values.push(sign * ((bits % 1_000_000) as f64 + 0.5) / VALUE_SCALE);
        }
        for v in values {
            for scale in [VALUE_SCALE, SQUARE_SCALE] {
                let (fast, slow) = (to_fixed(v, scale), slow_to(v, scale));
                assert_eq!(fast, slow, "{v:e} x {scale}");
                if let Some(x) = slow {
                    assert_eq!(from_fixed(x, scale).to_bits(), (x as f64 / scale).to_bits());
                }
            }
        }
        for x in [
            i128::MAX,
            i128::MIN,
            i128::from(i64::MAX) + 1,
            i128::from(i64::MIN),
        ] {
            assert_eq!(
                from_fixed(x, VALUE_SCALE).to_bits(),
                (x as f64 / VALUE_SCALE).to_bits()
            );
        }
    }
    use super::*;

    fn sample(v: f32) -> Sample {
        Sample {
            rgb: Vec3::new(v, 2.0 * v, 0.5 * v),
            illuminance_lx: 3.0 * v,
            rays: 1,
            missed: false,
        }
    }

    #[test]
    fn runs_add_up_like_single_samples() {
        // Ordinary values, huge ones (beyond the 64-bit path), negative, NaN and infinite
        // ones, in runs of every length (4000: several 64-bit runs in one call).
        let mut h = 7u64;
        let mut values = Vec::new();
        for i in 0..4000u32 {
            h = crate::render::sample_hash(h, i);
            let unit = (h >> 40) as f32 / (1u64 << 24) as f32;
            values.push(match i % 23 {
                0 => 3.0e8 * unit,
                1 => 1.0e10,
                2 => -unit,
                3 if i % 3 == 0 => f32::NAN,
                4 if i % 5 == 0 => f32::INFINITY,
                5 => 2.0e9,
                _ => unit * 100.0,
            });
        }
        for run_len in [1, 2, 3, 16, 64, 4000] {
            let (mut one, mut runs) = (PixelSum::default(), PixelSum::default());
            let mut rejected = 0;
            for chunk in values.chunks(run_len) {
                let samples: Vec<Sample> = chunk.iter().map(|&v| sample(v)).collect();
                samples.iter().for_each(|s| {
                    one.add(s);
                });
                rejected += runs.add_run(&samples);
            }
            assert_eq!(one, runs, "runs of {run_len}");
            assert_eq!(rejected, one.rejected, "runs of {run_len}");
            assert!(one.rejected > 0 && one.count > 3000);
        }
    }

    #[test]
    fn sums_do_not_depend_on_order_and_keep_precision() {
        let values: Vec<f32> = (0..1000)
            .map(|i| ((i * 7919) % 1000) as f32 * 0.37 + 1e-3)
            .collect();
        let mut forward = PixelSum::default();
        let mut backward = PixelSum::default();
        for v in &values {
            forward.add(&sample(*v));
        }
        for v in values.iter().rev() {
            backward.add(&sample(*v));
        }
        assert_eq!(forward, backward);
        let mut halves = PixelSum::default();
        let mut second = PixelSum::default();
        for v in &values[..400] {
            halves.add(&sample(*v));
        }
        for v in &values[400..] {
            second.add(&sample(*v));
        }
        assert!(halves.merge(&second));
        assert_eq!(halves, forward);
        let exact: f64 = values.iter().map(|v| f64::from(*v)).sum::<f64>() / 1000.0;
        assert!((f64::from(forward.mean_rgb().x) / exact - 1.0).abs() < 1e-6);
    }

    #[test]
    fn standard_error_matches_the_textbook_formula() {
        let mut p = PixelSum::default();
        for v in [1.0f32, 2.0, 3.0, 4.0] {
            p.add(&Sample {
                rgb: Vec3::splat(v),
                ..Sample::default()
            });
        }
        // Sample variance of 1..4 is 5/3; the standard error is sqrt(5/3 / 4).
        let se = p.luminance_std_error().unwrap_or(0.0);
        assert!((se - (5.0f64 / 12.0).sqrt()).abs() < 1e-6, "{se}");
    }

    #[test]
    fn values_out_of_range_are_rejected_and_counted() {
        let mut p = PixelSum::default();
        assert!(!p.add(&sample(f32::NAN)));
        assert!(!p.add(&sample(f32::INFINITY)));
        assert!(!p.add(&sample(1e30)));
        assert!(p.add(&sample(1e9)));
        assert_eq!((p.count, p.rejected), (1, 3));
        let mut film = Film::new(1, 1);
        film.pixels[0] = p;
        assert_eq!(film.rejected_samples(), 3);
    }
}
