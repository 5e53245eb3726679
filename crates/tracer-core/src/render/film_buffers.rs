//! The pixel buffer of the last large film dropped, kept for the next film.
//!
//! A 1280x720 film's cells are 44 MB (48 bytes a pixel). Fresh memory of that size comes from the
//! system a page at a time: on the machines raygine is benchmarked on, faulting it in cost about
//! 90 ms per frame, serially, before the first ray (against about 10 ms to zero a recycled
//! buffer). Renders that make film after film (`render_for`'s passes, benchmark frames, sweeps,
//! shards) reuse one buffer instead. At most one buffer is kept, so memory held between renders
//! is at most the largest film's.

use rayon::prelude::*;
use std::sync::{Mutex, PoisonError};

use super::film_cells::BaseCell as PixelSum;

/// Films with fewer pixels (tiles, thumbnails) allocate as usual: their memory is cheap, and
/// many of them are made and dropped at once on several threads.
pub const MIN_RECYCLED_PIXELS: usize = 1 << 16;

static SPARE: Mutex<Vec<PixelSum>> = Mutex::new(Vec::new());

/// `len` empty pixel sums, in the kept buffer when it is large enough.
pub(super) fn take(len: usize) -> Vec<PixelSum> {
    if len >= MIN_RECYCLED_PIXELS {
        let mut spare = SPARE.lock().unwrap_or_else(PoisonError::into_inner);
        if spare.capacity() >= len {
            let mut pixels = std::mem::take(&mut *spare);
            drop(spare);
            // Zeroed on every thread of the pool (the buffer is usually the same size).
            pixels.truncate(len);
            pixels.par_iter_mut().for_each(|p| *p = PixelSum::default());
            pixels.resize(len, PixelSum::default());
            return pixels;
        }
    }
    fresh(len)
}

/// `len` empty pixel sums in new memory: for a large film, zeroed pages straight from the
/// system (on huge pages where it has them), so nothing writes them before the render does,
/// and their page faults are taken by the threads that render into them, side by side.
fn fresh(len: usize) -> Vec<PixelSum> {
    if len < MIN_RECYCLED_PIXELS {
        return vec![PixelSum::default(); len];
    }
    crate::pages::zeroed_vec_on_huge_pages(len)
}

/// Keeps the buffer of a dropped film when it is large, in place of the one kept before.
pub(super) fn give(pixels: Vec<PixelSum>) {
    if pixels.capacity() >= MIN_RECYCLED_PIXELS {
        let old = {
            let mut spare = SPARE.lock().unwrap_or_else(PoisonError::into_inner);
            std::mem::replace(&mut *spare, pixels)
        };
        // Freed outside the lock.
        drop(old);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fresh_large_buffers_are_empty() {
        // Past the huge-page threshold (32 MiB), from zeroed system memory.
        let len = (40 << 20) / size_of::<PixelSum>();
        let pixels = fresh(len);
        assert_eq!(pixels.len(), len);
        assert!(pixels.iter().all(|p| *p == PixelSum::default()));
    }

    #[test]
    fn recycled_buffers_come_back_empty() {
        let len = MIN_RECYCLED_PIXELS + 3;
        let mut pixels = take(len);
        assert_eq!(pixels.len(), len);
        for p in &mut pixels {
            *p = PixelSum::dirty();
        }
        give(pixels);
        // Smaller, from the same buffer (or a fresh one if another test took it meanwhile):
        // empty either way.
        let again = take(len - 2);
        assert_eq!(again.len(), len - 2);
        assert!(again.iter().all(|p| *p == PixelSum::default()));
        give(again);
        let small = take(10);
        assert_eq!(small, vec![PixelSum::default(); 10]);
    }
}
