//! The pass plan of a progressive render: coarse previews, then full-resolution samples.

/// One pass over the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pass {
    /// One sample (at the block centre) per `block` x `block` pixels, filling the block. Shown
    /// until full-resolution samples arrive; never accumulated into the converged image.
    Preview { block: u32 },
    /// Sample number `index` of every pixel (0: pixel centre, then jittered), accumulated.
    Full { index: u32 },
    /// Round `round` of adaptive sampling: each pixel's next samples, as many as the round
    /// gives it ([`super::adaptive`]), accumulated.
    Adaptive { round: u32 },
}

/// Block sizes of the coarse previews, coarsest first. There is no 2x2 preview: the first full
/// pass's first quarter (one sample in every 2x2 block, see the session) shows the same
/// resolution from samples that are kept, at the same cost.
pub const PREVIEW_BLOCKS: [u32; 2] = [8, 4];

impl Pass {
    /// The pass after this one, or None when `target_spp` full samples are done.
    pub fn next(self, target_spp: u32) -> Option<Pass> {
        let next = match self {
            Pass::Preview { block } => match PREVIEW_BLOCKS.iter().position(|&b| b == block) {
                Some(i) if i + 1 < PREVIEW_BLOCKS.len() => Pass::Preview {
                    block: PREVIEW_BLOCKS[i + 1],
                },
                _ => Pass::Full { index: 0 },
            },
            Pass::Full { index } => Pass::Full { index: index + 1 },
            // The session decides when rounds end (from the film).
            Pass::Adaptive { round } => Pass::Adaptive { round: round + 1 },
        };
        match next {
            Pass::Full { index } if index >= target_spp.max(1) => None,
            p => Some(p),
        }
    }

    pub fn first() -> Pass {
        Pass::Preview {
            block: PREVIEW_BLOCKS[0],
        }
    }

    /// Tile edge for this pass: coarse passes cover more pixels per tile (same work per tile).
    pub fn tile_size(self) -> u32 {
        match self {
            Pass::Preview { block } => (16 * block).min(128),
            Pass::Full { .. } | Pass::Adaptive { .. } => 32,
        }
    }

    pub fn label(self) -> String {
        match self {
            Pass::Preview { block } => format!("preview {block}x{block}"),
            Pass::Full { index } => format!("sample {}", index + 1),
            Pass::Adaptive { round } => format!("adaptive round {}", round + 1),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plan_goes_coarse_to_fine_then_stops_at_target() {
        let mut p = Some(Pass::first());
        let mut plan = Vec::new();
        while let Some(pass) = p {
            plan.push(pass);
            p = pass.next(3);
        }
        assert_eq!(
            plan,
            vec![
                Pass::Preview { block: 8 },
                Pass::Preview { block: 4 },
                Pass::Full { index: 0 },
                Pass::Full { index: 1 },
                Pass::Full { index: 2 },
            ]
        );
    }
}
