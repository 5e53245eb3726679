//! The coordinator thread: waits for a job, then runs one generation's passes (previews, then
//! full samples) over the tiles on its rayon pool until the target, the time limit or a newer
//! generation.

use super::super::passes::Pass;
use super::super::pixel::{FrameSampler, NO_ILLUMINANCE};
use super::super::progressive_film::ProgressiveFilm;
use super::super::tiles::tiles_centre_out;
use super::priority::lower_thread_priority;
use super::shared::{Shared, full_frame, prepare_film, set_film_illuminance};
use super::tile_work::{FIRST_PASS_PHASES, PassContext, Phase, Progress, Round};
use super::{ILLUMINANCE_SAMPLES, SessionStats, Snapshot};
use crate::render::adaptive::{self, MIN_SAMPLES};
use rayon::prelude::*;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// Where a generation's passes start.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Start {
    /// From the first preview, on a fresh film.
    Fresh,
    /// At full sample `index` of a generation that finished without measuring the
    /// illuminance, now asked for: [`ILLUMINANCE_SAMPLES`] more samples, with it.
    Resume { index: u32 },
}

/// How a generation's run ended.
struct Outcome {
    /// All its passes ran (else a newer generation or the shutdown cut it short).
    finished: bool,
    /// Full samples per pixel done.
    samples: u32,
    /// Whether it measured the illuminance.
    illuminance: bool,
}

/// The coordinator: waits for a job, runs its passes, repeats.
pub(super) fn coordinator(shared: &Shared) {
    let mut pool: Option<(usize, rayon::ThreadPool)> = None;
    let mut done_generation = 0u64;
    // The last generation, when it finished without the illuminance: (its snapshot, samples).
    let mut unmeasured: Option<(Arc<Snapshot>, u32)> = None;
    loop {
        let (generation, snapshot, threads, start) = {
            let mut st = shared.lock();
            loop {
                if st.shutdown {
                    return;
                }
                match &st.job {
                    Some((g, s)) if *g != done_generation && !st.paused => {
                        break (*g, Arc::clone(s), st.threads, Start::Fresh);
                    }
                    _ => {}
                }
                if let Some((snap, samples)) = &unmeasured
                    && st.illuminance_wanted
                    && !st.paused
                    && shared.is_current(done_generation)
                {
                    let resume = Start::Resume { index: *samples };
                    break (done_generation, Arc::clone(snap), st.threads, resume);
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
        let outcome = run_generation(shared, p, generation, &snapshot, threads, start);
        done_generation = generation;
        unmeasured = (outcome.finished && !outcome.illuminance)
            .then(|| (Arc::clone(&snapshot), outcome.samples));
    }
}

/// Runs every pass of one generation unless a newer one arrives.
fn run_generation(
    shared: &Shared,
    pool: &rayon::ThreadPool,
    generation: u64,
    snap: &Snapshot,
    threads: usize,
    start: Start,
) -> Outcome {
    let mut started = Instant::now();
    let s = &snap.settings;
    // A resumed film whose adaptive rounds left pixels with different counts: one round of
    // ILLUMINANCE_SAMPLES more in every pixel, from each pixel's own count.
    let mut forced: Option<Round> = None;
    let (target, first_pass, rays_before) = match start {
        Start::Fresh => (s.samples_per_pixel.max(1), Pass::first(), 0),
        Start::Resume { index } => {
            // The generation's clock and ray count go on from where it finished.
            let st = shared.lock();
            let so_far = Duration::from_secs_f64(st.stats.elapsed_secs.max(0.0));
            started = started.checked_sub(so_far).unwrap_or(started);
            forced = st
                .film
                .as_ref()
                .filter(|f| f.generation == generation && f.accum.splat_paths.is_some())
                .map(|f| Round {
                    from: f.accum.counts().collect(),
                    extra: vec![ILLUMINANCE_SAMPLES; f.accum.len()],
                });
            let first = if forced.is_some() {
                Pass::Adaptive { round: 0 }
            } else {
                Pass::Full { index }
            };
            (index + ILLUMINANCE_SAMPLES, first, st.stats.rays)
        }
    };
    let resumed_round = forced.is_some();
    let mut outcome = Outcome {
        finished: false,
        samples: 0,
        illuminance: false,
    };
    {
        let mut st = shared.lock();
        match start {
            Start::Fresh => {
                st.stats = SessionStats {
                    generation,
                    target_spp: target,
                    threads,
                    paused: st.paused,
                    ..SessionStats::default()
                };
            }
            Start::Resume { .. } => {
                st.stats.target_spp = target;
                st.stats.finished = false;
            }
        }
    }
    if start == Start::Fresh && !prepare_film(shared, pool, generation, s) {
        return outcome;
    }
    let frame = FrameSampler::new(&snap.scene, &snap.setup, s);
    let rays = AtomicU64::new(rays_before);
    let pixels_done = AtomicU64::new(0);
    let mut full_started = None;
    let mut pass = Some(first_pass);
    while let Some(current) = pass {
        if !shared.is_current(generation) {
            return outcome;
        }
        // The illuminance, once asked for, from this pass on: no sample of it is traced yet.
        if frame.illuminance_from() == NO_ILLUMINANCE && shared.lock().illuminance_wanted {
            match current {
                Pass::Preview { .. } => frame.set_illuminance_from(0),
                Pass::Full { index } => frame.set_illuminance_from(index),
                Pass::Adaptive { .. } => {
                    // Counts differ: every pixel from its next sample on, and a round that
                    // gives every pixel some (the rounds by error may pass a pixel by).
                    frame.set_illuminance_from(0);
                    with_film(shared, generation, |f| {
                        f.measure_illuminance_from_now();
                        let from: Vec<u32> = f.accum.counts().collect();
                        let extra = vec![ILLUMINANCE_ROUND; from.len()];
                        forced.get_or_insert(Round { from, extra });
                    });
                }
            }
        }
        if !matches!(current, Pass::Adaptive { .. }) {
            set_film_illuminance(shared, generation, frame.illuminance_from());
        }
        if snap.time_limit.is_some_and(|limit| {
            started.elapsed() >= limit
                && matches!(current, Pass::Full { index } if index > 0)
                    | matches!(current, Pass::Adaptive { .. })
        }) {
            break;
        }
        let round = match current {
            Pass::Adaptive { .. } => match forced.take() {
                Some(r) => Some(r),
                None => match plan_round(shared, generation, target) {
                    Some(r) => Some(r),
                    None => break,
                },
            },
            _ => None,
        };
        {
            let mut st = shared.lock();
            st.stats.pass = current.label();
            st.stats.pass_fraction = 0.0;
        }
        if matches!(current, Pass::Full { index: 0 }) {
            full_started = Some(Instant::now());
        }
        pixels_done.store(0, Ordering::Relaxed);
        let tiles = tiles_centre_out(s.width, s.height, current.tile_size());
        // The first full pass goes over the frame in four interleaved quarters, so it fills the
        // frame evenly (no tiles of finished samples beside tiles of preview), shown upscaled
        // from the first quarter until the rest arrives.
        let phases: &[Option<Phase>] = match current {
            Pass::Full { index: 0 } => &FIRST_PASS_PHASES,
            _ => &[None],
        };
        for &phase in phases {
            let ctx = PassContext {
                shared,
                generation,
                frame: &frame,
                pass: current,
                phase,
                rays: &rays,
                progress: Progress {
                    started,
                    full_started,
                    pixels_done: &pixels_done,
                    pass_pixels: u64::from(s.width) * u64::from(s.height),
                },
                round: round.as_ref(),
            };
            pool.install(|| tiles.par_iter().for_each(|tile| ctx.run_tile(tile)));
            if !shared.is_current(generation) {
                return outcome;
            }
        }
        let mut st = shared.lock();
        let elapsed = started.elapsed().as_secs_f64();
        st.stats.passes_done += 1;
        st.stats.rays = rays.load(Ordering::Relaxed);
        st.stats.elapsed_secs = elapsed;
        st.stats.pass_fraction = 1.0;
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
                outcome.samples = index + 1;
                st.stats.samples_per_pixel = index + 1;
                st.stats.pass_fraction = 0.0;
                if let Some(t) = full_started {
                    st.stats.secs_per_sample =
                        Some(t.elapsed().as_secs_f64() / f64::from(index + 1));
                }
                if s.integrator.splats() {
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
            Pass::Adaptive { .. } => {
                let st = &mut *st;
                let generation_film = st.film.as_mut().filter(|f| f.generation == generation);
                if let Some(f) = generation_film {
                    f.accum.count_splat_paths();
                    let n = f.accum.len().max(1) as f64;
                    st.stats.samples_per_pixel = f.accum.min_samples();
                    st.stats.mean_samples_per_pixel = f.samples_added() as f64 / n;
                    st.stats.relative_noise = f.accum.relative_noise();
                    outcome.samples = st.stats.samples_per_pixel;
                }
                st.stats.pass_fraction = 0.0;
                if let Some(t) = full_started {
                    let done = st.stats.mean_samples_per_pixel.max(1.0);
                    st.stats.secs_per_sample = Some(t.elapsed().as_secs_f64() / done);
                }
                if s.integrator.splats() {
                    st.dirty.push(full_frame(s));
                }
            }
            Pass::Preview { .. } => {}
        }
        if let Pass::Full { index } = current {
            st.stats.mean_samples_per_pixel = f64::from(index + 1);
        }
        drop(st);
        shared.wake.notify_all();
        (shared.notify)();
        pass = match current {
            // After the uniform samples, the rest of the target goes by error.
            Pass::Full { index }
                if snap.adaptive && index + 1 >= MIN_SAMPLES && index + 1 < target =>
            {
                Some(Pass::Adaptive { round: 0 })
            }
            Pass::Adaptive { .. } if resumed_round => None,
            _ => current.next(target),
        };
    }
    let mut st = shared.lock();
    if shared.is_current(generation) {
        st.stats.finished = true;
        st.stats.rays = rays.load(Ordering::Relaxed);
        st.stats.elapsed_secs = started.elapsed().as_secs_f64();
        outcome.finished = true;
        outcome.illuminance = frame.illuminance_from() != NO_ILLUMINANCE;
    }
    drop(st);
    shared.wake.notify_all();
    (shared.notify)();
    outcome
}

/// Runs `f` on `generation`'s film (shown or pending) under the lock.
fn with_film(shared: &Shared, generation: u64, f: impl FnOnce(&mut ProgressiveFilm)) {
    let mut st = shared.lock();
    let st = &mut *st;
    let film = [st.film.as_mut(), st.pending.as_mut()]
        .into_iter()
        .flatten()
        .find(|film| film.generation == generation);
    if let Some(film) = film {
        f(film);
    }
}

/// Samples every pixel gets when the illuminance is asked for during adaptive rounds.
const ILLUMINANCE_ROUND: u32 = 4;

/// Cap of any pixel's count under adaptive sampling in the viewer.
const ROUND_CAP: u32 = 65_536;

/// The next adaptive round of `generation`: its share of the samples left to the target
/// (target × pixels in all), at least one per pixel on average and an eighth of those done,
/// given where the error is highest. None when the target is reached or no pixel gets one.
fn plan_round(shared: &Shared, generation: u64, target: u32) -> Option<Round> {
    let st = shared.lock();
    let film = st.film.as_ref().filter(|f| f.generation == generation)?;
    let pixels = film.accum.len() as u64;
    let done = film.samples_added();
    let left = (u64::from(target) * pixels).checked_sub(done)?;
    let budget = left.min(pixels.max(done / 8));
    if budget == 0 {
        return None;
    }
    let extra = adaptive::allocate(
        &film.accum,
        adaptive::Scale::Picture,
        budget,
        None,
        ROUND_CAP,
    );
    if extra.iter().all(|&m| m == 0) {
        return None;
    }
    let from = film.accum.counts().collect();
    Some(Round { from, extra })
}
