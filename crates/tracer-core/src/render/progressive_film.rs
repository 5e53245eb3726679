//! The film of one generation of a progressive render: accumulated full-resolution samples plus
//! the latest coarse preview, shown where a pixel has no full sample yet.

use super::film::Film;
use super::guides::{GuideFilm, GuideSum};
use super::pixel_sum::PixelSum;
use super::tiles::Tile;
use crate::integrator::Sample;
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
    /// Per pixel, the full samples whose camera ray hit nothing (display only: the viewer draws
    /// its backdrop there; films, exports and part files do not keep it).
    misses: Vec<u32>,
    /// Per pixel, whether the preview sample's camera ray hit nothing.
    preview_missed: Vec<bool>,
    /// Whether any preview value has been written (else the film shows nothing yet).
    pub has_preview: bool,
    /// Full-resolution samples added over all pixels (each traced one light subpath in
    /// bidirectional mode): splats are divided by this over the pixel count.
    samples_added: u64,
    /// Per pixel, its count when the illuminance was first measured, once that happened after
    /// adaptive rounds gave pixels different counts: its samples past it carry the
    /// illuminance. None: [`Film::illuminance_from`] says it for every pixel.
    illuminance_starts: Option<Vec<u32>>,
}

impl ProgressiveFilm {
    pub fn new(generation: u64, width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self {
            generation,
            accum: Film::new(width, height),
            preview_rgb: vec![Vec3::ZERO; n],
            preview_lx: vec![0.0; n],
            misses: vec![0; n],
            preview_missed: vec![false; n],
            has_preview: false,
            samples_added: 0,
            illuminance_starts: None,
        }
    }

    /// Keeps (or drops) the denoiser's guides beside the samples. Guides kept stay as they are
    /// (empty after [`ProgressiveFilm::reset`]); new ones start empty.
    pub fn set_guides(&mut self, on: bool) {
        match (&self.accum.guides, on) {
            (Some(_), true) => {}
            (None, true) => self.accum.guides = Some(GuideFilm::new(self.width(), self.height())),
            (_, false) => self.accum.guides = None,
        }
    }

    /// Empties the film for reuse by `generation` (no allocation), on the current rayon pool:
    /// at 1280x720 the cells are 44 MB. With the former 160-byte sums (147 MB) clearing them was
    /// most of a restart's first preview (25-35 ms on one thread of the 2-core test machine,
    /// 12-17 ms on two).
    pub fn reset(&mut self, generation: u64) {
        use rayon::prelude::*;
        const CHUNK: usize = 16 * 1024;
        self.generation = generation;
        self.accum.clear();
        if let Some(g) = self.accum.guides.as_mut() {
            g.pixels
                .par_chunks_mut(CHUNK)
                .for_each(|c| c.fill(GuideSum::default()));
        }
        self.preview_rgb.fill(Vec3::ZERO);
        self.preview_lx.fill(0.0);
        self.misses.fill(0);
        self.preview_missed.fill(false);
        self.has_preview = false;
        self.samples_added = 0;
        self.accum.illuminance_from = 0;
        self.accum.splat_paths = None;
        self.illuminance_starts = None;
    }

    /// The illuminance is measured from every pixel's next sample on (after adaptive rounds:
    /// the counts differ).
    pub fn measure_illuminance_from_now(&mut self) {
        self.accum.illuminance_from = 0;
        self.illuminance_starts = Some(self.accum.counts().collect());
    }

    /// Samples of pixel `i` whose illuminance was not measured.
    fn illuminance_skipped(&self, i: usize) -> u32 {
        match &self.illuminance_starts {
            Some(starts) => starts[i],
            None => self.accum.illuminance_from,
        }
    }

    /// Full samples added over all pixels.
    pub fn samples_added(&self) -> u64 {
        self.samples_added
    }

    /// Whether pixel `i` shows a measured illuminance: its full samples (or its block's, as
    /// for the colour) include one from [`Film::illuminance_from`] on, or it shows a preview
    /// of a render that measured it from the start.
    pub fn illuminance_measured(&self, i: usize) -> bool {
        match self.shown_source(i) {
            Some(j) => self.accum.count(j) > self.illuminance_skipped(j),
            None => self.accum.illuminance_from == 0 && self.illuminance_starts.is_none(),
        }
    }

    pub fn width(&self) -> u32 {
        self.accum.width
    }

    pub fn height(&self) -> u32 {
        self.accum.height
    }

    /// Fills a preview block's pixels (clipped to `tile`) with one sample's value.
    pub fn fill_preview(&mut self, rect: &Tile, sample: &Sample) {
        for (x, y) in rect.pixels() {
            let i = self.accum.index(x, y);
            self.preview_rgb[i] = sample.rgb;
            self.preview_lx[i] = sample.illuminance_lx;
            self.preview_missed[i] = sample.missed;
        }
        self.has_preview = true;
    }

    /// Adds runs of full samples: for pixel `pixels[k]`, its sums `sums[k]`, how many of
    /// their camera rays missed `missed[k]` and their guide sums `guides[k]` (when the film
    /// keeps guides). The pixels of a tile, or of a quarter of it (the first full pass).
    pub fn add_pixels(
        &mut self,
        pixels: &[(u32, u32)],
        sums: &[PixelSum],
        missed: &[u32],
        guides: &[GuideSum],
    ) {
        for (k, &(x, y)) in pixels.iter().enumerate() {
            let i = self.accum.index(x, y);
            self.accum.merge_pixel(i, &sums[k]);
            self.samples_added += u64::from(sums[k].count);
            self.misses[i] += missed[k];
            if let Some(g) = self.accum.guides.as_mut().zip(guides.get(k)) {
                g.0.pixels[i].merge(g.1);
            }
        }
    }

    /// The pixel whose full samples pixel `i` shows: itself once it has one, else, during the
    /// first full pass, the top-left pixel of its 2x2 block (the pass's first quarter), else
    /// none (the preview shows).
    fn shown_source(&self, i: usize) -> Option<usize> {
        if self.accum.count(i) > 0 {
            return Some(i);
        }
        let w = self.width() as usize;
        let (x, y) = (i % w, i / w);
        let anchor = (y & !1) * w + (x & !1);
        (self.accum.count(anchor) > 0).then_some(anchor)
    }

    /// The share (0..=1) of pixel `i` where the camera sees nothing: of its full samples, else
    /// its preview's. The background of the viewer's display, never of a render.
    pub fn background_fraction(&self, i: usize) -> f32 {
        let i = self.shown_source(i).unwrap_or(i);
        let count = self.accum.count(i);
        if count > 0 {
            (self.misses[i] as f32 / count as f32).min(1.0)
        } else {
            f32::from(u8::from(self.preview_missed[i]))
        }
    }

    /// Adds light-subpath splats (bidirectional mode).
    pub fn add_splats(&mut self, splats: &[crate::integrator::Splat]) {
        self.accum.add_splats(splats);
    }

    /// What pixel `i` shows: the mean of its full samples; before it has one, those of its
    /// 2x2 block's first pixel (the first full pass goes in quarters, see the session), else
    /// the preview.
    pub fn shown_rgb(&self, i: usize) -> Vec3 {
        match self.shown_source(i) {
            Some(j) => {
                let per_pixel = self.samples_added as f64 / self.accum.len().max(1) as f64;
                self.accum.pixel(j).mean_rgb_over(Some(per_pixel))
            }
            None => self.preview_rgb[i],
        }
    }

    /// Illuminance (lx) shown for pixel `i`, like [`ProgressiveFilm::shown_rgb`].
    pub fn shown_illuminance(&self, i: usize) -> f32 {
        match self.shown_source(i) {
            Some(j) => self
                .accum
                .pixel(j)
                .mean_illuminance_after(self.illuminance_skipped(j)),
            None => self.preview_lx[i],
        }
    }

    /// Every pixel's shown colour, row-major (the denoiser's input).
    pub fn shown_rgb_all(&self) -> Vec<Vec3> {
        (0..self.accum.len()).map(|i| self.shown_rgb(i)).collect()
    }

    /// A plain film of what is shown (one "sample" per pixel), for display mapping and export.
    pub fn shown(&self) -> Film {
        let n = self.accum.len();
        let rgb: Vec<Vec3> = (0..n).map(|i| self.shown_rgb(i)).collect();
        let lx: Vec<f32> = (0..n).map(|i| self.shown_illuminance(i)).collect();
        Film::from_values(self.width(), self.height(), &rgb, &lx)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::Splat;

    /// The share of a pixel's samples that saw nothing: the preview's until full samples
    /// arrive, then the full samples'.
    #[test]
    fn background_fraction_counts_the_samples_that_saw_nothing() {
        let mut film = ProgressiveFilm::new(1, 2, 1);
        let both = Tile {
            x0: 0,
            y0: 0,
            x1: 2,
            y1: 1,
        };
        let missed = Sample {
            missed: true,
            ..Sample::default()
        };
        let hit = Sample {
            rgb: Vec3::splat(1.0),
            ..Sample::default()
        };
        film.fill_preview(&both, &missed);
        assert_eq!(film.background_fraction(0), 1.0);
        // Pixel 0: one sample hit, one missed; pixel 1: two hits.
        for (a, b) in [(&hit, &hit), (&missed, &hit)] {
            let sums = [a, b].map(|s| {
                let mut sum = PixelSum::default();
                assert!(sum.add(s));
                sum
            });
            film.add_pixels(
                &[(0, 0), (1, 0)],
                &sums,
                &[u32::from(a.missed), u32::from(b.missed)],
                &[],
            );
        }
        assert_eq!(film.background_fraction(0), 0.5);
        assert_eq!(film.background_fraction(1), 0.0);
        film.reset(2);
        assert_eq!(film.background_fraction(0), 0.0);
    }

    /// During the first full pass a pixel without a sample shows its 2x2 block's first pixel
    /// (the pass's first quarter) once that has one, else the preview.
    #[test]
    fn first_pass_shows_the_blocks_first_pixel_upscaled() {
        let mut film = ProgressiveFilm::new(1, 4, 2);
        let all = Tile {
            x0: 0,
            y0: 0,
            x1: 4,
            y1: 2,
        };
        let preview = Sample {
            rgb: Vec3::splat(1.0),
            illuminance_lx: 10.0,
            ..Sample::default()
        };
        film.fill_preview(&all, &preview);
        let mut sums = vec![PixelSum::default(); 8];
        let full = Sample {
            rgb: Vec3::splat(4.0),
            illuminance_lx: 40.0,
            ..Sample::default()
        };
        assert!(sums[0].add(&full));
        let pixels: Vec<(u32, u32)> = all.pixels().collect();
        film.add_pixels(&pixels, &sums, &[0; 8], &[]);
        // Pixels 0, 1 (x = 1, y = 0), 4 (0, 1) and 5 (1, 1) form block (0, 0).
        for i in [0, 1, 4, 5] {
            assert_eq!(film.shown_rgb(i), Vec3::splat(4.0), "pixel {i}");
            assert_eq!(film.shown_illuminance(i), 40.0, "pixel {i}");
        }
        for i in [2, 3, 6, 7] {
            assert_eq!(film.shown_rgb(i), Vec3::splat(1.0), "pixel {i}");
        }
    }

    /// Mid-pass, splats are divided by the light subpaths traced so far, not by a pixel's own
    /// count: a pixel reads the same before and after the rest of the pass arrives.
    #[test]
    fn splats_are_normalised_by_the_light_paths_traced() {
        let mut film = ProgressiveFilm::new(1, 2, 1);
        let own = |film: &mut ProgressiveFilm, x: u32| {
            let mut sum = PixelSum::default();
            assert!(sum.add(&Sample::default()));
            film.add_pixels(&[(x, 0)], &[sum], &[0], &[]);
        };
        let splat = Splat {
            x: 0,
            y: 0,
            rgb: Vec3::splat(1.0),
        };
        // Pixel 0's sample and its light subpath (splatting 1 cd/m² onto pixel 0).
        own(&mut film, 0);
        film.add_splats(&[splat]);
        let half = film.shown_rgb(0);
        // Pixel 1's sample and its light subpath, splatting onto pixel 0 as well.
        own(&mut film, 1);
        film.add_splats(&[splat]);
        let full = film.shown_rgb(0);
        assert_eq!(half, Vec3::splat(2.0));
        assert_eq!(full, Vec3::splat(2.0));
    }
}
