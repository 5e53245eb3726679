//! One sensor point's exact sums: its illuminance, the squares and the count (64 bytes, where
//! a film's [`crate::render::PixelSum`] carries colour and splats a point never has).
//!
//! Each sample is rounded once to the film's fixed point (2⁻³² lx, squares to 2⁻⁴⁸ lx²), so sums
//! do not depend on the order samples arrive in and shards add up exactly.

use crate::render::{SquareSum, VALUE_SCALE};

/// The exact sum of some illuminance samples of one sensor point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SensorSum {
    /// Σ E, units of 2⁻³² lx.
    pub illuminance: i128,
    /// Σ E², exact to 2⁻⁴⁸ lx².
    pub square: SquareSum,
    /// Samples added.
    pub count: u32,
    /// Samples refused (not finite, or beyond the fixed-point range).
    pub rejected: u32,
}

impl SensorSum {
    /// Adds one sample of `e` lx; false (and counted as rejected) when it cannot be represented.
    pub fn add(&mut self, e: f32) -> bool {
        let e = f64::from(e);
        let fixed = crate::render::to_fixed(e, VALUE_SCALE).zip(SquareSum::of_luminance(e));
        let sum = fixed.and_then(|(v, q)| {
            Some(SensorSum {
                illuminance: self.illuminance.checked_add(v)?,
                square: self.square.checked_add(&q)?,
                count: self.count.checked_add(1)?,
                rejected: self.rejected,
            })
        });
        match sum {
            Some(s) => {
                *self = s;
                true
            }
            None => {
                self.rejected = self.rejected.saturating_add(1);
                false
            }
        }
    }

    /// Adds another sum of the same point; false when the result would overflow (the sum is then
    /// unchanged and `other`'s samples are counted as rejected).
    pub fn merge(&mut self, other: &SensorSum) -> bool {
        let sum = (|| {
            Some(SensorSum {
                illuminance: self.illuminance.checked_add(other.illuminance)?,
                square: self.square.checked_add(&other.square)?,
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

    /// Mean illuminance (lx); 0 without samples.
    pub fn mean(&self) -> f64 {
        if self.count == 0 {
            return 0.0;
        }
        crate::render::from_fixed(self.illuminance, VALUE_SCALE) / f64::from(self.count)
    }

    /// Standard error of the mean (lx); None with fewer than two samples.
    pub fn std_error(&self) -> Option<f64> {
        if self.count < 2 {
            return None;
        }
        let n = f64::from(self.count);
        let mean = self.mean();
        let var = (self.square.value() / n - mean * mean).max(0.0) * n / (n - 1.0);
        Some((var / n).sqrt())
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn a_sensor_sum_is_small_exact_and_textbook() {
        assert!(size_of::<SensorSum>() <= 64, "{}", size_of::<SensorSum>());
        // Sample variance of 1..4 is 5/3; the standard error sqrt(5/3 / 4); the same at 1e-4 lx
        // (relative), where the former 2^-16 squares rounded to 0.
        for scale in [1.0f32, 1e-4] {
            let mut s = SensorSum::default();
            for v in [1.0f32, 2.0, 3.0, 4.0] {
                assert!(s.add(v * scale));
            }
            let se = s.std_error().unwrap() / f64::from(scale);
            assert!((se - (5.0f64 / 12.0).sqrt()).abs() < 1e-5, "{scale}: {se}");
            assert!((s.mean() / f64::from(scale) - 2.5).abs() < 1e-6);
        }
        let (mut a, mut b, mut all) = (
            SensorSum::default(),
            SensorSum::default(),
            SensorSum::default(),
        );
        for (k, v) in [0.3f32, 7.0e9, 1e-6, 12.5].iter().enumerate() {
            all.add(*v);
            if k % 2 == 0 {
                a.add(*v)
            } else {
                b.add(*v)
            };
        }
        assert!(a.merge(&b));
        assert_eq!(a, all);
        assert!(!all.add(f32::NAN));
        assert_eq!((all.count, all.rejected), (4, 1));
    }
}
