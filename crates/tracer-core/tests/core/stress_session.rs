//! A restart storm on the progressive engine: two threads call `start` thousands of times with
//! random changes (light, intensity, camera, materials, samples, size, threads, pause) while a
//! third reads the film like the viewer does; then the storm stops. The last generation's film
//! must equal a one-shot render of its snapshot bit for bit, nothing may deadlock (every wait is
//! bounded) or panic, and the resident memory must stay flat.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::sync::{Arc, Mutex};
use std::thread;
use std::time::{Duration, Instant};

use tracer_core::render::{RenderSession, RenderSettings, Snapshot, render};
use tracer_core::scene::{LoadedScene, Material, Scene, builtin_cornell_box};

/// Parameter changes in all, split between the two starting threads.
const CHANGES: usize = 3000;
/// The whole test, storm, final render and shutdown included.
const WHOLE_TEST: Duration = Duration::from_secs(90);
/// Allowed growth of the resident set from after the warm-up to after the storm.
const RSS_GROWTH_LIMIT_KB: u64 = 150 * 1024;

/// xorshift64*: deterministic per thread, no dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    /// Uniform in `lo..hi`.
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// VmRSS of this process in kB (0 where /proc is absent).
fn rss_kb() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("VmRSS:"))
                .and_then(|v| v.split_whitespace().next()?.parse().ok())
        })
        .unwrap_or(0)
}

fn base_snapshot(loaded: &LoadedScene, scene: &Arc<Scene>) -> Snapshot {
    Snapshot {
        scene: Arc::clone(scene),
        setup: loaded.setup.clone(),
        settings: RenderSettings {
            width: 48,
            height: 32,
            samples_per_pixel: 2,
            max_depth: 3,
            ..RenderSettings::default()
        },
        time_limit: None,
        adaptive: false,
    }
}

/// One random change of the kind a user makes by dragging sliders.
fn change(rng: &mut Rng, snap: &mut Snapshot) {
    let setup = &mut snap.setup;
    match rng.below(7) {
        0 => {
            setup.lights[0].position = [
                rng.range(20.0, 536.0),
                rng.range(20.0, 540.0),
                rng.range(-540.0, -20.0),
            ];
        }
        1 => {
            if let Some(cd) = setup.lights[0].intensity_cd_mut() {
                *cd = rng.range(0.0, 500.0);
            }
        }
        2 => {
            setup.camera.position = [
                rng.range(100.0, 450.0),
                rng.range(100.0, 450.0),
                rng.range(300.0, 1200.0),
            ];
            setup.camera.fov_deg = rng.range(20.0, 80.0);
        }
        3 => {
            let slot = rng.below(setup.materials.len() as u64) as usize;
            let kd = [
                rng.range(0.0, 0.9),
                rng.range(0.0, 0.9),
                rng.range(0.0, 0.9),
            ];
            let ks = kd.map(|k| (1.0 - k) * 0.5);
            setup.materials[slot] = Material {
                kd,
                ks,
                glossiness: rng.range(0.0, 50.0),
                ..Material::default()
            };
        }
        4 => snap.settings.samples_per_pixel = 1 + rng.below(4) as u32,
        5 => {
            snap.settings.width = 32 + 8 * rng.below(4) as u32;
            snap.settings.height = 24 + 8 * rng.below(3) as u32;
        }
        _ => snap.settings.max_depth = 1 + rng.below(5) as u32,
    }
}

/// Runs `f` on its own thread and fails the test if it does not return within `limit`.
fn bounded<T: Send + 'static>(limit: Duration, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = mpsc::channel();
    thread::Builder::new()
        .name("stress-body".into())
        .spawn(move || {
            let _ = tx.send(f());
        })
        .unwrap();
    match rx.recv_timeout(limit) {
        Ok(value) => value,
        Err(mpsc::RecvTimeoutError::Timeout) => panic!("deadlock or hang: no result in {limit:?}"),
        Err(mpsc::RecvTimeoutError::Disconnected) => panic!("the test body panicked"),
    }
}

#[test]
fn restart_storm_ends_in_the_exact_picture_with_flat_memory() {
    let report = bounded(WHOLE_TEST, storm);
    println!("{report}");
}

/// What one storm round measured.
struct Round {
    secs: f64,
    reads: u64,
    progressed: usize,
    last_generation: u64,
}

fn storm() -> String {
    let rss_start = rss_kb();
    let loaded = builtin_cornell_box(None).unwrap();
    let scene = Arc::new(builtin_cornell_box(None).unwrap().scene);
    let base = base_snapshot(&loaded, &scene);
    let session = Arc::new(RenderSession::new(2, Arc::new(|| {})).unwrap());

    // Warm-up: the pool, films and allocator reach their steady state before memory is read.
    for spp in [1, 2] {
        let mut snap = base.clone();
        snap.settings.samples_per_pixel = spp;
        let g = session.start(snap);
        assert!(session.wait_for(Duration::from_secs(30), |s| s.generation == g && s.finished));
    }
    let rss_warm = rss_kb();
    // Two rounds: growth over the first shows what the storm costs at all, growth over the
    // second what it leaks (nothing, if memory is flat).
    let first = round(&session, &base, 1);
    let rss_first = rss_kb();
    let second = round(&session, &base, 2);
    let rss_second = rss_kb();

    let stop_started = Instant::now();
    let session = Arc::try_unwrap(session).expect("no other owner of the session");
    drop(session);
    let stop_secs = stop_started.elapsed().as_secs_f64();

    let growth = rss_second.saturating_sub(rss_warm);
    let report = format!(
        "restart storm: 2 rounds of {CHANGES} starts from 2 threads in {:.2} s and {:.2} s \
         ({:.0} starts/s), {} film reads, {} generations seen with finished passes, final \
         generations {} and {} bit-identical to one-shot renders; VmRSS {rss_start} kB at the \
         start, {rss_warm} kB after warm-up, {rss_first} kB after round 1, {rss_second} kB after \
         round 2 (+{growth} kB); shutdown {stop_secs:.3} s",
        first.secs,
        second.secs,
        CHANGES as f64 / first.secs,
        first.reads + second.reads,
        first.progressed + second.progressed,
        first.last_generation,
        second.last_generation,
    );
    assert!(
        rss_warm == 0 || growth < RSS_GROWTH_LIMIT_KB,
        "memory grew: {report}"
    );
    report
}

/// One storm of `CHANGES` starts, then a check of the final film against a one-shot render.
fn round(session: &Arc<RenderSession>, base: &Snapshot, seed: u64) -> Round {
    let started = Instant::now();
    let log: Arc<Mutex<Vec<(u64, Snapshot)>>> = Arc::new(Mutex::new(Vec::new()));
    let stop_reader = Arc::new(AtomicBool::new(false));
    let reader = {
        let session = Arc::clone(session);
        let stop = Arc::clone(&stop_reader);
        thread::spawn(move || {
            let mut reads = 0u64;
            let mut progressed = std::collections::HashSet::new();
            while !stop.load(Ordering::Relaxed) {
                let _ = session.take_dirty();
                let stats = session.stats();
                if stats.passes_done > 0 {
                    progressed.insert(stats.generation);
                }
                session.with_film(|f| {
                    if let Some(f) = f {
                        let _ = f.shown_rgb(0);
                    }
                });
                reads += 1;
                thread::sleep(Duration::from_micros(200));
            }
            (reads, progressed.len())
        })
    };
    let starters: Vec<_> = (0..2u64)
        .map(|t| {
            let session = Arc::clone(session);
            let log = Arc::clone(&log);
            let mut snap = base.clone();
            thread::spawn(move || {
                let mut rng = Rng(0x9E37_79B9_7F4A_7C15 ^ (seed << 8 | (t + 1)));
                for i in 0..CHANGES / 2 {
                    change(&mut rng, &mut snap);
                    // Record under the lock so the log order matches the generation order.
                    let mut log = log.lock().unwrap();
                    let g = session.start(snap.clone());
                    log.push((g, snap.clone()));
                    drop(log);
                    match rng.below(100) {
                        0 => session.set_paused(true),
                        1 => session.set_paused(false),
                        2 if i % 200 == 0 => session.set_threads(1 + rng.below(2) as usize),
                        // Some pauses between changes, so that many generations get as far as
                        // previews and full passes before they are cancelled.
                        3..=40 => thread::sleep(Duration::from_micros(rng.below(3000))),
                        _ => {}
                    }
                }
            })
        })
        .collect();
    for s in starters {
        s.join().expect("a starting thread panicked");
    }
    let secs = started.elapsed().as_secs_f64();
    session.set_paused(false);
    stop_reader.store(true, Ordering::Relaxed);
    let (reads, progressed) = reader.join().expect("the reading thread panicked");

    let log = log.lock().unwrap();
    assert_eq!(log.len(), CHANGES);
    let (last_generation, last) = log.iter().max_by_key(|(g, _)| *g).cloned().unwrap();
    assert_eq!(last_generation, session.generation());
    assert!(
        session.wait_for(Duration::from_secs(30), |s| s.generation == last_generation
            && s.finished),
        "the last generation did not finish: {:?}",
        session.stats()
    );
    let film = session.with_film(|f| {
        let f = f.expect("a film after the storm");
        assert_eq!(f.generation, last_generation);
        f.accum.clone()
    });
    let (expected, _) = render(&last.scene, &last.setup, &last.settings);
    assert_eq!(film.width, last.settings.width);
    assert_eq!(film, expected, "the final film differs from a fresh render");
    Round {
        secs,
        reads,
        progressed,
        last_generation,
    }
}
