//! The film's fixed point: each sample's values rounded once to integers, so sums are exact
//! and do not depend on the order samples arrive in.
//!
//! Scales: luminance and illuminance in units of 2⁻³² cd/m² (lx), squared luminance in units of
//! 2⁻⁴⁸ (cd/m²)² ([`super::square_sum`]). One sample may be at most 2⁶² cd/m² (lx) and its
//! luminance at most 2³⁹ cd/m²; a sample beyond that, or not a finite number, cannot be
//! represented.

use super::square_sum::SquareSum;
use crate::integrator::Sample;
use crate::light::LUMINANCE_WEIGHTS;

/// Fixed-point units per cd/m² (and per lx).
pub const VALUE_SCALE: f64 = 4_294_967_296.0; // 2^32
/// Largest fixed-point magnitude one sample may contribute (2^94): 2^33 samples fit in i128.
pub(super) const SAMPLE_LIMIT: f64 = 19_807_040_628_566_084_398_385_987_584.0;

/// A sample's values in fixed point: r, g, b and illuminance in units of 2⁻³², and its
/// luminance squared; None when one of them cannot be represented.
/// (All converted before any is tested: one branch, not five.)
#[inline(always)]
pub(super) fn fixed_values(s: &Sample) -> Option<([i128; 4], SquareSum)> {
    let y = f64::from(s.rgb.dot(LUMINANCE_WEIGHTS));
    let fixed = (
        to_fixed(f64::from(s.rgb.x), VALUE_SCALE),
        to_fixed(f64::from(s.rgb.y), VALUE_SCALE),
        to_fixed(f64::from(s.rgb.z), VALUE_SCALE),
        to_fixed(f64::from(s.illuminance_lx), VALUE_SCALE),
        SquareSum::of_luminance(y),
    );
    let (Some(r), Some(g), Some(b), Some(e), Some(q)) = fixed else {
        return None;
    };
    Some(([r, g, b, e], q))
}

pub(crate) fn to_fixed(v: f64, scale: f64) -> Option<i128> {
    let x = v * scale;
    if x.abs() < FAST_LIMIT {
        return Some(i128::from(round_half_away(x)));
    }
    let x = x.round();
    (x.is_finite() && x.abs() < SAMPLE_LIMIT).then_some(x as i128)
}

/// Below 2^62 a scaled value rounds through i64 (one instruction each way) instead of libm's
/// `round` and the soft 128-bit conversions, which took a tenth of a direct-light frame.
pub(super) const FAST_LIMIT: f64 = 4_611_686_018_427_387_904.0; // 2^62

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
pub(crate) fn from_fixed(x: i128, scale: f64) -> f64 {
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

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

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
            for scale in [VALUE_SCALE, 65_536.0] {
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
}
