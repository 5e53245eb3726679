//! The position index p: how much less a glare source annoys away from the line of sight than
//! on it (p = 1 on the line of sight, larger elsewhere; UGR and DGP divide by p²).
//!
//! Directions are in the observer's frame: x to the right, y up, z along the line of sight.
//! For a source in direction (x, y, z), z > 0, CIE 117's ratios are H/R = |y| / z (height over
//! the distance along the line of sight) and T/R = |x| / z (sideways over that distance).
//!
//! - **Above the line of sight** (y ≥ 0): Guth's index as CIE 117:1995 tabulates it (Table 4.1),
//!   bilinear in H/R and T/R. Beyond the table (H/R > 1.9 or T/R > 3.0) the ratio is held at
//!   the table's edge. Where the table leaves a cell empty (H/R 1.8 and 1.9 close to the
//!   vertical plane through the line of sight) the row's last value stands in for it.
//! - **Below the line of sight** (y < 0): Iwata's index as Radiance's evalglare 3.06 uses it
//!   (Iwata & Osterhaus 2010, with T. Kikuchi's correction): β = atan(tan σ √(1 + 0.3225 cos² τ))
//!   in degrees, p = exp(6.49·10⁻³ β + 2.1·10⁻⁴ β²), at most 16; σ is the angle from the line
//!   of sight and τ the angle from up in the plane across it, so tan σ √(1 + 0.3225 cos² τ) =
//!   √((T/R)² + 1.3225 (H/R)²). It meets Levin's form of Guth's index sideways (τ = 90°).
//!
//! [`levin`] is the closed form Radiance's `findglare` and evalglare use above the line of sight
//! (Levin's fit to Guth's data): kept to show where and by how much they differ from the table.

use glam::DVec3;

/// Which rule gave a position index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IndexRule {
    /// Inside CIE 117's table (above the line of sight).
    GuthTable,
    /// Above the line of sight, beyond the table or in one of its empty cells: its edge.
    GuthEdge,
    /// Below the line of sight: Iwata's index.
    Iwata,
}

impl IndexRule {
    pub fn label(self) -> &'static str {
        match self {
            IndexRule::GuthTable => "Guth, CIE 117 table",
            IndexRule::GuthEdge => "Guth, CIE 117 table held at its edge",
            IndexRule::Iwata => "Iwata, below the line of sight",
        }
    }
}

/// The steps of the table's axes: H/R 0, 0.1 … 1.9 (columns), T/R 0, 0.1 … 3.0 (rows).
pub const RATIO_STEP: f64 = 0.1;
pub const H_R_MAX: f64 = 1.9;
pub const T_R_MAX: f64 = 3.0;

const E: f64 = f64::NAN;

/// CIE 117:1995 Table 4.1, Guth's position index: one row per T/R (0.0 to 3.0), one column per
/// H/R (0.0 to 1.9); NaN where the standard prints no value. Typed from the transcription in
/// github.com/123VincentB/eulumdat-ugr (`guth.py`, MIT), which gives the row T/R = 2.7 the value
/// 7.50 at H/R = 0.6 "as published" (its neighbours suggest 7.05: kept as printed). The tests
/// hold a copy typed separately and check every cell, and check the table against Levin's fit.
#[rustfmt::skip]
pub const GUTH_TABLE: [[f64; 20]; 31] = [
    //  H/R 0.0   0.1   0.2   0.3   0.4   0.5   0.6   0.7   0.8   0.9   1.0    1.1    1.2    1.3    1.4    1.5    1.6    1.7    1.8    1.9
    [1.00, 1.26, 1.53, 1.90, 2.35, 2.86, 3.50, 4.20, 5.00, 6.00, 7.00,  8.10,  9.25, 10.35, 11.70, 13.15, 14.70, 16.20,     E,     E], // 0.0
    [1.05, 1.22, 1.46, 1.80, 2.20, 2.75, 3.40, 4.10, 4.80, 5.80, 6.80,  8.00,  9.10, 10.30, 11.60, 13.00, 14.60, 16.10,     E,     E], // 0.1
    [1.12, 1.30, 1.50, 1.80, 2.20, 2.66, 3.18, 3.88, 4.60, 5.50, 6.50,  7.60,  8.75,  9.85, 11.20, 12.70, 14.00, 15.70,     E,     E], // 0.2
    [1.22, 1.38, 1.60, 1.97, 2.25, 2.70, 3.25, 3.90, 4.60, 5.45, 6.45,  7.40,  8.40,  9.50, 10.85, 12.10, 13.70, 15.00,     E,     E], // 0.3
    [1.32, 1.47, 1.70, 1.96, 2.35, 2.80, 3.30, 3.90, 4.60, 5.40, 6.40,  7.30,  8.30,  9.40, 10.60, 11.90, 13.20, 14.60, 16.00,     E], // 0.4
    [1.43, 1.60, 1.82, 2.10, 2.48, 2.91, 3.40, 3.98, 4.70, 5.50, 6.40,  7.30,  8.30,  9.40, 10.50, 11.75, 13.00, 14.40, 15.70,     E], // 0.5
    [1.55, 1.72, 1.98, 2.30, 2.65, 3.10, 3.60, 4.10, 4.80, 5.50, 6.40,  7.35,  8.40,  9.40, 10.50, 11.70, 13.00, 14.10, 15.40,     E], // 0.6
    [1.70, 1.88, 2.12, 2.48, 2.87, 3.30, 3.78, 4.30, 4.88, 5.60, 6.50,  7.40,  8.50,  9.50, 10.50, 11.70, 12.85, 14.00, 15.20,     E], // 0.7
    [1.82, 2.00, 2.32, 2.70, 3.08, 3.50, 3.92, 4.50, 5.10, 5.75, 6.60,  7.50,  8.60,  9.50, 10.60, 11.75, 12.80, 14.00, 15.10,     E], // 0.8
    [1.96, 2.20, 2.54, 2.90, 3.30, 3.70, 4.20, 4.75, 5.30, 6.00, 6.75,  7.70,  8.70,  9.65, 10.75, 11.80, 12.90, 14.00, 15.00, 16.00], // 0.9
    [2.11, 2.40, 2.75, 3.10, 3.50, 3.91, 4.40, 5.00, 5.60, 6.20, 7.00,  7.90,  8.80,  9.75, 10.80, 11.90, 12.95, 14.00, 15.00, 16.00], // 1.0
    [2.30, 2.55, 2.92, 3.30, 3.72, 4.20, 4.70, 5.25, 5.80, 6.55, 7.20,  8.15,  9.00,  9.90, 10.95, 12.00, 13.00, 14.00, 15.00, 16.00], // 1.1
    [2.40, 2.75, 3.12, 3.50, 3.90, 4.35, 4.85, 5.50, 6.05, 6.70, 7.50,  8.30,  9.20, 10.00, 11.02, 12.10, 13.10, 14.00, 15.00, 16.00], // 1.2
    [2.55, 2.90, 3.30, 3.70, 4.20, 4.65, 5.20, 5.70, 6.30, 7.00, 7.70,  8.55,  9.35, 10.20, 11.20, 12.25, 13.20, 14.00, 15.00, 16.00], // 1.3
    [2.70, 3.10, 3.50, 3.90, 4.35, 4.85, 5.35, 5.85, 6.50, 7.25, 8.00,  8.70,  9.50, 10.40, 11.40, 12.40, 13.25, 14.05, 15.00, 16.00], // 1.4
    [2.85, 3.15, 3.65, 4.10, 4.55, 5.00, 5.50, 6.20, 6.80, 7.50, 8.20,  8.85,  9.70, 10.55, 11.50, 12.50, 13.30, 14.05, 15.02, 16.00], // 1.5
    [2.95, 3.40, 3.80, 4.25, 4.75, 5.20, 5.75, 6.30, 7.00, 7.65, 8.40,  9.00,  9.80, 10.80, 11.75, 12.60, 13.40, 14.20, 15.10, 16.00], // 1.6
    [3.10, 3.55, 4.00, 4.50, 4.90, 5.40, 5.95, 6.50, 7.20, 7.80, 8.50,  9.20, 10.00, 10.85, 11.85, 12.75, 13.45, 14.20, 15.10, 16.00], // 1.7
    [3.25, 3.70, 4.20, 4.65, 5.10, 5.60, 6.10, 6.75, 7.40, 8.00, 8.65,  9.35, 10.10, 11.00, 11.90, 12.80, 13.50, 14.20, 15.10, 16.00], // 1.8
    [3.43, 3.86, 4.30, 4.75, 5.20, 5.70, 6.30, 6.90, 7.50, 8.17, 8.80,  9.50, 10.20, 11.00, 12.00, 12.82, 13.55, 14.20, 15.10, 16.00], // 1.9
    [3.50, 4.00, 4.50, 4.90, 5.35, 5.80, 6.40, 7.10, 7.70, 8.30, 8.90,  9.60, 10.40, 11.10, 12.00, 12.85, 13.60, 14.30, 15.10, 16.00], // 2.0
    [3.60, 4.17, 4.65, 5.05, 5.50, 6.00, 6.60, 7.20, 7.82, 8.45, 9.00,  9.75, 10.50, 11.20, 12.10, 12.90, 13.70, 14.35, 15.10, 16.00], // 2.1
    [3.75, 4.25, 4.72, 5.20, 5.60, 6.10, 6.70, 7.35, 8.00, 8.55, 9.15,  9.85, 10.60, 11.30, 12.10, 12.90, 13.70, 14.40, 15.15, 16.00], // 2.2
    [3.85, 4.35, 4.80, 5.25, 5.70, 6.22, 6.80, 7.40, 8.10, 8.65, 9.30,  9.90, 10.70, 11.40, 12.20, 12.95, 13.70, 14.40, 15.20, 16.00], // 2.3
    [3.95, 4.40, 4.90, 5.35, 5.80, 6.30, 6.90, 7.50, 8.20, 8.80, 9.40, 10.00, 10.80, 11.50, 12.25, 13.00, 13.75, 14.45, 15.20, 16.00], // 2.4
    [4.00, 4.50, 4.96, 5.40, 5.85, 6.40, 6.95, 7.55, 8.25, 8.85, 9.50, 10.05, 10.85, 11.55, 12.30, 13.00, 13.80, 14.50, 15.25, 16.00], // 2.5
    [4.07, 4.55, 5.05, 5.47, 5.95, 6.46, 7.00, 7.65, 8.35, 8.95, 9.55, 10.10, 10.90, 11.60, 12.32, 13.00, 13.80, 14.50, 15.25, 16.00], // 2.6
    [4.10, 4.60, 5.10, 5.53, 6.00, 6.50, 7.50, 7.70, 8.40, 9.00, 9.60, 10.16, 10.92, 11.63, 12.35, 13.00, 13.80, 14.50, 15.25, 16.00], // 2.7
    [4.15, 4.62, 5.15, 5.56, 6.05, 6.55, 7.08, 7.73, 8.45, 9.05, 9.65, 10.20, 10.95, 11.65, 12.35, 13.00, 13.80, 14.50, 15.25, 16.00], // 2.8
    [4.20, 4.65, 5.17, 5.60, 6.07, 6.57, 7.12, 7.75, 8.50, 9.10, 9.70, 10.23, 10.95, 11.65, 12.35, 13.00, 13.80, 14.50, 15.25, 16.00], // 2.9
    [4.22, 4.67, 5.20, 5.65, 6.12, 6.60, 7.15, 7.80, 8.55, 9.12, 9.70, 10.23, 10.95, 11.65, 12.35, 13.00, 13.80, 14.50, 15.25, 16.00], // 3.0
];

/// The table's cell (row `t`, column `h`), an empty cell replaced by the row's last value.
fn cell(t: usize, h: usize) -> (f64, bool) {
    let row = &GUTH_TABLE[t];
    if row[h].is_finite() {
        return (row[h], false);
    }
    let last = row.iter().rev().copied().find(|v| v.is_finite());
    (last.unwrap_or(1.0), true)
}

/// Guth's index from the table at `h_r` = H/R and `t_r` = T/R (both ≥ 0), bilinear; whether an
/// edge rule was used.
pub fn guth_table(h_r: f64, t_r: f64) -> (f64, IndexRule) {
    let beyond = h_r > H_R_MAX || t_r > T_R_MAX;
    let h = h_r.clamp(0.0, H_R_MAX) / RATIO_STEP;
    let t = t_r.clamp(0.0, T_R_MAX) / RATIO_STEP;
    let (h0, t0) = (
        (h.floor() as usize).min(GUTH_TABLE[0].len() - 2),
        (t.floor() as usize).min(GUTH_TABLE.len() - 2),
    );
    let (fh, ft) = (h - h0 as f64, t - t0 as f64);
    let mut empty = false;
    let mut at = |ti: usize, hi: usize, w: f64| {
        if w == 0.0 {
            return 0.0;
        }
        let (v, e) = cell(ti, hi);
        empty |= e;
        v * w
    };
    let p = at(t0, h0, (1.0 - ft) * (1.0 - fh))
        + at(t0, h0 + 1, (1.0 - ft) * fh)
        + at(t0 + 1, h0, ft * (1.0 - fh))
        + at(t0 + 1, h0 + 1, ft * fh);
    let rule = if beyond || empty {
        IndexRule::GuthEdge
    } else {
        IndexRule::GuthTable
    };
    (p, rule)
}

/// evalglare holds both its indices at this value.
pub const MAX_INDEX: f64 = 16.0;

/// Iwata's index below the line of sight at `h_r` = H/R and `t_r` = T/R (as evalglare 3.06).
pub fn iwata(h_r: f64, t_r: f64) -> f64 {
    let beta = (t_r * t_r + 1.3225 * h_r * h_r).sqrt().atan().to_degrees();
    (6.49e-3 * beta + 2.1e-4 * beta * beta).exp().min(MAX_INDEX)
}

/// The position index of a source seen along `dir` (observer frame, any length), with the rule
/// that gave it; None behind the eye's plane (z ≤ 0), where neither index is defined.
pub fn position_index(dir: DVec3) -> Option<(f64, IndexRule)> {
    if dir.z <= 1e-12 {
        return None;
    }
    let h_r = dir.y.abs() / dir.z;
    let t_r = dir.x.abs() / dir.z;
    if dir.y >= 0.0 {
        Some(guth_table(h_r, t_r))
    } else {
        Some((iwata(h_r, t_r), IndexRule::Iwata))
    }
}

/// Levin's closed form of Guth's index (IES Lighting Handbook; Radiance's findglare and
/// evalglare above the line of sight): p = exp[(35.2 − 0.31889 τ − 1.22 e^(−2τ/9)) 10⁻³ σ +
/// (21 + 0.26667 τ − 0.002963 τ²) 10⁻⁵ σ²], σ the angle between the line of sight and the
/// source, τ the angle between the vertical plane through the line of sight and the plane through
/// the line of sight and the source, both in degrees.
pub fn levin(dir: DVec3) -> f64 {
    let d = dir.normalize_or_zero();
    let sigma = d.z.clamp(-1.0, 1.0).acos().to_degrees();
    let tau = d.x.abs().atan2(d.y.abs()).to_degrees();
    ((35.2 - 0.31889 * tau - 1.22 * (-2.0 * tau / 9.0).exp()) * 1e-3 * sigma
        + (21.0 + 0.26667 * tau - 0.002963 * tau * tau) * 1e-5 * sigma * sigma)
        .exp()
}

/// The index evalglare 3.06 gives the same direction: Levin's form above the line of sight,
/// Iwata's below, at most 16. With [`position_index`] it says how much of a UGR difference from
/// evalglare the two index functions explain.
pub fn evalglare_index(dir: DVec3) -> Option<f64> {
    if dir.z <= 1e-12 {
        return None;
    }
    if dir.y >= 0.0 {
        Some(levin(dir).min(MAX_INDEX))
    } else {
        Some(iwata(dir.y.abs() / dir.z, dir.x.abs() / dir.z))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn on_the_line_of_sight_p_is_one_and_grows_away_from_it() {
        assert_eq!(position_index(DVec3::Z), Some((1.0, IndexRule::GuthTable)));
        let p = |x: f64, y: f64| position_index(DVec3::new(x, y, 1.0)).map_or(0.0, |p| p.0);
        assert!((p(0.0, 0.5) - 2.86).abs() < 1e-9);
        assert!((p(1.0, 0.0) - 2.11).abs() < 1e-9);
        assert_eq!(position_index(DVec3::new(0.0, 1.0, 0.0)), None);
        // Below, sideways (τ = 90°) Iwata's index is Levin's: 30° off the line of sight.
        let side = DVec3::new(30f64.to_radians().tan(), -1e-9, 1.0);
        let below = position_index(side).map_or(0.0, |p| p.0);
        // (6.49e-3 against Levin's 35.2e-3 − 0.31889e-3 · 90 = 6.4999e-3: 0.03 % apart.)
        assert!((below / levin(side) - 1.0).abs() < 1e-3, "{below}");
        // Straight down 30°: β = atan(tan 30° · √1.3225) = 33.582°.
        let down = position_index(DVec3::new(0.0, -(30f64.to_radians().tan()), 1.0));
        let beta: f64 = 33.58228;
        let want = (6.49e-3 * beta + 2.1e-4 * beta * beta).exp();
        assert!((down.map_or(0.0, |p| p.0) / want - 1.0).abs() < 1e-4);
        assert_eq!(down.map(|p| p.1), Some(IndexRule::Iwata));
        // Further below, larger; at most exp(6.49e-3 · 90 + 2.1e-4 · 90²) = 9.83 at 90°.
        let far = position_index(DVec3::new(0.0, -50.0, 1.0)).map_or(0.0, |p| p.0);
        assert!(far > down.map_or(0.0, |p| p.0) && far < 9.83, "{far}");
    }

    #[test]
    fn between_cells_the_table_is_bilinear_and_its_edges_hold() {
        // Half-way between H/R 0.0 and 0.1 on T/R 0: (1.00 + 1.26) / 2.
        assert!((guth_table(0.05, 0.0).0 - 1.13).abs() < 1e-12);
        // The middle of four cells: their mean.
        let mid = (1.00 + 1.26 + 1.05 + 1.22) / 4.0;
        assert!((guth_table(0.05, 0.05).0 - mid).abs() < 1e-12);
        let (p, rule) = guth_table(2.5, 4.0);
        assert!((p - 16.0).abs() < 1e-9 && rule == IndexRule::GuthEdge);
        // An empty cell: the row's last value, and the rule says so.
        let (p, rule) = guth_table(1.9, 0.0);
        assert!((p - 16.2).abs() < 1e-9 && rule == IndexRule::GuthEdge);
        let (p, rule) = guth_table(1.7, 0.0);
        assert!((p - 16.2).abs() < 1e-9 && rule == IndexRule::GuthTable);
    }
}
