//! Tiles, passes and threads: turning the integrator into images. One-shot rendering lives here;
//! the progressive session of the viewer builds on the same film, sampler and tile order.

pub mod adaptive;
mod camera_rays;
mod film;
mod film_buffers;
mod film_cells;
mod fixed_point;
mod guides;
pub mod partial;
mod passes;
mod pixel;
mod pixel_sum;
mod progressive_film;
mod run_sums;
mod sampler;
mod session;
mod square_sum;
mod tiles;

pub use film::{Film, FilmError};
pub use fixed_point::VALUE_SCALE;
pub(crate) use fixed_point::{from_fixed, to_fixed};
pub use guides::{GUIDE_SCALE, Guide, GuideFilm, GuideSum, trace_guide};
pub use passes::{PREVIEW_BLOCKS, Pass};
pub use pixel::{BATCH_SAMPLES, BatchScratch, FrameSampler, NO_ILLUMINANCE};
pub use pixel_sum::{PixelSum, relative_error};
pub use progressive_film::ProgressiveFilm;
pub use sampler::{SampleJob, pixel_sample_offset, sample_hash};
pub use session::{ILLUMINANCE_SAMPLES, Notify, RenderSession, SessionStats, Snapshot};
pub use square_sum::{FINE_SQUARE_SCALE, SQUARE_SCALE, SquareSum};
pub use tiles::{Tile, tiles_centre_out};

use crate::integrator::IntegratorKind;
use crate::scene::{Scene, Setup};
use rayon::prelude::*;
use std::ops::Range;

/// Default maximum number of mirror reflections.
pub const DEFAULT_MAX_DEPTH: u32 = 5;

/// What to render, independent of the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    /// Samples per pixel: sample 0 at the pixel centre, later ones jittered.
    pub samples_per_pixel: u32,
    /// Maximum mirror reflections after the camera ray (direct mode).
    pub max_depth: u32,
    /// Light transport: direct (the coursework's model), path or bidirectional (global
    /// illumination).
    pub integrator: IntegratorKind,
    /// Path mode: non-delta bounces allowed (None: unlimited, the unbiased answer).
    pub max_bounces: Option<u32>,
    /// Whether to estimate each pixel's illuminance (lx) too. The bidirectional integrator
    /// measures it with a second (sensor) subpath, which costs about as much as the luminance;
    /// images that only show luminance can switch it off (the pixels then read 0 lx).
    pub pixel_illuminance: bool,
    /// Whether to sum the denoiser's albedo and normal guides beside the film (one more camera
    /// ray per sample, 56 bytes per pixel). They change no pixel's sums.
    pub guides: bool,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            width: 1280,
            height: 720,
            samples_per_pixel: 1,
            max_depth: DEFAULT_MAX_DEPTH,
            integrator: IntegratorKind::Direct,
            max_bounces: None,
            pixel_illuminance: true,
            guides: false,
        }
    }
}

/// Statistics of a finished render.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    pub rays: u64,
    pub elapsed_secs: f64,
    /// Samples every pixel received (fewer than asked when a time limit stopped the render;
    /// the fewest any pixel has under adaptive sampling).
    pub samples_per_pixel: u32,
    /// Samples per pixel on average (more than `samples_per_pixel` under adaptive sampling).
    pub mean_samples_per_pixel: f64,
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
/// the number of threads (see [`render_samples`]).
pub fn render(scene: &Scene, setup: &Setup, settings: &RenderSettings) -> (Film, RenderStats) {
    render_samples(scene, setup, settings, 0..settings.samples_per_pixel.max(1))
}

/// Renders sample after sample of the whole image until `settings.samples_per_pixel` or until
/// `time_limit` has passed (at least one pass). The film equals [`render`]'s with the number
/// of samples reached.
///
/// After a first pass alone, passes are rendered in chunks sized from the measured time per
/// pass to end by the limit (at most twice the passes done so far): one pass at a time, each a
/// parallel job of its own, left a quarter of a small image's time in thread start-up and
/// stragglers.
pub fn render_for(
    scene: &Scene,
    setup: &Setup,
    settings: &RenderSettings,
    time_limit: Option<std::time::Duration>,
) -> (Film, RenderStats) {
    if time_limit.is_none() {
        return render(scene, setup, settings);
    }
    render_with_progress(scene, setup, settings, time_limit, &mut |_| {})
}

/// Longest a chunk of passes of [`render_with_progress`] is planned to take, seconds: progress
/// is reported at least this often.
pub const PROGRESS_CHUNK_SECS: f64 = 2.0;

/// [`render_for`], in chunks of passes of at most about [`PROGRESS_CHUNK_SECS`] (with or
/// without a time limit), calling `progress` after each with the figures so far. The film is
/// the same as [`render`]'s with the number of samples reached.
pub fn render_with_progress(
    scene: &Scene,
    setup: &Setup,
    settings: &RenderSettings,
    time_limit: Option<std::time::Duration>,
    progress: &mut dyn FnMut(&RenderStats),
) -> (Film, RenderStats) {
    render_with_progress_mapped(
        scene,
        setup,
        settings,
        time_limit,
        &|_, r| r.clone(),
        progress,
    )
}

/// [`render_with_progress`] where pixel i takes the sample indices `map(i, pass)` in each pass
/// of indices `pass` (more of its own, say, where it needs them), disjoint across passes.
pub fn render_with_progress_mapped(
    scene: &Scene,
    setup: &Setup,
    settings: &RenderSettings,
    time_limit: Option<std::time::Duration>,
    map: &(dyn Fn(usize, &Range<u32>) -> Range<u32> + Sync),
    progress: &mut dyn FnMut(&RenderStats),
) -> (Film, RenderStats) {
    let started = std::time::Instant::now();
    let frame = FrameSampler::new(scene, setup, settings);
    let target = settings.samples_per_pixel.max(1);
    let mut film = new_film(settings);
    let mut rays = 0;
    let mut done = 0;
    let stats = |rays, done| RenderStats {
        rays,
        elapsed_secs: started.elapsed().as_secs_f64(),
        samples_per_pixel: done,
        mean_samples_per_pixel: f64::from(done),
    };
    while done < target {
        let elapsed = started.elapsed().as_secs_f64();
        let chunk = if done == 0 {
            1
        } else {
            let per_pass = (elapsed / f64::from(done)).max(1e-9);
            let mut fit = f64::from(target - done);
            if let Some(limit) = time_limit {
                fit = fit.min(((limit.as_secs_f64() - elapsed) / per_pass).floor());
                fit = fit.min(f64::from(done) * 2.0);
            }
            fit = fit.min((PROGRESS_CHUNK_SECS / per_pass).floor());
            (fit.max(1.0) as u32).clamp(1, target - done)
        };
        // Added in place (no second film): an overflow is counted as rejected samples.
        let range = done..done + chunk;
        let part_rays = render_pixel_ranges_into(&frame, settings, &|i| map(i, &range), &mut film);
        rays += part_rays;
        done += chunk;
        progress(&stats(rays, done));
        if time_limit.is_some_and(|limit| started.elapsed() >= limit) {
            break;
        }
    }
    (film, stats(rays, done))
}

/// Renders sample indices `samples` of every pixel. Films of disjoint ranges added with
/// [`Film::merge`] equal the film of their union, bit for bit: each sample depends on (pixel,
/// sample index) only, and sums are exact integers.
pub fn render_samples(
    scene: &Scene,
    setup: &Setup,
    settings: &RenderSettings,
    samples: Range<u32>,
) -> (Film, RenderStats) {
    let started = std::time::Instant::now();
    let frame = FrameSampler::new(scene, setup, settings);
    let (film, rays) = render_range(&frame, settings, samples.clone());
    let stats = RenderStats {
        rays,
        elapsed_secs: started.elapsed().as_secs_f64(),
        samples_per_pixel: samples.len() as u32,
        mean_samples_per_pixel: samples.len() as f64,
    };
    (film, stats)
}

/// Renders sample indices `samples(i)` of every pixel i (row-major index): pixels may get
/// different samples (adaptive sampling). The film's [`Film::splat_paths`] is set from its
/// counts. As for [`render_samples`], films of disjoint ranges add up to the film of their
/// union, and threads do not change the result.
pub fn render_pixels(
    scene: &Scene,
    setup: &Setup,
    settings: &RenderSettings,
    samples: &(dyn Fn(usize) -> Range<u32> + Sync),
) -> (Film, RenderStats) {
    let started = std::time::Instant::now();
    let frame = FrameSampler::new(scene, setup, settings);
    let (mut film, rays) = render_pixel_ranges(&frame, settings, samples);
    film.count_splat_paths();
    let total: u64 = film.counts().map(u64::from).sum();
    let stats = RenderStats {
        rays,
        elapsed_secs: started.elapsed().as_secs_f64(),
        samples_per_pixel: film.min_samples(),
        mean_samples_per_pixel: total as f64 / film.len().max(1) as f64,
    };
    (film, stats)
}

/// [`render_samples`] with a frame sampler made once; returns the film and the rays traced.
fn render_range(
    frame: &FrameSampler<'_>,
    settings: &RenderSettings,
    samples: Range<u32>,
) -> (Film, u64) {
    render_pixel_ranges(frame, settings, &|_| samples.clone())
}

/// Renders sample indices `samples(i)` of every pixel i (row-major index) into a new film;
/// returns it and the rays traced. Each sample depends on (pixel, sample index) only, so the
/// film does not depend on the number of threads, and adding films of disjoint ranges gives
/// the film of their union.
pub(crate) fn render_pixel_ranges(
    frame: &FrameSampler<'_>,
    settings: &RenderSettings,
    samples: &(dyn Fn(usize) -> Range<u32> + Sync),
) -> (Film, u64) {
    let mut film = new_film(settings);
    let rays = render_pixel_ranges_into(frame, settings, samples, &mut film);
    (film, rays)
}

/// Splats a band keeps before adding them to the film (about 1.3 MB): a 4K bidirectional
/// render once held every splat of the pass until its end.
const BAND_SPLATS: usize = 1 << 16;

/// Adds samples `samples(i)` of every pixel i to `film` (made with `settings`' size and
/// guides), band by band in parallel; returns the rays traced. Exact: the same sums as adding
/// a film of those samples.
pub(crate) fn render_pixel_ranges_into(
    frame: &FrameSampler<'_>,
    settings: &RenderSettings,
    samples: &(dyn Fn(usize) -> Range<u32> + Sync),
    film: &mut Film,
) -> u64 {
    let width = settings.width as usize;
    // Uneven counts (adaptive rounds) make uneven bands: rows one by one balance the threads.
    let first = samples(0).len();
    let even = (0..film.len()).all(|i| samples(i).len() == first);
    let band_rows: u32 = if even { BAND_ROWS } else { 1 };
    let band_len = width * band_rows as usize;
    let height = settings.height;
    let band_rays = film.par_bands(band_len, |band_index, band| {
        let y0 = band_index as u32 * band_rows;
        let y1 = (y0 + band_rows).min(height);
        let mut splats = Vec::new();
        let mut scratch = BatchScratch::default();
        let mut rays = 0;
        // Tile-wide columns of the band's rows, one after another.
        for x0 in (0..settings.width).step_by(TILE_SIZE as usize) {
            let x1 = (x0 + TILE_SIZE).min(settings.width);
            let order = (y0..y1)
                .flat_map(|y| (x0..x1).map(move |x| (x, y)))
                .map(|(x, y)| (x, y, samples(y as usize * width + x as usize)));
            rays += frame.for_each_sample(order, &mut scratch, &mut splats, |x, y, run| {
                band.add_run((y - y0) as usize * width + x as usize, run);
            });
            // Integer sums: the order splats arrive in does not matter.
            if splats.len() >= BAND_SPLATS {
                band.add_splats(&mut splats);
            }
        }
        band.add_splats(&mut splats);
        rays
    });
    if let Some(guides) = film.guides.as_mut() {
        add_guides(frame, settings, guides, samples);
    }
    band_rays.iter().sum()
}

fn new_film(settings: &RenderSettings) -> Film {
    if settings.guides {
        Film::with_guides(settings.width, settings.height)
    } else {
        Film::new(settings.width, settings.height)
    }
}

/// Adds the guides of samples `samples(i)` of every pixel i, band by band in parallel.
fn add_guides(
    frame: &FrameSampler<'_>,
    settings: &RenderSettings,
    guides: &mut GuideFilm,
    samples: &(dyn Fn(usize) -> Range<u32> + Sync),
) {
    let width = settings.width as usize;
    guides
        .pixels
        .par_chunks_mut((width * BAND_ROWS as usize).max(1))
        .enumerate()
        .for_each(|(band, pixels)| {
            let y0 = band * BAND_ROWS as usize;
            for (i, sum) in pixels.iter_mut().enumerate() {
                let (x, y) = ((i % width) as u32, (y0 + i / width) as u32);
                for s in samples(y0 * width + i) {
                    sum.add(&frame.guide(x, y, s));
                }
            }
        });
}
