//! Reproducible sample positions: each depends on (pixel, sample index) only, never on time or
//! thread, so any thread count and any interruption give the same image.

/// Sample `s` of pixel (`x`, `y`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SampleJob {
    pub x: u32,
    pub y: u32,
    pub s: u32,
}

/// A well-mixed 64-bit hash of a pixel index and a sample index (splitmix64 finaliser).
pub fn sample_hash(pixel_index: u64, sample_index: u32) -> u64 {
    let mut z = pixel_index
        .wrapping_mul(0x9E37_79B9_7F4A_7C15)
        .wrapping_add(u64::from(sample_index).wrapping_mul(0xD1B5_4A32_D192_ED03))
        .wrapping_add(0x632B_E59B_D9B4_E019);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Offset in the pixel (each in [0, 1)) of sample `s` of pixel (`x`, `y`). Sample 0 is the
/// centre; later samples follow the R2 low-discrepancy sequence, shifted per pixel by a hash so
/// neighbouring pixels do not share a pattern.
pub fn pixel_sample_offset(x: u32, y: u32, width: u32, s: u32) -> (f32, f32) {
    sample_offset(pixel_shift(x, y, width), s)
}

/// The per-pixel shift of the sequence (each in [0, 1)), the same for all of a pixel's samples.
pub(crate) fn pixel_shift(x: u32, y: u32, width: u32) -> (f64, f64) {
    let h = sample_hash(u64::from(y) * u64::from(width) + u64::from(x), 0);
    let shift_x = (h >> 40) as f64 / (1u64 << 24) as f64;
    let shift_y = ((h >> 16) & 0xFF_FFFF) as f64 / (1u64 << 24) as f64;
    (shift_x, shift_y)
}

/// Offset of sample `s` of the pixel with shift `shift` (see [`pixel_sample_offset`]).
#[inline]
pub(crate) fn sample_offset((shift_x, shift_y): (f64, f64), s: u32) -> (f32, f32) {
    if s == 0 {
        return (0.5, 0.5);
    }
    let n = f64::from(s);
    let fx = fract_non_negative(shift_x + n * R2_STEP.0);
    let fy = fract_non_negative(shift_y + n * R2_STEP.1);
    // f32 rounding could give 1.0 exactly; keep offsets inside the pixel.
    ((fx as f32).min(MAX_OFFSET), (fy as f32).min(MAX_OFFSET))
}

/// R2's increments per sample, 1/φ2 and 1/φ2², φ2 the plastic number.
pub(crate) const R2_STEP: (f64, f64) = (0.754_877_666_246_692_7, 0.569_840_290_998_053_3);
/// The largest offset in a pixel (the `f32` below 1).
pub(crate) const MAX_OFFSET: f32 = 0.999_999_94;

/// `x.fract()` for finite `0 <= x < 2^63`, bit for bit, without the libm `trunc` call that
/// `fract` makes on baseline x86_64 (a few per cent of a direct-light frame): the cast
/// truncates (one instruction each way through i64; u64 would take a dozen) and
/// `x - trunc(x)` is exact. Offsets stay below 2^33.
#[inline]
fn fract_non_negative(x: f64) -> f64 {
    debug_assert!((0.0..9_223_372_036_854_775_808.0).contains(&x));
    // SAFETY: the caller's `x` is finite and below 2^63 (sample offsets stay below 2^33), so
    // the truncation is exact and in range; unlike `as`, no saturation checks.
    x - unsafe { x.to_int_unchecked::<i64>() } as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fract_matches_the_standard_library_bit_for_bit() {
        let mut values = vec![0.0, 0.5, 1.0, 1.5, 0.999_999_999_999, 2f64.powi(52) + 0.5];
        values.extend([2f64.powi(53), 2f64.powi(60), (2f64.powi(63)).next_down()]);
        let mut h = 1u64;
        for i in 0..200_000u32 {
            h = sample_hash(h, i);
            let unit = (h >> 11) as f64 / (1u64 << 53) as f64;
            values.push(unit + f64::from(i) * 0.754_877_666_246_692_7);
            values.push(unit * 2f64.powi((i % 66) as i32));
        }
        for v in values.into_iter().filter(|v| *v < 2f64.powi(63)) {
            assert_eq!(fract_non_negative(v).to_bits(), v.fract().to_bits(), "{v}");
        }
    }

    #[test]
    fn offsets_are_inside_the_pixel_and_cover_it() {
        let mut quadrants = [0u32; 4];
        for s in 1..257 {
            let (dx, dy) = pixel_sample_offset(7, 3, 640, s);
            assert!((0.0..1.0).contains(&dx) && (0.0..1.0).contains(&dy));
            quadrants[usize::from(dx >= 0.5) + 2 * usize::from(dy >= 0.5)] += 1;
        }
        // A low-discrepancy sequence puts close to a quarter of the samples in each quadrant.
        for q in quadrants {
            assert!((56..=72).contains(&q), "{quadrants:?}");
        }
        assert_eq!(pixel_sample_offset(1, 2, 10, 0), (0.5, 0.5));
        assert_ne!(
            pixel_sample_offset(1, 2, 10, 5),
            pixel_sample_offset(2, 2, 10, 5)
        );
    }
}
