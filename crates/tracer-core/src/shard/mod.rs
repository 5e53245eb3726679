//! Work spread over machines: shard K of M renders (or measures) a contiguous range of the N
//! sample indices, writes the exact sums to a part file, and the parts merge into exactly what
//! one machine computes with all N samples (sums are integers and every sample depends only on
//! (pixel or point, sample index)).
//!
//! ```text
//!  shard 0: samples 0 .. N/M      ──▶ part 0 ─┐
//!  shard 1: samples N/M .. 2N/M   ──▶ part 1 ─┼─ check_set (same scene, setup, settings,
//!  …                                          │  version, N, M; every K once) ─▶ Film::merge
//!  shard M−1: … .. N              ──▶ part M−1┘
//! ```
//!
//! A part file ([`file`]) is a short text header (magic, format version, kind, raygine version,
//! scene hash, settings, N, M, K, payload length, checksum) and a binary payload written by
//! `render::partial` (a film) or `measure::partial` (grid sums).

mod file;
mod hash;
mod set;
pub mod varint;

pub use file::{PART_FORMAT, PartError, PartHeader, PartKind, read_part, write_part};
pub use hash::{StableHash, scene_hash};
pub use set::check_set;

use std::ops::Range;

/// Shard `index` (0-based) of `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Shard {
    pub index: u32,
    pub count: u32,
}

/// Why a shard cannot be run.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ShardError {
    #[error("--shard-count must be at least 1")]
    NoShards,
    #[error("--shard-index {index} is outside 0..{count} (shards are numbered from 0)")]
    IndexOutOfRange { index: u32, count: u32 },
    #[error(
        "{count} shards of {samples} samples: some shards would get no sample (use at most {samples} shards)"
    )]
    MoreShardsThanSamples { count: u32, samples: u32 },
}

impl Shard {
    /// A checked shard of `samples` samples.
    pub fn new(index: u32, count: u32, samples: u32) -> Result<Shard, ShardError> {
        if count == 0 {
            return Err(ShardError::NoShards);
        }
        if index >= count {
            return Err(ShardError::IndexOutOfRange { index, count });
        }
        if count > samples {
            return Err(ShardError::MoreShardsThanSamples { count, samples });
        }
        Ok(Shard { index, count })
    }

    /// The sample indices of this shard: the contiguous range ⌊K·N/M⌋ .. ⌊(K+1)·N/M⌋. The
    /// ranges of shards 0..M cover 0..N once each, and differ in length by at most one.
    pub fn samples(&self, total: u32) -> Range<u32> {
        let at = |k: u32| (u64::from(k) * u64::from(total) / u64::from(self.count.max(1))) as u32;
        at(self.index)..at(self.index + 1)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn shard_ranges_cover_every_sample_once() {
        for (n, m) in [(1, 1), (7, 3), (16, 4), (1000, 7), (5, 5)] {
            let mut next = 0;
            for k in 0..m {
                let r = Shard::new(k, m, n).unwrap().samples(n);
                assert_eq!(r.start, next);
                assert!(r.len() as u32 >= n / m && r.len() as u32 <= n / m + 1);
                next = r.end;
            }
            assert_eq!(next, n);
        }
        assert_eq!(
            Shard::new(2, 4, 4_000_000).unwrap().samples(4_000_000),
            2_000_000..3_000_000
        );
    }

    #[test]
    fn impossible_shards_are_refused() {
        assert_eq!(Shard::new(0, 0, 8), Err(ShardError::NoShards));
        assert!(matches!(
            Shard::new(4, 4, 8),
            Err(ShardError::IndexOutOfRange { .. })
        ));
        assert!(matches!(
            Shard::new(0, 9, 8),
            Err(ShardError::MoreShardsThanSamples { .. })
        ));
    }
}
