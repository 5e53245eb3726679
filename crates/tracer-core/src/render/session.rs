//! A progressive render session: one coordinator thread refines the current snapshot pass by
//! pass on its own rayon pool; starting a new snapshot cancels the old work at once.
//!
//! Workers check the generation between tiles and between rows inside a tile, so a restart never
//! waits for more than a row. Each generation has its own film; results of a stale generation
//! are dropped. The consumer is woken through a callback after every finished tile and reads what
//! changed with [`RenderSession::take_dirty`] and the pixels with [`RenderSession::with_film`].

use super::RenderSettings;
use super::film::PixelSum;
use super::passes::Pass;
use super::pixel::FrameSampler;
use super::progressive_film::ProgressiveFilm;
use super::tiles::{Tile, tiles_centre_out};
use crate::scene::{Scene, Setup};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// Everything one render generation needs; immutable once started.
#[derive(Clone, Debug)]
pub struct Snapshot {
    pub scene: Arc<Scene>,
    pub setup: Setup,
    /// Size, depth and the target number of samples per pixel.
    pub settings: RenderSettings,
    /// Stop after this long even when the sample target is not reached.
    pub time_limit: Option<Duration>,
}

/// Progress of the current generation.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SessionStats {
    pub generation: u64,
    /// Full-resolution samples every pixel has.
    pub samples_per_pixel: u32,
    pub target_spp: u32,
    /// The pass running (or last run), e.g. "preview 8x8" or "sample 3".
    pub pass: String,
    /// Passes finished, previews included.
    pub passes_done: u32,
    pub rays: u64,
    pub elapsed_secs: f64,
    /// Time from the start of the generation to its first complete coarse preview.
    pub first_preview_secs: Option<f64>,
    /// Time from the start of the generation until every pixel had one full sample.
    pub first_full_secs: Option<f64>,
    pub finished: bool,
    pub paused: bool,
    pub threads: usize,
    /// Remaining noise after the last full pass: RMS standard error of the pixels' luminance
    /// over the mean luminance (None before two samples per pixel).
    pub relative_noise: Option<f64>,
}

impl SessionStats {
    pub fn mrays_per_sec(&self) -> f64 {
        if self.elapsed_secs > 0.0 {
            self.rays as f64 / self.elapsed_secs / 1e6
        } else {
            0.0
        }
    }
}

/// Least time between whole-frame refreshes for splats (bidirectional mode), seconds.
const SPLAT_REFRESH_SECS: f64 = 0.5;

/// Callback that wakes the consumer (for a viewer: `request_repaint`).
pub type Notify = Arc<dyn Fn() + Send + Sync>;

struct State {
    job: Option<(u64, Arc<Snapshot>)>,
    /// The film shown: the newest generation with a complete first preview.
    film: Option<ProgressiveFilm>,
    /// The newest generation's film before its first preview is complete.
    pending: Option<ProgressiveFilm>,
    /// A film no longer shown, kept for reuse so restarts do not allocate.
    spare: Option<ProgressiveFilm>,
    dirty: Vec<Tile>,
    /// When the whole frame was last marked changed for splats.
    last_full_refresh: Option<std::time::Instant>,
    stats: SessionStats,
    paused: bool,
    shutdown: bool,
    threads: usize,
}

struct Shared {
    state: Mutex<State>,
    wake: Condvar,
    /// The newest generation handed out; workers compare against it to cancel.
    generation: AtomicU64,
    paused: AtomicBool,
    notify: Notify,
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, State> {
        // A worker that panicked while holding the lock leaves plain data behind; keep going.
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn is_current(&self, generation: u64) -> bool {
        self.generation.load(Ordering::Acquire) == generation
    }
}

/// The render engine behind the viewer.
pub struct RenderSession {
    shared: Arc<Shared>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl std::fmt::Debug for RenderSession {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RenderSession")
            .field("generation", &self.generation())
            .finish_non_exhaustive()
    }
}

impl RenderSession {
    /// Starts the coordinator thread with a pool of `threads` workers (0: all cores).
    pub fn new(threads: usize, notify: Notify) -> std::io::Result<Self> {
        let threads = if threads == 0 {
            std::thread::available_parallelism().map_or(1, |n| n.get())
        } else {
            threads
        };
        let shared = Arc::new(Shared {
            state: Mutex::new(State {
                job: None,
                film: None,
                pending: None,
                spare: None,
                dirty: Vec::new(),
                last_full_refresh: None,
                stats: SessionStats {
                    threads,
                    ..SessionStats::default()
                },
                paused: false,
                shutdown: false,
                threads,
            }),
            wake: Condvar::new(),
            generation: AtomicU64::new(0),
            paused: AtomicBool::new(false),
            notify,
        });
        let worker = Arc::clone(&shared);
        let thread = std::thread::Builder::new()
            .name("raygine-render".to_owned())
            .spawn(move || coordinator(&worker))?;
        Ok(Self {
            shared,
            thread: Some(thread),
        })
    }

    /// Renders `snapshot` from scratch as a new generation, cancelling the current one. The
    /// previous film stays readable until the new generation's first preview lands.
    pub fn start(&self, snapshot: Snapshot) -> u64 {
        let mut st = self.shared.lock();
        let generation = self.shared.generation.fetch_add(1, Ordering::AcqRel) + 1;
        st.job = Some((generation, Arc::new(snapshot)));
        drop(st);
        self.shared.wake.notify_all();
        generation
    }

    /// The newest generation started (0 before the first).
    pub fn generation(&self) -> u64 {
        self.shared.generation.load(Ordering::Acquire)
    }

    /// Pauses or resumes the refinement (the current film stays).
    pub fn set_paused(&self, paused: bool) {
        let mut st = self.shared.lock();
        st.paused = paused;
        st.stats.paused = paused;
        self.shared.paused.store(paused, Ordering::Release);
        drop(st);
        self.shared.wake.notify_all();
    }

    /// Sets the number of worker threads; takes effect from the next generation.
    pub fn set_threads(&self, threads: usize) {
        let mut st = self.shared.lock();
        st.threads = threads.max(1);
    }

    pub fn stats(&self) -> SessionStats {
        self.shared.lock().stats.clone()
    }

    /// Rectangles changed since the last call (all of the current film's generation).
    pub fn take_dirty(&self) -> Vec<Tile> {
        std::mem::take(&mut self.shared.lock().dirty)
    }

    /// Reads the film under the session's lock (keep `f` short: workers wait for it).
    pub fn with_film<R>(&self, f: impl FnOnce(Option<&ProgressiveFilm>) -> R) -> R {
        let st = self.shared.lock();
        f(st.film.as_ref())
    }

    /// Blocks until `pred(stats)` holds or `timeout` passes; returns whether it held.
    pub fn wait_for(&self, timeout: Duration, pred: impl Fn(&SessionStats) -> bool) -> bool {
        let deadline = Instant::now() + timeout;
        let mut st = self.shared.lock();
        loop {
            if pred(&st.stats) {
                return true;
            }
            let now = Instant::now();
            if now >= deadline {
                return false;
            }
            st = match self.shared.wake.wait_timeout(st, deadline - now) {
                Ok((g, _)) => g,
                Err(e) => e.into_inner().0,
            };
        }
    }
}

impl Drop for RenderSession {
    fn drop(&mut self) {
        self.shared.lock().shutdown = true;
        self.shared.generation.fetch_add(1, Ordering::AcqRel);
        self.shared.wake.notify_all();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// The coordinator: waits for a job, runs its passes, repeats.
fn coordinator(shared: &Shared) {
    let mut pool: Option<(usize, rayon::ThreadPool)> = None;
    let mut done_generation = 0u64;
    loop {
        let (generation, snapshot, threads) = {
            let mut st = shared.lock();
            loop {
                if st.shutdown {
                    return;
                }
                match &st.job {
                    Some((g, s)) if *g != done_generation && !st.paused => {
                        break (*g, Arc::clone(s), st.threads);
                    }
                    _ => {}
                }
                st = match shared.wake.wait(st) {
                    Ok(g) => g,
                    Err(e) => e.into_inner(),
                };
            }
        };
        if pool.as_ref().is_none_or(|(n, _)| *n != threads) {
            let built = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .thread_name(|i| format!("raygine-worker-{i}"))
                .start_handler(|_| lower_thread_priority())
                .build();
            match built {
                Ok(p) => pool = Some((threads, p)),
                Err(_) if pool.is_some() => {}
                Err(_) => return,
            }
        }
        let Some((_, p)) = pool.as_ref() else { return };
        run_generation(shared, p, generation, &snapshot, threads);
        done_generation = generation;
    }
}

/// How much render workers lower their priority (Linux nice increment), unless the
/// environment variable `RAYGINE_WORKER_NICE` (0..=19) says otherwise.
pub const DEFAULT_WORKER_NICE: i32 = 10;

/// Render workers yield the CPU to the interactive thread (the viewer's UI, the desktop's
/// software OpenGL): on Linux each thread has its own nice value.
fn lower_thread_priority() {
    #[cfg(target_os = "linux")]
    {
        let increment = std::env::var("RAYGINE_WORKER_NICE")
            .ok()
            .and_then(|v| v.trim().parse::<i32>().ok())
            .map_or(DEFAULT_WORKER_NICE, |n| n.clamp(0, 19));
        if increment > 0 {
            // SAFETY: `nice` takes a plain integer and only changes the calling thread's
            // scheduling priority; it touches no memory of ours. A failure (-1 with errno) leaves
            // the priority as it was, which is harmless, so the result is deliberately ignored.
            unsafe {
                libc::nice(increment);
            }
        }
    }
}

/// Runs every pass of one generation unless a newer one arrives.
fn run_generation(
    shared: &Shared,
    pool: &rayon::ThreadPool,
    generation: u64,
    snap: &Snapshot,
    threads: usize,
) {
    let started = Instant::now();
    let s = &snap.settings;
    let target = s.samples_per_pixel.max(1);
    {
        let mut st = shared.lock();
        st.stats = SessionStats {
            generation,
            target_spp: target,
            threads,
            paused: st.paused,
            ..SessionStats::default()
        };
    }
    if !prepare_film(shared, generation, s) {
        return;
    }
    let frame = FrameSampler::new(&snap.scene, &snap.setup, s);
    let rays = AtomicU64::new(0);
    let mut pass = Some(Pass::first());
    while let Some(current) = pass {
        if !shared.is_current(generation) {
            return;
        }
        if snap.time_limit.is_some_and(|limit| {
            started.elapsed() >= limit && matches!(current, Pass::Full { index } if index > 0)
        }) {
            break;
        }
        shared.lock().stats.pass = current.label();
        let tiles = tiles_centre_out(s.width, s.height, current.tile_size());
        let ctx = PassContext {
            shared,
            generation,
            frame: &frame,
            pass: current,
            rays: &rays,
        };
        pool.install(|| tiles.par_iter().for_each(|tile| ctx.run_tile(tile)));
        if !shared.is_current(generation) {
            return;
        }
        let mut st = shared.lock();
        let elapsed = started.elapsed().as_secs_f64();
        st.stats.passes_done += 1;
        st.stats.rays = rays.load(Ordering::Relaxed);
        st.stats.elapsed_secs = elapsed;
        match current {
            Pass::Preview { .. } if st.stats.first_preview_secs.is_none() => {
                st.stats.first_preview_secs = Some(elapsed);
                // The first complete preview replaces the previous generation's picture.
                if let Some(film) = st.pending.take() {
                    st.spare = st.film.replace(film);
                    st.dirty = vec![full_frame(s)];
                }
            }
            Pass::Full { index } => {
                st.stats.samples_per_pixel = index + 1;
                if s.integrator == crate::integrator::IntegratorKind::Bidirectional {
                    // The pass's last splats landed all over the picture.
                    st.dirty.push(full_frame(s));
                }
                if index > 0 {
                    st.stats.relative_noise = st
                        .film
                        .as_ref()
                        .filter(|f| f.generation == generation)
                        .and_then(|f| f.accum.relative_noise());
                }
                if index == 0 {
                    st.stats.first_full_secs = Some(elapsed);
                }
            }
            Pass::Preview { .. } => {}
        }
        drop(st);
        shared.wake.notify_all();
        (shared.notify)();
        pass = current.next(target);
    }
    let mut st = shared.lock();
    if shared.is_current(generation) {
        st.stats.finished = true;
        st.stats.rays = rays.load(Ordering::Relaxed);
        st.stats.elapsed_secs = started.elapsed().as_secs_f64();
    }
    drop(st);
    shared.wake.notify_all();
    (shared.notify)();
}

/// Readies this generation's film as `pending`, reusing a spare film of the same size. The
/// allocation or clearing happens outside the lock, so `start` and readers never wait for it.
/// Returns false when the generation went stale meanwhile.
fn prepare_film(shared: &Shared, generation: u64, s: &RenderSettings) -> bool {
    let recycled = {
        let mut st = shared.lock();
        st.spare.take().or_else(|| st.pending.take())
    };
    let film = match recycled {
        Some(mut f) if f.width() == s.width && f.height() == s.height => {
            f.reset(generation);
            f
        }
        _ => ProgressiveFilm::new(generation, s.width, s.height),
    };
    let mut st = shared.lock();
    if !shared.is_current(generation) {
        st.spare = Some(film);
        return false;
    }
    st.pending = Some(film);
    true
}

fn full_frame(s: &RenderSettings) -> Tile {
    Tile {
        x0: 0,
        y0: 0,
        x1: s.width,
        y1: s.height,
    }
}

struct PassContext<'a> {
    shared: &'a Shared,
    generation: u64,
    frame: &'a FrameSampler<'a>,
    pass: Pass,
    rays: &'a AtomicU64,
}

impl PassContext<'_> {
    /// Waits while paused; returns false when this generation is stale.
    fn keep_going(&self) -> bool {
        if self.shared.paused.load(Ordering::Acquire) {
            let mut st = self.shared.lock();
            while st.paused && !st.shutdown && self.shared.is_current(self.generation) {
                st = match self.shared.wake.wait(st) {
                    Ok(g) => g,
                    Err(e) => e.into_inner(),
                };
            }
        }
        self.shared.is_current(self.generation)
    }

    fn run_tile(&self, tile: &Tile) {
        if !self.keep_going() {
            return;
        }
        match self.pass {
            Pass::Preview { block } => self.preview_tile(tile, block),
            Pass::Full { index } => self.full_tile(tile, index),
        }
    }

    fn preview_tile(&self, tile: &Tile, block: u32) {
        let mut blocks = Vec::new();
        let mut rays = 0u64;
        for by in (tile.y0..tile.y1).step_by(block as usize) {
            if !self.shared.is_current(self.generation) {
                return;
            }
            for bx in (tile.x0..tile.x1).step_by(block as usize) {
                let rect = Tile {
                    x0: bx,
                    y0: by,
                    x1: (bx + block).min(tile.x1),
                    y1: (by + block).min(tile.y1),
                };
                let cx = (rect.x0 + rect.x1) as f32 * 0.5;
                let cy = (rect.y0 + rect.y1) as f32 * 0.5;
                let sample = self.frame.preview(cx, cy);
                rays += u64::from(sample.rays);
                blocks.push((rect, sample));
            }
        }
        self.rays.fetch_add(rays, Ordering::Relaxed);
        self.commit(tile, |film| {
            for (rect, s) in &blocks {
                film.fill_preview(rect, s);
            }
        });
    }

    fn full_tile(&self, tile: &Tile, index: u32) {
        let mut sums = Vec::with_capacity(tile.pixel_count());
        let mut missed = Vec::with_capacity(tile.pixel_count());
        let mut splats = Vec::new();
        let mut rays = 0u64;
        for y in tile.y0..tile.y1 {
            if !self.shared.is_current(self.generation) {
                return;
            }
            for x in tile.x0..tile.x1 {
                let sample = self.frame.sample(x, y, index, &mut splats);
                rays += u64::from(sample.rays);
                let mut sum = PixelSum::default();
                sum.add(&sample);
                sums.push(sum);
                missed.push(sample.missed);
            }
        }
        self.rays.fetch_add(rays, Ordering::Relaxed);
        self.commit(tile, |film| {
            film.add_tile(tile, &sums);
            film.add_misses(tile, &missed);
            film.add_splats(&splats);
        });
        if !splats.is_empty() {
            self.refresh_everywhere_now_and_then();
        }
    }

    /// Light subpaths land anywhere in the picture: mark the whole frame changed, at most every
    /// [`SPLAT_REFRESH_SECS`] (and at the end of every pass), so the display keeps up without
    /// remapping the whole picture for every tile.
    fn refresh_everywhere_now_and_then(&self) {
        let mut st = self.shared.lock();
        let due = st
            .last_full_refresh
            .is_none_or(|t| t.elapsed().as_secs_f64() >= SPLAT_REFRESH_SECS);
        let shown = st
            .film
            .as_ref()
            .is_some_and(|f| f.generation == self.generation);
        if due && shown && self.shared.is_current(self.generation) {
            st.last_full_refresh = Some(std::time::Instant::now());
            let (w, h) = (self.frame.basis.width, self.frame.basis.height);
            st.dirty.push(Tile {
                x0: 0,
                y0: 0,
                x1: w,
                y1: h,
            });
            drop(st);
            (self.shared.notify)();
        }
    }

    /// Applies a finished tile to this generation's film unless the generation is stale. Until
    /// the first preview pass is complete the new film is kept aside (the consumer keeps showing
    /// the previous picture); after that, the tile is marked dirty and the consumer woken.
    fn commit(&self, tile: &Tile, apply: impl FnOnce(&mut ProgressiveFilm)) {
        let mut st = self.shared.lock();
        // Checked under the lock: `start` bumps the generation under the same lock, so a stale
        // tile can never land in a newer film.
        if !self.shared.is_current(self.generation) {
            return;
        }
        let shown = st
            .film
            .as_ref()
            .is_some_and(|f| f.generation == self.generation);
        if shown {
            if let Some(film) = st.film.as_mut() {
                apply(film);
            }
            st.dirty.push(*tile);
            drop(st);
            (self.shared.notify)();
            return;
        }
        // Before the first preview is complete the tile goes to the pending film, prepared
        // (allocated) by the coordinator outside the lock.
        if let Some(film) = st
            .pending
            .as_mut()
            .filter(|f| f.generation == self.generation)
        {
            apply(film);
        }
    }
}
