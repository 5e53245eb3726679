//! Random numbers keyed by what they are for, and the warps that turn them into directions and
//! points.
//!
//! Every number a render draws is a pure function of (stream key, sample index, dimension):
//! [`SampleRng`] hashes the three together (a counter-based generator), so a sample's value never
//! depends on the thread that computed it, on the order of work or on what was drawn before in
//! another sample. One pixel's sample can be replayed alone for debugging.

mod warp;

pub use warp::{
    cosine_hemisphere, frame_from_normal, to_world, uniform_sphere, uniform_triangle_barycentric,
};

/// A stream of uniform numbers in [0, 1) for one sample: the key names the pixel (or sensor
/// point), the sample index the sample, and each call to [`SampleRng::next_f32`] the next
/// dimension.
#[derive(Clone, Debug)]
pub struct SampleRng {
    key: u64,
    dimension: u64,
}

impl SampleRng {
    /// The stream of sample `sample_index` of the pixel or point `key`.
    pub fn new(key: u64, sample_index: u32) -> Self {
        Self {
            key: mix(key.wrapping_mul(0x9E37_79B9_7F4A_7C15)
                ^ u64::from(sample_index).wrapping_mul(0xD1B5_4A32_D192_ED03)
                ^ 0x5851_F42D_4C95_7F2D),
            dimension: 0,
        }
    }

    /// A stream for a sub-purpose of this sample (for example the second path of a pixel
    /// sample), independent of this one's.
    pub fn split(&self, purpose: u64) -> Self {
        Self {
            key: mix(self.key ^ purpose.wrapping_mul(0xA076_1D64_78BD_642F)),
            dimension: 0,
        }
    }

    /// The next dimension's value, uniform in [0, 1).
    pub fn next_f32(&mut self) -> f32 {
        let bits = mix(self.key ^ self.dimension.wrapping_mul(0xE703_7ED1_A0B4_28DB));
        self.dimension += 1;
        // 24 bits: every value is exactly representable and strictly below 1.
        (bits >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
    }

    /// Two dimensions at once.
    pub fn next_2d(&mut self) -> (f32, f32) {
        let a = self.next_f32();
        (a, self.next_f32())
    }
}

/// The splitmix64 finaliser: a bijection of 64-bit words with good avalanche.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn streams_are_reproducible_uniform_and_distinct() {
        let mut a = SampleRng::new(7, 3);
        let mut b = SampleRng::new(7, 3);
        let xs: Vec<f32> = (0..1000).map(|_| a.next_f32()).collect();
        let ys: Vec<f32> = (0..1000).map(|_| b.next_f32()).collect();
        assert_eq!(xs, ys);
        assert!(xs.iter().all(|x| (0.0..1.0).contains(x)));
        let mean = xs.iter().sum::<f32>() / xs.len() as f32;
        assert!((mean - 0.5).abs() < 0.03, "{mean}");
        let mut c = SampleRng::new(7, 4);
        let mut d = SampleRng::new(8, 3);
        let first = xs[0];
        assert_ne!(first, c.next_f32());
        assert_ne!(first, d.next_f32());
        let mut s = SampleRng::new(7, 3).split(1);
        assert_ne!(first, s.next_f32());
    }

    /// Neighbouring keys and dimensions must not be correlated: the mean product of pairs is
    /// 1/4 for independent uniforms.
    #[test]
    fn neighbouring_streams_are_uncorrelated() {
        let n = 20_000;
        let mut sum = 0.0f64;
        for k in 0..n {
            let x = SampleRng::new(k, 0).next_f32();
            let y = SampleRng::new(k + 1, 0).next_f32();
            sum += f64::from(x) * f64::from(y);
        }
        let m = sum / n as f64;
        assert!((m - 0.25).abs() < 0.01, "{m}");
    }
}
