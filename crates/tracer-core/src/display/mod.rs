//! Display-time mapping of the HDR film: exposure, tone mapping, sRGB encoding, false colour.
//! Changing any of it re-maps the film; it never changes what was rendered.
//!
//! Calibration: with exposure 0 stops, a luminance of [`REFERENCE_LUMINANCE`] (100 cd/m², the
//! white of a typical display) maps to 1.0 before the tone curve.

mod false_colour;
mod lut;
mod mapper;
mod tonemap;

pub use false_colour::{FalseColour, FalseColourQuantity, FalseColourScale, Legend, LegendEntry};
pub use lut::ChannelLut;
pub use mapper::{DisplayMapper, luminance_sum_max};
pub use tonemap::{ToneMap, linear_to_srgb, srgb_to_linear};

use crate::render::Film;
use crate::scene::luminance;
use glam::Vec3;

/// Luminance (cd/m²) shown as display value 1.0 at exposure 0.
pub const REFERENCE_LUMINANCE: f32 = 100.0;

/// How to turn the film into display pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DisplaySettings {
    /// Exposure in stops (each stop doubles the linear values).
    pub exposure_stops: f32,
    /// Choose the exposure from the image: its log-average luminance maps to middle grey (0.18).
    pub auto_exposure: bool,
    pub tone_map: ToneMap,
    /// When set, pixels show a false-colour scale instead of the image.
    pub false_colour: Option<FalseColour>,
}

impl Default for DisplaySettings {
    fn default() -> Self {
        Self {
            exposure_stops: 0.0,
            auto_exposure: false,
            tone_map: ToneMap::Filmic,
            false_colour: None,
        }
    }
}

/// The exposure (stops) that maps the log-average luminance of the lit pixels to 0.18.
/// Pixels with no light (background, shadow) are left out; an all-black film gives 0.
pub fn auto_exposure_stops(film: &Film) -> f32 {
    let mut sum = 0.0f64;
    let mut n = 0u64;
    for i in 0..film.len() {
        let y = luminance(film.mean_rgb(i));
        if y > 1e-6 && y.is_finite() {
            sum += f64::from(y).ln();
            n += 1;
        }
    }
    if n == 0 {
        return 0.0;
    }
    let log_avg = (sum / n as f64).exp() as f32;
    (0.18 * REFERENCE_LUMINANCE / log_avg).log2()
}

impl DisplaySettings {
    /// The exposure actually applied to `film` (the automatic one when enabled).
    pub fn effective_exposure(&self, film: &Film) -> f32 {
        if self.auto_exposure {
            auto_exposure_stops(film)
        } else {
            self.exposure_stops
        }
    }

    /// Display colour (sRGB-encoded, 0..=255) of one linear pixel at a given exposure scale.
    pub fn map_pixel(&self, rgb: Vec3, illuminance_lx: f32, scale: f32) -> [u8; 4] {
        if let Some(fc) = &self.false_colour {
            let value = match fc.quantity {
                FalseColourQuantity::Luminance => luminance(rgb),
                FalseColourQuantity::Illuminance => illuminance_lx,
            };
            return fc.colour(value);
        }
        let mapped = self.tone_map.apply(rgb * scale);
        let enc = |c: f32| (linear_to_srgb(c) * 255.0 + 0.5).clamp(0.0, 255.0) as u8;
        [enc(mapped.x), enc(mapped.y), enc(mapped.z), 255]
    }

    /// Multiplier from cd/m² to the tone curve's input at `exposure_stops`.
    pub fn scale_for(exposure_stops: f32) -> f32 {
        exposure_stops.exp2() / REFERENCE_LUMINANCE
    }

    /// The whole film as RGBA8, row-major, top row first, at the effective exposure.
    pub fn map_film(&self, film: &Film) -> Vec<u8> {
        DisplayMapper::new(self, self.effective_exposure(film)).map_film::<4>(film)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_stop_doubles_linear_values() {
        let a = DisplaySettings::scale_for(0.0);
        let b = DisplaySettings::scale_for(1.0);
        assert!((b / a - 2.0).abs() < 1e-6);
        assert!((a * REFERENCE_LUMINANCE - 1.0).abs() < 1e-6);
    }

    #[test]
    fn clamp_tone_map_pixel_values() {
        let s = DisplaySettings {
            tone_map: ToneMap::Clamp,
            ..DisplaySettings::default()
        };
        let scale = DisplaySettings::scale_for(0.0);
        // 100 cd/m² grey is display white; 18 cd/m² is middle grey, sRGB 118.
        assert_eq!(
            s.map_pixel(Vec3::splat(100.0), 0.0, scale),
            [255, 255, 255, 255]
        );
        assert_eq!(s.map_pixel(Vec3::splat(18.0), 0.0, scale)[0], 118);
        assert_eq!(s.map_pixel(Vec3::ZERO, 0.0, scale), [0, 0, 0, 255]);
    }

    #[test]
    fn auto_exposure_maps_log_average_to_middle_grey() {
        let film = Film::from_values(2, 1, &[Vec3::splat(10.0), Vec3::splat(1000.0)], &[0.0; 2]);
        // log average = 100 cd/m², so 0.18 * 100 / 100 -> log2(0.18).
        let stops = auto_exposure_stops(&film);
        assert!((stops - 0.18f32.log2()).abs() < 1e-4, "{stops}");
    }
}
