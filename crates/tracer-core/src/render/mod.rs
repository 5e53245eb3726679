//! Tiles, passes and threads: turning the integrator into images. One-shot rendering lives here;
//! the progressive session of the viewer builds on the same film, sampler and tile order.

mod film;
mod passes;
mod progressive_film;
mod sampler;
mod session;
mod tiles;

pub use film::{Film, PixelSum};
pub use passes::{PREVIEW_BLOCKS, Pass};
pub use progressive_film::ProgressiveFilm;
pub use sampler::{pixel_sample_offset, sample_hash};
pub use session::{Notify, RenderSession, SessionStats, Snapshot};
pub use tiles::{Tile, tiles_centre_out};

use crate::scene::{Scene, Setup};
use crate::shading::{Prepared, trace};
use rayon::prelude::*;

/// Default maximum number of mirror reflections.
pub const DEFAULT_MAX_DEPTH: u32 = 5;

/// What to render, independent of the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    /// Samples per pixel: sample 0 at the pixel centre, later ones jittered.
    pub samples_per_pixel: u32,
    /// Maximum mirror reflections after the camera ray.
    pub max_depth: u32,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            width: 1280,
            height: 720,
            samples_per_pixel: 1,
            max_depth: DEFAULT_MAX_DEPTH,
        }
    }
}

/// Statistics of a finished render.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    pub rays: u64,
    pub elapsed_secs: f64,
}

impl RenderStats {
    pub fn mrays_per_sec(&self) -> f64 {
        if self.elapsed_secs > 0.0 {
            self.rays as f64 / self.elapsed_secs / 1e6
        } else {
            0.0
        }
    }
}

/// Tile edge in pixels for one-shot renders: each band of [`BAND_ROWS`] rows is traced in
/// blocks of this many columns, so neighbouring rays meet the same BVH nodes.
pub const TILE_SIZE: u32 = 32;

/// Rows per parallel work item of one-shot renders. Bands are written straight into the film
/// (no per-tile buffers, no merge), and small enough to balance the load on many cores.
pub const BAND_ROWS: u32 = 8;

/// Renders every sample of every pixel on the current rayon pool. The result does not depend on
/// the number of threads: each sample's position comes from (pixel, sample index) only, and each
/// pixel's samples are summed in sample order by one thread.
pub fn render(scene: &Scene, setup: &Setup, settings: &RenderSettings) -> (Film, RenderStats) {
    let started = std::time::Instant::now();
    let prep = Prepared::new(scene, setup, settings.max_depth);
    let basis = setup
        .camera
        .basis(setup.handedness, settings.width, settings.height);
    let spp = settings.samples_per_pixel.max(1);
    let mut film = Film::new(settings.width, settings.height);
    let width = settings.width as usize;
    let band_len = width * BAND_ROWS as usize;
    let rays: u64 = film
        .pixels
        .par_chunks_mut(band_len.max(1))
        .enumerate()
        .map(|(band, pixels)| {
            let y0 = band as u32 * BAND_ROWS;
            let rows = (pixels.len() / width.max(1)) as u32;
            let mut band_rays = 0u64;
            for x0 in (0..settings.width).step_by(TILE_SIZE as usize) {
                let x1 = (x0 + TILE_SIZE).min(settings.width);
                for y in y0..y0 + rows {
                    let row = (y - y0) as usize * width;
                    for x in x0..x1 {
                        let sum = &mut pixels[row + x as usize];
                        for s in 0..spp {
                            let (dx, dy) = pixel_sample_offset(x, y, settings.width, s);
                            let ray = basis.ray(x as f32 + dx, y as f32 + dy);
                            let sample = trace(&prep, &ray);
                            band_rays += u64::from(sample.rays);
                            sum.add(&sample);
                        }
                    }
                }
            }
            band_rays
        })
        .sum();
    let stats = RenderStats {
        rays,
        elapsed_secs: started.elapsed().as_secs_f64(),
    };
    (film, stats)
}
