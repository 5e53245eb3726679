//! Tone curves and the sRGB transfer function.

use glam::Vec3;

/// How linear display values above 1 are brought into range.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ToneMap {
    /// Values above 1 clip to white: linear, faithful below 1.
    Clamp,
    /// `x / (1 + x)` per channel.
    Reinhard,
    /// A filmic S-curve (the Narkowicz fit of the ACES reference curve), clipped to 0..1.
    #[default]
    Filmic,
}

impl ToneMap {
    pub const ALL: [ToneMap; 3] = [ToneMap::Clamp, ToneMap::Reinhard, ToneMap::Filmic];

    pub fn name(self) -> &'static str {
        match self {
            ToneMap::Clamp => "clamp",
            ToneMap::Reinhard => "reinhard",
            ToneMap::Filmic => "filmic",
        }
    }

    pub fn from_name(name: &str) -> Option<ToneMap> {
        Self::ALL
            .into_iter()
            .find(|t| t.name().eq_ignore_ascii_case(name))
    }

    /// Maps linear display values (1.0 = reference white) to 0..=1.
    pub fn apply(self, v: Vec3) -> Vec3 {
        // NaN becomes 0; huge values are capped so the curves' squares cannot overflow to inf/inf.
        let v = v.max(Vec3::ZERO).min(Vec3::splat(1.0e6));
        let out = match self {
            ToneMap::Clamp => v,
            ToneMap::Reinhard => v / (Vec3::ONE + v),
            ToneMap::Filmic => {
                let (a, b, c, d, e) = (2.51, 0.03, 2.43, 0.59, 0.14);
                (v * (v * a + b)) / (v * (v * c + d) + e)
            }
        };
        out.clamp(Vec3::ZERO, Vec3::ONE)
    }
}

/// The sRGB transfer function (IEC 61966-2-1), linear 0..1 to encoded 0..1.
pub fn linear_to_srgb(x: f32) -> f32 {
    let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// The inverse of [`linear_to_srgb`].
pub fn srgb_to_linear(x: f32) -> f32 {
    let x = x.clamp(0.0, 1.0);
    if x <= 0.040_45 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_known_points() {
        assert_eq!(linear_to_srgb(0.0), 0.0);
        assert!((linear_to_srgb(1.0) - 1.0).abs() < 1e-6);
        // 18 % grey encodes to about 0.4614 (118/255).
        assert!((linear_to_srgb(0.18) - 0.461_356).abs() < 1e-4);
        // The linear segment below the knee.
        assert!((linear_to_srgb(0.002) - 0.025_84).abs() < 1e-6);
        for i in 0..=100 {
            let x = i as f32 / 100.0;
            assert!((srgb_to_linear(linear_to_srgb(x)) - x).abs() < 1e-5);
        }
    }

    #[test]
    fn curves_are_monotonic_and_bounded() {
        for t in ToneMap::ALL {
            let mut last = -1.0;
            for i in 0..200 {
                let y = t.apply(Vec3::splat(i as f32 * 0.05)).x;
                assert!(y >= last && (0.0..=1.0).contains(&y), "{t:?}");
                last = y;
            }
        }
        assert!((ToneMap::Reinhard.apply(Vec3::ONE).x - 0.5).abs() < 1e-6);
        // Enormous values (a point light next to a wall) are white, never NaN or black.
        for t in ToneMap::ALL {
            let y = t.apply(Vec3::splat(1.0e21));
            assert!(y.min_element() > 0.999, "{t:?}: {y}");
        }
    }
}
