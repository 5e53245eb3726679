//! The exact sum of squared luminances, precise for dim pixels and wide enough for a lamp's hot
//! spot.
//!
//! One sample's square y² is rounded once, half away from zero, to units of 2⁻⁴⁸ (cd/m²)²:
//! a luminance of 10⁻⁴ cd/m² still has about 2.8 · 10⁶ units, so its standard error is right
//! to a millionth (the former units of 2⁻¹⁶ rounded any square below 0.0028² to 0). The value
//! is kept in two integers, `whole` in units of 2⁻¹⁶ and `fine` in units of 2⁻⁴⁸ with
//! 0 ≤ fine < 2³² after every addition: the sum is `whole · 2³² + fine` units of 2⁻⁴⁸. The
//! form is unique, so equal sums compare equal, and `whole` has the range the film's squares
//! always had (one sample up to 2³⁹ cd/m², 2³³ of them).

use super::fixed_point::{FAST_LIMIT, SAMPLE_LIMIT, round_half_away};

/// Units of 2⁻⁴⁸ per unit of 2⁻¹⁶: the split between `whole` and `fine`.
pub(super) const FINE_BITS: u32 = 32;
/// Units of 2⁻¹⁶ (cd/m²)² per (cd/m²)²: the scale of [`SquareSum::whole`].
pub const SQUARE_SCALE: f64 = 65_536.0; // 2^16
/// Units of 2⁻⁴⁸ (cd/m²)² per (cd/m²)²: the scale of [`SquareSum::fine`] and of the sum.
pub const FINE_SQUARE_SCALE: f64 = 281_474_976_710_656.0; // 2^48

/// Σ y² of some samples, exact, in units of 2⁻⁴⁸ (cd/m²)².
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, bytemuck::Zeroable)]
pub struct SquareSum {
    /// The whole part, units of 2⁻¹⁶ (cd/m²)².
    pub whole: i128,
    /// The rest, units of 2⁻⁴⁸ (cd/m²)², 0 ≤ fine < 2³².
    pub fine: i64,
}

impl SquareSum {
    /// The sum whose value is `whole · 2³² + fine` units (any `fine`); None past the range.
    pub fn from_parts(whole: i128, fine: i64) -> Option<SquareSum> {
        let carry = i128::from(fine >> FINE_BITS);
        Some(SquareSum {
            whole: whole.checked_add(carry)?,
            fine: fine & ((1 << FINE_BITS) - 1),
        })
    }

    /// The sum of `units` units of 2⁻⁴⁸.
    pub fn from_units(units: i128) -> SquareSum {
        SquareSum {
            whole: units >> FINE_BITS,
            fine: (units & ((1 << FINE_BITS) - 1)) as i64,
        }
    }

    /// The value in units of 2⁻⁴⁸, when it fits in an i128.
    pub fn units(&self) -> Option<i128> {
        self.whole
            .checked_mul(1 << FINE_BITS)?
            .checked_add(i128::from(self.fine))
    }

    /// One sample's square, `y · y` rounded to units of 2⁻⁴⁸; None when it cannot be
    /// represented (not finite, or past 2⁹⁴ units of 2⁻¹⁶).
    #[inline(always)]
    pub fn of_luminance(y: f64) -> Option<SquareSum> {
        let (whole, fine) = split_square(y * y * SQUARE_SCALE)?;
        Some(SquareSum { whole, fine }.normalised())
    }

    /// Adds another sum; None on overflow.
    #[inline(always)]
    pub fn checked_add(&self, other: &SquareSum) -> Option<SquareSum> {
        SquareSum::from_parts(self.whole.checked_add(other.whole)?, self.fine + other.fine)
    }

    /// The sum in (cd/m²)².
    pub fn value(&self) -> f64 {
        super::fixed_point::from_fixed(self.whole, SQUARE_SCALE)
            + self.fine as f64 / FINE_SQUARE_SCALE
    }

    /// `fine` back in [0, 2³²) (it may reach 2³³ after adding two normalised sums).
    #[inline(always)]
    fn normalised(self) -> SquareSum {
        let carry = self.fine >> FINE_BITS;
        SquareSum {
            whole: self.whole + i128::from(carry),
            fine: self.fine - (carry << FINE_BITS),
        }
    }
}

/// A square already scaled to units of 2⁻¹⁶ (`x = y² · 2¹⁶`) split into its whole part and its
/// remainder rounded half away from zero to units of 2⁻⁴⁸ (so the square in units of 2⁻⁴⁸,
/// rounded, is `whole · 2³² + rest`, with 0 ≤ rest ≤ 2³²); None when not representable.
/// Exact: below 2⁵² the truncation and `x - whole` are exact and `· 2³²` is a power of two;
/// above it `x` is whole and the remainder 0.
#[inline(always)]
pub(super) fn split_square(x: f64) -> Option<(i128, i64)> {
    if x.abs() < FAST_LIMIT {
        // SAFETY: |x| < 2^62 (false for NaN): the truncation is exact and in range.
        let whole: i64 = unsafe { x.to_int_unchecked() };
        let rest = round_half_away((x - whole as f64) * (1u64 << FINE_BITS) as f64);
        return Some((i128::from(whole), rest));
    }
    (x.is_finite() && x.abs() < SAMPLE_LIMIT).then_some((x as i128, 0))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn squares_are_exact_to_two_to_the_minus_48() {
        // A dim luminance keeps its square's digits: 1e-4 cd/m² squared is 1e-8, about 2.8e6
        // units; the units are y·y·2^48 rounded, whatever the split.
        for y in [1e-4f64, 3.7e-3, 0.5, 1.0, 3.999, 4.0, 1234.5, 1.0e9, 2.0e10] {
            let s = SquareSum::of_luminance(y).unwrap();
            assert!((0..1 << 32).contains(&s.fine), "{y}");
            let expected = y * y * FINE_SQUARE_SCALE;
            match s.units() {
                Some(u) if expected < 1e30 => assert_eq!(u, expected.round() as i128, "{y}"),
                _ => assert!((s.value() / (y * y) - 1.0).abs() < 1e-12, "{y}"),
            }
            assert!((s.value() / (y * y) - 1.0).abs() < 1e-6, "{y}");
        }
        assert!(SquareSum::of_luminance(f64::NAN).is_none());
        assert!(SquareSum::of_luminance(f64::INFINITY).is_none());
        assert!(SquareSum::of_luminance(1e30).is_none());
    }

    #[test]
    fn sums_are_unique_and_do_not_depend_on_order() {
        let ys = [1e-4, 2.5, 0.0312, 7.0e6, 1e-9, 3.0];
        let squares: Vec<SquareSum> = ys
            .iter()
            .map(|&y| SquareSum::of_luminance(y).unwrap())
            .collect();
        let forward = squares
            .iter()
            .fold(SquareSum::default(), |a, b| a.checked_add(b).unwrap());
        let backward = squares
            .iter()
            .rev()
            .fold(SquareSum::default(), |a, b| a.checked_add(b).unwrap());
        assert_eq!(forward, backward);
        let units: i128 = squares.iter().map(|s| s.units().unwrap()).sum();
        assert_eq!(SquareSum::from_units(units), forward);
        assert_eq!(forward.units(), Some(units));
        // Parts with a fine part past 2^32 (a run's sums) give the same sum.
        let (w, f) = (forward.whole - 3, forward.fine + (3 << 32));
        assert_eq!(SquareSum::from_parts(w, f), Some(forward));
        let total: f64 = ys.iter().map(|y| y * y).sum();
        assert!((forward.value() / total - 1.0).abs() < 1e-12);
    }
}
