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
    let x0 = h.state().document().setup.lights[0].position[0];
    let field = h
        .get_by_role_and_label(Role::SpinButton, "light x (mm)")
        .rect();
    drag_with(
        &mut h,
        field.center(),
        Vec2::new(30.0, 0.0),
        Modifiers::NONE,
    );
    let x1 = h.state().document().setup.lights[0].position[0];
    assert!(
        (25.0..=60.0).contains(&(x1 - x0)),
        "30 points moved the light {} mm",
        x1 - x0
    );
    drag_with(
        &mut h,
        field.center(),
        Vec2::new(30.0, 0.0),
        Modifiers::SHIFT,
    );
    let x2 = h.state().document().setup.lights[0].position[0];
    assert!(
        (2.5..=6.0).contains(&(x2 - x1)),
        "30 points with Shift moved the light {} mm",
        x2 - x1
    );

    let fov0 = h.state().document().setup.camera.fov_deg;
    let fov = h
        .get_by_role_and_label(Role::SpinButton, "field of view (°)")
        .rect();
    drag_with(&mut h, fov.center(), Vec2::new(28.0, 0.0), Modifiers::NONE);
    let fov1 = h.state().document().setup.camera.fov_deg;
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
    let home = h.state().document().setup.camera;
    let view = h.get_by_label("viewport").rect();

    drag_with(
        &mut h,
        view.center(),
        Vec2::new(60.0, 20.0),
        Modifiers::NONE,
    );
    let orbited = h.state().document().setup.camera;
    assert_ne!(orbited.position, home.position, "the drag did not orbit");

    drag_with(
        &mut h,
        view.center(),
        Vec2::new(30.0, 0.0),
        Modifiers::SHIFT,
    );
    let panned = h.state().document().setup.camera;
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
    let dollied = h.state().document().setup.camera;
    assert_ne!(dollied.position, panned.position, "the wheel did not dolly");

    let undo = |h: &mut Viewer| {
        h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
        h.step();
        h.state().document().setup.camera
    };
    assert_eq!(
        undo(&mut h),
        panned,
        "one undo takes back the whole wheel turn"
    );
    assert_eq!(undo(&mut h), orbited, "the next takes back the pan");
    assert_eq!(undo(&mut h), home, "and the next the orbit");

    // Away again, then Reset camera in the View menu (Home does the same).
    drag_with(
        &mut h,
        view.center(),
        Vec2::new(-80.0, 0.0),
        Modifiers::NONE,
    );
    assert_ne!(h.state().document().setup.camera, home);
    h.get_by_label("View").click();
    h.run_steps(2);
    h.get_by_role_and_label(Role::Button, "Reset camera Home")
        .click();
    h.run_steps(2);
    assert_eq!(
        h.state().document().setup.camera,
        home,
        "Reset camera did not return home"
    );
    let moved = undo(&mut h);
    assert_ne!(moved, home, "Ctrl+Z did not undo Reset camera");
    h.key_press(egui::Key::Home);
    h.run_steps(2);
    assert_eq!(
        h.state().document().setup.camera,
        home,
        "Home did not reset the camera"
    );
}

/// An orbit turns about the surface point where the drag started (shown while dragging), not
/// about the look-at point: the eye keeps its distance from that point.
#[test]
fn orbit_turns_about_the_surface_point_under_the_cursor() {
    let mut h = viewer();
    let before = h.state().document().setup.camera;
    let view = h.get_by_label("viewport").rect();
    // The left (red) wall, well off the view's axis.
    let from = view.lerp_inside(Vec2::new(0.1, 0.5));
    h.hover_at(from);
    h.drag_at(from);
    h.step();
    h.hover_at(from + Vec2::new(20.0, 0.0));
    h.step();
    let pivot = h.state().orbit_pivot().expect("no pivot while orbiting");
    let look_at = glam::Vec3::from(before.look_at);
    assert!(
        pivot.distance(look_at) > 50.0,
        "the pivot {pivot} is the look-at point {look_at}"
    );
    // The box is drawn left-handed: its red wall, on the left of the picture, is at x = 556.
    let b = h.state().document().scene.bounds;
    assert!(
        (pivot.x - b.min.x).abs().min((pivot.x - b.max.x).abs()) < 30.0,
        "the pivot {pivot} is not on the left wall"
    );
    for k in 2..=4 {
        h.hover_at(from + Vec2::new(20.0 * k as f32, 0.0));
        h.step();
    }
    h.drop_at(from + Vec2::new(80.0, 0.0));
    h.step();
    assert!(
        h.state().orbit_pivot().is_none(),
        "the pivot outlives the drag"
    );
    let after = h.state().document().setup.camera;
    let eye = |c: &tracer_core::scene::Camera| glam::Vec3::from(c.position);
    assert!(
        (eye(&after).distance(pivot) - eye(&before).distance(pivot)).abs()
            < 0.01 * eye(&before).distance(pivot),
        "the eye did not keep its distance from the pivot"
    );
    assert_ne!(
        after.look_at, before.look_at,
        "the look-at point turned with the view"
    );
}

const TIMEOUT: std::time::Duration = std::time::Duration::from_secs(15);

fn scratch_dir(test: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("rough-{test}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `text` as `dir/name` and opens it in the viewer; returns its path.
fn open_scene(h: &mut Viewer, dir: &std::path::Path, name: &str, text: &str) -> std::path::PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    h.state_mut().open_path(&path);
    h.state_mut().finish_loading_blocking(TIMEOUT);
    h.run_steps(2);
    path
}

/// Steps until `done` holds (or fails after TIMEOUT).
fn step_until(h: &mut Viewer, what: &str, done: impl Fn(&RaygineApp) -> bool) {
    let deadline = std::time::Instant::now() + TIMEOUT;
    while !done(h.state()) {
        assert!(std::time::Instant::now() < deadline, "timed out: {what}");
        h.step();
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
}

/// A 1 m x 1 m floor (two triangles) with an OBJ group name.
const FLOOR_OBJ: &str = "g floor\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3\nf 1 3 4\n";

/// 100 cd over the lower hemisphere from a 0.1 m luminous opening (units: metres).
const DOWN_IES: &str =
    "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0\n100 100 100\n";

/// Every load note is in View > Notes, in full, with the sidecar's file and line; the banner
/// points there instead of at a terminal.
#[test]
fn the_notes_window_lists_every_warning_with_file_and_line() {
    let mut h = viewer();
    let dir = scratch_dir("notes");
    let scene = dir.join("floor.obj");
    std::fs::write(&scene, FLOOR_OBJ).unwrap();
    let hidden: Vec<String> = (1..=6).map(|k| format!("\"missing_part_{k}\"")).collect();
    // Six unknown hidden keys and an unknown material: more than the banner can hold.
    std::fs::write(
        dir.join("floor.raygine.toml"),
        format!(
            "unit = \"m\"\nhidden = [{}]\n\n[materials.nothing_here]\nkd = [0.5, 0.5, 0.5]\n",
            hidden.join(", ")
        ),
    )
    .unwrap();
    h.state_mut().open_path(&scene);
    h.state_mut().finish_loading_blocking(TIMEOUT);
    h.run_steps(2);
    let notes = h.state().document().warnings.clone();
    assert!(notes.len() >= 7, "{notes:?}");
    let notice = h.state().notice().map(str::to_owned).unwrap_or_default();
    assert!(notice.contains("View > Notes"), "{notice}");
    assert!(!notice.contains("terminal"), "{notice}");
    assert!(
        notes.iter().any(|n| n.ends_with(
            "floor.raygine.toml:4: material nothing_here: the scene has no such brep or part"
        )),
        "{notes:?}"
    );
    assert!(
        notes
            .iter()
            .any(|n| n.contains("floor.raygine.toml:2: hidden missing_part_6")),
        "{notes:?}"
    );

    h.get_by_label("View").click();
    h.run_steps(2);
    h.get_by_label_contains("Notes (").click();
    h.run_steps(2);
    assert!(h.query_by_label_contains("Notes on this scene").is_some());
    for note in &notes {
        assert!(
            h.query_by_label(note).is_some(),
            "the Notes window does not show {note}"
        );
    }
}

/// The side panel opens at its top when a scene opens, wherever it was scrolled to.
#[test]
fn the_side_panel_opens_at_the_top() {
    let mut h = viewer();
    let top = h.get_by_label("Lights").rect().top();
    let panel_point = Pos2::new(150.0, 300.0);
    h.hover_at(panel_point);
    for _ in 0..10 {
        h.event(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Point,
            delta: Vec2::new(0.0, -200.0),
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Unknown,
            modifiers: Modifiers::NONE,
        });
        h.step();
    }
    h.run_steps(10);
    let scrolled = h.get_by_label("Lights").rect().top();
    assert!(
        scrolled < top - 100.0,
        "the panel did not scroll: {top} -> {scrolled}"
    );
    h.get_by_label("File").click();
    h.run_steps(2);
    h.get_by_label("Open built-in Cornell box").click();
    h.run_steps(3);
    let reopened = h.get_by_label("Lights").rect().top();
    assert!(
        (reopened - top).abs() < 1.0,
        "the panel opened at {reopened}, not at its top {top}"
    );
}

/// A luminaire added in the viewer whose file gives a luminous shape raygine does not draw (a
/// sphere) is warned about at once, named as the panel names it (Light 2), also in the Notes.
#[test]
fn adding_a_luminaire_with_an_unsupported_shape_warns_at_once_naming_the_light() {
    let mut h = viewer();
    let ies = scratch_dir("near").join("down.ies");
    std::fs::write(&ies, DOWN_IES.replace("0.1 0.1 0\n", "-0.1 -0.1 -0.1\n")).unwrap();
    h.state_mut().set_luminaire_path(&ies.display().to_string());
    h.step();
    h.get_by_role_and_label(Role::Button, "Add luminaire")
        .click();
    step_until(&mut h, "the luminaire", |app| {
        app.document().setup.lights.len() == 2
    });
    let notice = h.state().notice().map(str::to_owned).unwrap_or_default();
    assert!(
        notice.starts_with("Light 2: ") && notice.contains("drawn as a point"),
        "{notice}"
    );
    assert!(h.state().document().warnings.contains(&notice));
    // Its polar diagram names both planes and the peak, in cd.
    h.run_steps(2);
    assert!(h.query_by_label_contains("C0-C180").is_some());
    assert!(h.query_by_label_contains("C90-C270").is_some());
    assert!(h.query_by_label_contains("peak 100 cd").is_some());
    // One undo takes the luminaire away again.
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.step();
    assert_eq!(h.state().document().setup.lights.len(), 1);
}

/// A saved sidecar has no float noise and names a luminaire beside it by a relative path, so
/// the folder can move; it reads back to the same luminaire.
#[test]
fn the_saved_sidecar_is_tidy_and_its_luminaire_path_relative() {
    let mut h = viewer();
    let dir = scratch_dir("tidy");
    let scene = dir.join("floor.obj");
    std::fs::write(&scene, FLOOR_OBJ).unwrap();
    std::fs::create_dir_all(dir.join("lamps")).unwrap();
    let ies = dir.join("lamps").join("down.ies");
    std::fs::write(&ies, DOWN_IES).unwrap();
    h.state_mut().open_path(&scene);
    h.state_mut().finish_loading_blocking(TIMEOUT);
    h.step();
    h.state_mut().set_luminaire_path(&ies.display().to_string());
    h.step();
    h.get_by_role_and_label(Role::Button, "Add luminaire")
        .click();
    step_until(&mut h, "the luminaire", |app| {
        app.document().setup.lights.len() == 2
    });
    // A value with f32 noise, and a negative zero, as edits leave them.
    h.state_mut().setup_mut().materials[0].kd = [0.630_000_3, 0.065_000_004, 0.049_999_982];
    h.state_mut().setup_mut().lights[1].position[0] = -0.0;
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::S);
    h.step();
    step_until(&mut h, "the sidecar write", |app| !app.writing());
    let text = std::fs::read_to_string(dir.join("floor.raygine.toml")).unwrap();
    assert!(text.contains("file = \"lamps/down.ies\""), "{text}");
    assert!(text.contains("kd = [0.63, 0.065, 0.05]"), "{text}");
    assert!(!text.contains("-0.0"), "{text}");
    assert!(!text.contains(&dir.display().to_string()), "{text}");
    let loaded = tracer_core::scene::load(&scene, &tracer_core::scene::LoadOptions::default())
        .expect("the saved sidecar reads back");
    assert_eq!(loaded.setup.lights.len(), 2);
    assert_eq!(
        loaded.setup.lights[1].tag(),
        tracer_core::scene::KindTag::Luminaire
    );
}

/// The built-in box's saved settings open again from File > Open (or a drop): the box with its
/// sidecar, the camera and lights as saved.
#[test]
fn a_saved_box_sidecar_opens_in_the_viewer() {
    let mut h = viewer();
    let dir = scratch_dir("box-sidecar");
    let path = dir.join("my_box.raygine.toml");
    h.state_mut().setup_mut().camera.fov_deg = 25.0;
    *h.state_mut().setup_mut().lights[0]
        .intensity_cd_mut()
        .expect("a point light") = 321.0;
    let ctx = h.state().context().clone();
    h.state_mut().save_sidecar(&ctx, path.clone());
    step_until(&mut h, "the sidecar write", |app| !app.writing());
    // Back to the plain box, then open the saved settings.
    h.state_mut().request(raygine::unsaved::Switch::Builtin);
    h.run_steps(2);
    assert_eq!(
        h.state().document().setup.lights[0].intensity_cd(),
        Some(100.0)
    );
    h.state_mut().open_path(&path);
    h.state_mut().finish_loading_blocking(TIMEOUT);
    h.run_steps(2);
    let app = h.state();
    assert!(app.error().is_none(), "{:?}", app.error());
    assert_eq!(app.document().path, None, "the box has no scene file");
    assert_eq!(app.document().setup.camera.fov_deg, 25.0);
    assert_eq!(app.document().setup.lights[0].intensity_cd(), Some(321.0));
}

/// A tent 6 units across in an OBJ (millimetres unless told): the panel says it is tiny in mm
/// and offers metres in one click; its default key light shows digits, not "0 cd", and is not
/// flagged as outside the scene.
#[test]
fn a_small_object_offers_another_unit_in_one_click() {
    let mut h = viewer();
    let dir = scratch_dir("tiny");
    open_scene(
        &mut h,
        &dir,
        "tent.obj",
        "v -3 0 -3\nv 3 0 -3\nv 3 0 3\nv -3 0 3\nv 0 2 0\nf 1 2 3\nf 1 3 4\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n",
    );
    assert_eq!(
        h.state().document().setup.unit,
        tracer_core::scene::LengthUnit::Mm
    );
    assert!(
        h.query_by_label_contains("written in m?").is_some(),
        "no unit hint in the panel"
    );
    assert!(h.query_by_label("outside the scene's bounds").is_none());
    assert!(h.query_by_label_contains("L1 0 cd").is_none());
    h.get_by_role_and_label(Role::Button, "Use m").click();
    h.step();
    h.state_mut().finish_loading_blocking(TIMEOUT);
    h.run_steps(2);
    assert_eq!(
        h.state().document().setup.unit,
        tracer_core::scene::LengthUnit::M
    );
    assert!(h.query_by_label_contains("written in").is_none());
    assert!(h.query_by_label_contains("m across").is_some());
}

/// The box's work plane, a quarter up, passes through both blocks: the points inside them are
/// found (each reads 0 lx), counted in the panel and left out of the statistics.
#[test]
fn grid_points_inside_objects_are_counted_and_left_out() {
    let mut h = viewer();
    for group in ["Lights", "Camera", "Materials"] {
        h.get_by_label(group).click();
        h.step();
    }
    h.get_by_label("Measure").click();
    h.run_steps(2);
    // A denser plane than the default's 4 x 4, so each block holds several points.
    h.get_by_role_and_label(Role::Button, "Add work plane")
        .click();
    h.step();
    let mut g = h.state().document().setup.grids[0].clone();
    (g.nu, g.nv) = (12, 12);
    h.state_mut().setup_mut().grids[0] = g;
    step_until(&mut h, "the readings", |app| {
        app.measure()
            .readings()
            .is_some_and(|r| r.results.first().is_some_and(|g| g.points.len() == 144))
    });
    let r = h.state().measure().readings().unwrap().results[0].clone();
    let buried = r.buried_count();
    assert!(
        (10..=50).contains(&buried),
        "{buried} of 144 points inside objects"
    );
    for p in r.points.iter().filter(|p| p.buried) {
        assert!(
            p.illuminance_lx < 1e-9,
            "a point inside a block reads {} lx",
            p.illuminance_lx
        );
    }
    // Eavg is the mean of the measured points only (in direct light, points in the blocks'
    // shadows read 0 lx and stay in: they are real readings).
    let s = r.statistics();
    let lit: Vec<f64> = r
        .points
        .iter()
        .filter(|p| !p.buried)
        .map(|p| p.illuminance_lx)
        .collect();
    let mean = lit.iter().sum::<f64>() / lit.len() as f64;
    assert!(
        (s.e_avg_lx - mean).abs() < 1e-9 * mean,
        "{} vs {mean}",
        s.e_avg_lx
    );
    assert!(
        s.e_avg_lx > r.mean_lx(),
        "the buried zeros are still in the mean"
    );
    h.run_steps(2);
    assert!(
        h.query_by_label_contains(&format!("{buried} of 144 points inside objects"))
            .is_some()
    );
}

/// View > Ground plane puts a grey floor under a lone object: a surface listed like any other,
/// rendered, no unsaved edit, not written to the sidecar; undo still works across it, and it
/// comes off again.
#[test]
fn a_ground_plane_goes_under_a_lone_object() {
    let mut h = viewer();
    let dir = scratch_dir("ground");
    open_scene(
        &mut h,
        &dir,
        "tent.obj",
        "v -3 1 -3\nv 3 1 -3\nv 3 1 3\nv -3 1 3\nv 0 3 0\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n",
    );
    let slots = h.state().document().scene.slots.len();
    // An edit before, to undo after.
    h.state_mut().setup_mut().camera.fov_deg = 30.0;
    h.run_steps(2);
    h.get_by_label("View").click();
    h.run_steps(2);
    h.get_by_label("Ground plane").click();
    h.run_steps(3);
    let app = h.state();
    assert!(app.document().scene.has_ground());
    assert_eq!(app.document().scene.slots.len(), slots + 1);
    assert_eq!(app.document().setup.materials.len(), slots + 1);
    assert_eq!(app.document().setup.materials[slots].kd, [0.2; 3]);
    assert!(
        app.worker().current().unwrap().scene.has_ground(),
        "not rendered"
    );
    assert!(h.query_by_label("ground_plane").is_some(), "not listed");
    // The plane lies under the object: straight down from above its corner, outside it.
    let b = app.document().scene.bounds;
    let down = tracer_core::geometry::Ray::new(
        glam::Vec3::new(b.max.x + 1.0, b.max.y, b.max.z + 1.0),
        glam::Vec3::NEG_Y,
    );
    let hit = app
        .document()
        .scene
        .intersect(&down)
        .expect("no ground under the object");
    assert!((b.max.y - hit.t - b.min.y).abs() < 1e-4);
    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().document().setup.materials.len(), slots + 1);
    let ctx = h.state().context().clone();
    let side = dir.join("tent.raygine.toml");
    h.state_mut().save_sidecar(&ctx, side.clone());
    step_until(&mut h, "the sidecar write", |app| !app.writing());
    assert!(
        !std::fs::read_to_string(&side)
            .unwrap()
            .contains("ground_plane")
    );
    h.get_by_label("View").click();
    h.run_steps(2);
    h.get_by_label("Ground plane").click();
    h.run_steps(2);
    assert!(!h.state().document().scene.has_ground());
    assert_eq!(h.state().document().setup.materials.len(), slots);
}

/// Many lights are listed one line each under a summary, and only the selected one is edited:
/// clicking a line moves the editor to that light.
#[test]
fn many_lights_are_listed_and_one_is_edited() {
    let mut h = viewer();
    h.run_steps(2);
    for _ in 0..19 {
        h.state_mut().apply(raygine::command::Command::Edit(
            raygine::command::Edit::AddLight,
        ));
    }
    step_until(&mut h, "20 lights", |app| {
        app.document().setup.lights.len() == 20
    });
    h.run_steps(2);
    assert!(
        h.query_by_label_contains("20 lights: 20 point, 0 spot, 0 luminaire")
            .is_some(),
        "no summary of the lights"
    );
    // The editor shows one light (its "Remove" button), not twenty.
    assert_eq!(
        h.query_all_by_label("Remove").count(),
        1,
        "more than one light edited"
    );
    h.get_by_label_contains("Light 3: point").click();
    h.run_steps(2);
    assert!(
        h.query_by_label("Light 3").is_some(),
        "the editor did not move to light 3"
    );
}

/// The kind menu turns the box's point light into a spot and back: the intensity stays, the
/// spot gets its cone sliders, and the model holds a spot's data only while it is a spot.
#[test]
fn a_point_light_becomes_a_spot_and_back() {
    use tracer_core::scene::{KindTag, LightKind};
    let mut h = viewer();
    h.run_steps(2);
    let before = h.state().document().setup.lights[0].intensity_cd();
    h.get_by_label("kind").click();
    h.run_steps(2);
    h.get_by_label("spot").click();
    h.run_steps(3);
    let light = h.state().document().setup.lights[0].clone();
    let LightKind::Spot(spot) = light.kind else {
        panic!("not a spot: {light:?}");
    };
    assert_eq!(Some(spot.intensity_cd), before);
    assert!(spot.cone_deg > 0.0 && spot.falloff_deg >= spot.cone_deg);
    assert!(
        h.query_all_by_label_contains("cone (°)").count() > 0,
        "no cone slider for the spot"
    );
    h.get_by_label("kind").click();
    h.run_steps(2);
    h.get_by_label("point").click();
    h.run_steps(3);
    let light = &h.state().document().setup.lights[0];
    assert_eq!(light.tag(), KindTag::Point);
    assert_eq!(light.intensity_cd(), before);
    assert_eq!(h.query_all_by_label_contains("cone (°)").count(), 0);
}

/// A CI run failed once when the film was replaced (a new resolution scale) between the
/// viewer taking the changed tiles and drawing them: it read a tile of the old, larger film
/// from the new one. Rescaling and resizing while tiles arrive must never do that.
#[test]
fn rescaling_and_resizing_while_tiles_arrive_never_reads_a_stale_tile() {
    let mut h = super::box_viewer(Vec2::new(640.0, 420.0), IntegratorKind::Direct, 64, 1.0);
    let end = std::time::Instant::now() + std::time::Duration::from_secs(5);
    let mut round = 0_u32;
    while std::time::Instant::now() < end {
        round += 1;
        let scale = [1.0, 0.5, 0.75, 0.3][(round % 4) as usize];
        h.state_mut().render_prefs_mut().resolution_scale = scale;
        if round.is_multiple_of(5) {
            let grow = if round.is_multiple_of(10) { 80.0 } else { 0.0 };
            h.set_size(Vec2::new(640.0 + grow, 420.0 + grow / 2.0));
        }
        for _ in 0..(1 + round % 3) {
            h.run_steps(1);
            std::thread::sleep(std::time::Duration::from_millis((round % 4) as u64 * 3));
        }
    }
    assert!(round > 20, "only {round} rounds in 5 s");
    assert!(h.state().worker().with_film(|f| f.is_some()));
}
