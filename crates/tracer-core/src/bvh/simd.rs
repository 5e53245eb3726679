//! Four `f32` lanes for the box and triangle tests: SSE on x86_64, plain arrays elsewhere.
//! Every operation rounds exactly as the scalar operation does per lane (IEEE single precision,
//! no fused multiply-add), so the 4-wide triangle test gives the scalar test's results bit for bit.
//!
//! Soundness of the `unsafe` blocks: the SSE/SSE2 intrinsics are `unsafe` only because they are
//! `#[target_feature]` functions. This implementation is compiled only when `sse2` is enabled
//! for the whole target (`cfg(target_feature = "sse2")`, part of the x86_64 baseline), so the
//! instructions exist on every CPU the binary can run on. The two pointer intrinsics read or
//! write exactly 16 bytes through a reference to a `[f32; 4]` (the unaligned forms are used,
//! so no alignment is assumed).

#[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
mod imp {
    use std::arch::x86_64::*;

    /// Four lanes of `f32`.
    #[derive(Clone, Copy, Debug)]
    pub(crate) struct F4(__m128);

    /// A per-lane comparison result (all bits set or clear per lane).
    #[derive(Clone, Copy, Debug)]
    pub(crate) struct M4(__m128);

    macro_rules! sse {
        ($e:expr) => {
            // SAFETY: see the module docs (SSE2 is statically enabled).
            unsafe { $e }
        };
    }

    impl F4 {
        #[inline(always)]
        pub fn load(a: &[f32; 4]) -> Self {
            // SAFETY: `a` is a valid, readable 16-byte array; the load is unaligned.
            Self(unsafe { _mm_loadu_ps(a.as_ptr()) })
        }

        #[inline(always)]
        pub fn splat(x: f32) -> Self {
            Self(sse!(_mm_set1_ps(x)))
        }

        #[inline(always)]
        pub fn to_array(self) -> [f32; 4] {
            let mut out = [0.0; 4];
            // SAFETY: `out` is a valid, writable 16-byte array; the store is unaligned.
            unsafe { _mm_storeu_ps(out.as_mut_ptr(), self.0) };
            out
        }

        /// Per lane `if self > other { self } else { other }` (NaN in `self` keeps `other`).
        #[inline(always)]
        pub fn max_or(self, other: Self) -> Self {
            Self(sse!(_mm_max_ps(self.0, other.0)))
        }

        /// Per lane `if self < other { self } else { other }` (NaN in `self` keeps `other`).
        #[inline(always)]
        pub fn min_or(self, other: Self) -> Self {
            Self(sse!(_mm_min_ps(self.0, other.0)))
        }

        #[inline(always)]
        pub fn lt(self, o: Self) -> M4 {
            M4(sse!(_mm_cmplt_ps(self.0, o.0)))
        }

        #[inline(always)]
        pub fn gt(self, o: Self) -> M4 {
            M4(sse!(_mm_cmpgt_ps(self.0, o.0)))
        }

        #[inline(always)]
        pub fn le(self, o: Self) -> M4 {
            M4(sse!(_mm_cmple_ps(self.0, o.0)))
        }

        #[inline(always)]
        pub fn ge(self, o: Self) -> M4 {
            M4(sse!(_mm_cmpge_ps(self.0, o.0)))
        }

        /// Per lane `self != o` (true when either is NaN, as for `f32`).
        #[inline(always)]
        pub fn ne(self, o: Self) -> M4 {
            M4(sse!(_mm_cmpneq_ps(self.0, o.0)))
        }
    }

    impl M4 {
        /// Bit `i` set when lane `i` is true.
        #[inline(always)]
        pub fn bits(self) -> u32 {
            sse!(_mm_movemask_ps(self.0)) as u32
        }

        #[inline(always)]
        pub fn and(self, o: Self) -> Self {
            Self(sse!(_mm_and_ps(self.0, o.0)))
        }

        #[inline(always)]
        pub fn or(self, o: Self) -> Self {
            Self(sse!(_mm_or_ps(self.0, o.0)))
        }

        /// `self && !o` per lane.
        #[inline(always)]
        pub fn and_not(self, o: Self) -> Self {
            Self(sse!(_mm_andnot_ps(o.0, self.0)))
        }
    }

    macro_rules! binop {
        ($tr:ident, $f:ident, $intr:ident) => {
            impl std::ops::$tr for F4 {
                type Output = F4;
                #[inline(always)]
                fn $f(self, o: F4) -> F4 {
                    F4(sse!($intr(self.0, o.0)))
                }
            }
        };
    }
    binop!(Add, add, _mm_add_ps);
    binop!(Sub, sub, _mm_sub_ps);
    binop!(Mul, mul, _mm_mul_ps);
    binop!(Div, div, _mm_div_ps);
}

#[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
mod imp {
    /// Four lanes of `f32`.
    #[derive(Clone, Copy, Debug)]
    pub(crate) struct F4([f32; 4]);

    /// A per-lane comparison result.
    #[derive(Clone, Copy, Debug)]
    pub(crate) struct M4([bool; 4]);

    impl F4 {
        #[inline(always)]
        pub fn load(a: &[f32; 4]) -> Self {
            Self(*a)
        }
        #[inline(always)]
        pub fn splat(x: f32) -> Self {
            Self([x; 4])
        }
        #[inline(always)]
        pub fn to_array(self) -> [f32; 4] {
            self.0
        }
        #[inline(always)]
        pub fn max_or(self, o: Self) -> Self {
            Self(std::array::from_fn(|i| {
                if self.0[i] > o.0[i] {
                    self.0[i]
                } else {
                    o.0[i]
                }
            }))
        }
        #[inline(always)]
        pub fn min_or(self, o: Self) -> Self {
            Self(std::array::from_fn(|i| {
                if self.0[i] < o.0[i] {
                    self.0[i]
                } else {
                    o.0[i]
                }
            }))
        }
        #[inline(always)]
        pub fn lt(self, o: Self) -> M4 {
            M4(std::array::from_fn(|i| self.0[i] < o.0[i]))
        }
        #[inline(always)]
        pub fn gt(self, o: Self) -> M4 {
            M4(std::array::from_fn(|i| self.0[i] > o.0[i]))
        }
        #[inline(always)]
        pub fn le(self, o: Self) -> M4 {
            M4(std::array::from_fn(|i| self.0[i] <= o.0[i]))
        }
        #[inline(always)]
        pub fn ge(self, o: Self) -> M4 {
            M4(std::array::from_fn(|i| self.0[i] >= o.0[i]))
        }
        #[inline(always)]
        pub fn ne(self, o: Self) -> M4 {
            M4(std::array::from_fn(|i| self.0[i] != o.0[i]))
        }
    }

    impl M4 {
        #[inline(always)]
        pub fn bits(self) -> u32 {
            (0..4).map(|i| u32::from(self.0[i]) << i).sum()
        }
        #[inline(always)]
        pub fn and(self, o: Self) -> Self {
            Self(std::array::from_fn(|i| self.0[i] && o.0[i]))
        }
        #[inline(always)]
        pub fn or(self, o: Self) -> Self {
            Self(std::array::from_fn(|i| self.0[i] || o.0[i]))
        }
        #[inline(always)]
        pub fn and_not(self, o: Self) -> Self {
            Self(std::array::from_fn(|i| self.0[i] && !o.0[i]))
        }
    }

    macro_rules! binop {
        ($tr:ident, $f:ident, $op:tt) => {
            impl std::ops::$tr for F4 {
                type Output = F4;
                #[inline(always)]
                fn $f(self, o: F4) -> F4 {
                    F4(std::array::from_fn(|i| self.0[i] $op o.0[i]))
                }
            }
        };
    }
    binop!(Add, add, +);
    binop!(Sub, sub, -);
    binop!(Mul, mul, *);
    binop!(Div, div, /);
}

pub(crate) use imp::F4;
