//! The one display path: every picture raygine shows or writes (the viewer's texture, its
//! exports, the CLI's PNG) goes through [`DisplayMapper`], so a pixel gets the same code
//! wherever it is shown.

use super::{ChannelLut, DisplaySettings};
use crate::render::Film;
use crate::scene::luminance;
use glam::Vec3;
use rayon::prelude::*;

/// The display mapping at one exposure: [`DisplaySettings::map_pixel`], through a
/// [`ChannelLut`] where one can stand in for it.
pub struct DisplayMapper {
    display: DisplaySettings,
    scale: f32,
    lut: Option<ChannelLut>,
}

impl std::fmt::Debug for DisplayMapper {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DisplayMapper")
            .field("display", &self.display)
            .field("scale", &self.scale)
            .field("lut", &self.lut.is_some())
            .finish()
    }
}

impl DisplayMapper {
    /// The mapping of `display` at `exposure_stops` (the effective exposure, automatic or not).
    pub fn new(display: &DisplaySettings, exposure_stops: f32) -> Self {
        let scale = DisplaySettings::scale_for(exposure_stops);
        Self {
            display: *display,
            scale,
            lut: ChannelLut::new(display, scale),
        }
    }

    /// Whether this mapping is `display` at `exposure_stops` (for callers that keep one).
    pub fn is_for(&self, display: &DisplaySettings, exposure_stops: f32) -> bool {
        self.display == *display && self.scale == DisplaySettings::scale_for(exposure_stops)
    }

    /// Display colour (sRGB-encoded RGBA8) of a pixel of mean colour `rgb` (cd/m² per channel)
    /// and illuminance `illuminance_lx`.
    #[inline]
    pub fn map(&self, rgb: Vec3, illuminance_lx: f32) -> [u8; 4] {
        match &self.lut {
            Some(lut) => [lut.code(rgb.x), lut.code(rgb.y), lut.code(rgb.z), 255],
            None => self.display.map_pixel(rgb, illuminance_lx, self.scale),
        }
    }

    /// The whole film, row-major, top row first, `CHANNELS` bytes a pixel (3: RGB, 4: RGBA),
    /// rows in parallel on the current rayon pool.
    pub fn map_film<const CHANNELS: usize>(&self, film: &Film) -> Vec<u8> {
        let width = (film.width as usize).max(1);
        let mut out = vec![0u8; film.pixels.len() * CHANNELS];
        out.par_chunks_mut(width * CHANNELS)
            .zip(film.pixels.par_chunks(width))
            .for_each(|(row, sums)| {
                for (o, p) in row.chunks_exact_mut(CHANNELS).zip(sums) {
                    let code = self.map(p.mean_rgb(), p.mean_illuminance());
                    o.copy_from_slice(&code[..CHANNELS]);
                }
            });
        out
    }
}

/// Luminance figures of a film: the sum over pixels of the mean Rec. 709 luminance and the
/// largest pixel luminance, cd/m². Summed in pixel order, so they do not depend on threads.
pub fn luminance_sum_max(film: &Film) -> (f64, f32) {
    film.pixels.iter().fold((0.0f64, 0.0f32), |(sum, max), p| {
        let y = luminance(p.mean_rgb());
        (sum + f64::from(y), max.max(y))
    })
}
