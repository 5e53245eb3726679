//! Adaptive rounds in the progressive session (the viewer): after 16 samples in every pixel,
//! the rest of the target goes by error; the film is exactly each pixel's samples 0..n rendered
//! in one shot, on one thread or two; the illuminance asked for after the rounds began is
//! measured from each pixel's own count on.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::sync::Arc;
use std::time::Duration;
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::adaptive::MIN_SAMPLES;
use tracer_core::render::{
    ILLUMINANCE_SAMPLES, RenderSession, RenderSettings, Snapshot, render_pixels,
};
use tracer_core::scene::builtin_cornell_box;

const WAIT: Duration = Duration::from_secs(120);

fn snapshot(integrator: IntegratorKind, spp: u32) -> (Snapshot, Arc<tracer_core::scene::Scene>) {
    let loaded = builtin_cornell_box(None).unwrap();
    let scene = Arc::new(loaded.scene);
    let snap = Snapshot {
        scene: Arc::clone(&scene),
        setup: loaded.setup,
        settings: RenderSettings {
            width: 40,
            height: 30,
            samples_per_pixel: spp,
            integrator,
            pixel_illuminance: false,
            ..RenderSettings::default()
        },
        time_limit: None,
        adaptive: true,
    };
    (snap, scene)
}

#[test]
fn adaptive_rounds_spend_the_target_where_the_error_is_and_match_a_one_shot_render() {
    for integrator in [IntegratorKind::Bidirectional, IntegratorKind::Path] {
        let (snap, scene) = snapshot(integrator, 40);
        let mut films = Vec::new();
        for threads in [1, 2] {
            let session = RenderSession::new(threads, Arc::new(|| {})).unwrap();
            let generation = session.start(snap.clone());
            assert!(session.wait_for(WAIT, |st| st.generation == generation && st.finished));
            let stats = session.stats();
            let film = session.with_film(|f| f.unwrap().accum.clone());
            let total: u64 = film.counts().map(u64::from).sum();
            let pixels = film.len() as u64;
            let hi = film.counts().max().unwrap();
            println!(
                "{integrator}, {threads} threads: {:.1} spp on average, {} to {hi}, {}",
                stats.mean_samples_per_pixel, stats.samples_per_pixel, stats.pass
            );
            assert!(stats.pass.starts_with("adaptive round"), "{}", stats.pass);
            assert!(film.min_samples() >= MIN_SAMPLES, "{integrator}");
            assert!(hi > 2 * MIN_SAMPLES, "{integrator}: no pixel got more");
            assert!(
                total <= 40 * pixels && total > 38 * pixels,
                "{integrator}: {total}"
            );
            assert!((stats.mean_samples_per_pixel - total as f64 / pixels as f64).abs() < 1e-9);
            films.push(film);
        }
        assert_eq!(films[0], films[1], "{integrator}: threads");
        let counts: Vec<u32> = films[0].counts().collect();
        let (oneshot, _) = render_pixels(&scene, &snap.setup, &snap.settings, &|i| 0..counts[i]);
        assert_eq!(
            films[0].pixels().collect::<Vec<_>>(),
            oneshot.pixels().collect::<Vec<_>>(),
            "{integrator}: one shot"
        );
        assert_eq!(films[0].splat_paths, oneshot.splat_paths, "{integrator}");
    }
}

#[test]
fn illuminance_asked_after_the_rounds_is_measured_from_each_pixels_count() {
    let (snap, scene) = snapshot(IntegratorKind::Bidirectional, 24);
    let session = RenderSession::new(2, Arc::new(|| {})).unwrap();
    let generation = session.start(snap.clone());
    assert!(session.wait_for(WAIT, |st| st.generation == generation && st.finished));
    let before: Vec<u32> = session.with_film(|f| f.unwrap().accum.counts().collect());
    assert!(before.iter().any(|&n| n != before[0]), "rounds ran");
    session.measure_illuminance();
    assert!(session.wait_for(WAIT, |st| st.finished
        && st.pass == "adaptive round 1"
        && st.mean_samples_per_pixel > 24.0 + f64::from(ILLUMINANCE_SAMPLES) - 0.5));
    assert_eq!(session.generation(), generation, "no restart");
    let (after, measured) = session.with_film(|f| {
        let f = f.unwrap();
        let n = f.accum.len();
        (f.accum.clone(), (0..n).all(|i| f.illuminance_measured(i)))
    });
    assert!(measured);
    // Each pixel: its samples before[i] .. before[i] + 16 carry the illuminance, exactly as
    // rendering them with it.
    let with_lx = RenderSettings {
        pixel_illuminance: true,
        ..snap.settings
    };
    let (later, _) = render_pixels(&scene, &snap.setup, &with_lx, &|i| {
        before[i]..before[i] + ILLUMINANCE_SAMPLES
    });
    for (i, (a, b)) in after.pixels().zip(later.pixels()).enumerate() {
        assert_eq!(a.count, before[i] + ILLUMINANCE_SAMPLES, "pixel {i}");
        assert_eq!(a.illuminance, b.illuminance, "pixel {i}");
    }
}

#[test]
fn illuminance_asked_during_the_rounds_reaches_every_pixel() {
    let (snap, _) = snapshot(IntegratorKind::Path, 400);
    let session = RenderSession::new(2, Arc::new(|| {})).unwrap();
    let generation = session.start(snap);
    assert!(session.wait_for(WAIT, |st| st.generation == generation
        && st.pass.starts_with("adaptive round")
        && !st.finished));
    session.measure_illuminance();
    assert!(session.wait_for(WAIT, |st| st.finished));
    assert_eq!(session.generation(), generation, "no restart");
    session.with_film(|f| {
        let f = f.unwrap();
        let n = f.accum.len();
        let measured = (0..n).filter(|&i| f.illuminance_measured(i)).count();
        let lit = (0..n).filter(|&i| f.shown_illuminance(i) > 0.0).count();
        println!("{measured} of {n} pixels measured, {lit} lit");
        assert_eq!(measured, n);
        assert!(lit > n / 2);
    });
}
