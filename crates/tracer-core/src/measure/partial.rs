//! A measurement as the payload of a part file (see `crate::shard`): what the readings are
//! written with (unit, integrator, maintenance factor), the grids exactly as measured, then
//! every point's exact sums in grid order. Merging needs no scene: the grids give the points.

use super::grid::Grid;
use super::sensor_sum::SensorSum;
use super::sensors::MeasureSettings;
use crate::render::SquareSum;
use crate::shard::varint::{Decoder, Encoder};

/// A point's sums in file order: Σ E, Σ E² (whole, fine), count, rejected.
fn encode_sum(e: &mut Encoder, s: &SensorSum) {
    for v in [
        s.illuminance,
        s.square.whole,
        i128::from(s.square.fine),
        i128::from(s.count),
        i128::from(s.rejected),
    ] {
        e.i128(v);
    }
}

/// The sum [`encode_sum`] wrote; None when unreadable or out of range.
fn decode_sum(d: &mut Decoder<'_>) -> Option<SensorSum> {
    let (illuminance, whole, fine) = (d.i128()?, d.i128()?, d.i128()?);
    let fine = i64::try_from(fine)
        .ok()
        .filter(|f| (0..1 << 32).contains(f))?;
    Some(SensorSum {
        illuminance,
        square: SquareSum { whole, fine },
        count: u32::try_from(d.i128()?).ok()?,
        rejected: u32::try_from(d.i128()?).ok()?,
    })
}

/// The sums of some samples of every point of every grid, with what is needed to report them.
#[derive(Clone, Debug, PartialEq)]
pub struct MeasurePart {
    /// The scene unit's symbol (mm, cm, m): positions are in it.
    pub unit: String,
    /// The integrator's name (direct, path).
    pub integrator: String,
    /// The setup's maintenance factor (applied when reporting, as `raygine measure` does).
    pub maintenance_factor: f32,
    pub grids: Vec<Grid>,
    /// One per point, grid after grid, i fastest.
    pub sums: Vec<SensorSum>,
}

fn put_vec3(e: &mut Encoder, v: [f32; 3]) {
    for c in v {
        e.f32(c);
    }
}

fn get_vec3(d: &mut Decoder<'_>) -> Option<[f32; 3]> {
    Some([d.f32()?, d.f32()?, d.f32()?])
}

impl MeasurePart {
    pub fn encode(&self) -> Vec<u8> {
        let mut e = Encoder::default();
        e.str(&self.unit);
        e.str(&self.integrator);
        e.f32(self.maintenance_factor);
        e.u64(self.grids.len() as u64);
        for g in &self.grids {
            e.str(&g.name);
            e.u32(g.nu);
            e.u32(g.nv);
            for v in [g.origin, g.u, g.v, g.normal] {
                put_vec3(&mut e, v);
            }
        }
        e.u64(self.sums.len() as u64);
        for s in &self.sums {
            encode_sum(&mut e, s);
        }
        e.bytes
    }

    /// The part a payload holds, or what is wrong with it.
    pub fn decode(payload: &[u8]) -> Result<MeasurePart, String> {
        let mut d = Decoder::new(payload);
        let bad = |what: &str| format!("{what} is unreadable");
        let unit = d.str().ok_or_else(|| bad("the unit"))?;
        let integrator = d.str().ok_or_else(|| bad("the integrator"))?;
        let maintenance_factor = d.f32().ok_or_else(|| bad("the maintenance factor"))?;
        let count = d.u64().ok_or_else(|| bad("the grid count"))?;
        if count > payload.len() as u64 {
            return Err("the grid count does not fit in the payload".to_owned());
        }
        let mut grids = Vec::with_capacity(count as usize);
        for i in 0..count {
            let grid = (|| {
                Some(Grid {
                    name: d.str()?,
                    nu: d.u32()?,
                    nv: d.u32()?,
                    origin: get_vec3(&mut d)?,
                    u: get_vec3(&mut d)?,
                    v: get_vec3(&mut d)?,
                    normal: get_vec3(&mut d)?,
                    task: None,
                    observers: Vec::new(),
                })
            })()
            .ok_or_else(|| bad(&format!("grid {i}")))?;
            grids.push(grid);
        }
        let points: u64 = grids.iter().map(|g| g.point_count() as u64).sum();
        let n = d.u64().ok_or_else(|| bad("the point count"))?;
        if n != points || n > payload.len() as u64 {
            return Err(format!("{n} sums for {points} grid points"));
        }
        let mut sums = Vec::with_capacity(n as usize);
        for i in 0..n {
            sums.push(decode_sum(&mut d).ok_or_else(|| bad(&format!("point {i}")))?);
        }
        if !d.is_at_end() {
            return Err("bytes after the last point".to_owned());
        }
        Ok(MeasurePart {
            unit,
            integrator,
            maintenance_factor,
            grids,
            sums,
        })
    }
}

/// What a measurement's sums depend on besides the scene, setup and sample range.
pub fn settings_line(s: &MeasureSettings) -> String {
    let bounces = s
        .max_bounces
        .map_or_else(|| "none".to_owned(), |n| n.to_string());
    format!("grids {} max_bounces={bounces}", s.integrator.name())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    #[test]
    fn a_measurement_survives_the_payload_bit_for_bit() {
        let grid = Grid::new(
            "floor",
            [0.1, 0.0, -2.0],
            [4.0, 0.0, 0.0],
            [0.0, 0.0, 2.0],
            3,
            2,
            Some([0.0, 1.0, 0.0]),
        )
        .unwrap();
        let mut sums = vec![SensorSum::default(); 6];
        sums[4].illuminance = 1 << 100;
        sums[4].square = SquareSum::from_units(1 << 90);
        sums[4].count = 9;
        sums[5].rejected = 2;
        let part = MeasurePart {
            unit: "m".into(),
            integrator: "path".into(),
            maintenance_factor: 0.8,
            grids: vec![grid],
            sums,
        };
        let payload = part.encode();
        assert_eq!(MeasurePart::decode(&payload).unwrap(), part);
        assert!(MeasurePart::decode(&payload[..payload.len() - 2]).is_err());
    }
}
