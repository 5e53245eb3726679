//! A lookup table for the display mapping of one channel: the tone curve and sRGB encoding
//! without their `powf` calls, for mapping whole films quickly (CLI images, viewer textures).

use super::DisplaySettings;
use glam::Vec3;

/// What [`DisplaySettings::map_pixel`] gives one channel, without its three `powf` calls per
/// pixel (they cost more than tracing the Cornell box at 1 spp).
///
/// The tone curves and the sRGB encoding act on each channel alone and rise with the value, so a
/// channel's 8-bit code is the number of codes `k` whose threshold `t_k` (the smallest value that
/// maps to `k` or more) it reaches. Thresholds are found by bisection on the bit patterns of
/// non-negative floats (ordered like the values), calling `map_pixel` itself, so the table
/// follows the display code wherever it changes. Bucketing by the top 16 bits of the float makes
/// most lookups one load. Where f32 rounding makes the curve itself wobble across a code boundary
/// (a few ulps wide), the table gives the neighbouring code: at most 1 apart, and rare (tested).
/// [`ChannelLut::new`] checks the per-channel assumption and gives `None` (use `map_pixel`) for
/// false colour or any curve where it does not hold; values at or above the limit, where the
/// filmic curve overflows, go to `map_pixel` one by one.
pub struct ChannelLut {
    display: DisplaySettings,
    scale: f32,
    /// Bits of the first value the table does not cover.
    limit_bits: u32,
    /// `thresholds[k - 1]`: bits of the smallest value whose code is `k` or more (`u32::MAX`: none
    /// below the limit).
    thresholds: [u32; 255],
    /// Per bucket of 2^16 bit patterns below the limit: the code at its first value and at its last.
    buckets: Vec<[u8; 2]>,
}

const BUCKET_SHIFT: u32 = 16;

/// Display values (cd/m² times the exposure scale) up to this are mapped through the table.
const LUT_MAX_DISPLAY_VALUE: f32 = 1e15;

impl ChannelLut {
    /// The table for `display` at exposure `scale` (see [`DisplaySettings::scale_for`]); `None`
    /// where a table cannot stand in for [`DisplaySettings::map_pixel`] (false colour).
    pub fn new(display: &DisplaySettings, scale: f32) -> Option<ChannelLut> {
        let limit = LUT_MAX_DISPLAY_VALUE / scale;
        if display.false_colour.is_some() || !(limit.is_finite() && limit > 0.0) {
            return None;
        }
        let limit_bits = limit.to_bits();
        let f =
            |bits: u32| display.map_pixel(Vec3::new(f32::from_bits(bits), 0.0, 0.0), 0.0, scale)[0];
        let mut thresholds = [u32::MAX; 255];
        for (i, t) in thresholds.iter_mut().enumerate() {
            let k = i as u8 + 1;
            // The smallest bits in [0, limit_bits) with f(bits) >= k, if any.
            let (mut lo, mut hi) = (0u32, limit_bits);
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if f(mid) >= k {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            if lo < limit_bits {
                *t = lo;
            }
        }
        let count = |bits: u32| thresholds.partition_point(|&t| t <= bits) as u8;
        let buckets = (0..=(limit_bits - 1) >> BUCKET_SHIFT)
            .map(|b| {
                let first = b << BUCKET_SHIFT;
                let last = (first | ((1 << BUCKET_SHIFT) - 1)).min(limit_bits - 1);
                [count(first), count(last)]
            })
            .collect();
        let lut = ChannelLut {
            display: *display,
            scale,
            limit_bits,
            thresholds,
            buckets,
        };
        // The per-channel, non-decreasing assumption, checked on sample colours.
        let probes = [
            0.0f32, 1e-4, 0.003, 0.02, 0.18, 0.5, 0.9, 1.0, 3.0, 40.0, 1e4, 1e20,
        ];
        for &r in &probes {
            for &g in &probes {
                for &b in &probes {
                    let v = Vec3::new(r, g, b) / scale;
                    let [pr, pg, pb, _] = display.map_pixel(v, 0.0, scale);
                    if [pr, pg, pb] != [lut.code(v.x), lut.code(v.y), lut.code(v.z)] {
                        return None;
                    }
                }
            }
        }
        Some(lut)
    }

    /// The 8-bit code of one linear channel value (cd/m²); NaN and negatives map like 0.
    #[inline]
    pub fn code(&self, value: f32) -> u8 {
        let bits = if value > 0.0 { value.to_bits() } else { 0 };
        if bits >= self.limit_bits {
            let v = Vec3::new(value, 0.0, 0.0);
            return self.display.map_pixel(v, 0.0, self.scale)[0];
        }
        let [first, last] = self.buckets[(bits >> BUCKET_SHIFT) as usize];
        if first == last {
            first
        } else {
            let between = &self.thresholds[first as usize..last as usize];
            first + between.partition_point(|&t| t <= bits) as u8
        }
    }
}

impl std::fmt::Debug for ChannelLut {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ChannelLut")
            .field("scale", &self.scale)
            .finish_non_exhaustive()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::display::ToneMap;

    #[test]
    fn table_agrees_with_map_pixel() {
        for tone_map in ToneMap::ALL {
            for stops in [-3.0f32, 0.0, 2.5] {
                let display = DisplaySettings {
                    tone_map,
                    exposure_stops: stops,
                    ..DisplaySettings::default()
                };
                let scale = DisplaySettings::scale_for(stops);
                let Some(lut) = ChannelLut::new(&display, scale) else {
                    panic!("no table for {tone_map:?}");
                };
                let (mut off_by_one, mut n) = (0, 0);
                // Values from 1e-6 to 1e8 cd/m², geometrically spaced, plus 0 and huge ones.
                let mut v = 1e-6f32;
                while v < 1e8 {
                    let want = display.map_pixel(Vec3::new(v, 0.0, 0.0), 0.0, scale)[0];
                    let got = lut.code(v);
                    assert!(
                        want.abs_diff(got) <= 1,
                        "{tone_map:?} {stops} {v}: {want} vs {got}"
                    );
                    off_by_one += usize::from(want != got);
                    n += 1;
                    v *= 1.0007;
                }
                assert!(off_by_one * 1000 < n, "{off_by_one} of {n} off by one");
                assert_eq!(lut.code(0.0), 0);
                assert_eq!(lut.code(f32::NAN), 0);
                assert_eq!(
                    lut.code(1e30),
                    display.map_pixel(Vec3::splat(1e30), 0.0, scale)[0]
                );
            }
        }
        let false_colour = DisplaySettings {
            false_colour: Some(crate::display::FalseColour {
                quantity: crate::display::FalseColourQuantity::Luminance,
                scale: crate::display::FalseColourScale::Log,
                min: 1.0,
                max: 100.0,
            }),
            ..DisplaySettings::default()
        };
        assert!(ChannelLut::new(&false_colour, 0.01).is_none());
    }
}
