//! Eight `f32` lanes for the packet traversal and camera rays: one AVX register where the CPU has AVX2 (picked
//! at run time), plain arrays elsewhere. Every operation rounds per lane exactly as the scalar
//! `f32` operation does (no fused multiply-add), and `max_or`/`min_or` keep the second operand
//! when the first is NaN, as the SSE and AVX instructions do, so both kinds give the same bits.

// Lane loops index arrays by lane on purpose.
#![allow(clippy::needless_range_loop)]

use crate::geometry::Ray;

/// Eight lanes of `f32`.
pub(crate) trait Lanes8: Copy {
    type Mask: Mask8;
    fn splat(x: f32) -> Self;
    fn from_array(a: [f32; 8]) -> Self;
    fn to_array(self) -> [f32; 8];
    fn add(self, o: Self) -> Self;
    fn sub(self, o: Self) -> Self;
    fn mul(self, o: Self) -> Self;
    fn div(self, o: Self) -> Self;
    /// Correctly rounded, as `f32::sqrt`.
    fn sqrt(self) -> Self;
    /// The sign bit cleared, as `f32::abs`.
    fn abs(self) -> Self;
    /// Per lane `if self > o { self } else { o }`.
    fn max_or(self, o: Self) -> Self;
    /// Per lane `if self < o { self } else { o }`.
    fn min_or(self, o: Self) -> Self;
    fn lt(self, o: Self) -> Self::Mask;
    fn gt(self, o: Self) -> Self::Mask;
    fn le(self, o: Self) -> Self::Mask;
    fn ge(self, o: Self) -> Self::Mask;
    /// True when either is NaN, as for `f32`.
    fn ne(self, o: Self) -> Self::Mask;
    /// Per lane `if m { a } else { b }`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// Per lane `i`: the fraction of `base + (n0 + i) · step` (in `f64`, multiplied then
    /// added, no fused operation), rounded to `f32`: eight steps of a rank-1 lattice sequence.
    /// `base`, `step` ≥ 0 and the sums below 2^53.
    fn fract_steps(base: f64, n0: u32, step: f64) -> Self;
    /// Eight rows of eight lanes into eight columns: lane `i` of column `j` is lane `j` of row
    /// `i` (its own inverse).
    fn transpose(rows: [Self; 8]) -> [Self; 8];
    /// The greatest lane (no lane may be NaN).
    fn max_lane(self) -> f32;
    /// Running sums: lane `i` holds lanes 0..=i added, in three steps (neighbours, pairs, then
    /// the low half's total into the high half), every kind in the same order.
    fn prefix_sum(self) -> Self;
}

/// One lane of [`Lanes8::fract_steps`]: `x - trunc(x)` is exact (the truncation through
/// `i64`, which `x` < 2^53 fits, avoids the libm call `trunc` makes on baseline x86_64).
#[inline(always)]
pub(crate) fn fract_step(base: f64, n: u32, step: f64) -> f32 {
    let x = base + f64::from(n) * step;
    (x - (x as i64) as f64) as f32
}

/// Eight rays as rows, row `i` from `ray(i)`: origin x, y, z, direction x, y, z, `t_min`,
/// `t_max`. (`ray` only loads, so it needs no AVX of its own.)
#[inline(always)]
pub(crate) fn ray_rows<'r, L: Lanes8>(ray: impl Fn(usize) -> &'r Ray) -> [L; 8] {
    let row = |i: usize| {
        let r = ray(i);
        let (o, d) = (r.origin, r.dir);
        [o.x, o.y, o.z, d.x, d.y, d.z, r.t_min, r.t_max]
    };
    [
        L::from_array(row(0)),
        L::from_array(row(1)),
        L::from_array(row(2)),
        L::from_array(row(3)),
        L::from_array(row(4)),
        L::from_array(row(5)),
        L::from_array(row(6)),
        L::from_array(row(7)),
    ]
}

/// Eight rays in lanes, lane `i` from `ray(i)`: the columns origin x, y, z, direction x, y, z,
/// `t_min`, `t_max` ([`ray_rows`] by one transpose).
#[inline(always)]
pub(crate) fn ray_columns<'r, L: Lanes8>(ray: impl Fn(usize) -> &'r Ray) -> [L; 8] {
    L::transpose(ray_rows(ray))
}

/// A per-lane condition.
pub(crate) trait Mask8: Copy {
    fn and(self, o: Self) -> Self;
    fn or(self, o: Self) -> Self;
    /// `self && !o` per lane.
    fn and_not(self, o: Self) -> Self;
    /// Bit `i` set when lane `i` is true.
    fn bits(self) -> u32;
    /// Lane `i` true when bit `i` is set.
    fn from_bits(bits: u32) -> Self;
}

/// Plain arrays, for every CPU.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Scalar8([f32; 8]);

#[derive(Clone, Copy, Debug)]
pub(crate) struct ScalarMask8([bool; 8]);

impl Scalar8 {
    #[inline(always)]
    fn zip(self, o: Self, f: impl Fn(f32, f32) -> f32) -> Self {
        let mut out = [0.0; 8];
        for i in 0..8 {
            out[i] = f(self.0[i], o.0[i]);
        }
        Self(out)
    }

    #[inline(always)]
    fn test(self, o: Self, f: impl Fn(f32, f32) -> bool) -> ScalarMask8 {
        let mut out = [false; 8];
        for i in 0..8 {
            out[i] = f(self.0[i], o.0[i]);
        }
        ScalarMask8(out)
    }
}

impl Lanes8 for Scalar8 {
    type Mask = ScalarMask8;

    #[inline(always)]
    fn splat(x: f32) -> Self {
        Self([x; 8])
    }
    #[inline(always)]
    fn from_array(a: [f32; 8]) -> Self {
        Self(a)
    }
    #[inline(always)]
    fn to_array(self) -> [f32; 8] {
        self.0
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.zip(o, |a, b| a + b)
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self.zip(o, |a, b| a - b)
    }
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        self.zip(o, |a, b| a * b)
    }
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        self.zip(o, |a, b| a / b)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Self(self.0.map(f32::sqrt))
    }
    #[inline(always)]
    fn abs(self) -> Self {
        Self(self.0.map(f32::abs))
    }
    #[inline(always)]
    fn max_or(self, o: Self) -> Self {
        self.zip(o, |a, b| if a > b { a } else { b })
    }
    #[inline(always)]
    fn min_or(self, o: Self) -> Self {
        self.zip(o, |a, b| if a < b { a } else { b })
    }
    #[inline(always)]
    fn lt(self, o: Self) -> ScalarMask8 {
        self.test(o, |a, b| a < b)
    }
    #[inline(always)]
    fn gt(self, o: Self) -> ScalarMask8 {
        self.test(o, |a, b| a > b)
    }
    #[inline(always)]
    fn le(self, o: Self) -> ScalarMask8 {
        self.test(o, |a, b| a <= b)
    }
    #[inline(always)]
    fn ge(self, o: Self) -> ScalarMask8 {
        self.test(o, |a, b| a >= b)
    }
    #[inline(always)]
    fn ne(self, o: Self) -> ScalarMask8 {
        self.test(o, |a, b| a != b)
    }
    #[inline(always)]
    fn select(m: ScalarMask8, a: Self, b: Self) -> Self {
        let mut out = [0.0; 8];
        for i in 0..8 {
            out[i] = if m.0[i] { a.0[i] } else { b.0[i] };
        }
        Self(out)
    }
    #[inline(always)]
    fn fract_steps(base: f64, n0: u32, step: f64) -> Self {
        Self(std::array::from_fn(|i| {
            fract_step(base, n0.wrapping_add(i as u32), step)
        }))
    }
    #[inline(always)]
    fn transpose(rows: [Self; 8]) -> [Self; 8] {
        std::array::from_fn(|j| Self(std::array::from_fn(|i| rows[i].0[j])))
    }
    #[inline(always)]
    fn max_lane(self) -> f32 {
        self.0
            .into_iter()
            .fold(f32::NEG_INFINITY, |a, b| if b > a { b } else { a })
    }
    #[inline(always)]
    fn prefix_sum(self) -> Self {
        // As the AVX kind: zeros are added where nothing is shifted in.
        let x = self.0;
        let s1: [f32; 8] = std::array::from_fn(|i| x[i] + if i % 4 >= 1 { x[i - 1] } else { 0.0 });
        let s2: [f32; 8] =
            std::array::from_fn(|i| s1[i] + if i % 4 >= 2 { s1[i - 2] } else { 0.0 });
        Self(std::array::from_fn(|i| {
            s2[i] + if i >= 4 { s2[3] } else { 0.0 }
        }))
    }
}

impl Mask8 for ScalarMask8 {
    #[inline(always)]
    fn and(self, o: Self) -> Self {
        Self(std::array::from_fn(|i| self.0[i] && o.0[i]))
    }
    #[inline(always)]
    fn or(self, o: Self) -> Self {
        Self(std::array::from_fn(|i| self.0[i] || o.0[i]))
    }
    #[inline(always)]
    fn and_not(self, o: Self) -> Self {
        Self(std::array::from_fn(|i| self.0[i] && !o.0[i]))
    }
    #[inline(always)]
    fn bits(self) -> u32 {
        let mut bits = 0;
        for i in 0..8 {
            bits |= u32::from(self.0[i]) << i;
        }
        bits
    }
    #[inline(always)]
    fn from_bits(bits: u32) -> Self {
        Self(std::array::from_fn(|i| bits & (1 << i) != 0))
    }
}

/// One AVX register.
///
/// Soundness: the intrinsics need AVX. Values of these types are only made and used inside
/// functions compiled with `#[target_feature(enable = "avx2")]` (the AVX2 entry points of the
/// packet traversal and of the camera rays, reached only after
/// `is_x86_feature_detected!("avx2")`), into which these
/// `#[inline(always)]` methods inline. Loads and stores go through `[f32; 8]` references of
/// exactly 32 bytes (unaligned forms).
#[cfg(target_arch = "x86_64")]
pub(crate) use avx::Avx8;

#[cfg(target_arch = "x86_64")]
mod avx;

#[cfg(test)]
mod tests {
    use super::*;

    fn rows() -> [[f32; 8]; 8] {
        std::array::from_fn(|i| std::array::from_fn(|j| (10 * i + j) as f32))
    }

    fn check<L: Lanes8>() {
        let rows = rows();
        let columns = L::transpose(rows.map(L::from_array));
        let back = L::transpose(columns);
        for (i, row) in back.iter().enumerate() {
            assert_eq!(row.to_array(), rows[i], "row {i} after transposing twice");
        }
        for (j, column) in columns.iter().enumerate() {
            let lanes = column.to_array();
            for (i, lane) in lanes.iter().enumerate() {
                assert_eq!(*lane, rows[i][j], "lane {i} of column {j}");
            }
        }
    }

    /// The greatest lane wherever it sits, infinite ones too.
    fn greatest<L: Lanes8>() {
        for at in 0..8 {
            for (low, high) in [(-3.5, 9.25), (f32::NEG_INFINITY, f32::INFINITY)] {
                let mut lanes = [1.0, 2.0, -1.0, 0.5, 4.0, -2.0, 3.0, 0.0];
                lanes[at] = low;
                lanes[7 - at] = high;
                let l = L::from_array(lanes);
                assert_eq!(l.max_lane(), high, "greatest of {lanes:?}");
            }
        }
    }

    fn masks_round_trip<L: Lanes8>() {
        for bits in 0..256 {
            assert_eq!(L::Mask::from_bits(bits).bits(), bits);
        }
        // Lane by lane against the comparison that sets it.
        let lanes = L::from_array([0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);
        assert_eq!(lanes.lt(L::splat(3.0)).bits(), 0b0000_0111);
        assert_eq!(L::Mask::from_bits(0b0000_0111).bits(), 0b0000_0111);
    }

    /// Running sums against sequential ones, and bit for bit against the plain lanes.
    fn running<L: Lanes8>() {
        let mut rng = crate::sampling::SampleRng::new(5, 0);
        for _ in 0..1000 {
            let x: [f32; 8] = std::array::from_fn(|_| rng.next_f32() * 100.0);
            let got = L::from_array(x).prefix_sum().to_array();
            assert_eq!(got, Scalar8(x).prefix_sum().to_array(), "{x:?}");
            let mut sum = 0.0f32;
            for (i, lane) in x.iter().enumerate() {
                sum += lane;
                assert!(
                    (got[i] - sum).abs() <= 1e-4 * sum,
                    "lane {i} of {x:?}: {got:?}"
                );
            }
        }
    }

    #[test]
    fn transpose_and_masks_match_the_plain_lanes() {
        running::<Scalar8>();
        check::<Scalar8>();
        greatest::<Scalar8>();
        masks_round_trip::<Scalar8>();
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            check::<Avx8>();
            greatest::<Avx8>();
            masks_round_trip::<Avx8>();
            running::<Avx8>();
        } else {
            eprintln!("skipping the AVX lanes: this CPU has no AVX2");
        }
    }
}
