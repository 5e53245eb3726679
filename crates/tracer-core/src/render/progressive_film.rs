//! The film of one generation of a progressive render: accumulated full-resolution samples plus
//! the latest coarse preview, shown where a pixel has no full sample yet.

use super::film::{Film, PixelSum};
use super::tiles::Tile;
use glam::Vec3;

#[derive(Clone, Debug)]
pub struct ProgressiveFilm {
    /// The render generation these pixels belong to.
    pub generation: u64,
    /// Accumulated full-resolution samples (the converging image).
    pub accum: Film,
    /// Coarse preview values (luminance per channel, illuminance), one per pixel.
    preview_rgb: Vec<Vec3>,
    preview_lx: Vec<f32>,
    /// Whether any preview value has been written (else the film shows nothing yet).
    pub has_preview: bool,
}

impl ProgressiveFilm {
    pub fn new(generation: u64, width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self {
            generation,
            accum: Film::new(width, height),
            preview_rgb: vec![Vec3::ZERO; n],
            preview_lx: vec![0.0; n],
            has_preview: false,
        }
    }

    /// Empties the film for reuse by `generation` (no allocation).
    pub fn reset(&mut self, generation: u64) {
        self.generation = generation;
        self.accum.pixels.fill(PixelSum::default());
        self.preview_rgb.fill(Vec3::ZERO);
        self.preview_lx.fill(0.0);
        self.has_preview = false;
    }

    pub fn width(&self) -> u32 {
        self.accum.width
    }

    pub fn height(&self) -> u32 {
        self.accum.height
    }

    /// Fills a preview block's pixels (clipped to `tile`) with one sample's value.
    pub fn fill_preview(&mut self, rect: &Tile, rgb: Vec3, lx: f32) {
        for (x, y) in rect.pixels() {
            let i = self.accum.index(x, y);
            self.preview_rgb[i] = rgb;
            self.preview_lx[i] = lx;
        }
        self.has_preview = true;
    }

    pub fn add_tile(&mut self, tile: &Tile, sums: &[PixelSum]) {
        self.accum.add_tile(tile, sums);
    }

    /// What pixel `i` shows: the mean of its full samples, else the preview.
    pub fn shown_rgb(&self, i: usize) -> Vec3 {
        if self.accum.pixels[i].count > 0 {
            self.accum.mean_rgb(i)
        } else {
            self.preview_rgb[i]
        }
    }

    /// Illuminance (lx) shown for pixel `i`, like [`ProgressiveFilm::shown_rgb`].
    pub fn shown_illuminance(&self, i: usize) -> f32 {
        if self.accum.pixels[i].count > 0 {
            self.accum.mean_illuminance(i)
        } else {
            self.preview_lx[i]
        }
    }

    /// A plain film of what is shown (one "sample" per pixel), for display mapping and export.
    pub fn shown(&self) -> Film {
        let n = self.accum.pixels.len();
        let rgb: Vec<Vec3> = (0..n).map(|i| self.shown_rgb(i)).collect();
        let lx: Vec<f32> = (0..n).map(|i| self.shown_illuminance(i)).collect();
        Film::from_values(self.width(), self.height(), &rgb, &lx)
    }
}
