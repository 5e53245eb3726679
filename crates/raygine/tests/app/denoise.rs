//! The viewer's denoised display: the toggle (D) flips picture and raw without restarting the
//! render, the status bar says so, and every readout stays on the film's sums. Without Open
//! Image Denoise the toggle is disabled with the reason. Tests that need the library skip
//! without it, and fail under CI (RAYGINE_REQUIRE_OIDN=1, set by check.sh).

#![allow(clippy::unwrap_used, clippy::expect_used)]

use egui::Vec2;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use raygine::app::RaygineApp;
use raygine::denoise_view::Availability;
use std::time::{Duration, Instant};
use tracer_core::integrator::IntegratorKind;

type Viewer = Harness<'static, RaygineApp>;

fn viewer() -> Viewer {
    let mut h = crate::box_viewer(
        Vec2::new(720.0, 480.0),
        IntegratorKind::Bidirectional,
        2,
        0.5,
    );
    h.run_steps(3);
    h
}

/// Steps the app until `done` or `secs` have passed.
fn step_until(h: &mut Viewer, secs: u64, done: impl Fn(&RaygineApp) -> bool) -> bool {
    let end = Instant::now() + Duration::from_secs(secs);
    while Instant::now() < end {
        h.run_steps(1);
        if done(h.state()) {
            return true;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    false
}

/// Waits for the denoiser to load; false (skipped) when it is not there.
fn denoiser_ready(h: &mut Viewer) -> bool {
    step_until(h, 30, |a| a.denoise().availability != Availability::Loading);
    match &h.state().denoise().availability {
        Availability::Ready(_) => true,
        other => {
            assert!(
                std::env::var_os("RAYGINE_REQUIRE_OIDN").is_none(),
                "RAYGINE_REQUIRE_OIDN is set and the denoiser is {other:?}"
            );
            eprintln!("skipped: {other:?}");
            false
        }
    }
}

#[test]
fn d_flips_the_denoised_picture_without_touching_the_render_or_its_readouts() {
    let mut h = viewer();
    if !denoiser_ready(&mut h) {
        return;
    }
    assert!(h.state().denoise().wanted(IntegratorKind::Bidirectional));
    let shown = step_until(&mut h, 120, |a| a.worker().denoised_shown().is_some());
    assert!(shown, "no denoised picture after 120 s");
    assert!(
        h.query_by_label("denoised display · readouts unbiased")
            .is_some()
    );
    let generation = h.state().worker().generation();
    let sums = |h: &Viewer| {
        h.state()
            .worker()
            .with_film(|f| f.map(|f| f.accum.pixels().collect::<Vec<_>>()))
            .unwrap()
    };
    // Let the render finish, so the sums stand still while the toggle is flipped.
    assert!(step_until(&mut h, 120, |a| a.worker().stats().finished));
    let before = sums(&h);
    h.key_press(egui::Key::D);
    h.run_steps(3);
    assert!(
        h.state().worker().denoised_shown().is_none(),
        "D did not show the raw picture"
    );
    assert!(
        h.query_by_label("denoised display · readouts unbiased")
            .is_none()
    );
    assert_eq!(
        h.state().worker().generation(),
        generation,
        "D restarted the render"
    );
    assert_eq!(sums(&h), before, "the toggle changed the film's sums");
    h.key_press(egui::Key::D);
    assert!(step_until(&mut h, 60, |a| a
        .worker()
        .denoised_shown()
        .is_some()));
    assert_eq!(h.state().worker().generation(), generation);
    assert_eq!(sums(&h), before);
    // Direct mode starts with the toggle off.
    assert!(!h.state().denoise().wanted(IntegratorKind::Direct));
}

#[test]
fn without_the_library_the_toggle_is_disabled_and_says_why() {
    let mut h = viewer();
    step_until(&mut h, 30, |a| {
        a.denoise().availability != Availability::Loading
    });
    // As a machine without the library would have it (whatever this one has).
    h.state_mut()
        .set_denoiser_availability(Availability::Unavailable(
            "not found (tried libOpenImageDenoise.so.2)".to_owned(),
        ));
    h.run_steps(3);
    assert!(
        h.query_by_label_contains("denoise unavailable: not found")
            .is_some(),
        "no reason shown"
    );
    let wanted = h.state().denoise().wanted(IntegratorKind::Bidirectional);
    h.key_press(egui::Key::D);
    h.run_steps(2);
    assert_eq!(
        h.state().denoise().wanted(IntegratorKind::Bidirectional),
        wanted,
        "D changed a toggle that cannot work"
    );
    assert!(h.state().worker().denoised_shown().is_none());
    // Nothing else changed: the render goes on and shows the raw picture.
    assert!(step_until(&mut h, 60, |a| a.picture_drawn()));
}
