//! False-colour views of luminance (cd/m²) or illuminance (lx), with an exact legend.

/// Which per-pixel quantity is shown.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FalseColourQuantity {
    #[default]
    Luminance,
    Illuminance,
}

impl FalseColourQuantity {
    pub fn unit(self) -> &'static str {
        match self {
            FalseColourQuantity::Luminance => "cd/m²",
            FalseColourQuantity::Illuminance => "lx",
        }
    }
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FalseColourScale {
    Linear,
    #[default]
    Log,
}

/// A false-colour mapping of `quantity` over `min..=max` (min > 0 for a log scale).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FalseColour {
    pub quantity: FalseColourQuantity,
    pub scale: FalseColourScale,
    pub min: f32,
    pub max: f32,
}

/// One legend entry: a value and the colour it is shown in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LegendEntry {
    pub value: f32,
    pub rgba: [u8; 4],
}

/// The legend of a false-colour view, low to high.
#[derive(Clone, Debug, PartialEq)]
pub struct Legend {
    pub unit: &'static str,
    pub entries: Vec<LegendEntry>,
}

/// The palette, low to high: blue, cyan, green, yellow, red, then white above the range.
const PALETTE: [[f32; 3]; 5] = [
    [0.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [0.0, 1.0, 0.0],
    [1.0, 1.0, 0.0],
    [1.0, 0.0, 0.0],
];

impl FalseColour {
    /// Position of `value` on the scale, 0 at `min` and 1 at `max` (unclamped, NaN-safe).
    pub fn position(&self, value: f32) -> f32 {
        let (lo, hi) = (self.min, self.max.max(self.min * (1.0 + 1e-6) + 1e-12));
        let t = match self.scale {
            FalseColourScale::Linear => (value - lo) / (hi - lo),
            FalseColourScale::Log => {
                let lo = lo.max(1e-9);
                if value <= 0.0 {
                    -1.0
                } else {
                    (value / lo).ln() / (hi.max(lo * 1.000_001) / lo).ln()
                }
            }
        };
        if t.is_nan() { -1.0 } else { t }
    }

    /// The value at scale position `t` (inverse of [`FalseColour::position`]).
    pub fn value_at(&self, t: f32) -> f32 {
        match self.scale {
            FalseColourScale::Linear => self.min + t * (self.max - self.min),
            FalseColourScale::Log => {
                let lo = self.min.max(1e-9);
                lo * (self.max / lo).powf(t)
            }
        }
    }

    /// Colour for a value: black below the range, white above, palette in between.
    pub fn colour(&self, value: f32) -> [u8; 4] {
        let t = self.position(value);
        if t < 0.0 {
            return [0, 0, 0, 255];
        }
        if t > 1.0 {
            return [255, 255, 255, 255];
        }
        let x = t * (PALETTE.len() - 1) as f32;
        let i = (x.floor() as usize).min(PALETTE.len() - 2);
        let f = x - i as f32;
        let (a, b) = (PALETTE[i], PALETTE[i + 1]);
        let mix = |k: usize| ((a[k] + (b[k] - a[k]) * f) * 255.0 + 0.5) as u8;
        [mix(0), mix(1), mix(2), 255]
    }

    /// `steps + 1` legend entries at equal positions along the scale, each with the exact value
    /// that position represents and the colour drawn for it.
    pub fn legend(&self, steps: usize) -> Legend {
        let steps = steps.max(1);
        let entries = (0..=steps)
            .map(|k| {
                let t = k as f32 / steps as f32;
                let value = self.value_at(t);
                LegendEntry {
                    value,
                    rgba: self.colour(value),
                }
            })
            .collect();
        Legend {
            unit: self.quantity.unit(),
            entries,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_legend_values_are_exact_decades() {
        let fc = FalseColour {
            quantity: FalseColourQuantity::Illuminance,
            scale: FalseColourScale::Log,
            min: 1.0,
            max: 10_000.0,
        };
        let legend = fc.legend(4);
        let values: Vec<f32> = legend.entries.iter().map(|e| e.value).collect();
        for (v, want) in values.iter().zip([1.0, 10.0, 100.0, 1000.0, 10_000.0]) {
            assert!((v / want - 1.0).abs() < 1e-5, "{values:?}");
        }
        assert_eq!(legend.unit, "lx");
        assert_eq!(legend.entries[0].rgba, [0, 0, 255, 255]);
        assert_eq!(legend.entries[4].rgba, [255, 0, 0, 255]);
        // A pixel of exactly a legend value gets that entry's colour.
        assert_eq!(fc.colour(100.0), legend.entries[2].rgba);
        assert_eq!(fc.colour(0.5), [0, 0, 0, 255]);
        assert_eq!(fc.colour(20_000.0), [255, 255, 255, 255]);
    }

    #[test]
    fn linear_scale_positions() {
        let fc = FalseColour {
            quantity: FalseColourQuantity::Luminance,
            scale: FalseColourScale::Linear,
            min: 0.0,
            max: 200.0,
        };
        assert!((fc.position(50.0) - 0.25).abs() < 1e-6);
        assert!((fc.value_at(0.75) - 150.0).abs() < 1e-4);
        assert_eq!(fc.colour(100.0), [0, 255, 0, 255]);
    }
}
