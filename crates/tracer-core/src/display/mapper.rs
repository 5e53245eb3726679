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
        let skipped = film.illuminance_from;
        let paths = film.splat_paths;
        let mut out = vec![0u8; film.len() * CHANNELS];
        out.par_chunks_mut(width * CHANNELS)
            .enumerate()
            .for_each(|(y, row)| {
                for (x, o) in row.chunks_exact_mut(CHANNELS).enumerate() {
                    let p = film.pixel(y * width + x);
                    let code = self.map(p.mean_rgb_over(paths), p.mean_illuminance_after(skipped));
                    o.copy_from_slice(&code[..CHANNELS]);
                }
            });
        out
    }

    /// [`Self::map_film`] and [`luminance_sum_max`] in one pass over the film (each pixel's
    /// mean read once): the same bytes and the same figures.
    pub fn map_film_and_luminance<const CHANNELS: usize>(
        &self,
        film: &Film,
    ) -> (Vec<u8>, f64, f32) {
        let width = (film.width as usize).max(1);
        let skipped = film.illuminance_from;
        let paths = film.splat_paths;
        let mut out = vec![0u8; film.len() * CHANNELS];
        let rows: Vec<(f64, f32)> = out
            .par_chunks_mut(width * CHANNELS)
            .enumerate()
            .map(|(y, row)| {
                let (mut sum, mut max) = (0.0f64, 0.0f32);
                for (x, o) in row.chunks_exact_mut(CHANNELS).enumerate() {
                    let p = film.pixel(y * width + x);
                    let rgb = p.mean_rgb_over(paths);
                    let y = luminance(rgb);
                    sum += f64::from(y);
                    max = max.max(y);
                    let code = self.map(rgb, p.mean_illuminance_after(skipped));
                    o.copy_from_slice(&code[..CHANNELS]);
                }
                (sum, max)
            })
            .collect();
        let (sum, max) = add_rows(&rows);
        (out, sum, max)
    }
}

/// Luminance figures of a film: the sum over pixels of the mean Rec. 709 luminance and the
/// largest pixel luminance, cd/m². Each row is summed in pixel order and the rows' sums in row
/// order, so the figures do not depend on threads.
pub fn luminance_sum_max(film: &Film) -> (f64, f32) {
    let width = (film.width as usize).max(1);
    let paths = film.splat_paths;
    let rows: Vec<(f64, f32)> = (0..film.len().div_ceil(width))
        .into_par_iter()
        .map(|row| {
            let end = ((row + 1) * width).min(film.len());
            (row * width..end).fold((0.0f64, 0.0f32), |(sum, max), i| {
                let y = luminance(film.pixel(i).mean_rgb_over(paths));
                (sum + f64::from(y), max.max(y))
            })
        })
        .collect();
    add_rows(&rows)
}

/// The rows' luminance figures added in row order.
fn add_rows(rows: &[(f64, f32)]) -> (f64, f32) {
    rows.iter()
        .fold((0.0, 0.0), |(sum, max), &(s, m)| (sum + s, max.max(m)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_pass_maps_and_sums_like_the_two_passes() {
        let (w, h) = (37u32, 23u32);
        let n = (w * h) as usize;
        // Values from black to far over white, with a few hot pixels.
        let rgb: Vec<Vec3> = (0..n)
            .map(|i| {
                let t = i as f32 * 0.37;
                let hot = if i % 101 == 7 { 5.0e4 } else { 1.0 };
                Vec3::new(t.sin().abs() * 300.0, t * 0.5, (i % 13) as f32) * hot
            })
            .collect();
        let lx: Vec<f32> = (0..n).map(|i| i as f32 * 2.5).collect();
        let film = Film::from_values(w, h, &rgb, &lx);
        for display in [
            DisplaySettings::default(),
            DisplaySettings {
                exposure_stops: -2.5,
                ..DisplaySettings::default()
            },
        ] {
            let mapper = DisplayMapper::new(&display, display.exposure_stops);
            let (bytes, sum, max) = mapper.map_film_and_luminance::<3>(&film);
            assert_eq!(bytes, mapper.map_film::<3>(&film));
            let (want_sum, want_max) = luminance_sum_max(&film);
            assert_eq!(sum.to_bits(), want_sum.to_bits());
            assert_eq!(max.to_bits(), want_max.to_bits());
            // Against the plain definition (summation order aside).
            let plain: f64 = rgb.iter().map(|c| f64::from(luminance(*c))).sum();
            assert!((sum - plain).abs() <= 1e-9 * plain, "{sum} vs {plain}");
            let plain_max = rgb.iter().map(|c| luminance(*c)).fold(0.0f32, f32::max);
            assert!((max - plain_max).abs() <= 1e-3 * plain_max);
        }
    }
}
