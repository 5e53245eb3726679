//! What the session's threads share: the job, the films and the statistics under one lock, the
//! generation counter workers compare against, and the double-buffered films (the one shown,
//! the next generation's until its first preview is complete, a spare for reuse).

use super::super::RenderSettings;
use super::super::progressive_film::ProgressiveFilm;
use super::super::tiles::Tile;
use super::{Notify, SessionStats, Snapshot};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};

pub(super) struct State {
    pub job: Option<(u64, Arc<Snapshot>)>,
    /// The film shown: the newest generation with a complete first preview.
    pub film: Option<ProgressiveFilm>,
    /// The newest generation's film before its first preview is complete.
    pub pending: Option<ProgressiveFilm>,
    /// A film no longer shown, kept for reuse so restarts do not allocate.
    pub spare: Option<ProgressiveFilm>,
    pub dirty: Vec<Tile>,
    /// When the whole frame was last marked changed for splats.
    pub last_full_refresh: Option<std::time::Instant>,
    pub stats: SessionStats,
    pub paused: bool,
    pub shutdown: bool,
    pub threads: usize,
    /// The illuminance has been shown: measured from the next pass on, in this generation and
    /// every later one (`RenderSession::measure_illuminance`).
    pub illuminance_wanted: bool,
}

pub(super) struct Shared {
    pub state: Mutex<State>,
    pub wake: Condvar,
    /// The newest generation handed out; workers compare against it to cancel.
    pub generation: AtomicU64,
    pub paused: AtomicBool,
    pub notify: Notify,
}

impl Shared {
    pub fn lock(&self) -> MutexGuard<'_, State> {
        // A worker that panicked while holding the lock leaves plain data behind; keep going.
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    pub fn is_current(&self, generation: u64) -> bool {
        self.generation.load(Ordering::Acquire) == generation
    }
}

/// Readies this generation's film as `pending`, reusing a spare film of the same size. The
/// allocation or clearing happens outside the lock (clearing on `pool`), so `start` and readers
/// never wait for it. Returns false when the generation went stale meanwhile.
pub(super) fn prepare_film(
    shared: &Shared,
    pool: &rayon::ThreadPool,
    generation: u64,
    s: &RenderSettings,
) -> bool {
    let recycled = {
        let mut st = shared.lock();
        st.spare.take().or_else(|| st.pending.take())
    };
    let film = match recycled {
        Some(mut f) if f.width() == s.width && f.height() == s.height => {
            pool.install(|| f.reset(generation));
            f.set_guides(s.guides);
            f
        }
        _ => {
            let mut f = ProgressiveFilm::new(generation, s.width, s.height);
            f.set_guides(s.guides);
            f
        }
    };
    let mut st = shared.lock();
    if !shared.is_current(generation) {
        st.spare = Some(film);
        return false;
    }
    st.pending = Some(film);
    true
}

/// Makes `generation`'s film hold its illuminance from sample `from` on, as its sampler does.
pub(super) fn set_film_illuminance(shared: &Shared, generation: u64, from: u32) {
    let mut st = shared.lock();
    let st = &mut *st;
    for film in [st.pending.as_mut(), st.film.as_mut()]
        .into_iter()
        .flatten()
    {
        if film.generation == generation {
            film.accum.illuminance_from = from;
        }
    }
}

pub(super) fn full_frame(s: &RenderSettings) -> Tile {
    Tile {
        x0: 0,
        y0: 0,
        x1: s.width,
        y1: s.height,
    }
}
