//! A small fixed-seed random generator (SplitMix64) and cosine-weighted hemisphere sampling for
//! the W3 diffuse rays. Any good generator will do (BENCHMARK.md); this one needs no crate.

use glam::Vec3;

#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
    }
}

/// A cosine-weighted unit direction about the unit normal `n` (Malley's method: a uniform point
/// on the unit disc lifted onto the hemisphere).
pub fn cosine_direction(n: Vec3, u1: f32, u2: f32) -> Vec3 {
    let r = u1.sqrt();
    let phi = std::f32::consts::TAU * u2;
    let (x, y) = (r * phi.cos(), r * phi.sin());
    let z = (1.0 - u1).max(0.0).sqrt();
    let (t, b) = n.any_orthonormal_pair();
    (t * x + b * y + n * z).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_stream() {
        let (mut a, mut b) = (SplitMix64::new(7), SplitMix64::new(7));
        for _ in 0..100 {
            assert_eq!(a.next_u64(), b.next_u64());
        }
        let x = SplitMix64::new(1).next_f32();
        assert!((0.0..1.0).contains(&x));
    }

    #[test]
    fn cosine_directions_stay_in_the_hemisphere() {
        let n = Vec3::new(0.3, -0.8, 0.52).normalize();
        let mut rng = SplitMix64::new(3);
        let mut mean_cos = 0.0;
        for _ in 0..10_000 {
            let d = cosine_direction(n, rng.next_f32(), rng.next_f32());
            assert!((d.length() - 1.0).abs() < 1e-4);
            assert!(d.dot(n) >= -1e-6);
            mean_cos += d.dot(n) / 10_000.0;
        }
        // E[cos] for a cosine-weighted hemisphere is 2/3.
        assert!((mean_cos - 2.0 / 3.0).abs() < 0.01, "{mean_cos}");
    }
}
