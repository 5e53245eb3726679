//! The 64-bit sums of a run of one pixel's samples, for [`PixelSum::add_run`]: each of a
//! sample's values scaled to fixed point and rounded half away from zero, exactly as the
//! film's exact path rounds it, then added as an integer. The squared luminance is split as
//! [`super::square_sum`] keeps it: a whole part in units of 2⁻¹⁶ and a remainder in units of
//! 2⁻⁴⁸, summed apart. Where the CPU has AVX2 (checked at
//! run time) a sample's luminance per channel and its illuminance are converted together in
//! four `f64` lanes; elsewhere one by one. Both give the same integers, so the film's sums do
//! not depend on the CPU.
//!
//! A run comes back as `None` when any value is out of range (large, NaN or infinite); the
//! caller then adds its samples one by one through the exact path.
//!
//! [`PixelSum::add_run`]: super::pixel_sum::PixelSum::add_run

use super::fixed_point::{VALUE_SCALE, round_half_away};
use super::square_sum::{FINE_BITS, SQUARE_SCALE};
use crate::integrator::Sample;
use crate::light::LUMINANCE_WEIGHTS;

/// Most samples summed in one run: each term is at most 2^52 in size ([`SCALAR_LIMIT`]), so
/// 1024 of them stay below 2^62 and a run's sums cannot overflow.
pub(super) const RUN_SAMPLES: usize = 1024;

/// The scalar path takes scaled values below 2^52 in size (its truncation is exact there).
const SCALAR_LIMIT: f64 = 4_503_599_627_370_496.0; // 2^52

/// Squares (in units of 2⁻¹⁶) below 2^51 take the runs: their whole parts convert exactly in
/// the lanes, and 1024 of them stay below 2^61.
const SQUARE_LIMIT: f64 = 2_251_799_813_685_248.0; // 2^51

/// 2³²: a square's remainder (in units of 2⁻¹⁶) times this is in units of 2⁻⁴⁸.
const FINE: f64 = (1u64 << FINE_BITS) as f64;

/// The sums of `run` (at most [`RUN_SAMPLES`] samples): Σ r, g, b, illuminance in units of
/// 2⁻³², then Σ luminance² as its whole parts in units of 2⁻¹⁶ and its rounded remainders in
/// units of 2⁻⁴⁸; None when a value is out of the fast range.
pub(super) fn run_sums(run: &[Sample]) -> Option<[i64; 6]> {
    debug_assert!(run.len() <= RUN_SAMPLES);
    #[cfg(target_arch = "x86_64")]
    if is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2, the only feature `avx2::run_sums` is compiled for.
        return unsafe { avx2::run_sums(run) };
    }
    scalar_run_sums(run)
}

/// Values whose whole part (in units of 2³² fixed-point units) is below 2^40 in size take
/// [`wide_run_sums`]: 1024 of them stay far below 2^62.
const WIDE_LIMIT: f64 = 1_099_511_627_776.0; // 2^40

/// 2⁻³²: a scaled value times this is its whole part's scale (exact: a power of two).
const SPLIT: f64 = 1.0 / 4_294_967_296.0;

/// [`run_sums`] for runs with larger values (very bright pixels: a lamp millimetres away gives
/// millions of lux): each scaled value `x` split into a whole number `h` of 2³² units and a
/// remainder, `x = h · 2³² + l` with `|l| < 2³²`, both exact; `l` has the sign of `x`, so
/// rounding `x` half away from zero is `h · 2³²` plus `l` rounded the same way. The sums of `h`
/// and of the rounded `l` come back as one 128-bit sum per value (the squared luminance in
/// units of 2⁻⁴⁸, split as [`square_parts`] splits it); None when a value's `h` is 2^40 or
/// more in size, a square is past [`SQUARE_LIMIT`] (or NaN, or infinite).
pub(super) fn wide_run_sums(run: &[Sample]) -> Option<[i128; 5]> {
    debug_assert!(run.len() <= RUN_SAMPLES);
    #[cfg(target_arch = "x86_64")]
    if is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2, the only feature `avx2::wide_run_sums` is compiled for.
        return unsafe { avx2::wide_run_sums(run) };
    }
    scalar_wide_run_sums(run)
}

/// The whole part and the remainder of the scaled value `x`, as integers (`x` rounded half
/// away from zero is `h · 2³² + l`); None when out of range.
#[inline(always)]
fn split(x: f64) -> Option<(i64, i64)> {
    let m = x * SPLIT;
    let in_range = m.abs() < WIDE_LIMIT;
    if !in_range {
        return None;
    }
    // SAFETY: |m| < 2^40 (false for NaN): the truncation is exact and in range.
    let h: i64 = unsafe { m.to_int_unchecked() };
    // m - h is m's fraction (exact), and times 2^32 exact: |l| < 2^32.
    let l = (m - h as f64) * (1.0 / SPLIT);
    Some((h, round_half_away(l)))
}

/// A square in units of 2⁻¹⁶ as its whole part and its remainder rounded half away from zero
/// in units of 2⁻⁴⁸ (exact below 2⁵², like [`split`]); 0 and `in_range` cleared past
/// [`SQUARE_LIMIT`] (NaN included). Without a branch.
#[inline(always)]
fn square_parts(x: f64, in_range: &mut bool) -> (i64, i64) {
    let ok = x.abs() < SQUARE_LIMIT;
    *in_range &= ok;
    let x = if ok { x } else { 0.0 };
    // SAFETY: |x| < 2^51: the truncation is exact and in range.
    let h: i64 = unsafe { x.to_int_unchecked() };
    (h, round_half_away((x - h as f64) * FINE))
}

fn scalar_wide_run_sums(run: &[Sample]) -> Option<[i128; 5]> {
    let (mut whole, mut rest) = ([0i64; 5], [0i64; 5]);
    let mut in_range = true;
    for s in run {
        let scaled = scaled_values(s);
        for k in 0..4 {
            let (h, l) = split(scaled[k])?;
            whole[k] += h;
            rest[k] += l;
        }
        let (h, l) = square_parts(scaled[4], &mut in_range);
        whole[4] += h;
        rest[4] += l;
    }
    in_range.then(|| join(whole, rest))
}

/// Σ h · 2³² + Σ l per value.
#[inline(always)]
fn join(whole: [i64; 5], rest: [i64; 5]) -> [i128; 5] {
    std::array::from_fn(|k| (i128::from(whole[k]) << 32) + i128::from(rest[k]))
}

/// A sample's five values scaled to fixed-point units, before rounding: r, g, b and
/// illuminance times 2³², luminance squared times 2¹⁶ (its whole part's unit).
#[inline(always)]
fn scaled_values(s: &Sample) -> [f64; 5] {
    [
        f64::from(s.rgb.x) * VALUE_SCALE,
        f64::from(s.rgb.y) * VALUE_SCALE,
        f64::from(s.rgb.z) * VALUE_SCALE,
        f64::from(s.illuminance_lx) * VALUE_SCALE,
        scaled_luminance_sq(s),
    ]
}

/// Luminance squared in units of 2⁻¹⁶ (cd/m²)², before rounding.
#[inline(always)]
fn scaled_luminance_sq(s: &Sample) -> f64 {
    let y = f64::from(s.rgb.dot(LUMINANCE_WEIGHTS));
    y * y * SQUARE_SCALE
}

/// One value into a run's sum, without a branch: out of range (NaN included) it counts 0 and
/// clears `in_range`.
#[inline(always)]
fn add_scaled(sum: &mut i64, x: f64, in_range: &mut bool) {
    let ok = x.abs() < SCALAR_LIMIT;
    *in_range &= ok;
    *sum += round_half_away(if ok { x } else { 0.0 });
}

fn scalar_run_sums(run: &[Sample]) -> Option<[i64; 6]> {
    let mut sums = [0i64; 6];
    let mut in_range = true;
    for s in run {
        let scaled = scaled_values(s);
        for (sum, x) in sums.iter_mut().zip(&scaled[..4]) {
            add_scaled(sum, *x, &mut in_range);
        }
        let (h, l) = square_parts(scaled[4], &mut in_range);
        sums[4] += h;
        sums[5] += l;
    }
    in_range.then_some(sums)
}

/// Four lanes of `f64`: r, g, b and illuminance of one sample.
///
/// Per lane: `x = v · 2³²` (exact, as in the scalar path); `t = trunc(x)`; the remainder
/// `x - t` (exact); `t` moved one away from zero when the remainder is at least one half. The
/// whole number `t` becomes an `i64` through the bits of `t + 1.5 · 2⁵²`, exact for
/// `|t| < 2⁵¹`, the lanes' range (values up to 2⁵² take the scalar path's way through
/// `None` and the exact path, which gives the same sums).
#[cfg(target_arch = "x86_64")]
mod avx2 {
    use super::{
        FINE, LUMINANCE_WEIGHTS, RUN_SAMPLES, SPLIT, SQUARE_LIMIT, SQUARE_SCALE, Sample,
        VALUE_SCALE, WIDE_LIMIT, join, scaled_luminance_sq, square_parts,
    };
    use std::arch::x86_64::*;

    /// Values below 2^51 in size (where the bit trick is exact).
    const LANE_LIMIT: f64 = 2_251_799_813_685_248.0; // 2^51
    /// 1.5 · 2⁵²: added to a whole number below 2⁵¹ in size, its bits less this one's bits
    /// are the number.
    const MAGIC: f64 = 6_755_399_441_055_744.0;

    /// Four scaled values rounded half away from zero, as `i64` lanes, and which were in
    /// range (all bits set); out-of-range lanes give 0. (A function, not a closure, so the
    /// intrinsics inline into the AVX2 caller.)
    #[inline(always)]
    fn round_lanes(x: __m256d) -> (__m256i, __m256d) {
        // SAFETY: only called from `run_sums`, compiled for AVX2; no memory operands.
        unsafe {
            let ok = _mm256_cmp_pd::<_CMP_LT_OQ>(
                _mm256_andnot_pd(_mm256_set1_pd(-0.0), x),
                _mm256_set1_pd(LANE_LIMIT),
            );
            let x = _mm256_and_pd(x, ok);
            let t = _mm256_round_pd::<{ _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC }>(x);
            let frac = _mm256_sub_pd(x, t);
            // All ones (-1) where the remainder rounds away from zero.
            let up = _mm256_castpd_si256(_mm256_cmp_pd::<_CMP_GE_OQ>(frac, _mm256_set1_pd(0.5)));
            let down = _mm256_castpd_si256(_mm256_cmp_pd::<_CMP_LE_OQ>(frac, _mm256_set1_pd(-0.5)));
            let magic = _mm256_set1_pd(MAGIC);
            let whole = _mm256_sub_epi64(
                _mm256_castpd_si256(_mm256_add_pd(t, magic)),
                _mm256_castpd_si256(magic),
            );
            (_mm256_add_epi64(_mm256_sub_epi64(whole, up), down), ok)
        }
    }

    /// Four scaled values split as `super::split` does, as `i64` lanes: the whole parts, the
    /// rounded remainders, and which were in range (all bits set); out-of-range lanes give 0.
    #[inline(always)]
    fn split_lanes(x: __m256d) -> (__m256i, __m256i, __m256d) {
        // SAFETY: only called from `wide_run_sums`, compiled for AVX2; no memory operands.
        let m = unsafe { _mm256_mul_pd(x, _mm256_set1_pd(SPLIT)) };
        whole_and_rest(m, WIDE_LIMIT)
    }

    /// Four squares in units of 2⁻¹⁶ split as `super::square_parts` does: the whole parts
    /// (units of 2⁻¹⁶) and the rounded remainders (units of 2⁻⁴⁸), and which were in range.
    #[inline(always)]
    fn square_lanes(x: __m256d) -> (__m256i, __m256i, __m256d) {
        whole_and_rest(x, SQUARE_LIMIT)
    }

    /// Four values `m` as whole numbers (below `limit` in size, at most 2⁵¹) and their
    /// fractions times 2³² rounded half away from zero, with the range test.
    #[inline(always)]
    fn whole_and_rest(m: __m256d, limit: f64) -> (__m256i, __m256i, __m256d) {
        debug_assert!(limit <= SQUARE_LIMIT && SPLIT * FINE == 1.0);
        // SAFETY: only called from `run_sums` and `wide_run_sums`, compiled for AVX2; no
        // memory operands.
        unsafe {
            let ok = _mm256_cmp_pd::<_CMP_LT_OQ>(
                _mm256_andnot_pd(_mm256_set1_pd(-0.0), m),
                _mm256_set1_pd(limit),
            );
            let m = _mm256_and_pd(m, ok);
            let h = _mm256_round_pd::<{ _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC }>(m);
            let l = _mm256_mul_pd(_mm256_sub_pd(m, h), _mm256_set1_pd(FINE));
            let magic = _mm256_set1_pd(MAGIC);
            let whole = _mm256_sub_epi64(
                _mm256_castpd_si256(_mm256_add_pd(h, magic)),
                _mm256_castpd_si256(magic),
            );
            let (rest, _) = round_lanes(l);
            (whole, rest, ok)
        }
    }

    #[target_feature(enable = "avx2")]
    pub(super) fn wide_run_sums(run: &[Sample]) -> Option<[i128; 5]> {
        debug_assert!(run.len() <= RUN_SAMPLES);
        let (mut whole, mut rest) = (_mm256_setzero_si256(), _mm256_setzero_si256());
        let (mut q_whole, mut q_rest) = (_mm256_setzero_si256(), _mm256_setzero_si256());
        let mut ok_all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
        let value_scale = _mm256_set1_pd(VALUE_SCALE);
        let square_scale = _mm256_set1_pd(SQUARE_SCALE);
        let mut four = run.chunks_exact(4);
        for quad in four.by_ref() {
            for s in quad {
                let v = _mm_set_ps(s.illuminance_lx, s.rgb.z, s.rgb.y, s.rgb.x);
                let (h, l, ok) = split_lanes(_mm256_mul_pd(_mm256_cvtps_pd(v), value_scale));
                ok_all = _mm256_and_pd(ok_all, ok);
                whole = _mm256_add_epi64(whole, h);
                rest = _mm256_add_epi64(rest, l);
            }
            let y = |s: &Sample| f64::from(s.rgb.dot(LUMINANCE_WEIGHTS));
            let y = _mm256_set_pd(y(&quad[3]), y(&quad[2]), y(&quad[1]), y(&quad[0]));
            let (h, l, ok) = square_lanes(_mm256_mul_pd(_mm256_mul_pd(y, y), square_scale));
            ok_all = _mm256_and_pd(ok_all, ok);
            q_whole = _mm256_add_epi64(q_whole, h);
            q_rest = _mm256_add_epi64(q_rest, l);
        }
        let (mut q_h, mut q_l) = (
            lanes_of(q_whole).iter().sum::<i64>(),
            lanes_of(q_rest).iter().sum::<i64>(),
        );
        let mut q_in_range = true;
        for s in four.remainder() {
            let v = _mm_set_ps(s.illuminance_lx, s.rgb.z, s.rgb.y, s.rgb.x);
            let (h, l, ok) = split_lanes(_mm256_mul_pd(_mm256_cvtps_pd(v), value_scale));
            ok_all = _mm256_and_pd(ok_all, ok);
            whole = _mm256_add_epi64(whole, h);
            rest = _mm256_add_epi64(rest, l);
            let (h, l) = square_parts(scaled_luminance_sq(s), &mut q_in_range);
            q_h += h;
            q_l += l;
        }
        if _mm256_movemask_pd(ok_all) != 0b1111 || !q_in_range {
            return None;
        }
        let (w, r) = (lanes_of(whole), lanes_of(rest));
        Some(join(
            [w[0], w[1], w[2], w[3], q_h],
            [r[0], r[1], r[2], r[3], q_l],
        ))
    }

    /// The four `i64` lanes of `v`.
    #[inline(always)]
    fn lanes_of(v: __m256i) -> [i64; 4] {
        let mut lanes = [0i64; 4];
        // SAFETY: `lanes` is 32 writable bytes; the store is unaligned; AVX is present.
        unsafe { _mm256_storeu_si256(lanes.as_mut_ptr().cast(), v) };
        lanes
    }

    /// Adds sample `s`'s luminance per channel and illuminance, rounded in four lanes, to
    /// `sums`, and its range test to `ok_all`.
    #[inline(always)]
    fn add_channels(s: &Sample, sums: &mut __m256i, ok_all: &mut __m256d) {
        // SAFETY: only called from `run_sums`, compiled for AVX2; no memory operands.
        unsafe {
            let v = _mm_set_ps(s.illuminance_lx, s.rgb.z, s.rgb.y, s.rgb.x);
            let scaled = _mm256_mul_pd(_mm256_cvtps_pd(v), _mm256_set1_pd(VALUE_SCALE));
            let (rounded, ok) = round_lanes(scaled);
            *ok_all = _mm256_and_pd(*ok_all, ok);
            *sums = _mm256_add_epi64(*sums, rounded);
        }
    }

    #[target_feature(enable = "avx2")]
    pub(super) fn run_sums(run: &[Sample]) -> Option<[i64; 6]> {
        debug_assert!(run.len() <= RUN_SAMPLES);
        let square_scale = _mm256_set1_pd(SQUARE_SCALE);
        let mut sums = _mm256_setzero_si256();
        let (mut q_whole, mut q_rest) = (_mm256_setzero_si256(), _mm256_setzero_si256());
        let mut ok_all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
        let mut four = run.chunks_exact(4);
        for quad in four.by_ref() {
            // Luminance per channel and illuminance of each sample, four lanes at a time.
            for s in quad {
                add_channels(s, &mut sums, &mut ok_all);
            }
            // The four samples' luminance squared in one vector (y · y · 2¹⁶, as the scalar
            // path multiplies), split into whole parts and remainders.
            let y = |s: &Sample| f64::from(s.rgb.dot(LUMINANCE_WEIGHTS));
            let y = _mm256_set_pd(y(&quad[3]), y(&quad[2]), y(&quad[1]), y(&quad[0]));
            let (h, l, ok) = square_lanes(_mm256_mul_pd(_mm256_mul_pd(y, y), square_scale));
            ok_all = _mm256_and_pd(ok_all, ok);
            q_whole = _mm256_add_epi64(q_whole, h);
            q_rest = _mm256_add_epi64(q_rest, l);
        }
        let mut q_h = lanes_of(q_whole).iter().sum::<i64>();
        let mut q_l = lanes_of(q_rest).iter().sum::<i64>();
        let mut q_in_range = true;
        for s in four.remainder() {
            add_channels(s, &mut sums, &mut ok_all);
            let (h, l) = square_parts(scaled_luminance_sq(s), &mut q_in_range);
            q_h += h;
            q_l += l;
        }
        let all_in_range = _mm256_movemask_pd(ok_all) == 0b1111;
        let lanes = lanes_of(sums);
        (all_in_range && q_in_range).then_some([lanes[0], lanes[1], lanes[2], lanes[3], q_h, q_l])
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixed_point::fixed_values;
    use super::*;
    use glam::Vec3;

    fn sample(rgb: [f32; 3], e: f32) -> Sample {
        Sample {
            rgb: Vec3::from_array(rgb),
            illuminance_lx: e,
            rays: 1,
            missed: false,
        }
    }

    #[test]
    fn lanes_and_scalar_give_the_same_sums() {
        // Halves and near-halves of the fixed-point unit (both signs), tiny, whole, large and
        // out-of-range values, in runs of several lengths.
        let unit = (VALUE_SCALE as f32).recip();
        let mut h = 11u64;
        let mut values = vec![
            0.0,
            -0.0,
            unit * 0.5,
            -unit * 0.5,
            unit * 1.5,
            -unit * 2.5,
            unit * 0.499_999_97,
            unit * 0.500_000_06,
            1.0,
            -3.25,
            1.0e5,
            4.0e5,
            -4.0e5,
        ];
        for i in 0..3000u32 {
            h = crate::render::sample_hash(h, i);
            let u = (h >> 40) as f32 / (1u64 << 24) as f32;
            values.push(match i % 7 {
                0 => u * unit * 4.0 - unit * 2.0,
                1 => u * 1.0e-3,
                2 => (u - 0.5) * 300.0,
                3 => u * 3.0e5,
                _ => u * 50.0,
            });
        }
        let samples: Vec<Sample> = values
            .chunks(4)
            .filter(|c| c.len() == 4)
            .map(|c| sample([c[0], c[1], c[2]], c[3]))
            .collect();
        // The largest scaled value of a run: the lanes take below 2^51, the scalar path 2^52.
        let largest = |run: &[Sample]| {
            run.iter()
                .flat_map(|s| {
                    let v = [s.rgb.x, s.rgb.y, s.rgb.z, s.illuminance_lx];
                    v.map(|v| (f64::from(v) * VALUE_SCALE).abs())
                        .into_iter()
                        .chain([scaled_luminance_sq(s)])
                })
                .fold(0.0, f64::max)
        };
        let (mut fast, mut quads) = (0, 0);
        for len in [1, 3, 4, 5, 64, 700] {
            for run in samples.chunks(len) {
                let sums = run_sums(run);
                match (sums, scalar_run_sums(run)) {
                    (Some(lanes), Some(scalar)) => assert_eq!(lanes, scalar, "run of {len}"),
                    (None, None) => {}
                    (None, Some(_)) => assert!(largest(run) >= 2f64.powi(51), "run of {len}"),
                    (Some(_), None) => panic!("the lanes took a value out of range"),
                }
                fast += usize::from(len == 1 && sums.is_some());
                quads += usize::from(len == 4 && sums.is_some());
            }
        }
        // Runs of four take the lanes' own luminance-squared path.
        assert!(quads > samples.len() / 4 / 2, "{quads} runs of four");
        // The comparison is not vacuous: almost every single sample takes the fast path.
        assert!(fast > samples.len() * 9 / 10, "{fast} of {}", samples.len());
        let big = [sample([6.0e5, 0.0, 0.0], 0.0)];
        assert_eq!(scalar_run_sums(&big).map(|_| ()), Some(()));
        // Beyond the lanes' 2^51 the fast path declines (the exact path gives the same sums).
        #[cfg(target_arch = "x86_64")]
        if is_x86_feature_detected!("avx2") {
            assert_eq!(run_sums(&big), None);
        }
        for bad in [f32::NAN, f32::INFINITY, 2.0e9] {
            assert_eq!(run_sums(&[sample([1.0, bad, 1.0], 0.0)]), None);
            assert_eq!(scalar_run_sums(&[sample([1.0, 1.0, 1.0], bad)]), None);
        }
    }

    #[test]
    fn wide_sums_match_the_exact_path() {
        // Values past the 64-bit runs (up to 2 · 10^8 cd/m², whose square still fits), with
        // remainders near halves of the fixed-point unit, both signs, mixed with ordinary
        // ones; a few past the wide range.
        let unit = (VALUE_SCALE as f32).recip();
        let mut h = 5u64;
        let mut values = Vec::new();
        for i in 0..6000u32 {
            h = crate::render::sample_hash(h, i);
            let u = (h >> 40) as f32 / (1u64 << 24) as f32;
            values.push(match i % 9 {
                0 => u * 3.0e6,
                1 => -u * 2.0e8,
                2 => 1.0e8 * u,
                3 => 4.0e5 + unit * 0.5,
                4 => -(7.0e5 + u),
                5 => u * 1.0e-3 + unit * 1.5,
                6 if i % 5 == 0 => 3.0e12,
                7 => -(u * 1.0e-3) - unit * 2.5,
                _ => (u - 0.5) * 300.0,
            });
        }
        // Green mostly cancels red and blue in the luminance: the wide runs take squares of
        // luminances up to about 1.8 · 10^5 cd/m² (brighter ones go through the exact path),
        // while their channels reach 10^8.
        let w = LUMINANCE_WEIGHTS;
        let samples: Vec<Sample> = values
            .chunks(4)
            .filter(|c| c.len() == 4)
            .map(|c| {
                let g = (c[1] * 1.0e-3).clamp(-1.0e5, 1.0e5) - (w.x * c[0] + w.z * c[2]) / w.y;
                sample([c[0], g, c[2]], c[3])
            })
            .collect();
        let (mut compared, mut declined) = (0, 0);
        for len in [1, 3, 4, 5, 64, 700] {
            for run in samples.chunks(len) {
                // What the exact path adds: each representable sample's five values, alone.
                // (Squares past an i128 of 2^-48 units only occur in runs the wide path
                // declines.)
                let mut expected = [0i128; 5];
                for (v, q) in run.iter().filter_map(fixed_values) {
                    for (e, v) in expected.iter_mut().zip(v) {
                        *e += v;
                    }
                    let q = q.units().unwrap_or(i128::MAX / 4096);
                    expected[4] = expected[4].saturating_add(q);
                }
                match (wide_run_sums(run), scalar_wide_run_sums(run)) {
                    (Some(lanes), Some(scalar)) => {
                        assert_eq!(lanes, scalar, "run of {len}");
                        assert_eq!(lanes, expected, "run of {len}");
                        compared += 1;
                    }
                    (None, None) => declined += 1,
                    other => panic!("lanes and scalar disagree on a run of {len}: {other:?}"),
                }
            }
        }
        // Both outcomes happen, and most runs of one sample are compared.
        assert!(
            compared > samples.len() && declined > 0,
            "{compared} {declined}"
        );
        let bright = [sample([1.0, 2.0, 3.0], 2.0e6)];
        assert_eq!(run_sums(&bright), None, "past the 64-bit runs");
        assert!(wide_run_sums(&bright).is_some());
        for bad in [f32::NAN, f32::INFINITY, 3.0e12] {
            assert_eq!(wide_run_sums(&[sample([1.0, bad, 1.0], 0.0)]), None);
            assert_eq!(scalar_wide_run_sums(&[sample([1.0, 1.0, 1.0], bad)]), None);
        }
    }
}
