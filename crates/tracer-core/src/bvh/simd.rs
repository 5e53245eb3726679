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

        /// Per lane `|x|` (the sign bit cleared).
        #[inline(always)]
        pub fn abs(self) -> Self {
            Self(sse!(_mm_andnot_ps(_mm_set1_ps(-0.0), self.0)))
        }

        /// Per lane `if m { x } else { 0.0 }`.
        #[inline(always)]
        pub fn keep(self, m: M4) -> Self {
            Self(sse!(_mm_and_ps(m.0, self.0)))
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
        #[inline(always)]
        pub fn abs(self) -> Self {
            Self(self.0.map(f32::abs))
        }
        #[inline(always)]
        pub fn keep(self, m: M4) -> Self {
            Self(std::array::from_fn(
                |i| if m.0[i] { self.0[i] } else { 0.0 },
            ))
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

#[cfg(target_arch = "x86_64")]
pub(crate) use avx2::{Avx2, Slabs8};

/// The eight-box slab test in one AVX register per plane, for CPUs that have AVX2 and FMA
/// (checked at run time). Each slab distance is one fused multiply-subtract,
/// `t = plane * (1/d) - origin * (1/d)`, with `origin * (1/d)` computed once per ray.
///
/// Why that stays conservative: rounding `origin * (1/d)` (and the origin itself) moves the
/// origin the test effectively uses by at most about `2 |o| ulp`, so [`Avx2::slabs`] moves it
/// on purpose by `4 |o| ulp` (plus a tiny floor) backwards for entry distances and forwards for
/// exit distances: every box is tested as if a little larger. The remaining relative errors
/// (the rounded reciprocal and the fused operation's one rounding) are covered by the exit
/// distance scale, as in the four-lane test. A zero direction component gets a huge finite
/// reciprocal (`1e18` with its sign) instead of infinity, so no `inf - inf` can appear.
///
/// Soundness: [`Avx2`] can only be made by [`Avx2::detect`], which checks that the CPU has
/// AVX2 and FMA, so its methods may use those instructions. They are `#[inline(always)]` and
/// only called from traversal functions compiled with `#[target_feature(enable =
/// "avx2,fma")]`, where the intrinsics inline.
#[cfg(target_arch = "x86_64")]
mod avx2 {
    use std::arch::x86_64::*;

    /// Proof that this CPU has AVX2 and FMA.
    #[derive(Clone, Copy, Debug)]
    pub(crate) struct Avx2(());

    /// A ray's slab planes for [`Avx2::enter`], per axis: the reciprocal direction for entry
    /// distances and its scaled copy for exit distances, each with the matching (moved)
    /// origin times it.
    #[derive(Clone, Copy)]
    pub(crate) struct Slabs8 {
        inv_dir: [__m256; 3],
        origin_near: [__m256; 3],
        inv_dir_exit: [__m256; 3],
        origin_far: [__m256; 3],
        t_min: __m256,
    }

    /// The reciprocal used for a zero direction component.
    const HUGE_RECIPROCAL: f32 = 1e18;
    /// How far the origin is moved, relative to its coordinate.
    const ORIGIN_SLACK: f32 = 4.0 * f32::EPSILON;
    /// The smallest move (for coordinates at or near zero).
    const ORIGIN_SLACK_FLOOR: f32 = 1e-30;

    /// Each of three values in all lanes. (A function, not a closure: closures do not inherit
    /// the caller's AVX target feature, and the intrinsic would become a call.) Only called
    /// through [`Avx2`] methods.
    #[inline(always)]
    fn splat3(x: [f32; 3]) -> [__m256; 3] {
        // SAFETY: reached only from `Avx2::slabs`, so AVX is present; no memory operands.
        unsafe {
            [
                _mm256_set1_ps(x[0]),
                _mm256_set1_ps(x[1]),
                _mm256_set1_ps(x[2]),
            ]
        }
    }

    impl Avx2 {
        /// `Some` when the CPU has AVX2 and FMA (the check is cached by the standard library).
        #[inline(always)]
        pub fn detect() -> Option<Self> {
            (is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma"))
                .then_some(Self(()))
        }

        /// `inv_dir` and `exit_scale` as in the four-lane test (`inv_dir` may hold infinities).
        #[inline(always)]
        pub fn slabs(
            self,
            origin: [f32; 3],
            inv_dir: [f32; 3],
            exit_scale: f32,
            t_min: f32,
        ) -> Slabs8 {
            let inv = inv_dir.map(|r| {
                if r.is_finite() {
                    r
                } else {
                    HUGE_RECIPROCAL.copysign(r)
                }
            });
            let slack = origin.map(|o| o.abs() * ORIGIN_SLACK + ORIGIN_SLACK_FLOOR);
            let near: [f32; 3] =
                std::array::from_fn(|a| (origin[a] + slack[a].copysign(inv[a])) * inv[a]);
            let far: [f32; 3] = std::array::from_fn(|a| {
                (origin[a] - slack[a].copysign(inv[a])) * (inv[a] * exit_scale)
            });
            let exit = inv.map(|r| r * exit_scale);
            Slabs8 {
                inv_dir: splat3(inv),
                origin_near: splat3(near),
                inv_dir_exit: splat3(exit),
                origin_far: splat3(far),
                // SAFETY: AVX is present (`self` exists); set1 has no memory operands.
                t_min: unsafe { _mm256_set1_ps(t_min) },
            }
        }

        /// For eight boxes (`near[axis]` / `far[axis]`: the planes the ray enters and leaves
        /// through, per lane): the lanes the ray meets within `[t_min, t_max]` as bits, and
        /// where it enters each (never later than it does).
        #[inline(always)]
        pub fn enter(
            self,
            s: &Slabs8,
            near: [&[[f32; 4]; 2]; 3],
            far: [&[[f32; 4]; 2]; 3],
            t_max: f32,
        ) -> (u32, [f32; 8]) {
            // SAFETY: AVX2/FMA are present (`self` exists). Each load reads exactly the 32
            // contiguous bytes of a `[[f32; 4]; 2]` reference (unaligned form); the store
            // writes the 32 bytes of `out`.
            unsafe {
                let mut t_near = s.t_min;
                let mut t_far = _mm256_set1_ps(t_max);
                for axis in 0..3 {
                    let n = _mm256_loadu_ps(near[axis].as_ptr().cast::<f32>());
                    let f = _mm256_loadu_ps(far[axis].as_ptr().cast::<f32>());
                    let tn = _mm256_fmsub_ps(n, s.inv_dir[axis], s.origin_near[axis]);
                    let tf = _mm256_fmsub_ps(f, s.inv_dir_exit[axis], s.origin_far[axis]);
                    t_near = _mm256_max_ps(tn, t_near);
                    t_far = _mm256_min_ps(tf, t_far);
                }
                let bits = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(t_near, t_far)) as u32;
                let mut out = [0.0f32; 8];
                _mm256_storeu_ps(out.as_mut_ptr(), t_near);
                (bits, out)
            }
        }
    }
}
