//! Piecewise-constant densities for sampling an environment map: one over a row's cells, and
//! one over the rows of a grid (pbrt's `PiecewiseConstant1D/2D` are the model).

/// A density over [0, 1) constant on each of `n` equal cells, proportional to the weights.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Distribution1d {
    /// Running sums of the weights, normalised: `cdf[0]` = 0, `cdf[n]` = 1.
    cdf: Vec<f32>,
    /// The sum of the weights (0: nothing to sample).
    total: f64,
}

impl Distribution1d {
    /// Over `weights` (each finite and ≥ 0).
    pub(super) fn new(weights: &[f32]) -> Self {
        let mut sums = Vec::with_capacity(weights.len() + 1);
        let mut total = 0.0f64;
        sums.push(0.0);
        for &w in weights {
            total += f64::from(w.max(0.0));
            sums.push(total);
        }
        let cdf = if total > 0.0 {
            sums.iter().map(|s| (s / total) as f32).collect()
        } else {
            sums.iter().map(|_| 0.0).collect()
        };
        Self { cdf, total }
    }

    pub(super) fn total(&self) -> f64 {
        self.total
    }

    fn cells(&self) -> usize {
        self.cdf.len() - 1
    }

    /// The cell `u` falls in, where in it (in [0, 1)), and the cell's probability.
    pub(super) fn sample(&self, u: f32) -> Option<(usize, f32, f32)> {
        if self.total <= 0.0 {
            return None;
        }
        // The last cell whose running sum is at or below u, skipping empty cells.
        let i = self.cdf.partition_point(|&c| c <= u).clamp(1, self.cells()) - 1;
        let p = self.cdf[i + 1] - self.cdf[i];
        if p <= 0.0 {
            return None;
        }
        let within = ((u - self.cdf[i]) / p).clamp(0.0, 1.0 - f32::EPSILON);
        Some((i, within, p))
    }

    /// The probability of cell `i`.
    pub(super) fn probability(&self, i: usize) -> f32 {
        match (self.cdf.get(i), self.cdf.get(i + 1)) {
            (Some(a), Some(b)) => b - a,
            _ => 0.0,
        }
    }
}

/// A density over [0, 1)² constant on each cell of a `width` x `height` grid: a row by the
/// rows' sums, then a cell within it.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Distribution2d {
    rows: Vec<Distribution1d>,
    marginal: Distribution1d,
    width: usize,
}

impl Distribution2d {
    /// Over `weights`, row by row (`width` per row).
    pub(super) fn new(weights: &[f32], width: usize) -> Self {
        let rows: Vec<Distribution1d> = weights.chunks(width).map(Distribution1d::new).collect();
        let sums: Vec<f32> = rows.iter().map(|r| r.total() as f32).collect();
        Self {
            marginal: Distribution1d::new(&sums),
            rows,
            width,
        }
    }

    /// The sum of every weight.
    pub(super) fn total(&self) -> f64 {
        self.marginal.total()
    }

    /// A point of [0, 1)² from `u`, and its density there.
    pub(super) fn sample(&self, u: [f32; 2]) -> Option<([f32; 2], f32)> {
        let (row, y, p_row) = self.marginal.sample(u[1])?;
        let (col, x, p_col) = self.rows[row].sample(u[0])?;
        let height = self.rows.len();
        let point = [
            (col as f32 + x) / self.width as f32,
            (row as f32 + y) / height as f32,
        ];
        let density = p_row * p_col * (self.width * height) as f32;
        Some((point, density))
    }

    /// The density at `point` of [0, 1)².
    pub(super) fn density(&self, point: [f32; 2]) -> f32 {
        let height = self.rows.len();
        let col = ((point[0] * self.width as f32) as usize).min(self.width - 1);
        let row = ((point[1] * height as f32) as usize).min(height - 1);
        self.marginal.probability(row)
            * self.rows[row].probability(col)
            * (self.width * height) as f32
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn picks_follow_the_weights_and_densities_match() {
        let weights = [0.0, 1.0, 3.0, 0.0, 2.0, 2.0];
        let d = Distribution2d::new(&weights, 3);
        let n = 60_000;
        let mut counts = [0u32; 6];
        for i in 0..n {
            let u = [
                ((i * 7919) % n) as f32 / n as f32,
                (i as f32 + 0.5) / n as f32,
            ];
            let (p, density) = d.sample(u).unwrap();
            let cell = (p[1] * 2.0) as usize * 3 + (p[0] * 3.0) as usize;
            counts[cell] += 1;
            assert!((density - d.density(p)).abs() < 1e-4 * density, "{p:?}");
        }
        for (cell, &c) in counts.iter().enumerate() {
            let want = weights[cell] / 8.0 * n as f32;
            assert!(
                (c as f32 - want).abs() <= 0.01 * n as f32,
                "cell {cell}: {c} vs {want}"
            );
        }
        // Densities: weight / mean weight.
        assert!((d.density([0.5, 0.25]) - 1.0 / (8.0 / 6.0)).abs() < 1e-5);
        assert_eq!(d.density([0.1, 0.25]), 0.0);
        assert!(
            Distribution2d::new(&[0.0; 4], 2)
                .sample([0.5, 0.5])
                .is_none()
        );
    }
}
