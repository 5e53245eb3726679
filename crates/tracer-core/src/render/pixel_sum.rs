//! One pixel's exact sums: luminance per channel, illuminance, squared luminance and the
//! splats, with the sample count, in the fixed point of [`super::fixed_point`]. Its mean and
//! standard error converge as samples accumulate.

use super::fixed_point::{VALUE_SCALE, fixed_values, from_fixed, to_fixed};
use super::run_sums::{RUN_SAMPLES, run_sums, wide_run_sums};
use super::square_sum::SquareSum;
use crate::integrator::Sample;
use crate::light::LUMINANCE_WEIGHTS;
use glam::Vec3;

/// The exact sum of some samples of one pixel. All zero bits is the empty sum (`Zeroable`): a
/// large film's memory comes zeroed from the system, and is touched first by the render.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Zeroable)]
pub struct PixelSum {
    /// Σ luminance per channel, units of 2⁻³² cd/m².
    pub rgb: [i128; 3],
    /// Σ illuminance, units of 2⁻³² lx.
    pub illuminance: i128,
    /// Σ (Rec. 709 luminance)², exact to 2⁻⁴⁸ (cd/m²)² ([`SquareSum`]).
    pub luminance_sq: SquareSum,
    /// Σ luminance per channel that light subpaths of every pixel's samples splatted here
    /// (bidirectional mode), units of 2⁻³² cd/m²; divided by this pixel's count like its own.
    pub splat_rgb: [i128; 3],
    /// Σ over light subpaths of the squared Rec. 709 luminance each splatted here (all of one
    /// subpath's splats into this pixel count as one value), exact to 2⁻⁴⁸ (cd/m²)²: the
    /// variance the splats add to the pixel's mean (see [`PixelSum::luminance_std_error`]).
    pub splat_luminance_sq: SquareSum,
    /// Samples added.
    pub count: u32,
    /// Samples refused (not finite, or beyond the fixed-point range).
    pub rejected: u32,
}

impl PixelSum {
    /// Adds one sample; returns false (and counts it as rejected) when it cannot be represented.
    pub fn add(&mut self, s: &Sample) -> bool {
        let Some(([r, g, b, e], q)) = fixed_values(s) else {
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
                self.luminance_sq.checked_add(&q)?,
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
                luminance_sq: SquareSum::from_parts(i128::from(sums[4]), sums[5])
                    .unwrap_or_default(),
                splat_rgb: [0; 3],
                splat_luminance_sq: SquareSum::default(),
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
            luminance_sq: SquareSum::from_units(sums[4]),
            splat_rgb: [0; 3],
            splat_luminance_sq: SquareSum::default(),
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
            SquareSum::of_luminance(y),
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
                self.splat_luminance_sq.checked_add(&q)?,
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
                luminance_sq: self.luminance_sq.checked_add(&other.luminance_sq)?,
                splat_rgb: [
                    self.splat_rgb[0].checked_add(other.splat_rgb[0])?,
                    self.splat_rgb[1].checked_add(other.splat_rgb[1])?,
                    self.splat_rgb[2].checked_add(other.splat_rgb[2])?,
                ],
                splat_luminance_sq: self
                    .splat_luminance_sq
                    .checked_add(&other.splat_luminance_sq)?,
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

    /// Mean luminance per channel (cd/m²); black without samples. The splats are divided by
    /// this pixel's own count: right when every pixel of the film has the same count (see
    /// [`PixelSum::mean_rgb_over`] for films whose counts differ).
    pub fn mean_rgb(&self) -> Vec3 {
        self.mean_rgb_over(None)
    }

    /// Mean luminance per channel (cd/m²), the splats divided by `light_paths` (the light
    /// subpaths traced per pixel of the whole film: total samples over pixels), or by this
    /// pixel's own count when None. Adaptive sampling gives pixels different counts, while the
    /// splats come from every pixel's samples, so there they must be normalised by the
    /// film's light subpaths, never by the receiving pixel's count.
    pub fn mean_rgb_over(&self, light_paths: Option<f64>) -> Vec3 {
        if self.count == 0 {
            return Vec3::ZERO;
        }
        let n = f64::from(self.count);
        let channel = |c: usize| match light_paths {
            // One division of the whole sum, as films of equal counts always had.
            None => from_fixed(self.rgb[c].saturating_add(self.splat_rgb[c]), VALUE_SCALE) / n,
            Some(m) => {
                from_fixed(self.rgb[c], VALUE_SCALE) / n
                    + from_fixed(self.splat_rgb[c], VALUE_SCALE) / m.max(1e-9)
            }
        };
        Vec3::new(channel(0) as f32, channel(1) as f32, channel(2) as f32)
    }

    /// Mean illuminance (lx).
    pub fn mean_illuminance(&self) -> f32 {
        self.mean_illuminance_after(0)
    }

    /// Mean illuminance (lx) of the samples past the first `skipped` (those whose illuminance
    /// was not measured, see `Film::illuminance_from`); 0 before there is one.
    pub fn mean_illuminance_after(&self, skipped: u32) -> f32 {
        let n = self.count.saturating_sub(skipped);
        if n == 0 {
            return 0.0;
        }
        (from_fixed(self.illuminance, VALUE_SCALE) / f64::from(n)) as f32
    }

    /// Mean Rec. 709 luminance (cd/m²), splats included, in f64 (the splats over this pixel's
    /// count, as [`PixelSum::mean_rgb`]).
    pub fn mean_luminance(&self) -> f64 {
        self.mean_luminance_over(None)
    }

    /// Mean Rec. 709 luminance (cd/m²), the splats over `light_paths` per pixel (see
    /// [`PixelSum::mean_rgb_over`]), in f64.
    pub fn mean_luminance_over(&self, light_paths: Option<f64>) -> f64 {
        if self.count == 0 {
            return 0.0;
        }
        let w = LUMINANCE_WEIGHTS.as_dvec3();
        let n = f64::from(self.count);
        let Some(m) = light_paths else {
            let total =
                |c: usize| from_fixed(self.rgb[c].saturating_add(self.splat_rgb[c]), VALUE_SCALE);
            return (w.x * total(0) + w.y * total(1) + w.z * total(2)) / n;
        };
        let splats = w.x * from_fixed(self.splat_rgb[0], VALUE_SCALE)
            + w.y * from_fixed(self.splat_rgb[1], VALUE_SCALE)
            + w.z * from_fixed(self.splat_rgb[2], VALUE_SCALE);
        self.own_mean_luminance() + splats / m.max(1e-9)
    }

    /// Mean Rec. 709 luminance of the pixel's own samples (without splats), in f64.
    pub fn own_mean_luminance(&self) -> f64 {
        if self.count == 0 {
            return 0.0;
        }
        let w = LUMINANCE_WEIGHTS.as_dvec3();
        let sum = w.x * from_fixed(self.rgb[0], VALUE_SCALE)
            + w.y * from_fixed(self.rgb[1], VALUE_SCALE)
            + w.z * from_fixed(self.rgb[2], VALUE_SCALE);
        sum / f64::from(self.count)
    }

    /// The sample variance of the pixel's own samples' luminance ((cd/m²)², one sample's, not
    /// the mean's); None with fewer than two samples.
    pub fn own_luminance_variance(&self) -> Option<f64> {
        if self.count < 2 {
            return None;
        }
        let n = f64::from(self.count);
        let mean = self.own_mean_luminance();
        let mean_sq = self.luminance_sq.value() / n;
        Some((mean_sq - mean * mean).max(0.0) * n / (n - 1.0))
    }

    /// Standard error of the mean luminance (cd/m²), splats included; None with fewer than two
    /// samples (the splats over this pixel's count, as [`PixelSum::mean_rgb`]).
    pub fn luminance_std_error(&self) -> Option<f64> {
        self.luminance_std_error_over(None)
    }

    /// Standard error of the mean luminance (cd/m²), splats included, with the splats over
    /// `light_paths` per pixel (see [`PixelSum::mean_rgb_over`]); None with fewer than two
    /// samples.
    ///
    /// The mean is Σ own samples / n + Σ splats / m. The n own samples are independent and
    /// alike, so their part contributes their sample variance / n. The splats come from the
    /// light subpaths of every pixel's samples: independent and alike too, each adding a value
    /// c_j (zero for most), so their part of the variance of the mean is Σ_j Var(c_j) / m²,
    /// which Σ_j c_j² / m² estimates. It leaves out −Σ_j E[c_j]² / m², which is the squared
    /// mean of the splats over the number of light subpaths (the image's samples): negligible,
    /// and it errs on the side of a larger error. A light subpath also lights its own pixel's
    /// sample through other connections; that correlation is ignored (a subpath rarely splats
    /// into its own pixel).
    pub fn luminance_std_error_over(&self, light_paths: Option<f64>) -> Option<f64> {
        let var = self.own_luminance_variance()?;
        let n = f64::from(self.count);
        let m = light_paths.unwrap_or(n).max(1e-9);
        let splat_var = self.splat_luminance_sq.value() / (m * m);
        Some((var / n + splat_var).sqrt())
    }
}

/// A standard error relative to `scale` (a luminance or an illuminance): infinite when the
/// scale is 0 and the error is not, 0 when both are.
pub fn relative_error(se: f64, scale: f64) -> f64 {
    if scale > 0.0 {
        se / scale
    } else if se > 0.0 {
        f64::INFINITY
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
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
    }
}
