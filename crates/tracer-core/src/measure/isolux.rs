//! Isolux lines over a grid's readings: round levels (1, 2, 5 × 10^k lx) and the segments where
//! the values cross them (marching squares over the points), in grid coordinates (i, j).

/// Up to five round isolux levels (1, 2, 5 × 10^k lx) strictly between `min` and `max`.
pub fn isolux_levels(min: f64, max: f64) -> Vec<f64> {
    if !(max > 0.0 && max.is_finite()) {
        return Vec::new();
    }
    let lo = min.max(max / 1000.0);
    let mut levels = Vec::new();
    let mut decade = 10f64.powf(lo.log10().floor());
    while decade <= max {
        for m in [1.0, 2.0, 5.0] {
            let v = m * decade;
            if v > lo && v < max {
                levels.push(v);
            }
        }
        decade *= 10.0;
    }
    // Keep at most five, spread over the range.
    if levels.len() > 5 {
        let step = levels.len() as f64 / 5.0;
        levels = (0..5).map(|k| levels[(k as f64 * step) as usize]).collect();
    }
    levels
}

/// Line segments (in grid cell-centre coordinates i, j) where the values cross `level`.
pub fn isolux_segments(values: &[f64], nu: usize, nv: usize, level: f64) -> Vec<[(f64, f64); 2]> {
    let at = |i: usize, j: usize| values[j * nu + i];
    let mut out = Vec::new();
    for j in 0..nv.saturating_sub(1) {
        for i in 0..nu.saturating_sub(1) {
            // Corners counter-clockwise: (i, j), (i+1, j), (i+1, j+1), (i, j+1).
            let c = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
            let mut crossings = Vec::with_capacity(4);
            for k in 0..4 {
                let (a, b) = (c[k], c[(k + 1) % 4]);
                let (va, vb) = (at(a.0, a.1), at(b.0, b.1));
                if (va < level) != (vb < level) {
                    let t = (level - va) / (vb - va);
                    crossings.push((
                        a.0 as f64 + t * (b.0 as f64 - a.0 as f64),
                        a.1 as f64 + t * (b.1 as f64 - a.1 as f64),
                    ));
                }
            }
            if crossings.len() == 2 {
                out.push([crossings[0], crossings[1]]);
            } else if crossings.len() == 4 {
                out.push([crossings[0], crossings[1]]);
                out.push([crossings[2], crossings[3]]);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn levels_are_round_and_inside_the_range() {
        assert_eq!(isolux_levels(30.0, 600.0), vec![50.0, 100.0, 200.0, 500.0]);
        assert!(isolux_levels(0.0, 0.0).is_empty());
        assert!(isolux_levels(1.0, 1e6).len() <= 5);
    }

    #[test]
    fn a_ramp_crosses_its_midpoint_halfway() {
        // 3 x 2 values rising along i: 0, 10, 20; the 5 lx line sits at i = 0.5 in both rows.
        let values = [0.0, 10.0, 20.0, 0.0, 10.0, 20.0];
        let segs = isolux_segments(&values, 3, 2, 5.0);
        assert_eq!(segs.len(), 1);
        for (i, _) in segs[0] {
            assert!((i - 0.5).abs() < 1e-12);
        }
    }
}
