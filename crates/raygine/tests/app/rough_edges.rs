//! The rough edges a new user met (issue "The viewer and command line as a new user finds
//! them"): drag speeds, camera undo and reset, the panel's scroll, and the rest, each through
//! the widgets a user touches.

use egui::accesskit::Role;
use egui::{Modifiers, Pos2, Vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use raygine::app::RaygineApp;
use tracer_core::integrator::IntegratorKind;

type Viewer = Harness<'static, RaygineApp>;

fn viewer() -> Viewer {
    let mut h = super::box_viewer(Vec2::new(960.0, 640.0), IntegratorKind::Direct, 4, 0.25);
    h.run_steps(3);
    h
}

/// A press at `from`, moves in four steps to `from + by` with `modifiers` held, a release.
fn drag_with(h: &mut Viewer, from: Pos2, by: Vec2, modifiers: Modifiers) {
    h.event(egui::Event::ModifiersChanged(modifiers));
    h.hover_at(from);
    h.event(egui::Event::PointerButton {
        pos: from,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers,
    });
    h.step();
    for k in 1..=4 {
        h.hover_at(from + by * (k as f32 / 4.0));
        h.step();
    }
    h.event(egui::Event::PointerButton {
        pos: from + by,
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers,
    });
    h.step();
    h.event(egui::Event::ModifiersChanged(Modifiers::NONE));
    h.remove_cursor();
    h.step();
}

/// 30 points of drag move the box's light about 40 mm (the box is 556 mm wide), with Shift a
/// tenth of that; 28 points move the field of view about 6°, not from 39° to 85°.
#[test]
fn drags_move_lengths_by_the_scenes_size_and_shift_is_fine() {
    let mut h = viewer();
    let x0 = h.state().doc.setup.lights[0].position[0];
    let field = h.get_by_role_and_label(Role::SpinButton, "light x (mm)").rect();
    drag_with(&mut h, field.center(), Vec2::new(30.0, 0.0), Modifiers::NONE);
    let x1 = h.state().doc.setup.lights[0].position[0];
    assert!(
        (25.0..=60.0).contains(&(x1 - x0)),
        "30 points moved the light {} mm",
        x1 - x0
    );
    drag_with(&mut h, field.center(), Vec2::new(30.0, 0.0), Modifiers::SHIFT);
    let x2 = h.state().doc.setup.lights[0].position[0];
    assert!(
        (2.5..=6.0).contains(&(x2 - x1)),
        "30 points with Shift moved the light {} mm",
        x2 - x1
    );

    let fov0 = h.state().doc.setup.camera.fov_deg;
    let fov = h.get_by_role_and_label(Role::SpinButton, "field of view (°)").rect();
    drag_with(&mut h, fov.center(), Vec2::new(28.0, 0.0), Modifiers::NONE);
    let fov1 = h.state().doc.setup.camera.fov_deg;
    assert!(
        (4.0..=8.0).contains(&(fov1 - fov0)),
        "28 points moved the field of view from {fov0}° to {fov1}°"
    );
}

/// Runs frames until the wheel has rested long enough for its dolly to be one undo step.
fn rest(h: &mut Viewer) {
    for _ in 0..5 {
        std::thread::sleep(std::time::Duration::from_millis(120));
        h.step();
    }
}

/// A finished orbit, pan or wheel dolly is one undo step each; Reset camera returns to the
/// scene's own camera and is itself undone by Ctrl+Z.
#[test]
fn camera_moves_undo_one_gesture_at_a_time_and_reset_camera_returns_home() {
    let mut h = viewer();
    let home = h.state().doc.setup.camera;
    let view = h.get_by_label("viewport").rect();

    drag_with(&mut h, view.center(), Vec2::new(60.0, 20.0), Modifiers::NONE);
    let orbited = h.state().doc.setup.camera;
    assert_ne!(orbited.position, home.position, "the drag did not orbit");
    assert_eq!(orbited.look_at, home.look_at, "an orbit keeps the look-at point");

    drag_with(&mut h, view.center(), Vec2::new(30.0, 0.0), Modifiers::SHIFT);
    let panned = h.state().doc.setup.camera;
    assert_ne!(panned.look_at, orbited.look_at, "Shift+drag did not pan");

    h.hover_at(view.center());
    for _ in 0..6 {
        h.event(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Point,
            delta: Vec2::new(0.0, 40.0),
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Unknown,
            modifiers: Modifiers::NONE,
        });
        h.step();
    }
    rest(&mut h);
    let dollied = h.state().doc.setup.camera;
    assert_ne!(dollied.position, panned.position, "the wheel did not dolly");

    let undo = |h: &mut Viewer| {
        h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
        h.step();
        h.state().doc.setup.camera
    };
    assert_eq!(undo(&mut h), panned, "one undo takes back the whole wheel turn");
    assert_eq!(undo(&mut h), orbited, "the next takes back the pan");
    assert_eq!(undo(&mut h), home, "and the next the orbit");

    // Away again, then Reset camera in the View menu (Home does the same).
    drag_with(&mut h, view.center(), Vec2::new(-80.0, 0.0), Modifiers::NONE);
    assert_ne!(h.state().doc.setup.camera, home);
    h.get_by_label("View").click();
    h.step();
    h.get_by_label("Reset camera").click();
    h.run_steps(2);
    assert_eq!(h.state().doc.setup.camera, home, "Reset camera did not return home");
    let moved = undo(&mut h);
    assert_ne!(moved, home, "Ctrl+Z did not undo Reset camera");
    h.key_press(egui::Key::Home);
    h.run_steps(2);
    assert_eq!(h.state().doc.setup.camera, home, "Home did not reset the camera");
}
