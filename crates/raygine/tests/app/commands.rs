//! The command path: what the menus, the shortcuts and the windows ask for is applied in one
//! place, so the same request gives the same result wherever it comes from.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use egui::Vec2;
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use raygine::app::{AppOptions, RaygineApp};
use raygine::command::Command;
use raygine::file_ops::DialogPurpose;
use raygine::unsaved::Switch;
use std::time::Duration;
use tracer_core::integrator::IntegratorKind;

const TIMEOUT: Duration = Duration::from_secs(15);

type Viewer = Harness<'static, RaygineApp>;

/// The real app, built-in Cornell box, direct light at 1 spp (these tests need no picture).
fn viewer() -> Viewer {
    let mut h = Harness::builder()
        .with_size(Vec2::new(960.0, 640.0))
        .with_accessibility_check(false)
        .build_eframe(|cc| {
            RaygineApp::new(
                cc,
                AppOptions {
                    threads: 1,
                    ignore_last_scene: true,
                    ..AppOptions::default()
                },
            )
            .unwrap()
        });
    h.state_mut().render_prefs_mut().target_spp = 1;
    h.state_mut().render_prefs_mut().integrator = IntegratorKind::Direct;
    h.run_steps(3);
    h
}

/// Opening a scene that does not exist shows why, and keeps the scene that was open.
#[test]
fn a_bad_path_from_the_path_window_is_an_error() {
    let mut h = viewer();
    let missing = std::env::temp_dir().join("raygine-no-such-dir/none.shp");
    h.state_mut()
        .apply(Command::PromptPath(DialogPurpose::Open));
    h.state_mut()
        .apply(Command::RunPathAction(DialogPurpose::Open, missing.clone()));
    h.state_mut().finish_loading_blocking(TIMEOUT);
    h.run_steps(2);
    let app = h.state();
    let error = app.error().map(str::to_owned).expect("no error shown");
    assert!(error.contains("none.shp"), "{error}");
    assert_eq!(app.document().path, None, "the built-in scene stays");
}

/// Every way of installing a document clears the last error (the built-in box did not).
#[test]
fn switching_to_the_builtin_scene_clears_the_error() {
    let mut h = viewer();
    h.state_mut().apply(raygine::command::Command::Error(
        "an earlier failure".to_owned(),
    ));
    h.state_mut().apply(Command::Switch(Switch::Builtin));
    h.run_steps(2);
    assert_eq!(h.state().error(), None);
}

/// Pause from the View menu and from the P key are one action: each toggles both the flag and
/// the render.
#[test]
fn pause_from_the_menu_and_the_key_agree() {
    let mut h = viewer();
    h.get_by_label("View").click();
    h.run_steps(2);
    // The button's name carries its shortcut.
    h.get_by_role_and_label(Role::Button, "Pause rendering P")
        .click();
    h.run_steps(2);
    assert!(h.state().paused());
    assert!(
        h.state().worker().stats().paused,
        "the render did not pause"
    );
    h.key_press(egui::Key::P);
    h.run_steps(2);
    assert!(!h.state().paused());
    assert!(
        !h.state().worker().stats().paused,
        "the render did not resume"
    );
}

/// A failed background write is shown as the error (nothing is dropped).
#[test]
fn a_failed_write_is_shown() {
    let mut h = viewer();
    let path = std::env::temp_dir().join("raygine-no-such-dir/grids.csv");
    h.state_mut().apply(Command::WriteText {
        path,
        text: "x".to_owned(),
    });
    let deadline = std::time::Instant::now() + TIMEOUT;
    while h.state().writing() && std::time::Instant::now() < deadline {
        h.step();
        std::thread::sleep(Duration::from_millis(5));
    }
    let error = h
        .state()
        .error()
        .map(str::to_owned)
        .expect("no error shown");
    assert!(error.contains("grids.csv"), "{error}");
}
