//! A progressive render session: one coordinator thread refines the current snapshot pass by
//! pass on its own rayon pool; starting a new snapshot cancels the old work at once.
//!
//! Workers check the generation between tiles and between rows inside a tile, so a restart never
//! waits for more than a row. Each generation has its own film; results of a stale generation
//! are dropped. The consumer is woken through a callback after every finished tile and reads what
//! changed with [`RenderSession::take_dirty`] and the pixels with [`RenderSession::with_film`].

//!
//! Layout: this file is the API ([`RenderSession`] and what it reports); `shared.rs` the state
//! the threads share and the double-buffered films; `coordinator.rs` the thread that runs one
//! generation's passes; `tile_work.rs` what a worker does with one tile; `priority.rs` the
//! workers' lower CPU priority.

mod coordinator;
mod priority;
mod shared;
mod tile_work;

use super::RenderSettings;
use super::progressive_film::ProgressiveFilm;
use super::tiles::Tile;
use crate::scene::{Scene, Setup};
use shared::{Shared, State};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

/// Samples a generation that finished without the illuminance renders once it is asked for.
pub const ILLUMINANCE_SAMPLES: u32 = 16;

/// Everything one render generation needs; immutable once started.
#[derive(Clone, Debug)]
pub struct Snapshot {
    pub scene: Arc<Scene>,
    pub setup: Setup,
    /// Size, depth and the target number of samples per pixel.
    pub settings: RenderSettings,
    /// Stop after this long even when the sample target is not reached.
    pub time_limit: Option<Duration>,
    /// After [`super::adaptive::MIN_SAMPLES`] in every pixel, give the rest of the target's
    /// samples (target × pixels in all) where the error is highest, in rounds.
    pub adaptive: bool,
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
    /// Share (0..=1) of the running pass's pixels done, refreshed after every tile.
    pub pass_fraction: f64,
    /// Time per full sample per pixel so far (seconds), once a full pass has made progress.
    pub secs_per_sample: Option<f64>,
    pub finished: bool,
    pub paused: bool,
    pub threads: usize,
    /// Remaining noise after the last full pass: RMS standard error of the pixels' luminance
    /// over the mean luminance (None before two samples per pixel).
    pub relative_noise: Option<f64>,
    /// Samples per pixel on average (above `samples_per_pixel` once adaptive rounds run).
    pub mean_samples_per_pixel: f64,
}

impl SessionStats {
    /// Full samples per pixel done, with the running full pass's share: 2.4 is two samples
    /// everywhere and the third in 40 % of the pixels.
    pub fn samples_done(&self) -> f64 {
        let running = self.pass.starts_with("sample") && !self.finished;
        let done =
            f64::from(self.samples_per_pixel) + if running { self.pass_fraction } else { 0.0 };
        done.max(self.mean_samples_per_pixel)
    }

    /// Estimated seconds until the target: the samples left at the rate so far (None before a
    /// full pass has made progress, and once finished).
    pub fn eta_secs(&self) -> Option<f64> {
        if self.finished {
            return None;
        }
        let left = (f64::from(self.target_spp) - self.samples_done()).max(0.0);
        self.secs_per_sample.map(|s| s * left)
    }

    pub fn mrays_per_sec(&self) -> f64 {
        if self.elapsed_secs > 0.0 {
            self.rays as f64 / self.elapsed_secs / 1e6
        } else {
            0.0
        }
    }
}

/// Callback that wakes the consumer (for a viewer: `request_repaint`).
pub type Notify = Arc<dyn Fn() + Send + Sync>;

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
                illuminance_wanted: false,
            }),
            wake: Condvar::new(),
            generation: AtomicU64::new(0),
            paused: AtomicBool::new(false),
            notify,
        });
        let worker = Arc::clone(&shared);
        let thread = std::thread::Builder::new()
            .name("raygine-render".to_owned())
            .spawn(move || coordinator::coordinator(&worker))?;
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

    /// The pixels' illuminance is to be shown: measure it from the next pass on (never a
    /// restart), and from the start in later generations. A generation that had finished
    /// without it renders [`ILLUMINANCE_SAMPLES`] more samples, with it.
    pub fn measure_illuminance(&self) {
        let mut st = self.shared.lock();
        if st.illuminance_wanted {
            return;
        }
        st.illuminance_wanted = true;
        drop(st);
        self.shared.wake.notify_all();
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
