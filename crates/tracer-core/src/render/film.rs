//! The HDR film: per-pixel sums of linear luminance (cd/m² per channel) and of the first hit's
//! illuminance (lx), with a sample count, so the mean converges as samples accumulate.

use super::tiles::Tile;
use crate::shading::Sample;
use glam::Vec3;

/// The sum of some samples of one pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelSum {
    pub rgb: Vec3,
    pub illuminance_lx: f32,
    pub count: u32,
}

impl PixelSum {
    pub fn add(&mut self, s: &Sample) {
        self.rgb += s.rgb;
        self.illuminance_lx += s.illuminance_lx;
        self.count += 1;
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    pub width: u32,
    pub height: u32,
    /// Row-major, top row first.
    pub pixels: Vec<PixelSum>,
}

impl Film {
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: vec![PixelSum::default(); width as usize * height as usize],
        }
    }

    pub fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    /// Adds a tile's sums (in the tile's row-major pixel order).
    pub fn add_tile(&mut self, tile: &Tile, sums: &[PixelSum]) {
        for ((x, y), s) in tile.pixels().zip(sums) {
            let i = self.index(x, y);
            let p = &mut self.pixels[i];
            p.rgb += s.rgb;
            p.illuminance_lx += s.illuminance_lx;
            p.count += s.count;
        }
    }

    /// Mean linear luminance per channel (cd/m²); black where no sample landed yet.
    pub fn mean_rgb(&self, i: usize) -> Vec3 {
        let p = self.pixels[i];
        if p.count == 0 {
            Vec3::ZERO
        } else {
            p.rgb / p.count as f32
        }
    }

    /// Mean illuminance (lx) on the surface seen in pixel `i`.
    pub fn mean_illuminance(&self, i: usize) -> f32 {
        let p = self.pixels[i];
        if p.count == 0 {
            0.0
        } else {
            p.illuminance_lx / p.count as f32
        }
    }

    /// All mean colours, row-major.
    pub fn mean_rgb_all(&self) -> Vec<Vec3> {
        (0..self.pixels.len()).map(|i| self.mean_rgb(i)).collect()
    }

    /// The fewest samples any pixel has.
    pub fn min_samples(&self) -> u32 {
        self.pixels.iter().map(|p| p.count).min().unwrap_or(0)
    }
}
