//! How a film stores its pixels' exact sums: 48 bytes a pixel for its own samples, 40 more
//! for splats once a light subpath splats into the film, and a sparse table of full-width sums
//! for the few pixels that outgrow them.
//!
//! A [`PixelSum`] holds eleven 128-bit integers (184 bytes), enough for any sample the film
//! accepts, 2³³ times over. Almost every pixel needs far less: its luminance and illuminance
//! sums fit in 64 bits (2⁻³² units: up to 2³¹ cd/m² · samples) and its squares in 96 bits
//! (2⁻⁴⁸ units). A cell holds those; a pixel whose sums would leave them (a lamp seen directly
//! at thousands of samples, the built-in box's hot spot at 10⁹-10¹⁰ cd/m², a rejected sample)
//! moves to the table as a [`PixelSum`], exactly, and stays there. Integer sums do not care
//! when a pixel moved: every pixel reads the same sums as a film of [`PixelSum`]s would hold,
//! so images are bit-identical to those of the wide film.

use super::pixel_sum::PixelSum;
use super::run_sums::{RUN_SAMPLES, run_sums};
use super::square_sum::SquareSum;
use crate::integrator::{Sample, Splat};
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::{Mutex, PoisonError};

/// A pixel's own samples: Σ r, g, b, illuminance (units of 2⁻³²), Σ y² (a 96-bit integer of
/// 2⁻⁴⁸ units, low word and high word) and the count; 48 bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Zeroable)]
#[repr(C)]
pub struct BaseCell {
    sums: [i64; 4],
    square_lo: u64,
    square_hi: i32,
    /// Samples added; [`MOVED`] when the pixel's sums live in the table.
    count: u32,
}

/// A pixel's splats: Σ r, g, b (2⁻³² units) and Σ of their squared luminances (96 bits of
/// 2⁻⁴⁸ units); 40 bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Zeroable)]
#[repr(C)]
pub struct SplatCell {
    rgb: [i64; 3],
    square_lo: u64,
    square_hi: i32,
    /// 1 when the pixel's splat sums live in the table.
    moved: u32,
}

/// The count of a cell whose pixel moved to the table (no cell reaches it: cells count at
/// most 2³¹ − 1 samples).
const MOVED: u32 = u32::MAX;
/// Most samples a cell counts.
const CELL_COUNT_LIMIT: u32 = (1 << 31) - 1;

/// A 96-bit square: the cell's two words as an i128.
fn square_of(lo: u64, hi: i32) -> i128 {
    (i128::from(hi) << 64) | i128::from(lo)
}

/// The two words of a 96-bit square; None when `units` needs more bits.
fn square_words(units: i128) -> Option<(u64, i32)> {
    let hi = i32::try_from(units >> 64).ok()?;
    Some((units as u64, hi))
}

/// Puts `new` in `slot` when there is one; whether there was (a cell's sums that fit).
fn replace_with<T>(slot: &mut T, new: Option<T>) -> bool {
    new.map(|v| *slot = v).is_some()
}

/// `a + b` for a cell's 64-bit sum and a wide sum; None past 64 bits.
fn add64(a: i64, b: i128) -> Option<i64> {
    a.checked_add(i64::try_from(b).ok()?)
}

impl BaseCell {
    /// A cell with sums in it, for tests of buffers that must come back empty.
    #[cfg(test)]
    pub(super) fn dirty() -> BaseCell {
        BaseCell {
            sums: [7, -8, 9, 1],
            square_lo: 3,
            square_hi: 1,
            count: 5,
        }
    }

    fn moved(&self) -> bool {
        self.count == MOVED
    }

    /// The cell's sums as a [`PixelSum`] (own samples only).
    fn widen(&self) -> PixelSum {
        let s = self.sums.map(i128::from);
        PixelSum {
            rgb: [s[0], s[1], s[2]],
            illuminance: s[3],
            luminance_sq: SquareSum::from_units(square_of(self.square_lo, self.square_hi)),
            count: self.count,
            ..PixelSum::default()
        }
    }

    /// Adds the own-sample sums of `o`; false (and the cell unchanged) when they do not fit.
    fn try_add(&mut self, o: &PixelSum) -> bool {
        let sum = (|| {
            if o.rejected != 0 {
                return None;
            }
            let square =
                square_of(self.square_lo, self.square_hi).checked_add(o.luminance_sq.units()?)?;
            let (square_lo, square_hi) = square_words(square)?;
            let count = self.count.checked_add(o.count)?;
            Some(BaseCell {
                sums: [
                    add64(self.sums[0], o.rgb[0])?,
                    add64(self.sums[1], o.rgb[1])?,
                    add64(self.sums[2], o.rgb[2])?,
                    add64(self.sums[3], o.illuminance)?,
                ],
                square_lo,
                square_hi,
                count: (count <= CELL_COUNT_LIMIT).then_some(count)?,
            })
        })();
        replace_with(self, sum)
    }
}

impl BaseCell {
    /// Adds a run's 64-bit sums ([`run_sums`]: r, g, b, illuminance, the square's whole part
    /// and remainder) of `n` samples; false (and the cell unchanged) when they do not fit.
    #[inline]
    fn try_add_run(&mut self, sums: &[i64; 6], n: u32) -> bool {
        let sum = (|| {
            let square = SquareSum::from_parts(i128::from(sums[4]), sums[5])?.units()?;
            let (square_lo, square_hi) =
                square_words(square_of(self.square_lo, self.square_hi).checked_add(square)?)?;
            let count = self.count.checked_add(n)?;
            Some(BaseCell {
                sums: [
                    self.sums[0].checked_add(sums[0])?,
                    self.sums[1].checked_add(sums[1])?,
                    self.sums[2].checked_add(sums[2])?,
                    self.sums[3].checked_add(sums[3])?,
                ],
                square_lo,
                square_hi,
                count: (count <= CELL_COUNT_LIMIT).then_some(count)?,
            })
        })();
        replace_with(self, sum)
    }
}

impl SplatCell {
    fn widen(&self) -> PixelSum {
        let s = self.rgb.map(i128::from);
        PixelSum {
            splat_rgb: s,
            splat_luminance_sq: SquareSum::from_units(square_of(self.square_lo, self.square_hi)),
            ..PixelSum::default()
        }
    }

    /// Adds the splat sums of `o`; false (and the cell unchanged) when they do not fit.
    fn try_add(&mut self, o: &PixelSum) -> bool {
        let sum = (|| {
            if o.rejected != 0 {
                return None;
            }
            let square = square_of(self.square_lo, self.square_hi)
                .checked_add(o.splat_luminance_sq.units()?)?;
            let (square_lo, square_hi) = square_words(square)?;
            Some(SplatCell {
                rgb: [
                    add64(self.rgb[0], o.splat_rgb[0])?,
                    add64(self.rgb[1], o.splat_rgb[1])?,
                    add64(self.rgb[2], o.splat_rgb[2])?,
                ],
                square_lo,
                square_hi,
                moved: 0,
            })
        })();
        replace_with(self, sum)
    }
}

/// The own-sample part of a pixel sum (splat fields zero).
fn own_part(p: &PixelSum) -> PixelSum {
    PixelSum {
        splat_rgb: [0; 3],
        splat_luminance_sq: SquareSum::default(),
        ..*p
    }
}

/// The splat part of a pixel sum (own fields zero; its rejected samples stay with the own
/// part).
fn splat_part(p: &PixelSum) -> PixelSum {
    PixelSum {
        splat_rgb: p.splat_rgb,
        splat_luminance_sq: p.splat_luminance_sq,
        ..PixelSum::default()
    }
}

fn has_splats(p: &PixelSum) -> bool {
    p.splat_rgb != [0; 3] || p.splat_luminance_sq != SquareSum::default()
}

/// Adds `o` to pixel `i` of a cell slice and its table; false when the sum overflowed (then
/// counted as rejected in the table, as [`PixelSum::merge`] counts it).
fn merge_base(
    cell: &mut BaseCell,
    wide: &mut HashMap<u32, PixelSum>,
    i: u32,
    o: &PixelSum,
) -> bool {
    if !cell.moved() && cell.try_add(o) {
        return true;
    }
    let entry = wide.entry(i).or_insert_with(|| {
        let w = cell.widen();
        *cell = BaseCell {
            count: MOVED,
            ..BaseCell::default()
        };
        w
    });
    entry.merge(o)
}

/// The splat layer: allocated when the first splat arrives.
#[derive(Clone, Debug, Default)]
struct SplatLayer {
    cells: Vec<SplatCell>,
    wide: HashMap<u32, PixelSum>,
}

impl SplatLayer {
    fn new(len: usize) -> Self {
        Self {
            cells: crate::pages::zeroed_vec_on_huge_pages(len),
            wide: HashMap::new(),
        }
    }

    /// Adds the splat part of `o` to pixel `i`; false on overflow.
    fn merge(&mut self, i: usize, o: &PixelSum) -> bool {
        let cell = &mut self.cells[i];
        if cell.moved == 0 && cell.try_add(o) {
            return true;
        }
        let entry = self.wide.entry(i as u32).or_insert_with(|| {
            let w = cell.widen();
            *cell = SplatCell {
                moved: 1,
                ..SplatCell::default()
            };
            w
        });
        entry.merge(o)
    }

    fn get(&self, i: usize) -> PixelSum {
        let cell = &self.cells[i];
        if cell.moved == 0 {
            cell.widen()
        } else {
            self.wide.get(&(i as u32)).copied().unwrap_or_default()
        }
    }

    fn add_splats(&mut self, width: u32, height: u32, splats: &[Splat]) {
        for s in splats {
            if s.x < width && s.y < height {
                let i = s.y as usize * width as usize + s.x as usize;
                let mut p = PixelSum::default();
                p.add_splat(s.rgb);
                self.merge(i, &p);
            }
        }
    }
}

/// A film's pixels: cells, the table of pixels that outgrew them, and the splat layer.
#[derive(Clone, Debug)]
pub struct FilmPixels {
    base: Vec<BaseCell>,
    wide: HashMap<u32, PixelSum>,
    splats: Option<Box<SplatLayer>>,
}

impl PartialEq for FilmPixels {
    /// Equal when every pixel holds the same sums, however they are stored.
    fn eq(&self, other: &Self) -> bool {
        self.len() == other.len() && (0..self.len()).all(|i| self.get(i) == other.get(i))
    }
}

impl FilmPixels {
    /// `len` empty pixels (`base`: zeroed cells, from the film's buffer store).
    pub(super) fn from_cells(base: Vec<BaseCell>) -> Self {
        Self {
            base,
            wide: HashMap::new(),
            splats: None,
        }
    }

    /// The cells, for the buffer store when the film is dropped.
    pub(super) fn take_cells(&mut self) -> Vec<BaseCell> {
        std::mem::take(&mut self.base)
    }

    pub fn len(&self) -> usize {
        self.base.len()
    }

    pub fn is_empty(&self) -> bool {
        self.base.is_empty()
    }

    /// Pixel `i`'s sums.
    pub fn get(&self, i: usize) -> PixelSum {
        let cell = &self.base[i];
        let mut p = if cell.moved() {
            self.wide.get(&(i as u32)).copied().unwrap_or_default()
        } else {
            cell.widen()
        };
        if let Some(layer) = &self.splats {
            let s = layer.get(i);
            p.splat_rgb = s.splat_rgb;
            p.splat_luminance_sq = s.splat_luminance_sq;
            p.rejected = p.rejected.saturating_add(s.rejected);
        }
        p
    }

    /// Pixel `i`'s sample count (without widening it).
    pub fn count(&self, i: usize) -> u32 {
        let cell = &self.base[i];
        if cell.moved() {
            self.wide.get(&(i as u32)).map_or(0, |p| p.count)
        } else {
            cell.count
        }
    }

    /// Adds `o` to pixel `i`; false when the sum would overflow (its samples are then counted
    /// as rejected, as [`PixelSum::merge`] does).
    pub fn merge(&mut self, i: usize, o: &PixelSum) -> bool {
        let own = merge_base(&mut self.base[i], &mut self.wide, i as u32, &own_part(o));
        if !has_splats(o) {
            return own;
        }
        let len = self.len();
        let layer = self
            .splats
            .get_or_insert_with(|| Box::new(SplatLayer::new(len)));
        layer.merge(i, &splat_part(o)) && own
    }

    /// Empties every pixel, keeping the cells' memory.
    pub fn clear(&mut self) {
        const CHUNK: usize = 16 * 1024;
        self.base
            .par_chunks_mut(CHUNK)
            .for_each(|c| c.fill(BaseCell::default()));
        self.wide.clear();
        if let Some(layer) = self.splats.as_mut() {
            layer
                .cells
                .par_chunks_mut(CHUNK)
                .for_each(|c| c.fill(SplatCell::default()));
            layer.wide.clear();
        }
    }

    /// Replaces pixel `i`'s sums with `p`.
    pub fn set(&mut self, i: usize, p: &PixelSum) {
        self.base[i] = BaseCell::default();
        self.wide.remove(&(i as u32));
        if let Some(layer) = self.splats.as_mut() {
            layer.cells[i] = SplatCell::default();
            layer.wide.remove(&(i as u32));
        }
        self.merge(i, p);
    }

    /// Adds splats (each everything one light subpath sent to its pixel) of a `width` x
    /// `height` film.
    pub fn add_splats(&mut self, width: u32, height: u32, splats: &[Splat]) {
        if splats.is_empty() {
            return;
        }
        let len = self.len();
        self.splats
            .get_or_insert_with(|| Box::new(SplatLayer::new(len)))
            .add_splats(width, height, splats);
    }

    /// Samples refused anywhere: only pixels in the table can have any.
    pub fn rejected(&self) -> u64 {
        let own: u64 = self.wide.values().map(|p| u64::from(p.rejected)).sum();
        let splats: u64 = self
            .splats
            .as_ref()
            .map_or(0, |l| l.wide.values().map(|p| u64::from(p.rejected)).sum());
        own + splats
    }

    /// Pixels whose sums outgrew their cells (own samples, splats).
    pub fn moved_pixels(&self) -> (usize, usize) {
        (
            self.wide.len(),
            self.splats.as_ref().map_or(0, |l| l.wide.len()),
        )
    }

    /// Bytes of memory the pixels hold (cells, splat cells, table entries).
    pub fn bytes(&self) -> usize {
        let entry = size_of::<(u32, PixelSum)>() + 8;
        let splats = self.splats.as_ref().map_or(0, |l| {
            l.cells.capacity() * size_of::<SplatCell>() + l.wide.capacity() * entry
        });
        self.base.capacity() * size_of::<BaseCell>() + self.wide.capacity() * entry + splats
    }

    /// Runs `f` on bands of `band_len` pixels in parallel, each band able to add to its own
    /// pixels and to add splats anywhere (`f` gets the band's index and the band); returns
    /// what `f` returned, in band order.
    pub(super) fn par_bands<R: Send>(
        &mut self,
        band_len: usize,
        width: u32,
        height: u32,
        f: impl Fn(usize, &mut Band<'_>) -> R + Sync,
    ) -> Vec<R> {
        let band_len = band_len.max(1);
        let bands = self.len().div_ceil(band_len);
        // Each band takes the table entries of its own pixels.
        let mut tables: Vec<HashMap<u32, PixelSum>> = vec![HashMap::new(); bands];
        for (i, p) in self.wide.drain() {
            tables[i as usize / band_len].insert(i, p);
        }
        let len = self.len();
        let splats = Mutex::new(self.splats.take());
        let results: Vec<(HashMap<u32, PixelSum>, R)> = self
            .base
            .par_chunks_mut(band_len)
            .zip(tables.into_par_iter())
            .enumerate()
            .map(|(k, (cells, wide))| {
                let mut band = Band {
                    cells,
                    first: k * band_len,
                    wide,
                    splats: &splats,
                    len,
                    width,
                    height,
                };
                let r = f(k, &mut band);
                (band.wide, r)
            })
            .collect();
        self.splats = splats.into_inner().unwrap_or_else(PoisonError::into_inner);
        results
            .into_iter()
            .map(|(wide, r)| {
                self.wide.extend(wide);
                r
            })
            .collect()
    }
}

/// Some consecutive pixels of a film, for one thread ([`FilmPixels::par_bands`]).
pub struct Band<'a> {
    cells: &'a mut [BaseCell],
    /// Index of the band's first pixel in the film.
    first: usize,
    wide: HashMap<u32, PixelSum>,
    splats: &'a Mutex<Option<Box<SplatLayer>>>,
    len: usize,
    width: u32,
    height: u32,
}

impl Band<'_> {
    /// Adds `o` (own samples; splat fields are ignored) to the band's pixel `k` (0-based in
    /// the band).
    pub fn merge(&mut self, k: usize, o: &PixelSum) -> bool {
        debug_assert!(!has_splats(o));
        let i = (self.first + k) as u32;
        merge_base(&mut self.cells[k], &mut self.wide, i, o)
    }

    /// Adds the samples `run` (all of the band's pixel `k`), exactly as adding their
    /// [`PixelSum::add_run`] would; returns how many were rejected. A short run of ordinary
    /// values goes straight into the cell from its 64-bit sums.
    pub fn add_run(&mut self, k: usize, run: &[Sample]) -> u32 {
        let cell = &mut self.cells[k];
        if !cell.moved()
            && run.len() <= RUN_SAMPLES
            && let Some(sums) = run_sums(run)
            && cell.try_add_run(&sums, run.len() as u32)
        {
            return 0;
        }
        let mut sum = PixelSum::default();
        let rejected = sum.add_run(run);
        self.merge(k, &sum);
        rejected
    }

    /// Adds splats into the film (anywhere), and empties `splats`.
    pub fn add_splats(&self, splats: &mut Vec<Splat>) {
        if splats.is_empty() {
            return;
        }
        let mut layer = self.splats.lock().unwrap_or_else(PoisonError::into_inner);
        layer
            .get_or_insert_with(|| Box::new(SplatLayer::new(self.len)))
            .add_splats(self.width, self.height, splats);
        splats.clear();
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;
    use crate::integrator::Sample;
    use glam::Vec3;

    #[test]
    fn cells_are_small() {
        assert_eq!(size_of::<BaseCell>(), 48);
        assert_eq!(size_of::<SplatCell>(), 40);
    }

    fn sample(v: f32) -> Sample {
        Sample {
            rgb: Vec3::new(v, 0.5 * v, 2.0 * v),
            illuminance_lx: 3.0 * v,
            rays: 1,
            missed: false,
        }
    }

    #[test]
    fn pixels_read_the_sums_of_wide_pixels_whenever_they_move() {
        // Ordinary values, a hot spot's (past 64 bits at 2^-32 after one sample), rejected
        // ones, and splats of both kinds, added in runs to cells and to wide sums alike.
        let values = [
            1.0,
            0.25,
            3.0e9,
            7.0,
            1.0e-4,
            f32::NAN,
            2.0e10,
            5.0e5,
            0.0,
            1e30,
        ];
        let mut cells = FilmPixels::from_cells(vec![BaseCell::default(); 4]);
        let mut wide = [PixelSum::default(); 4];
        for (k, v) in values.iter().enumerate() {
            let i = k % 4;
            let mut p = PixelSum::default();
            p.add_run(&[sample(*v), sample(v * 0.5)]);
            p.add_splat(Vec3::splat(*v));
            assert_eq!(cells.merge(i, &p), wide[i].merge(&p), "{v}");
            for (j, w) in wide.iter().enumerate() {
                assert_eq!(cells.get(j), *w, "after {v}: pixel {j}");
                assert_eq!(cells.count(j), w.count);
            }
        }
        let rejected: u64 = wide.iter().map(|p| u64::from(p.rejected)).sum();
        assert_eq!(cells.rejected(), rejected);
        assert!(rejected > 0);
        // Some moved, some did not.
        let (own, splats) = cells.moved_pixels();
        assert!(
            (1..4).contains(&own) && (1..4).contains(&splats),
            "{own} {splats}"
        );
        // Replacing a pixel clears what it held.
        cells.set(2, &wide[1]);
        assert_eq!(cells.get(2), wide[1]);
    }

    #[test]
    fn bands_add_like_the_film() {
        let mut film = FilmPixels::from_cells(vec![BaseCell::default(); 10]);
        let mut p = PixelSum::default();
        p.add(&sample(3.0e9));
        film.merge(7, &p);
        let mut q = PixelSum::default();
        q.add(&sample(2.0));
        film.par_bands(3, 5, 2, |k, band| {
            for j in 0..3 {
                if k * 3 + j < 10 {
                    band.merge(j, &q);
                }
            }
            band.add_splats(&mut vec![Splat {
                x: k as u32,
                y: 1,
                rgb: Vec3::ONE,
            }]);
        });
        let mut expected = p;
        expected.merge(&q);
        assert_eq!(own_part(&film.get(7)), expected);
        assert_eq!(film.get(0).count, 1);
        assert_eq!(film.get(5 + 2).splat_rgb, film.get(5).splat_rgb);
        assert!(film.get(5).splat_rgb[0] > 0);
        assert_eq!(film.get(9).splat_rgb, [0; 3]);
    }
}

#[cfg(test)]
mod run_tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;
    use glam::Vec3;

    #[test]
    fn runs_into_cells_equal_runs_into_wide_sums() {
        // Per pixel, runs of ordinary values, then a hot spot's, NaN and huge ones: the cells
        // (through their fast path or not) end with the sums of PixelSum::add_run.
        let runs: Vec<Vec<f32>> = vec![
            vec![1.0, 2.0, 0.001],
            vec![0.25; 300],
            vec![3.0e9, 1.0],
            vec![f32::NAN, 4.0],
            vec![1e30],
            vec![7.5e5; 5],
            vec![],
        ];
        let mut film = FilmPixels::from_cells(vec![BaseCell::default(); 3]);
        let mut wide = [PixelSum::default(); 3];
        let mut rejected = [0u32; 3];
        for (r, run) in runs.iter().enumerate() {
            let samples: Vec<Sample> = run
                .iter()
                .map(|&v| Sample {
                    rgb: Vec3::new(v, 0.5 * v, 0.25 * v),
                    illuminance_lx: 2.0 * v,
                    rays: 1,
                    missed: false,
                })
                .collect();
            film.par_bands(1, 3, 1, |k, band| {
                if (k + r) % 2 == 0 {
                    band.add_run(0, &samples);
                }
            });
            for (k, w) in wide.iter_mut().enumerate() {
                if (k + r) % 2 == 0 {
                    rejected[k] += w.add_run(&samples);
                }
            }
            for (k, w) in wide.iter().enumerate() {
                assert_eq!(film.get(k), *w, "after run {r}: pixel {k}");
            }
        }
        assert!(film.moved_pixels().0 > 0);
        assert_eq!(film.rejected(), u64::from(rejected.iter().sum::<u32>()));
    }
}
