//! The progressive engine: determinism, cancellation, convergence, pause.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use glam::Vec3;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;
use tracer_core::render::{RenderSession, RenderSettings, Snapshot, render};
use tracer_core::scene::{LoadedScene, builtin_cornell_box};

const WAIT: Duration = Duration::from_secs(60);

fn cornell() -> LoadedScene {
    builtin_cornell_box(None).unwrap()
}

fn snapshot(loaded: &LoadedScene, scene: &Arc<tracer_core::scene::Scene>, spp: u32) -> Snapshot {
    Snapshot {
        scene: Arc::clone(scene),
        setup: loaded.setup.clone(),
        settings: RenderSettings {
            width: 96,
            height: 64,
            samples_per_pixel: spp,
            max_depth: 5,
            ..RenderSettings::default()
        },
        time_limit: None,
        adaptive: false,
    }
}

fn session(threads: usize) -> RenderSession {
    RenderSession::new(threads, Arc::new(|| {})).unwrap()
}

fn finished_accum(s: &RenderSession, generation: u64) -> tracer_core::render::Film {
    assert!(s.wait_for(WAIT, |st| st.generation == generation && st.finished));
    s.with_film(|f| {
        let f = f.expect("a film");
        assert_eq!(f.generation, generation);
        f.accum.clone()
    })
}

#[test]
fn converged_film_is_identical_for_one_and_two_threads_and_one_shot() {
    let loaded = cornell();
    let scene = Arc::new(builtin_cornell_box(None).unwrap().scene);
    for integrator in tracer_core::integrator::IntegratorKind::ALL {
        let mut snap = snapshot(&loaded, &scene, 4);
        snap.settings.integrator = integrator;
        let one = session(1);
        let two = session(2);
        let a = finished_accum(&one, one.start(snap.clone()));
        let b = finished_accum(&two, two.start(snap.clone()));
        assert_eq!(a, b, "{integrator}");
        let (oneshot, _) = render(&scene, &snap.setup, &snap.settings);
        assert_eq!(a, oneshot, "{integrator}");
    }
    let snap = snapshot(&loaded, &scene, 4);
    let (a, _) = render(&scene, &snap.setup, &snap.settings);
    assert!(a.pixels().all(|p| p.count == 4));
    let lit = a
        .pixels()
        .filter(|p| p.mean_rgb().max_element() > 0.0)
        .count();
    assert!(lit > a.len() / 2, "the box should be mostly lit: {lit}");
}

#[test]
fn restart_mid_render_gives_the_same_image_and_never_mixes_generations() {
    let loaded = cornell();
    let scene = Arc::new(builtin_cornell_box(None).unwrap().scene);
    let s = session(2);
    let first = snapshot(&loaded, &scene, 64);
    let mut moved = first.clone();
    moved.setup.lights[0].position = [100.0, 500.0, -100.0];
    // Many interleaved restarts, some of them mid-pass.
    for i in 0..40 {
        s.start(if i % 2 == 0 {
            first.clone()
        } else {
            moved.clone()
        });
        std::thread::sleep(Duration::from_micros(300 * (i % 5)));
    }
    let mut last = moved.clone();
    last.settings.samples_per_pixel = 3;
    let generation = s.start(last.clone());
    let film = finished_accum(&s, generation);
    let (reference, _) = render(&scene, &last.setup, &last.settings);
    assert_eq!(
        film, reference,
        "the final film must be exactly the last state's"
    );
    // And the same snapshot restarted gives the same bits again.
    let again = finished_accum(&s, s.start(last.clone()));
    assert_eq!(again, reference);
}

#[test]
fn previews_come_first_and_do_not_bias_the_image() {
    let loaded = cornell();
    let scene = Arc::new(builtin_cornell_box(None).unwrap().scene);
    let wakes = Arc::new(AtomicUsize::new(0));
    let w = Arc::clone(&wakes);
    let s = RenderSession::new(
        2,
        Arc::new(move || {
            w.fetch_add(1, Ordering::Relaxed);
        }),
    )
    .unwrap();
    let snap = snapshot(&loaded, &scene, 2);
    let generation = s.start(snap.clone());
    let film = finished_accum(&s, generation);
    let stats = s.stats();
    assert_eq!(stats.passes_done, 2 + 2, "two previews then two samples");
    assert_eq!(stats.samples_per_pixel, 2);
    let (p, f) = (
        stats.first_preview_secs.unwrap(),
        stats.first_full_secs.unwrap(),
    );
    assert!(p <= f);
    assert!(stats.rays > 0);
    assert!(wakes.load(Ordering::Relaxed) > 0, "the consumer is woken");
    // Preview samples are not in the accumulation: exactly 2 samples per pixel.
    let (reference, _) = render(&scene, &snap.setup, &snap.settings);
    assert_eq!(film, reference);
    // Dirty rectangles were reported for the shown generation.
    assert!(!s.take_dirty().is_empty());
}

#[test]
fn accumulated_mean_converges_to_an_independent_reference() {
    // The reference: the average over a 128x128 stratified grid of sub-pixel positions, traced
    // directly with the integrator, for a few pixels on the tall block's edge (where
    // antialiasing matters).
    let loaded = cornell();
    let scene = Arc::new(builtin_cornell_box(None).unwrap().scene);
    let settings = RenderSettings {
        width: 96,
        height: 64,
        samples_per_pixel: 256,
        max_depth: 5,
        ..RenderSettings::default()
    };
    let (film, _) = render(&scene, &loaded.setup, &settings);
    let lit = tracer_core::lit_scene::LitScene::new(&scene, &loaded.setup, 5);
    let basis = loaded.setup.camera.basis(loaded.setup.handedness, 96, 64);
    let mut checked = 0;
    for y in 0..64u32 {
        for x in 0..96u32 {
            let i = film.index(x, y);
            let mean = film.mean_rgb(i);
            // Pick pixels that are neither flat nor empty: edges.
            let c = tracer_core::integrator::trace_direct(
                &lit,
                &basis.ray(x as f32 + 0.5, y as f32 + 0.5).unwrap(),
                &mut rng(),
            );
            let corner = tracer_core::integrator::trace_direct(
                &lit,
                &basis.ray(x as f32 + 0.01, y as f32 + 0.01).unwrap(),
                &mut rng(),
            );
            if (c.rgb - corner.rgb).length() < 1.0 || checked >= 8 {
                continue;
            }
            let n = 128;
            let mut sum = Vec3::ZERO;
            let mut brightest = 0.0f32;
            for sy in 0..n {
                for sx in 0..n {
                    let fx = (sx as f32 + 0.5) / n as f32;
                    let fy = (sy as f32 + 0.5) / n as f32;
                    let v = tracer_core::integrator::trace_direct(
                        &lit,
                        &basis.ray(x as f32 + fx, y as f32 + fy).unwrap(),
                        &mut rng(),
                    )
                    .rgb;
                    brightest = brightest.max(v.max_element());
                    sum += v;
                }
            }
            let reference = sum / (n * n) as f32;
            let err = (mean - reference).abs().max_element();
            // Error relative to the pixel's contrast: an edge's coverage must be right to 2 %.
            let scale = brightest.max(1.0);
            assert!(err / scale < 0.02, "pixel ({x},{y}): {mean} vs {reference}");
            checked += 1;
        }
    }
    assert!(checked >= 6, "found only {checked} edge pixels");
}

#[test]
fn pause_holds_and_resume_finishes() {
    let loaded = cornell();
    let scene = Arc::new(builtin_cornell_box(None).unwrap().scene);
    let s = session(2);
    s.set_paused(true);
    let generation = s.start(snapshot(&loaded, &scene, 2));
    assert!(!s.wait_for(Duration::from_millis(300), |st| st.finished
        && st.generation == generation));
    s.set_paused(false);
    let film = finished_accum(&s, generation);
    assert!(film.pixels().all(|p| p.count == 2));
}

#[test]
fn time_limit_stops_before_the_target() {
    let loaded = cornell();
    let scene = Arc::new(builtin_cornell_box(None).unwrap().scene);
    let s = session(2);
    let mut snap = snapshot(&loaded, &scene, 1_000_000);
    snap.time_limit = Some(Duration::from_millis(200));
    let generation = s.start(snap);
    assert!(s.wait_for(WAIT, |st| st.finished && st.generation == generation));
    let st = s.stats();
    assert!(st.samples_per_pixel >= 1 && st.samples_per_pixel < 1_000_000);
    assert!(st.elapsed_secs < 5.0);
}

/// A random stream for direct-mode traces (the built-in box has no emitters: nothing draws).
fn rng() -> tracer_core::sampling::SampleRng {
    tracer_core::sampling::SampleRng::new(0, 0)
}

/// The film records where the camera saw nothing (the viewer's backdrop goes there): with a
/// field of view wider than the box's opening the corners see only background and the centre
/// none, in every mode, while the accumulated sums there stay those of black.
#[test]
fn the_film_knows_where_the_camera_saw_nothing() {
    let loaded = cornell();
    let scene = Arc::new(builtin_cornell_box(None).unwrap().scene);
    for integrator in tracer_core::integrator::IntegratorKind::ALL {
        let mut snap = snapshot(&loaded, &scene, 2);
        snap.settings.integrator = integrator;
        snap.setup.camera.fov_deg = 120.0;
        let s = session(2);
        let generation = s.start(snap.clone());
        assert!(s.wait_for(WAIT, |st| st.generation == generation && st.finished));
        s.with_film(|f| {
            let f = f.unwrap();
            let (w, h) = (f.width(), f.height());
            let corner = f.accum.index(0, 0);
            let centre = f.accum.index(w / 2, h / 2);
            assert_eq!(f.background_fraction(corner), 1.0, "{integrator}");
            assert_eq!(f.accum.mean_rgb(corner), Vec3::ZERO, "{integrator}");
            assert_eq!(f.background_fraction(centre), 0.0, "{integrator}");
            assert!(f.accum.mean_rgb(centre).max_element() > 0.0, "{integrator}");
        });
    }
}

/// The status figures move within a pass (after every tile), not only between passes: a long
/// first full pass shows its share done, the time and the rays growing, and an estimate of the
/// time to the target. The pass fills the frame in quarters: midway, the pixels done are the
/// first quarter's (every 2x2 block's first pixel), not some tiles complete and others empty.
#[test]
fn status_moves_within_a_pass_and_the_first_pass_fills_evenly() {
    let loaded = cornell();
    let scene = Arc::new(builtin_cornell_box(None).unwrap().scene);
    let mut snap = snapshot(&loaded, &scene, 8);
    snap.settings.width = 480;
    snap.settings.height = 360;
    snap.settings.integrator = tracer_core::integrator::IntegratorKind::Bidirectional;
    let s = session(1);
    let g = s.start(snap);
    let in_first_pass =
        |st: &tracer_core::render::SessionStats| st.generation == g && st.pass == "sample 1";
    assert!(s.wait_for(WAIT, |st| in_first_pass(st) && st.pass_fraction > 0.02));
    let a = s.stats();
    let mid = s.with_film(|f| {
        let f = f.unwrap();
        let counted = |px: u32, py: u32| {
            let mut n = 0;
            for y in (py..f.height()).step_by(2) {
                for x in (px..f.width()).step_by(2) {
                    n += f.accum.count(f.accum.index(x, y));
                }
            }
            n
        };
        [counted(0, 0), counted(1, 1), counted(1, 0), counted(0, 1)]
    });
    assert!(s.wait_for(WAIT, |st| in_first_pass(st)
        && st.pass_fraction > a.pass_fraction + 0.02));
    let b = s.stats();
    assert_eq!(b.samples_per_pixel, 0, "{b:?}");
    assert!(b.elapsed_secs > a.elapsed_secs, "{a:?} {b:?}");
    assert!(b.rays > a.rays, "{a:?} {b:?}");
    assert!(b.samples_done() > a.samples_done(), "{a:?} {b:?}");
    let eta = b.eta_secs().expect("an estimate of the time left");
    assert!(eta > 0.0 && eta.is_finite(), "{b:?}");
    // Midway through the first quarter only the first quarter has samples.
    if a.pass_fraction < 0.25 {
        assert!(mid[0] > 0 && mid[1..] == [0, 0, 0], "{mid:?} at {a:?}");
    }
}
