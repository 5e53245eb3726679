//! The AVX kind of [`super::Lanes8`]: one 256-bit register per eight lanes, used only where the
//! CPU has AVX (checked at run time by the callers).

use super::{Lanes8, Mask8};
use std::arch::x86_64::*;

#[derive(Clone, Copy, Debug)]
pub(crate) struct Avx8(__m256);

#[derive(Clone, Copy, Debug)]
pub(crate) struct AvxMask8(__m256);

macro_rules! avx {
    ($e:expr) => {
        // SAFETY: see the soundness note on `Avx8` (AVX is present where this runs).
        unsafe { $e }
    };
}

impl Lanes8 for Avx8 {
    type Mask = AvxMask8;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        Self(avx!(_mm256_set1_ps(x)))
    }
    #[inline(always)]
    fn from_array(a: [f32; 8]) -> Self {
        Self(avx!(_mm256_loadu_ps(a.as_ptr())))
    }
    #[inline(always)]
    fn to_array(self) -> [f32; 8] {
        let mut out = [0.0; 8];
        avx!(_mm256_storeu_ps(out.as_mut_ptr(), self.0));
        out
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self(avx!(_mm256_add_ps(self.0, o.0)))
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self(avx!(_mm256_sub_ps(self.0, o.0)))
    }
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        Self(avx!(_mm256_mul_ps(self.0, o.0)))
    }
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        Self(avx!(_mm256_div_ps(self.0, o.0)))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Self(avx!(_mm256_sqrt_ps(self.0)))
    }
    #[inline(always)]
    fn abs(self) -> Self {
        Self(avx!(_mm256_andnot_ps(_mm256_set1_ps(-0.0), self.0)))
    }
    #[inline(always)]
    fn max_or(self, o: Self) -> Self {
        Self(avx!(_mm256_max_ps(self.0, o.0)))
    }
    #[inline(always)]
    fn min_or(self, o: Self) -> Self {
        Self(avx!(_mm256_min_ps(self.0, o.0)))
    }
    #[inline(always)]
    fn lt(self, o: Self) -> AvxMask8 {
        AvxMask8(avx!(_mm256_cmp_ps::<_CMP_LT_OQ>(self.0, o.0)))
    }
    #[inline(always)]
    fn gt(self, o: Self) -> AvxMask8 {
        AvxMask8(avx!(_mm256_cmp_ps::<_CMP_GT_OQ>(self.0, o.0)))
    }
    #[inline(always)]
    fn le(self, o: Self) -> AvxMask8 {
        AvxMask8(avx!(_mm256_cmp_ps::<_CMP_LE_OQ>(self.0, o.0)))
    }
    #[inline(always)]
    fn ge(self, o: Self) -> AvxMask8 {
        AvxMask8(avx!(_mm256_cmp_ps::<_CMP_GE_OQ>(self.0, o.0)))
    }
    #[inline(always)]
    fn ne(self, o: Self) -> AvxMask8 {
        AvxMask8(avx!(_mm256_cmp_ps::<_CMP_NEQ_UQ>(self.0, o.0)))
    }
    #[inline(always)]
    fn select(m: AvxMask8, a: Self, b: Self) -> Self {
        Self(avx!(_mm256_blendv_ps(b.0, a.0, m.0)))
    }
    #[inline(always)]
    fn fract_steps(base: f64, n0: u32, step: f64) -> Self {
        let (lo, hi) = (
            fract_steps4(base, n0, step),
            fract_steps4(base, n0.wrapping_add(4), step),
        );
        Self(avx!(_mm256_set_m128(hi, lo)))
    }
    #[inline(always)]
    fn transpose(rows: [Self; 8]) -> [Self; 8] {
        avx!({
            let [r0, r1, r2, r3, r4, r5, r6, r7] = rows.map(|r| r.0);
            // Pairs of rows interleaved: (a0 b0 a1 b1 | a4 b4 a5 b5), (a2 b2 a3 b3 | ...).
            let (a01, b01) = (_mm256_unpacklo_ps(r0, r1), _mm256_unpackhi_ps(r0, r1));
            let (a23, b23) = (_mm256_unpacklo_ps(r2, r3), _mm256_unpackhi_ps(r2, r3));
            let (a45, b45) = (_mm256_unpacklo_ps(r4, r5), _mm256_unpackhi_ps(r4, r5));
            let (a67, b67) = (_mm256_unpacklo_ps(r6, r7), _mm256_unpackhi_ps(r6, r7));
            // Columns j and j + 4 of rows 0-3 (then 4-7) in the two halves.
            let c0 = _mm256_shuffle_ps::<0x44>(a01, a23);
            let c1 = _mm256_shuffle_ps::<0xEE>(a01, a23);
            let c2 = _mm256_shuffle_ps::<0x44>(b01, b23);
            let c3 = _mm256_shuffle_ps::<0xEE>(b01, b23);
            let d0 = _mm256_shuffle_ps::<0x44>(a45, a67);
            let d1 = _mm256_shuffle_ps::<0xEE>(a45, a67);
            let d2 = _mm256_shuffle_ps::<0x44>(b45, b67);
            let d3 = _mm256_shuffle_ps::<0xEE>(b45, b67);
            [
                Self(_mm256_permute2f128_ps::<0x20>(c0, d0)),
                Self(_mm256_permute2f128_ps::<0x20>(c1, d1)),
                Self(_mm256_permute2f128_ps::<0x20>(c2, d2)),
                Self(_mm256_permute2f128_ps::<0x20>(c3, d3)),
                Self(_mm256_permute2f128_ps::<0x31>(c0, d0)),
                Self(_mm256_permute2f128_ps::<0x31>(c1, d1)),
                Self(_mm256_permute2f128_ps::<0x31>(c2, d2)),
                Self(_mm256_permute2f128_ps::<0x31>(c3, d3)),
            ]
        })
    }
    #[inline(always)]
    fn max_lane(self) -> f32 {
        avx!({
            let m = _mm_max_ps(
                _mm256_castps256_ps128(self.0),
                _mm256_extractf128_ps::<1>(self.0),
            );
            let m = _mm_max_ps(m, _mm_movehl_ps(m, m));
            _mm_cvtss_f32(_mm_max_ss(m, _mm_shuffle_ps::<1>(m, m)))
        })
    }
    #[inline(always)]
    fn prefix_sum(self) -> Self {
        avx!({
            let zero = _mm256_setzero_ps();
            // Each half's lanes moved up by one, then by two, zeros shifted in.
            let by1 =
                _mm256_blend_ps::<0b0001_0001>(_mm256_permute_ps::<0b10_01_00_00>(self.0), zero);
            let s1 = _mm256_add_ps(self.0, by1);
            let by2 = _mm256_blend_ps::<0b0011_0011>(_mm256_permute_ps::<0b01_00_00_00>(s1), zero);
            let s2 = _mm256_add_ps(s1, by2);
            // The low half's last lane into every lane of the high half.
            let last = _mm256_permute_ps::<0b11_11_11_11>(s2);
            let carry = _mm256_permute2f128_ps::<0x08>(last, last);
            Self(_mm256_add_ps(s2, carry))
        })
    }
}

/// Four lanes of [`Lanes8::fract_steps`] in `f64` (`n` exact below 2^32), as
/// `super::fract_step` per lane. (A function, not a closure, so it inlines into the AVX
/// caller.)
#[inline(always)]
fn fract_steps4(base: f64, first: u32, step: f64) -> __m128 {
    avx!({
        let n = _mm256_set_pd(
            f64::from(first.wrapping_add(3)),
            f64::from(first.wrapping_add(2)),
            f64::from(first.wrapping_add(1)),
            f64::from(first),
        );
        let x = _mm256_add_pd(_mm256_set1_pd(base), _mm256_mul_pd(n, _mm256_set1_pd(step)));
        let t = _mm256_round_pd::<{ _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC }>(x);
        _mm256_cvtpd_ps(_mm256_sub_pd(x, t))
    })
}

impl Mask8 for AvxMask8 {
    #[inline(always)]
    fn and(self, o: Self) -> Self {
        Self(avx!(_mm256_and_ps(self.0, o.0)))
    }
    #[inline(always)]
    fn or(self, o: Self) -> Self {
        Self(avx!(_mm256_or_ps(self.0, o.0)))
    }
    #[inline(always)]
    fn and_not(self, o: Self) -> Self {
        Self(avx!(_mm256_andnot_ps(o.0, self.0)))
    }
    #[inline(always)]
    fn bits(self) -> u32 {
        avx!(_mm256_movemask_ps(self.0)) as u32
    }
    #[inline(always)]
    fn from_bits(bits: u32) -> Self {
        avx!({
            let lane_bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
            let set = _mm256_and_si256(_mm256_set1_epi32(bits as i32), lane_bits);
            Self(_mm256_castsi256_ps(_mm256_cmpeq_epi32(set, lane_bits)))
        })
    }
}
