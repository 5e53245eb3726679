//! The viewer's first seconds on a scene: previews in the mode's own transport (bidirectional
//! previews show the light a path tracer misses), status figures that move within a pass, and
//! the exposure: set on a scene's first view, held while editing, the user's once set, and kept
//! per scene.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use egui::Vec2;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use raygine::app::RaygineApp;
use raygine::scene_exposure::{SceneExposure, median_exposure_stops, scene_key};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use tracer_core::integrator::IntegratorKind;

type Viewer = Harness<'static, RaygineApp>;

const TIMEOUT: Duration = Duration::from_secs(120);

fn viewer(integrator: IntegratorKind, target_spp: u32, scale: f32) -> Viewer {
    let mut h = crate::box_viewer(Vec2::new(800.0, 560.0), integrator, target_spp, scale);
    h.run_steps(2);
    h
}

/// Steps the app until `done` holds (panics after [`TIMEOUT`]).
fn step_until(h: &mut Viewer, what: &str, done: impl Fn(&RaygineApp) -> bool) {
    let end = Instant::now() + TIMEOUT;
    loop {
        h.run_steps(1);
        if done(h.state()) {
            return;
        }
        assert!(Instant::now() < end, "timed out waiting for {what}");
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Mean luminance of the top sixth of the picture shown (the box's ceiling and the walls' tops),
/// once the previews are complete and a third of the first full pass is in, before any pixel
/// has a second sample.
fn ceiling_band_of_the_preview(integrator: IntegratorKind) -> f64 {
    let mut h = viewer(integrator, 64, 0.5);
    let g = h.state().worker().generation();
    assert!(g >= 1, "no render started");
    step_until(&mut h, "the previews", |a| {
        let s = a.worker().stats();
        s.generation >= g && s.passes_done >= 2 && s.pass_fraction > 0.3
    });
    let (band, spp) = h.state().worker().with_film(|f| {
        let f = f.expect("a film");
        let (w, rows) = (f.width() as usize, (f.height() / 6) as usize);
        let sum: f64 = (0..w * rows)
            .map(|i| f64::from(tracer_core::light::luminance(f.shown_rgb(i))))
            .sum();
        (sum / (w * rows) as f64, f.accum.min_samples())
    });
    assert!(spp <= 1, "{integrator}: {spp} spp already");
    band
}

/// The case: bidirectional previews were path-traced, so the light that reaches the
/// box's ceiling from the hot spot above the lamp (20-60 % of it, BENCHMARK.md) was missing
/// from the pictures shown while dragging. Now they are bidirectional (without splats), and
/// brighter there than the path tracer's by far more than their noise.
#[test]
fn bidirectional_previews_show_the_light_a_path_traced_preview_misses() {
    let bdpt = ceiling_band_of_the_preview(IntegratorKind::Bidirectional);
    let path = ceiling_band_of_the_preview(IntegratorKind::Path);
    println!("top band of the preview: bidirectional {bdpt:.1} cd/m², path {path:.1} cd/m²");
    assert!(bdpt > 1.15 * path, "bidirectional {bdpt} vs path {path}");
}

/// Within one long pass the status figures move: elapsed time, samples done (with the pass's
/// share) and the time left, as the status bar shows them.
#[test]
fn status_figures_advance_within_one_pass() {
    let mut h = viewer(IntegratorKind::Bidirectional, 64, 1.0);
    let g = h.state().worker().generation();
    assert!(g >= 1, "no render started");
    let in_first_full = |a: &RaygineApp| {
        let s = a.worker().stats();
        s.generation >= g && s.pass == "sample 1" && s.pass_fraction > 0.01
    };
    step_until(&mut h, "the first full pass", in_first_full);
    let a = h.state().worker().stats();
    std::thread::sleep(Duration::from_millis(300));
    step_until(&mut h, "progress", |app| {
        let s = app.worker().stats();
        s.pass == "sample 1" && s.pass_fraction > a.pass_fraction + 0.01
    });
    let b = h.state().worker().stats();
    assert_eq!(b.samples_per_pixel, 0, "{b:?}");
    assert!(b.elapsed_secs > a.elapsed_secs, "{a:?} → {b:?}");
    assert!(b.samples_done() > a.samples_done(), "{a:?} → {b:?}");
    assert!(b.eta_secs().is_some_and(|t| t > 0.0), "{b:?}");
    // The status bar shows them.
    h.run_steps(1);
    let label = format!("{:.1}/64 spp · sample 1", b.samples_done());
    let shown = h
        .query_by_label_contains(" left")
        .and_then(|n| n.accesskit_node().value())
        .expect("a status line with the time left");
    assert!(
        shown.contains("/64 spp · sample 1"),
        "{shown} (near {label})"
    );
}

fn scratch_dir(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("first-view-{test}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A floor with a tent over it, `size` mm across (lit by the default light).
fn tent_scene(size: f32) -> String {
    let (s, h) = (size, size * 0.6);
    format!(
        ";; written by raygine's UI tests\n\
         define breps floor\n\
         vertices 4\n\
         0 0 0\n{s} 0 0\n{s} 0 -{s}\n0 0 -{s}\n\
         triangles 2\n0 1 2\n0 2 3\n\
         parts 1\n0 0\n\
         enddef\n\
         \n\
         define breps tent\n\
         vertices 3\n\
         0 0 -{s}\n{s} 0 -{s}\n{m} {h} -{s}\n\
         triangles 1\n0 1 2\n\
         parts 1\n0\n\
         enddef\n",
        m = s * 0.5
    )
}

fn open(h: &mut Viewer, path: &Path) {
    h.state_mut().open_path(path);
    h.state_mut().finish_loading_blocking(TIMEOUT);
    h.run_steps(1);
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
}

/// Waits until the current scene's exposure is settled and its first full pass shown.
fn first_full_pass(h: &mut Viewer) {
    let g = h.state().worker().generation();
    step_until(h, "the first full pass", |a| {
        let s = a.worker().stats();
        s.generation >= g && s.samples_per_pixel >= 1 && a.exposure_held()
    });
}

#[test]
fn exposure_is_set_on_first_view_held_while_editing_and_kept_per_scene() {
    let mut h = viewer(IntegratorKind::Direct, 4, 0.5);
    first_full_pass(&mut h);
    // The box: automatic, from its first full pass, mapping its median surface to middle grey.
    let app = h.state();
    let box_key = scene_key(None);
    let box_stops = app.display().exposure_stops;
    assert_eq!(
        app.prefs().exposures.get(&box_key),
        Some(&SceneExposure {
            stops: box_stops,
            by_user: false
        })
    );
    let median_now = app
        .worker()
        .with_film(|f| f.and_then(|f| median_exposure_stops(f, |_| false)))
        .unwrap();
    assert!(
        (median_now - box_stops).abs() < 0.5,
        "{median_now} vs {box_stops}"
    );

    // Editing restarts the render; the exposure holds.
    let light = h.state().document().setup.lights[0].position;
    h.state_mut().setup_mut().lights[0].position = [light[0] + 80.0, light[1] - 150.0, light[2]];
    let g = h.state().worker().generation();
    step_until(&mut h, "the edit's render", |a| {
        let s = a.worker().stats();
        s.generation > g && s.finished
    });
    assert_eq!(h.state().display().exposure_stops, box_stops);

    // Another scene: its own first view.
    let dir = scratch_dir("per-scene");
    let (a_path, b_path) = (dir.join("a.shp"), dir.join("b.shp"));
    std::fs::write(&a_path, tent_scene(2000.0)).unwrap();
    std::fs::write(&b_path, tent_scene(500.0)).unwrap();
    open(&mut h, &a_path);
    first_full_pass(&mut h);
    let a_key = scene_key(Some(&a_path));
    let a_auto = h.state().prefs().exposures[&a_key];
    assert!(!a_auto.by_user);
    assert_eq!(a_auto.stops, h.state().display().exposure_stops);
    // The user's own exposure for it wins.
    let mine = a_auto.stops + 1.75;
    h.state_mut().display_mut().exposure_stops = mine;
    h.run_steps(2);
    assert_eq!(
        h.state().prefs().exposures[&a_key],
        SceneExposure {
            stops: mine,
            by_user: true
        }
    );
    // A third scene, then back to the second: it comes back as the user left it.
    open(&mut h, &b_path);
    first_full_pass(&mut h);
    assert!(
        h.state()
            .prefs()
            .exposures
            .contains_key(&scene_key(Some(&b_path)))
    );
    open(&mut h, &a_path);
    assert_eq!(h.state().display().exposure_stops, mine);
    first_full_pass(&mut h);
    h.run_steps(3);
    assert_eq!(h.state().display().exposure_stops, mine);
    assert_eq!(h.state().prefs().exposures[&box_key].stops, box_stops);
}
