//! UI tests that drive the real viewer (`RaygineApp`) headlessly with egui_kittest.
//!
//! Real render threads run during these tests. A test never sleeps for a fixed time to "let the
//! render finish": it steps frames until the engine reports the current generation finished and
//! the texture shows it (`settle`), with a timeout.
//!
//! A `TextureMirror` stands in for the GPU: it applies every texture upload the app makes (whole
//! textures and the partial tile updates), so the tests can check what the viewport would show.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use egui::accesskit::Role;
use egui::{ColorImage, Event, ImageData, Key, Modifiers, PointerButton, Pos2, TextureId, Vec2};
use egui_kittest::kittest::Queryable;
use egui_kittest::{Harness, TestRenderer};
use glam::Vec3;
use raygine::app::{AppOptions, RaygineApp};
use raygine::render_worker::texture_rect;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tracer_core::integrator::IntegratorKind;
use tracer_core::scene::framing_camera;

/// Samples per pixel the tests render to: enough to be a real progressive render, fast in debug.
const TEST_SPP: u32 = 4;
/// Longest wait for a render, a load or a write.
const TIMEOUT: Duration = Duration::from_secs(15);
const LIGHT_X: &str = "light x (mm)";
const EXPOSURE: &str = "exposure (stops)";

// ---------------------------------------------------------------------------------------------
// Harness and helpers
// ---------------------------------------------------------------------------------------------

/// A headless stand-in for the GPU: the latest content of every texture.
#[derive(Clone, Default)]
struct TextureMirror(Arc<Mutex<HashMap<TextureId, ColorImage>>>);

impl TestRenderer for TextureMirror {
    fn handle_delta(&mut self, delta: &mut egui::TexturesDelta) {
        let mut textures = self.0.lock().unwrap();
        for (id, deltas) in delta.set.drain() {
            for d in deltas {
                let ImageData::Color(patch) = &d.image;
                match d.pos {
                    None => {
                        textures.insert(id, (**patch).clone());
                    }
                    Some([x0, y0]) => {
                        let texture = textures
                            .get_mut(&id)
                            .expect("a partial update of a texture that was never set");
                        let [w, h] = patch.size;
                        for y in 0..h {
                            let dst = (y0 + y) * texture.size[0] + x0;
                            texture.pixels[dst..dst + w]
                                .copy_from_slice(&patch.pixels[y * w..(y + 1) * w]);
                        }
                    }
                }
            }
        }
        for id in delta.free.drain() {
            textures.remove(&id);
        }
    }
}

impl TextureMirror {
    /// The film texture: the one texture of the film's size that is not the font atlas.
    fn film(&self, size: [usize; 2]) -> ColorImage {
        let textures = self.0.lock().unwrap();
        let found: Vec<&ColorImage> = textures
            .iter()
            .filter(|(id, t)| **id != TextureId::default() && t.size == size)
            .map(|(_, t)| t)
            .collect();
        assert_eq!(found.len(), 1, "expected one film texture of {size:?}");
        found[0].clone()
    }
}

type Viewer = Harness<'static, RaygineApp>;

/// The real app in a 960x640 window, built-in Cornell box, 2 render threads, fast sample target.
fn viewer() -> (Viewer, TextureMirror) {
    let mirror = TextureMirror::default();
    let mut h = Harness::builder()
        .with_size(Vec2::new(960.0, 640.0))
        // Checked once, explicitly, in `every_input_widget_has_a_name`.
        .with_accessibility_check(false)
        .renderer(mirror.clone())
        .build_eframe(|cc| {
            RaygineApp::new(
                cc,
                AppOptions {
                    scene: None,
                    threads: 2,
                    ignore_last_scene: true,
                    unit: None,
                },
            )
            .unwrap()
        });
    h.state_mut().render_prefs_mut().target_spp = TEST_SPP;
    // UI mechanics are tested on the cheaper direct mode; `starts_in_global_illumination`
    // covers the default.
    h.state_mut().render_prefs_mut().integrator = IntegratorKind::Direct;
    settle(&mut h);
    (h, mirror)
}

/// The viewer starts in global-illumination mode, and its film is brighter than direct light's
/// (light reflected by the walls reaches the ceiling, which direct light misses but for the
/// spot above the lamp).
#[test]
fn starts_in_global_illumination() {
    let (mut h, _mirror) = viewer();
    let mean = |h: &Viewer| {
        h.state().worker().with_film(|f| {
            let f = f.unwrap();
            (0..f.accum.len())
                .map(|i| f64::from(tracer_core::scene::luminance(f.shown_rgb(i))))
                .sum::<f64>()
        })
    };
    let direct = mean(&h);
    assert_eq!(
        RaygineApp::default_integrator(),
        IntegratorKind::Bidirectional,
        "a new user gets global illumination (bidirectional)"
    );
    h.state_mut().render_prefs_mut().integrator = IntegratorKind::Bidirectional;
    h.state_mut().render_prefs_mut().target_spp = 1;
    settle(&mut h);
    let gi = mean(&h);
    assert!(gi > 1.3 * direct, "GI {gi} vs direct {direct}");
}

fn render_done(app: &RaygineApp) -> bool {
    let w = &app.worker();
    let s = w.stats();
    !app.loading()
        && w.current().is_some()
        && s.finished
        && s.generation == w.generation()
        && w.shown_generation() == w.generation()
}

/// Steps frames until the current generation is finished and a frame after that has uploaded
/// its last tiles, or panics after [`TIMEOUT`].
fn settle(h: &mut Viewer) {
    let deadline = Instant::now() + TIMEOUT;
    loop {
        let done_before = render_done(h.state());
        h.step();
        if done_before && render_done(h.state()) {
            return;
        }
        assert!(Instant::now() < deadline, "the render did not finish");
        h.state().worker().wait_finished(Duration::from_millis(20));
        std::thread::sleep(Duration::from_millis(2));
    }
}

/// Steps frames (the app polls its background work each frame) until `done` holds.
fn step_until(h: &mut Viewer, what: &str, done: impl Fn(&RaygineApp) -> bool) {
    let deadline = Instant::now() + TIMEOUT;
    while !done(h.state()) {
        assert!(Instant::now() < deadline, "timed out waiting for {what}");
        h.step();
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// The film as shown (linear cd/m² per channel), with its size.
fn film_rgb(app: &RaygineApp) -> ([usize; 2], Vec<Vec3>) {
    app.worker()
        .with_film(|f| {
            let f = f?;
            let n = f.width() as usize * f.height() as usize;
            let rgb = (0..n).map(|i| f.shown_rgb(i)).collect();
            Some(([f.width() as usize, f.height() as usize], rgb))
        })
        .expect("no film yet")
}

/// The film through the app's current display mapping (and the backdrop), as the texture should
/// hold it.
fn expected_texture(app: &RaygineApp) -> ColorImage {
    assert!(!app.display().auto_exposure && !app.false_colour_on());
    let exposure = app.display().exposure_stops;
    app.worker()
        .with_film(|f| f.map(|f| texture_rect(f, app.display(), exposure, None, None, None)))
        .expect("no film yet")
}

/// Fraction of pixels whose colour differs by more than 1 % (relative) between two films.
/// The largest difference between two 8-bit images, in code values.
fn max_code_diff(a: &[u8], b: &[u8]) -> u8 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| x.abs_diff(*y))
        .max()
        .unwrap_or(0)
}

fn changed_fraction(a: &[Vec3], b: &[Vec3]) -> f64 {
    assert_eq!(a.len(), b.len());
    let changed = a
        .iter()
        .zip(b)
        .filter(|(p, q)| (**p - **q).abs().max_element() > 0.01 * p.max(**q).max_element() + 1e-6)
        .count();
    changed as f64 / a.len() as f64
}

fn light_x(app: &RaygineApp) -> f32 {
    app.document().setup.lights[0].position[0]
}

/// A directory of its own for one test under cargo's scratch space.
fn scratch_dir(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("viewer-{test}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A small Lumicept scene with two breps, "floor" and "lamp_shade". `floor_triangle` is the
/// floor's second triangle (a bad vertex index makes the file broken).
fn two_brep_scene(floor_triangle: &str) -> String {
    format!(
        ";; written by raygine's UI tests\n\
         define breps floor\n\
         vertices 4\n\
         0 0 0\n\
         1000 0 0\n\
         1000 0 -1000\n\
         0 0 -1000\n\
         triangles 2\n\
         0 1 2\n\
         {floor_triangle}\n\
         parts 1\n\
         0 0\n\
         enddef\n\
         \n\
         define breps lamp_shade\n\
         vertices 3\n\
         400 800 -400\n\
         600 800 -400\n\
         500 800 -600\n\
         triangles 1\n\
         0 1 2\n\
         parts 1\n\
         0\n\
         enddef\n\
         \n\
         set breps floor\n\
         rotation 0 0 0\n\
         translation 0 0 0\n\
         scale 1 1 1\n\
         enddef\n\
         set breps lamp_shade\n\
         rotation 0 0 0\n\
         translation 0 0 0\n\
         scale 1 1 1\n\
         enddef\n"
    )
}

fn brep_names(app: &RaygineApp) -> Vec<String> {
    app.document()
        .scene
        .breps
        .iter()
        .map(|b| b.name.clone())
        .collect()
}

/// Asserts that the side panel lists each brep name.
fn assert_listed(h: &Viewer, names: &[&str]) {
    for name in names {
        assert!(
            h.query_by_label(name).is_some(),
            "the side panel does not list brep {name}"
        );
    }
}

/// Loads `path` through the app's own loader (as a dropped file or a recent file would).
fn open(h: &mut Viewer, path: &Path) {
    h.state_mut().open_path(path);
    h.state_mut().finish_loading_blocking(TIMEOUT);
    assert!(!h.state().loading(), "loading {} hung", path.display());
    h.state_mut().render_prefs_mut().target_spp = TEST_SPP;
    // UI mechanics are tested on the cheaper direct mode; `starts_in_global_illumination`
    // covers the default.
    h.state_mut().render_prefs_mut().integrator = IntegratorKind::Direct;
    settle(h);
}

/// A primary-button click at `pos` without moving (egui sees a click, not a drag).
fn click_at(h: &mut Viewer, pos: Pos2) {
    h.hover_at(pos);
    for pressed in [true, false] {
        h.event(Event::PointerButton {
            pos,
            button: PointerButton::Primary,
            pressed,
            modifiers: Modifiers::NONE,
        });
    }
    h.step();
}

/// A primary-button drag from `from` by `by`, in a few moves, released at the end.
fn drag(h: &mut Viewer, from: Pos2, by: Vec2) {
    h.hover_at(from);
    h.drag_at(from);
    h.step();
    for k in 1..=4 {
        h.hover_at(from + by * (k as f32 / 4.0));
        h.step();
    }
    h.drop_at(from + by);
    h.step();
}

// ---------------------------------------------------------------------------------------------
// Tests
// ---------------------------------------------------------------------------------------------

#[test]
fn dragging_the_light_slider_restarts_the_render_and_changes_the_film() {
    let (mut h, mirror) = viewer();
    let generation = h.state().worker().generation();
    let x0 = light_x(h.state());
    let (size, before) = film_rgb(h.state());
    assert_eq!(mirror.film(size).pixels, expected_texture(h.state()).pixels);

    let slider = h.get_by_role_and_label(Role::SpinButton, LIGHT_X).rect();
    // Left: the light moves towards the green wall and stays inside the box.
    drag(&mut h, slider.center(), Vec2::new(-30.0, 0.0));
    let x1 = light_x(h.state());
    assert!(
        (x1 - x0).abs() > 10.0,
        "the drag moved the light from {x0} only to {x1}"
    );

    settle(&mut h);
    let app = h.state();
    assert!(app.worker().generation() > generation, "no new generation");
    let key = app.worker().current().unwrap();
    assert_eq!(key.setup.lights[0].position[0], x1, "renders a stale light");
    let (size_after, after) = film_rgb(app);
    assert_eq!(size, size_after);
    let changed = changed_fraction(&before, &after);
    assert!(
        changed > 0.2,
        "only {:.1} % of pixels changed",
        changed * 1e2
    );
    // The viewport shows the new film through the display mapping.
    assert_eq!(mirror.film(size).pixels, expected_texture(app).pixels);
}

#[test]
fn exposure_remaps_the_texture_without_restarting() {
    let (mut h, mirror) = viewer();
    let generation = h.state().worker().generation();
    let (size, film_before) = film_rgb(h.state());
    let texture_before = mirror.film(size);

    h.get_by_role_and_label(Role::Slider, EXPOSURE)
        .set_value_accesskit(2.0);
    h.run_steps(3);

    let app = h.state();
    assert_eq!(app.display().exposure_stops, 2.0);
    assert_eq!(
        app.worker().generation(),
        generation,
        "exposure restarted the render"
    );
    assert!(app.worker().stats().finished);
    assert_eq!(film_rgb(app).1, film_before, "the film changed");
    let texture_after = mirror.film(size);
    assert_ne!(texture_after.pixels, texture_before.pixels, "no re-map");
    assert_eq!(texture_after.pixels, expected_texture(app).pixels);
}

#[test]
fn opening_a_scene_by_typed_path_lists_its_breps() {
    let (mut h, _mirror) = viewer();
    let path = scratch_dir("open").join("two_breps.shp");
    std::fs::write(&path, two_brep_scene("0 2 3")).unwrap();

    h.key_press_modifiers(Modifiers::COMMAND, Key::O);
    h.step();
    assert!(
        h.state().prompt().is_some(),
        "Ctrl+O did not open the path window"
    );
    let field = h.get_by_role_and_label(Role::TextInput, "Path:");
    field.focus();
    field.type_text(&path.display().to_string());
    h.step();
    h.get_by_role_and_label(Role::Button, "Open").click();
    h.step();
    step_until(&mut h, "the scene to load", |app| !app.loading());
    h.step();

    let app = h.state();
    assert!(app.error().is_none(), "{:?}", app.error());
    assert!(app.prompt().is_none(), "the path window stayed open");
    assert_eq!(app.document().path.as_deref(), Some(path.as_path()));
    assert_eq!(brep_names(app), ["floor", "lamp_shade"]);
    assert_listed(&h, &["floor", "lamp_shade"]);
    assert!(
        h.query_by_label("red_wall").is_none(),
        "the old scene is still listed"
    );
    settle(&mut h);
}

#[test]
fn opening_the_course_cornell_box_lists_its_breps() {
    let Some(path) = raygine_fixtures::shared("scenes/cornell/cornel_box0.shp") else {
        return;
    };
    let (mut h, _mirror) = viewer();
    open(&mut h, &path);
    h.step();
    let names = ["brs_0", "brs_1", "brs_2", "brs_3", "brs_4"];
    assert_eq!(brep_names(h.state()), names);
    assert_listed(&h, &names);
}

#[test]
fn a_broken_file_shows_an_error_and_keeps_the_scene() {
    let (mut h, _mirror) = viewer();
    let dir = scratch_dir("broken");
    let good = dir.join("two_breps.shp");
    std::fs::write(&good, two_brep_scene("0 2 3")).unwrap();
    open(&mut h, &good);
    let scene = Arc::clone(&h.state().document().scene);
    let generation = h.state().worker().generation();

    let broken = dir.join("broken.shp");
    let text = two_brep_scene("0 2 7");
    let bad_line = text.lines().position(|l| l == "0 2 7").unwrap() + 1;
    std::fs::write(&broken, text).unwrap();
    h.state_mut().open_path(&broken);
    h.state_mut().finish_loading_blocking(TIMEOUT);
    h.step();

    let app = h.state();
    let error = app.error().expect("no error shown");
    assert!(
        error.contains("broken.shp"),
        "error without the file: {error}"
    );
    assert!(
        error.contains(&format!("line {bad_line}")),
        "error without line {bad_line}: {error}"
    );
    assert!(
        error.contains("vertex 7"),
        "error without the cause: {error}"
    );
    assert!(
        Arc::ptr_eq(&app.document().scene, &scene),
        "the scene was replaced"
    );
    assert_eq!(app.document().path.as_deref(), Some(good.as_path()));
    assert_eq!(brep_names(app), ["floor", "lamp_shade"]);
    assert_eq!(
        app.worker().generation(),
        generation,
        "the render restarted"
    );
    assert_listed(&h, &["floor", "lamp_shade"]);
}

#[test]
fn opening_the_integra_room_lists_its_twenty_materials() {
    let Some(path) = raygine_fixtures::shared("scenes/ipur-room2/room2.shp") else {
        return;
    };
    let (mut h, _mirror) = viewer();
    // Loaded but not rendered to the end: 11,452 triangles under nine lights take long in a
    // debug build, and the list does not depend on the picture.
    h.state_mut().open_path(&path);
    h.state_mut().finish_loading_blocking(TIMEOUT);
    h.step();
    h.step();
    let app = h.state();
    assert!(app.error().is_none(), "{:?}", app.error());
    assert_eq!(app.document().scene.slots.len(), 20);
    assert_eq!(app.document().setup.lights.len(), 9);
    // Each part with its .atr attribute (the material's name in the bundle) beside it.
    let parts: Vec<String> = (1..=20)
        .map(|i| format!("proom2_{i:04} · a{i:06}"))
        .collect();
    let parts: Vec<&str> = parts.iter().map(String::as_str).collect();
    assert_listed(&h, &parts);
    // The filter narrows the list to what holds its text.
    h.get_by_role_and_label(Role::TextInput, "filter").focus();
    h.step();
    h.get_by_role_and_label(Role::TextInput, "filter")
        .type_text("a000003");
    h.run_steps(2);
    assert_eq!(h.state().part_filter(), "a000003");
    assert!(h.query_by_label("proom2_0003 · a000003").is_some());
    assert!(h.query_by_label("proom2_0004 · a000004").is_none());
}

#[test]
fn a_broken_integra_bundle_shows_file_and_line_and_keeps_the_scene() {
    let (mut h, _mirror) = viewer();
    let dir = scratch_dir("broken_bundle");
    let good = dir.join("two_breps.shp");
    std::fs::write(&good, two_brep_scene("0 2 3")).unwrap();
    open(&mut h, &good);
    let scene = Arc::clone(&h.state().document().scene);

    let room = dir.join("room.shp");
    std::fs::write(&room, two_brep_scene("0 2 3")).unwrap();
    std::fs::create_dir_all(dir.join("room")).unwrap();
    std::fs::write(dir.join("room/room.atr"), "Attr a1\n  kd nope\nenddef\n").unwrap();
    h.state_mut().open_path(&room);
    h.state_mut().finish_loading_blocking(TIMEOUT);
    h.step();

    let app = h.state();
    let error = app.error().expect("no error shown");
    assert!(error.contains("room.atr:2: kd"), "{error}");
    assert!(!error.contains('\n'), "not one line: {error}");
    assert!(
        Arc::ptr_eq(&app.document().scene, &scene),
        "the scene was replaced"
    );
    assert_eq!(app.document().path.as_deref(), Some(good.as_path()));
}

#[test]
fn exported_png_matches_an_independent_render() {
    let (mut h, _mirror) = viewer();
    // A non-default exposure, so the export must apply the display mapping, not a default one.
    h.get_by_role_and_label(Role::Slider, EXPOSURE)
        .set_value_accesskit(1.5);
    h.step();
    settle(&mut h);

    let path = scratch_dir("export").join("view.png");
    let ctx = h.state().context().clone();
    h.state_mut().export_png(&ctx, path.clone());
    step_until(&mut h, "the PNG write", |app| !app.writing());
    let app = h.state();
    assert!(app.error().is_none(), "{:?}", app.error());
    let notice = app.notice().unwrap_or_default();
    assert!(notice.contains("view.png"), "notice: {notice}");

    let key = app.worker().current().unwrap().clone();
    assert_eq!(key.settings.samples_per_pixel, TEST_SPP);
    let (film, _) = tracer_core::render::render(&key.scene, &key.setup, &key.settings);
    let expected = app.display().map_film(&film);
    let png = image::open(&path).unwrap().to_rgba8();
    assert_eq!(
        [png.width(), png.height()],
        [key.settings.width, key.settings.height]
    );
    let worst = max_code_diff(png.as_raw(), &expected);
    assert!(worst <= 1, "the PNG differs by up to {worst} code values");
}

#[test]
fn undo_and_redo_restore_the_light_position() {
    let (mut h, _mirror) = viewer();
    let x0 = light_x(h.state());

    // A typed or assistive-technology value: committed on the next frame (no pointer held).
    h.get_by_role_and_label(Role::SpinButton, LIGHT_X)
        .set_value_accesskit(f64::from(x0) + 120.0);
    h.run_steps(2);
    let x1 = light_x(h.state());
    assert_eq!(x1, x0 + 120.0);

    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    assert_eq!(light_x(h.state()), x0, "Ctrl+Z did not restore the light");
    settle(&mut h);
    let current = h.state().worker().current().unwrap();
    assert_eq!(
        current.setup.lights[0].position[0], x0,
        "renders the undone light"
    );

    h.key_press_modifiers(Modifiers::COMMAND.plus(Modifiers::SHIFT), Key::Z);
    h.step();
    assert_eq!(light_x(h.state()), x1, "Ctrl+Shift+Z did not redo");

    // A whole pointer drag is one step: one undo returns to where the drag started.
    let slider = h.get_by_role_and_label(Role::SpinButton, LIGHT_X).rect();
    drag(
        &mut h,
        slider.center(),
        Vec2::new(slider.width() * 0.25, 0.0),
    );
    assert_ne!(light_x(h.state()), x1);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    assert_eq!(
        light_x(h.state()),
        x1,
        "one undo did not undo the whole drag"
    );
}

#[test]
fn clicking_the_left_wall_selects_its_red_material() {
    let (mut h, _mirror) = viewer();
    assert_eq!(h.state().selected_slot(), None);
    let view = h.get_by_label("viewport").rect();
    // The red wall fills the left part of the picture between the opening and the back wall.
    click_at(&mut h, view.lerp_inside(Vec2::new(0.15, 0.5)));

    let app = h.state();
    let slot = app.selected_slot().expect("the click selected nothing");
    let label = app.document().scene.slot_label(slot);
    assert!(label.starts_with("red_wall"), "selected {label}");
    let kd = app.document().setup.materials[slot as usize].kd;
    assert!(kd[0] > 4.0 * kd[1], "not a red material: {kd:?}");
    h.step();
    assert!(
        h.query_by_label_contains("Material of red_wall").is_some(),
        "the materials panel does not show the selection"
    );
}

#[test]
fn orbit_then_f_frames_the_scene() {
    let (mut h, _mirror) = viewer();
    let start = h.state().document().setup.camera;
    let view = h.get_by_label("viewport").rect();
    drag(&mut h, view.center(), Vec2::new(120.0, 40.0));
    let orbited = h.state().document().setup.camera;
    assert_ne!(orbited, start, "dragging the viewport did not orbit");
    assert_eq!(h.state().selected_slot(), None, "a drag is not a click");

    h.key_press(Key::F);
    h.step();
    let app = h.state();
    let framed = framing_camera(&app.document().scene, orbited.fov_deg);
    assert_eq!(
        app.document().setup.camera,
        framed,
        "F did not frame the scene"
    );
    settle(&mut h);
    let current = h.state().worker().current().unwrap();
    assert_eq!(current.setup.camera, framed, "renders a stale camera");
}

#[test]
fn every_input_widget_has_a_name() {
    let (mut h, _mirror) = viewer();
    // Open the path window too, and select a material so its editors show.
    h.key_press_modifiers(Modifiers::COMMAND, Key::O);
    h.step();
    h.get_by_label("red_wall").click();
    h.run_steps(3);
    let unnamed = h.unnamed_widgets();
    assert!(
        unnamed.is_empty(),
        "unnamed widgets:\n{}",
        unnamed.join("\n")
    );
}

/// The screen positions `scripts/smoke_viewer.sh` clicks and samples hold for the window size the
/// viewer opens with (1400x860 points, 1 pixel per point under Xvfb).
#[test]
fn smoke_script_layout_holds() {
    let mut h = Harness::builder()
        .with_size(Vec2::new(1400.0, 860.0))
        .with_accessibility_check(false)
        .build_eframe(|cc| {
            RaygineApp::new(
                cc,
                AppOptions {
                    scene: None,
                    threads: 1,
                    ignore_last_scene: true,
                    unit: None,
                },
            )
            .unwrap()
        });
    h.step();
    let slider = h.get_by_role_and_label(Role::SpinButton, LIGHT_X).rect();
    let view = h.get_by_label("viewport").rect();
    eprintln!("light x slider {slider:?}, viewport {view:?}");
    // scripts/smoke_viewer.sh: SLIDER_X/SLIDER_Y, PANEL_W and BAR_H.
    assert!(
        slider.contains(Pos2::new(138.0, 175.0)),
        "slider moved: {slider:?}"
    );
    assert!(
        (view.min.x - 378.0).abs() < 12.0,
        "viewport moved: {view:?}"
    );
    assert!((view.min.y - 25.0).abs() < 6.0, "viewport moved: {view:?}");
    assert!(
        (860.0 - view.max.y - 25.0).abs() < 6.0,
        "viewport moved: {view:?}"
    );
}

/// File > Render image…: a chosen size and sample count rendered in the background, then saved
/// through the display mapping; the file has the chosen size and matches a one-shot render.
#[test]
fn render_image_job_writes_the_chosen_size() {
    let (mut h, _mirror) = viewer();
    settle(&mut h);
    let path = scratch_dir("render-image").join("big.png");
    h.state_mut()
        .fill_render_image_form(raygine::app::RenderImageForm {
            width: 200,
            height: 120,
            samples: 3,
            path: path.display().to_string(),
        });
    // The form and the help window draw (every glyph in them must exist in the fonts).
    h.state_mut().show_help();
    h.step();
    h.state_mut().start_render_image(path.clone());
    assert!(
        h.state().rendering_image(),
        "the job runs in the background"
    );
    step_until(&mut h, "the render-image job and its write", |app| {
        !app.rendering_image() && !app.writing()
    });
    let app = h.state();
    assert!(app.error().is_none(), "{:?}", app.error());
    assert!(app.notice().unwrap_or_default().contains("big.png"));
    let png = image::open(&path).unwrap().to_rgba8();
    assert_eq!([png.width(), png.height()], [200, 120]);
    let settings = tracer_core::render::RenderSettings {
        width: 200,
        height: 120,
        samples_per_pixel: 3,
        max_depth: app.render_prefs().max_depth,
        integrator: app.render_prefs().integrator,
        max_bounces: None,
        pixel_illuminance: true,
        guides: false,
    };
    let (film, _) =
        tracer_core::render::render(&app.document().scene, &app.document().setup, &settings);
    let expected = app.effective_display().map_film(&film);
    let worst = max_code_diff(png.as_raw(), &expected);
    assert_eq!(
        worst, 0,
        "the saved image is the render through the display mapping"
    );
}

/// A luminaire added from a typed IES path lights the scene: it is listed with its flux (lm),
/// the render restarts, and an empty path is refused with a message instead of an attempt.
#[test]
fn adding_a_luminaire_from_a_typed_path() {
    let (mut h, _mirror) = viewer();
    let path = scratch_dir("luminaire").join("down.ies");
    // 100 cd over the lower hemisphere: 2π · 100 = 628 lm.
    std::fs::write(
        &path,
        "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0\n100 100 100\n",
    )
    .unwrap();
    h.get_by_role_and_label(Role::Button, "Add luminaire")
        .click();
    h.step();
    assert!(
        h.state()
            .error()
            .unwrap_or_default()
            .contains("type the path"),
        "{:?}",
        h.state().error()
    );
    let generation = h.state().worker().generation();
    let field = h.get_by_role_and_label(Role::TextInput, "luminaire file");
    field.focus();
    field.type_text(&path.display().to_string());
    h.step();
    h.get_by_role_and_label(Role::Button, "Add luminaire")
        .click();
    h.run_steps(3);
    let app = h.state();
    assert!(app.error().is_none(), "{:?}", app.error());
    let lum = app
        .document()
        .setup
        .lights
        .iter()
        .find(|l| l.tag() == tracer_core::scene::KindTag::Luminaire)
        .expect("a luminaire");
    assert!((lum.flux_lm() - 628.3).abs() < 1.0, "{}", lum.flux_lm());
    assert!(
        app.worker().generation() > generation,
        "the render restarted"
    );
    assert!(h.query_by_label_contains("flux 628 lm").is_some());
}

/// Folds the groups above the Measure group (and Render below it when `fold_render`) so its
/// widgets are on screen in the test window, then opens it.
fn open_measure(h: &mut Viewer, fold_render: bool) {
    let groups: &[&str] = if fold_render {
        &["Lights", "Camera", "Materials", "Render"]
    } else {
        &["Lights", "Camera", "Materials"]
    };
    for group in groups {
        h.get_by_label(group).click();
        h.step();
    }
    h.get_by_label("Measure").click();
    h.run_steps(2);
}

/// The Measure panel adds a work plane over the Cornell box's floor, measures it in the
/// background and shows its statistics; the readings equal `measure_grids` at the same samples.
#[test]
fn measure_panel_adds_a_work_plane_and_shows_its_statistics() {
    let (mut h, _mirror) = viewer();
    open_measure(&mut h, false);
    h.get_by_role_and_label(Role::Button, "Add work plane")
        .click();
    h.step();
    assert_eq!(h.state().document().setup.grids.len(), 1);
    let grid = h.state().document().setup.grids[0].clone();
    assert_eq!(grid.name, "workplane1");
    // The box is 0.55 m tall: the work plane goes a quarter of the way up, below the camera at
    // mid-height, and the user is told.
    let b = h.state().document().scene.bounds;
    assert!((grid.origin[1] - (b.min.y + 0.25 * b.extent().y)).abs() < 1e-2);
    assert!(h.state().notice().unwrap_or_default().contains("small"));
    step_until(&mut h, "the first refinement", |app| {
        app.measure().readings().is_some_and(|r| r.samples >= 16)
    });
    h.step();
    let readings = h.state().measure().readings().unwrap();
    let r = &readings.results[0];
    assert_eq!(r.points.len(), grid.point_count());
    assert!(h.query_by_label_contains("Emin ").is_some());
    assert!(h.query_by_label_contains("U0 ").is_some());
    // The profile along the middle row is plotted, with a row slider.
    assert!(
        h.query_all_by_label_contains("profile row j")
            .next()
            .is_some()
    );
    let app = h.state();
    let settings = tracer_core::measure::MeasureSettings {
        integrator: app.render_prefs().integrator,
        max_bounces: None,
        samples: readings.samples,
        time_limit: None,
        target_error: None,
    };
    let (scene, setup) = (
        std::sync::Arc::clone(&app.document().scene),
        app.document().setup.clone(),
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let direct = pool.install(|| tracer_core::measure::measure_grids(&scene, &setup, &settings));
    assert_eq!(
        direct[0].points, r.points,
        "the viewer's readings are the CLI's"
    );
}

/// Ctrl+drag over the picture draws the luminance meter instead of orbiting; it reads the mean
/// luminance of the film's pixels in the rectangle.
#[test]
fn ctrl_drag_measures_the_mean_luminance_of_a_rectangle() {
    let (mut h, _mirror) = viewer();
    let view = h.get_by_label("viewport").rect();
    let camera = h.state().document().setup.camera;
    let from = view.min + view.size() * Vec2::new(0.3, 0.6);
    h.event(Event::ModifiersChanged(Modifiers::COMMAND));
    drag(&mut h, from, view.size() * Vec2::new(0.2, 0.15));
    h.event(Event::ModifiersChanged(Modifiers::NONE));
    h.step();
    assert_eq!(
        h.state().document().setup.camera,
        camera,
        "a Ctrl+drag must not orbit"
    );
    let m = h.state().meter().expect("a meter rectangle");
    assert!(m.x1 > m.x0 + 10 && m.y1 > m.y0 + 10, "{m:?}");
    settle(&mut h);
    let app = h.state();
    let (reading, manual) = app.worker().with_film(|f| {
        let f = f.unwrap();
        let mut sum = 0.0;
        for y in m.y0..m.y1 {
            for x in m.x0..m.x1 {
                sum += f.accum.pixel(f.accum.index(x, y)).mean_luminance();
            }
        }
        let n = f64::from((m.x1 - m.x0) * (m.y1 - m.y0));
        (m.read(f, |_, _| false).unwrap(), sum / n)
    });
    assert!((reading.mean_cd_m2 - manual).abs() < 1e-9 * manual.max(1.0));
    assert!(
        reading.mean_cd_m2 > 1.0,
        "the floor and blocks are lit: {reading:?}"
    );
    assert!(reading.std_error_cd_m2.is_some());
}

/// A grid on the clicked floor lies in the floor's plane, just above it, facing up, covering it.
#[test]
fn a_grid_on_the_selected_surface_covers_it() {
    let (mut h, _mirror) = viewer();
    open_measure(&mut h, false);
    let floor = h.state().document().scene.slots_for_key("floor").unwrap()[0];
    h.state_mut()
        .apply(raygine::command::Command::Select(Some(floor)));
    h.step();
    h.get_by_role_and_label(Role::Button, "Add grid on selected surface")
        .click();
    h.step();
    let g = h
        .state()
        .document()
        .setup
        .grids
        .last()
        .cloned()
        .expect("a grid");
    assert_eq!(g.name, "floor1");
    assert!(g.normal[1] > 0.999, "facing up: {:?}", g.normal);
    let b = h.state().document().scene.bounds;
    assert!(
        g.origin[1] > b.min.y && g.origin[1] < b.min.y + 2.0,
        "{:?}",
        g.origin
    );
    // The floor of the built-in box is about 556 x 559 mm.
    let area = glam::Vec3::from(g.u).cross(glam::Vec3::from(g.v)).length();
    assert!((area / (556.0 * 559.2) - 1.0).abs() < 0.02, "{area}");
    assert!(g.nu >= 2 && g.nv >= 2);
}

/// Save report writes the readings' CSV beside the scene at once and asks the window for the
/// screenshot that becomes the PNG (written when it arrives; `report::crop` is unit-tested).
#[test]
fn save_report_writes_the_csv_and_waits_for_the_picture() {
    let (mut h, _mirror) = viewer();
    let dir = scratch_dir("report");
    h.state_mut().set_document_path(dir.join("box.shp"));
    open_measure(&mut h, true);
    h.get_by_role_and_label(Role::Button, "Add work plane")
        .click();
    h.step();
    step_until(&mut h, "the first refinement", |app| {
        app.measure().readings().is_some_and(|r| r.samples >= 16)
    });
    h.run_steps(2);
    h.get_by_role_and_label(Role::Button, "Save view + CSV")
        .click();
    h.step();
    let csv = std::fs::read_to_string(dir.join("box.grids.csv")).unwrap();
    assert!(csv.starts_with("grid,i,j,x,y,z,illuminance_lx,std_error_lx\nworkplane1,"));
    assert!(h.state().report_pending() || h.state().notice().is_some());
}

/// File > Save report… writes the PDF in the background: the UI keeps stepping, the banner
/// names the file and each grid's verdict, and the file is a PDF.
#[test]
fn save_report_writes_a_pdf_in_the_background() {
    let (mut h, _mirror) = viewer();
    let dir = scratch_dir("pdf-report");
    h.state_mut().set_document_path(dir.join("box.shp"));
    open_measure(&mut h, true);
    h.get_by_role_and_label(Role::Button, "Add work plane")
        .click();
    h.step();
    let pdf = dir.join("box.pdf");
    // What the path window's Save does once the dialog (or the typed path) gave the file.
    h.state_mut()
        .run_path_action(raygine::file_ops::DialogPurpose::SaveReport, pdf.clone());
    // The UI keeps stepping while a background job writes it.
    step_until(&mut h, "the report", |app| {
        app.notice().is_some_and(|n| n.contains("wrote the report"))
    });
    let notice = h.state().notice().unwrap_or_default().to_owned();
    assert!(
        notice.contains("wrote the report") && notice.contains("box.pdf"),
        "{notice}"
    );
    let bytes = std::fs::read(&pdf).unwrap();
    assert!(bytes.starts_with(b"%PDF-"), "not a PDF");
}

// ---------------------------------------------------------------------------------------------
// Issue 19: the rough edges a new user hits
// ---------------------------------------------------------------------------------------------

/// Types `text` as a keyboard does: each character's key press (when it has a key) and its text.
fn type_keys(h: &mut Viewer, text: &str) {
    for c in text.chars() {
        if let Some(key) = Key::from_name(&c.to_ascii_uppercase().to_string()) {
            h.event(Event::Key {
                key,
                physical_key: None,
                pressed: true,
                repeat: false,
                modifiers: Modifiers::NONE,
            });
        }
        h.event(Event::Text(c.to_string()));
        if let Some(key) = Key::from_name(&c.to_ascii_uppercase().to_string()) {
            h.event(Event::Key {
                key,
                physical_key: None,
                pressed: false,
                repeat: false,
                modifiers: Modifiers::NONE,
            });
        }
    }
    h.step();
}

/// Ctrl+O puts the keyboard in the path field: typed letters go into it (P does not pause, F
/// does not frame, Ctrl+Z does not undo the scene), and Enter opens the scene.
#[test]
fn ctrl_o_focuses_the_path_field_and_enter_opens() {
    let (mut h, _mirror) = viewer();
    let path = scratch_dir("ctrl-o-pf").join("pf_scene.shp");
    std::fs::write(&path, two_brep_scene("0 2 3")).unwrap();
    let x0 = light_x(h.state());
    h.get_by_role_and_label(Role::SpinButton, LIGHT_X)
        .set_value_accesskit(f64::from(x0) + 50.0);
    h.run_steps(2);
    // Orbit, so F would visibly change the camera.
    let view = h.get_by_label("viewport").rect();
    drag(&mut h, view.center(), Vec2::new(80.0, 20.0));
    let camera = h.state().document().setup.camera;

    h.key_press_modifiers(Modifiers::COMMAND, Key::O);
    h.run_steps(2);
    type_keys(&mut h, "pf");
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    let app = h.state();
    assert!(!app.paused(), "typing p paused rendering");
    assert_eq!(
        app.document().setup.camera,
        camera,
        "typing f framed the scene"
    );
    assert_eq!(
        light_x(app),
        x0 + 50.0,
        "Ctrl+Z in the field undid a scene edit"
    );
    assert_eq!(app.prompt().map(|p| p.text.as_str()), Some(""));

    type_keys(&mut h, &path.display().to_string());
    assert_eq!(
        h.state().prompt().map(|p| p.text.clone()),
        Some(path.display().to_string())
    );
    h.key_press(Key::Enter);
    h.run_steps(2);
    // The light was moved: the viewer asks before dropping the edit.
    assert!(h.state().pending_switch().is_some());
    h.get_by_role_and_label(Role::Button, "Discard changes")
        .click();
    h.step();
    step_until(&mut h, "the scene to load", |app| !app.loading());
    let app = h.state();
    assert!(app.error().is_none(), "{:?}", app.error());
    assert!(
        app.prompt().is_none(),
        "Enter did not close the path window"
    );
    assert_eq!(app.document().path.as_deref(), Some(path.as_path()));
    assert!(!app.paused());
}

/// A scene opened while rendering is paused resumes rendering, and no frame draws the previous
/// scene's picture for it.
#[test]
fn a_scene_opened_while_paused_never_shows_the_old_picture() {
    let (mut h, _mirror) = viewer();
    h.key_press(Key::P);
    h.step();
    assert!(h.state().paused());
    assert!(h.state().picture_drawn());
    let old_generation = h.state().worker().generation();
    let path = scratch_dir("paused-open").join("two_breps.shp");
    std::fs::write(&path, two_brep_scene("0 2 3")).unwrap();
    h.state_mut().open_path(&path);
    h.state_mut().finish_loading_blocking(TIMEOUT);
    assert!(!h.state().loading());
    let deadline = Instant::now() + TIMEOUT;
    loop {
        h.step();
        let app = h.state();
        let first = app.worker().scene_first_generation();
        if app.picture_drawn() {
            assert!(first > old_generation, "the new scene was never started");
            assert!(
                app.worker().shown_generation() >= first,
                "a frame drew the old scene's picture (generation {} < {first})",
                app.worker().shown_generation()
            );
        }
        if app.picture_drawn() && render_done(app) {
            break;
        }
        assert!(Instant::now() < deadline, "the new scene never rendered");
        std::thread::sleep(Duration::from_millis(10));
    }
    assert!(!h.state().paused(), "opening a scene resumes rendering");
}

/// Banners have a dismiss button, and they expire on their own.
#[test]
fn banners_can_be_dismissed_and_expire() {
    let (mut h, _mirror) = viewer();
    h.state_mut().apply(raygine::command::Command::Error(
        "something failed".to_owned(),
    ));
    h.state_mut().apply(raygine::command::Command::Notice(
        "something saved".to_owned(),
    ));
    h.step();
    assert!(h.query_by_label_contains("something failed").is_some());
    h.get_by_role_and_label(Role::Button, "Dismiss error")
        .click();
    h.step();
    assert_eq!(h.state().error(), None, "the error was not dismissed");
    assert!(
        h.state().notice().is_some(),
        "dismissing the error hid the notice"
    );
    h.step();
    assert!(h.query_by_label_contains("something failed").is_none());

    h.state_mut().set_notice_duration(Duration::from_millis(50));
    std::thread::sleep(Duration::from_millis(60));
    h.run_steps(2);
    assert_eq!(h.state().notice(), None, "the notice did not expire");
}

/// A drag of a light's position stays within the scene's bounds; a typed value may go outside, and then the
/// panel says so and the picture's hint tells "every pixel is 0 cd/m²".
#[test]
fn light_sliders_keep_to_the_bounds_and_a_light_outside_is_pointed_out() {
    let (mut h, _mirror) = viewer();
    let bounds = h.state().document().scene.bounds;
    let slider = h.get_by_role_and_label(Role::SpinButton, LIGHT_X).rect();
    // Left and down: 500 points of drag, 700 mm at the box's speed, more than the box is wide.
    drag(&mut h, slider.center(), Vec2::new(-250.0, 250.0));
    let x = light_x(h.state());
    assert!(
        (x - bounds.min.x).abs() < 1.0,
        "a drag left took the light to x = {x}, outside {bounds:?}"
    );
    assert!(h.query_by_label("outside the scene's bounds").is_none());
    assert_eq!(h.state().picture_hint(), None);

    h.get_by_role_and_label(Role::SpinButton, LIGHT_X)
        .set_value_accesskit(-5000.0);
    h.run_steps(2);
    assert_eq!(light_x(h.state()), -5000.0, "a typed value may go anywhere");
    settle(&mut h);
    h.step();
    assert!(h.query_by_label("outside the scene's bounds").is_some());
    let hint = h
        .state()
        .picture_hint()
        .map(str::to_owned)
        .unwrap_or_default();
    assert!(
        hint.starts_with("Every pixel is 0 cd/m²") && hint.contains("Light 1 is outside"),
        "hint: {hint}"
    );
}

/// A picture that is black only because of the exposure gets its own hint.
#[test]
fn a_picture_black_at_this_exposure_says_so() {
    let (mut h, _mirror) = viewer();
    assert_eq!(h.state().picture_hint(), None);
    h.get_by_role_and_label(Role::Slider, EXPOSURE)
        .set_value_accesskit(-12.0);
    h.run_steps(2);
    let hint = h
        .state()
        .picture_hint()
        .map(str::to_owned)
        .unwrap_or_default();
    assert!(hint.starts_with("Black at this exposure"), "hint: {hint}");
    // The panel's checkbox is below the test window's fold.
    h.state_mut().display_mut().auto_exposure = true;
    h.run_steps(2);
    assert_eq!(h.state().picture_hint(), None);
}

/// A 20-point drag on the intensity changes it by a little (about 10 %), not by a factor of 50.
#[test]
fn intensity_drag_is_fine() {
    let (mut h, _mirror) = viewer();
    let i0 = h.state().document().setup.lights[0]
        .intensity_cd()
        .unwrap_or(0.0);
    let field = h
        .get_by_role_and_label(Role::SpinButton, "intensity (cd)")
        .rect();
    drag(&mut h, field.center(), Vec2::new(20.0, 0.0));
    let i1 = h.state().document().setup.lights[0]
        .intensity_cd()
        .unwrap_or(0.0);
    let ratio = i1 / i0;
    assert!(ratio > 1.02 && ratio < 1.3, "{i0} -> {i1}");
    h.get_by_role_and_label(Role::Button, "×2").click();
    h.step();
    assert_eq!(
        h.state().document().setup.lights[0]
            .intensity_cd()
            .unwrap_or(0.0),
        2.0 * i1
    );
}

/// A typed value applies when committed (Enter), not at each keystroke, and undoes in one step.
#[test]
fn a_typed_value_is_one_undo_step() {
    let (mut h, _mirror) = viewer();
    let i0 = h.state().document().setup.lights[0]
        .intensity_cd()
        .unwrap_or(0.0);
    let field = h
        .get_by_role_and_label(Role::SpinButton, "intensity (cd)")
        .rect();
    click_at(&mut h, field.center());
    h.step();
    h.key_press_modifiers(Modifiers::COMMAND, Key::A);
    h.step();
    type_keys(&mut h, "150");
    type_keys(&mut h, "");
    assert_eq!(
        h.state().document().setup.lights[0]
            .intensity_cd()
            .unwrap_or(0.0),
        i0,
        "the value applied before it was committed"
    );
    h.key_press(Key::Enter);
    h.run_steps(2);
    assert_eq!(
        h.state().document().setup.lights[0]
            .intensity_cd()
            .unwrap_or(0.0),
        150.0
    );
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    assert_eq!(
        h.state().document().setup.lights[0]
            .intensity_cd()
            .unwrap_or(0.0),
        i0,
        "one undo did not return to the value before typing"
    );
    assert!(
        !h.state().history().can_undo(),
        "typing left more than one step"
    );
}

/// Add light puts the new light beside the first one, inside the room.
#[test]
fn add_light_offsets_the_new_light() {
    let (mut h, _mirror) = viewer();
    h.get_by_role_and_label(Role::Button, "Add light").click();
    h.step();
    let app = h.state();
    let b = app.document().scene.bounds;
    let [a, n] = [
        &app.document().setup.lights[0],
        &app.document().setup.lights[1],
    ];
    let gap = a.position().distance(n.position());
    assert!(
        gap > 0.1 * b.extent().max_element(),
        "the new light is {gap} from the first"
    );
    let p = n.position();
    assert!(
        b.contains(&tracer_core::Aabb { min: p, max: p }),
        "the new light left the room: {p}"
    );
}

/// The viewer has unit and handedness controls: a unit reads the scene again in it, a
/// handedness mirrors the camera's picture; `--units` reaches the viewer.
#[test]
fn unit_and_handedness_controls() {
    let (mut h, _mirror) = viewer();
    h.get_by_role_and_label(Role::ComboBox, "unit").click();
    h.run_steps(2);
    h.get_by_label("m").click();
    h.run_steps(2);
    let app = h.state();
    assert_eq!(app.document().setup.unit, tracer_core::scene::LengthUnit::M);
    assert!(
        h.query_by_role_and_label(Role::SpinButton, "light x (m)")
            .is_some(),
        "sliders still in mm"
    );
    settle(&mut h);
    let generation = h.state().worker().generation();
    h.get_by_role_and_label(Role::ComboBox, "handedness")
        .click();
    h.run_steps(2);
    h.get_by_label("right-handed").click();
    h.run_steps(2);
    let app = h.state();
    assert_eq!(
        app.document().setup.handedness,
        tracer_core::scene::Handedness::Right
    );
    assert!(
        app.worker().generation() > generation,
        "the render did not restart"
    );

    // `raygine --units m` parses, and the option reaches the app.
    use clap::Parser;
    let cli = raygine::cli::Cli::try_parse_from(["raygine", "--units", "m", "room.shp"]).unwrap();
    assert_eq!(cli.units, Some(tracer_core::scene::LengthUnit::M));
    let h = Harness::builder()
        .with_size(Vec2::new(640.0, 400.0))
        .with_accessibility_check(false)
        .build_eframe(|cc| {
            RaygineApp::new(
                cc,
                AppOptions {
                    scene: None,
                    threads: 1,
                    ignore_last_scene: true,
                    unit: Some(tracer_core::scene::LengthUnit::Cm),
                },
            )
            .unwrap()
        });
    assert_eq!(
        h.state().document().setup.unit,
        tracer_core::scene::LengthUnit::Cm
    );
}

/// Reflectance can be typed (one grey value, or 0-1 per channel), and Kd + Ks above 1 is shown
/// (the sum per channel, and a notice saying what was scaled down) instead of scaled silently.
#[test]
fn reflectance_numbers_and_the_kd_ks_limit_are_shown() {
    let (mut h, _mirror) = viewer();
    h.get_by_label("red_wall").click();
    h.run_steps(2);
    let slot = h.state().selected_slot().unwrap() as usize;
    h.get_all_by_role_and_label(Role::SpinButton, "grey")
        .next()
        .unwrap()
        .set_value_accesskit(0.5);
    h.run_steps(2);
    assert_eq!(h.state().document().setup.materials[slot].kd, [0.5; 3]);
    assert!(h.query_by_label_contains("Kd + Ks = 0.500").is_some());

    // Ks red 0.8: Kd + Ks = 1.3 in red.
    h.get_all_by_role_and_label(Role::SpinButton, "or")
        .nth(3)
        .unwrap()
        .set_value_accesskit(0.8);
    h.run_steps(2);
    let m = h.state().document().setup.materials[slot];
    assert!((m.kd[0] + m.ks[0] - 1.0).abs() < 1e-5, "{m:?}");
    let notice = h.state().notice().map(str::to_owned).unwrap_or_default();
    assert!(
        notice.contains("Kd + Ks was above 1 in red (1.30"),
        "notice: {notice}"
    );
    assert!(h.query_by_label_contains("Kd + Ks = 1.000").is_some());
}

/// Browse… on a desktop without a file-dialog service returns at once with nothing: the window
/// says why, and the typed path stays.
#[test]
fn browse_without_a_portal_says_why_and_keeps_the_path() {
    let (mut h, _mirror) = viewer();
    h.key_press_modifiers(Modifiers::COMMAND, Key::O);
    h.run_steps(2);
    type_keys(&mut h, "/tmp/typed.shp");
    // What rfd does without a portal (a real dialog never opens in tests).
    h.state_mut()
        .finish_dialog(raygine::file_ops::DialogPurpose::Open, None);
    h.run_steps(2);
    let prompt = h.state().prompt().expect("the path window closed");
    assert_eq!(prompt.text, "/tmp/typed.shp");
    assert!(
        prompt
            .note
            .as_deref()
            .unwrap_or_default()
            .contains("No file dialog opened"),
        "{:?}",
        prompt.note
    );
    assert!(h.query_by_label_contains("No file dialog opened").is_some());
}

/// In the smallest window the side panel leaves the viewport its minimum width, and View > Side
/// panel hides the panel to give the picture the whole window.
#[test]
fn a_small_window_keeps_a_usable_viewport() {
    let mut h = Harness::builder()
        .with_size(Vec2::new(640.0, 400.0))
        .with_accessibility_check(false)
        .build_eframe(|cc| {
            RaygineApp::new(
                cc,
                AppOptions {
                    scene: None,
                    threads: 1,
                    ignore_last_scene: true,
                    unit: None,
                },
            )
            .unwrap()
        });
    h.run_steps(3);
    let view = h.get_by_label("viewport").rect();
    assert!(
        view.width() >= raygine::app::MIN_VIEWPORT_WIDTH - 1.0,
        "viewport {view:?}"
    );
    h.get_by_label("View").click();
    h.run_steps(2);
    h.get_by_label("Side panel").click();
    h.run_steps(3);
    assert!(!h.state().side_panel_shown());
    let view = h.get_by_label("viewport").rect();
    assert!(view.width() > 630.0, "viewport {view:?}");
}

/// In a narrow window the status bar stays one line (cut off at the edge) instead of wrapping:
/// a wrapped line shrank the viewport, the new size restarted the render, the new figures
/// unwrapped it again, and the render restarted every frame without finishing.
#[test]
fn a_narrow_window_keeps_one_status_line_and_the_render_finishes() {
    let (mut h, _mirror) = viewer();
    h.set_size(Vec2::new(700.0, 500.0));
    h.run_steps(2);
    settle(&mut h);
    let view = h.get_by_label("viewport").rect();
    assert!(
        500.0 - view.max.y < 30.0,
        "the status bar wraps: viewport {view:?}"
    );
    // Rendering again (a new light position): the viewport keeps its size frame after frame.
    h.state_mut().setup_mut().lights[0].position[0] -= 50.0;
    h.step();
    let generation = h.state().worker().generation();
    let size = h.state().viewport_px();
    for _ in 0..20 {
        h.step();
        assert_eq!(h.state().viewport_px(), size, "the viewport changed size");
        std::thread::sleep(Duration::from_millis(5));
    }
    assert_eq!(
        h.state().worker().generation(),
        generation,
        "the render restarted"
    );
    settle(&mut h);
}

/// The false-colour legend has rows for above the range (white) and below it (black; on a log
/// scale that includes 0), matching the colours drawn; the viewer draws it with false colour on.
#[test]
fn false_colour_legend_covers_above_and_below_the_range() {
    use tracer_core::display::{FalseColour, FalseColourQuantity, FalseColourScale};
    let fc = FalseColour {
        quantity: FalseColourQuantity::Illuminance,
        scale: FalseColourScale::Log,
        min: 1.0,
        max: 10_000.0,
    };
    let rows = raygine::viewport_ui::legend_rows(&fc);
    assert_eq!(rows.len(), 11);
    assert_eq!(rows[0].0, "> 10000");
    assert_eq!(rows[0].1, fc.colour(2e4));
    let last = rows.last().unwrap();
    assert_eq!(last.0, "< 1.00, 0");
    assert_eq!(last.1, fc.colour(0.0));
    assert_eq!(last.1, fc.colour(0.5));
    let linear = FalseColour {
        scale: FalseColourScale::Linear,
        min: 0.0,
        ..fc
    };
    assert_eq!(
        raygine::viewport_ui::legend_rows(&linear).last().unwrap().0,
        "< 0"
    );

    let (mut h, _mirror) = viewer();
    h.state_mut().set_false_colour(true);
    h.run_steps(3);
    assert!(h.state().effective_display().false_colour.is_some());
}

/// Save scene settings writes each array (positions, colours) on one line.
#[test]
fn the_sidecar_keeps_each_array_on_one_line() {
    let (mut h, _mirror) = viewer();
    let path = scratch_dir("sidecar-arrays").join("box.raygine.toml");
    let ctx = h.state().context().clone();
    h.state_mut().save_sidecar(&ctx, path.clone());
    step_until(&mut h, "the sidecar write", |app| !app.writing());
    assert!(h.state().error().is_none(), "{:?}", h.state().error());
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.lines()
            .any(|l| l.starts_with("position = [") && l.ends_with(']')),
        "{text}"
    );
    assert!(
        !text.lines().any(|l| l.trim_end() == "position = ["),
        "arrays split over lines:\n{text}"
    );
    // It reads back to the same setup.
    let sidecar: tracer_core::scene::Sidecar = toml::from_str(&text).unwrap();
    assert_eq!(
        sidecar.lights.map(|l| l.len()),
        Some(h.state().document().setup.lights.len())
    );
}

/// Switching scenes or quitting with unsaved edits asks first: Cancel keeps the edits, Discard
/// drops them, Save writes the sidecar and goes on; without edits nothing asks.
#[test]
fn unsaved_edits_are_not_thrown_away_without_asking() {
    let (mut h, _mirror) = viewer();
    let dir = scratch_dir("unsaved");
    let path = dir.join("two_breps.shp");
    std::fs::write(&path, two_brep_scene("0 2 3")).unwrap();
    open(&mut h, &path);
    assert!(!h.state().has_unsaved_edits());
    let x0 = light_x(h.state());
    h.get_by_role_and_label(Role::SpinButton, "light x (mm)")
        .set_value_accesskit(f64::from(x0) + 40.0);
    h.run_steps(2);
    assert!(h.state().has_unsaved_edits());

    // The built-in box from the File menu: asked, then cancelled.
    h.state_mut().request(raygine::unsaved::Switch::Builtin);
    h.run_steps(2);
    assert!(h.query_by_label("Unsaved changes").is_some());
    h.get_by_role_and_label(Role::Button, "Cancel").click();
    h.step();
    assert!(h.state().pending_switch().is_none());
    assert_eq!(h.state().document().path.as_deref(), Some(path.as_path()));
    assert_eq!(light_x(h.state()), x0 + 40.0, "Cancel dropped the edit");

    // Ctrl+Q: asked; Save writes the sidecar and quits.
    h.key_press_modifiers(Modifiers::COMMAND, Key::Q);
    h.run_steps(2);
    assert_eq!(
        h.state().pending_switch(),
        Some(&raygine::unsaved::Switch::Quit)
    );
    h.get_by_role_and_label(Role::Button, "Save and continue")
        .click();
    h.step();
    step_until(&mut h, "the sidecar write", |app| !app.writing());
    let sidecar = std::fs::read_to_string(dir.join("two_breps.raygine.toml")).unwrap();
    assert!(
        sidecar.contains(&format!("{}", x0 + 40.0)),
        "the saved sidecar lacks the moved light:\n{sidecar}"
    );
    assert!(!h.state().has_unsaved_edits());

    // Nothing unsaved: switching does not ask.
    h.state_mut().request(raygine::unsaved::Switch::Builtin);
    h.step();
    assert!(h.state().pending_switch().is_none());
    assert_eq!(h.state().document().path, None);
}

/// The colour picker's numeric row ("U8", the copy button "📋", R G B) and the viewer's own
/// labels draw with glyphs the fonts have (no missing-glyph boxes).
#[test]
fn the_colour_picker_and_labels_have_their_glyphs() {
    let (h, _mirror) = viewer();
    let font = egui::FontId::proportional(14.0);
    for text in ["U8 📋 R G B", "× ÷2 ×2 cd/m² lx °", "Kd + Ks = 1.000"] {
        assert!(
            h.ctx.fonts_mut(|f| f.has_glyphs(&font, text)),
            "a glyph of {text:?} is missing"
        );
    }
}

/// Where the camera ray hit nothing the viewport shows the backdrop (a dark gradient), while an
/// unlit surface (0 cd/m²) stays black; the exported PNG keeps the background black.
#[test]
fn the_background_is_told_apart_from_unlit_surfaces() {
    let (mut h, mirror) = viewer();
    // The light behind the green wall: every surface the camera sees is unlit.
    h.get_by_role_and_label(Role::SpinButton, LIGHT_X)
        .set_value_accesskit(-5000.0);
    h.run_steps(2);
    settle(&mut h);
    h.step();
    let (size, rgb) = film_rgb(h.state());
    assert!(rgb.iter().all(|p| *p == Vec3::ZERO), "something is lit");
    let [w, height] = size;
    let texture = mirror.film(size);
    assert_eq!(texture.pixels, expected_texture(h.state()).pixels);
    let fraction = |x: usize, y: usize| {
        h.state()
            .worker()
            .with_film(|f| f.unwrap().background_fraction(y * w + x))
    };
    // The Cornell box's opening is narrower than the picture: its left column sees outside;
    // the middle sees the back wall.
    let (mid, bottom) = (height / 2, height - 1);
    for (x, y) in [(0, mid), (0, bottom)] {
        assert_eq!(fraction(x, y), 1.0, "({x}, {y}) sees the box");
        let shown = texture.pixels[y * w + x];
        assert_eq!(shown, raygine::backdrop::colour_at(y as u32, height as u32));
        assert_ne!(shown, egui::Color32::BLACK);
    }
    assert_ne!(texture.pixels[0], texture.pixels[bottom * w], "no gradient");
    assert_eq!(fraction(w / 2, mid), 0.0);
    assert_eq!(texture.pixels[mid * w + w / 2], egui::Color32::BLACK);

    let path = scratch_dir("backdrop").join("view.png");
    let ctx = h.state().context().clone();
    h.state_mut().export_png(&ctx, path.clone());
    step_until(&mut h, "the PNG write", |app| !app.writing());
    let png = image::open(&path).unwrap().to_rgb8();
    assert_eq!(
        png.get_pixel(0, mid as u32).0,
        [0, 0, 0],
        "the export has a backdrop"
    );
}

/// A Lumicept scene of one box brep from `lo` to `hi` (twelve triangles).
fn box_scene(lo: [f32; 3], hi: [f32; 3]) -> String {
    let mut text =
        String::from(";; written by raygine's UI tests\ndefine breps slab\nvertices 8\n");
    for i in 0..8 {
        let pick = |axis: usize| {
            if i >> axis & 1 == 0 {
                lo[axis]
            } else {
                hi[axis]
            }
        };
        text += &format!("{} {} {}\n", pick(0), pick(1), pick(2));
    }
    text += "triangles 12\n";
    for [a, b, c, d] in [
        [0, 1, 3, 2],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 3, 7, 5],
    ] {
        text += &format!("{a} {b} {c}\n{a} {c} {d}\n");
    }
    text += "parts 1\n0 0 0 0 0 0 0 0 0 0\n0 0\nenddef\n\n";
    text += "set breps slab\nrotation 0 0 0\ntranslation 0 0 0\nscale 1 1 1\nenddef\n";
    text
}

/// An object whose largest outline is seen along X (a slab standing in the YZ plane) opens
/// seen from +X, not from +Z where it is a thin edge; after orbiting, F frames it from +X again.
#[test]
fn an_object_opens_seen_from_its_largest_side() {
    let (mut h, _mirror) = viewer();
    assert_eq!(
        h.state().document().setup.camera.position,
        [278.0, 273.0, 800.0],
        "the Cornell box keeps its camera"
    );
    let path = scratch_dir("largest-side").join("slab.shp");
    std::fs::write(&path, box_scene([0.0, 0.0, 0.0], [50.0, 1000.0, 2000.0])).unwrap();
    open(&mut h, &path);
    let from_x = |h: &Viewer| {
        let camera = h.state().document().setup.camera;
        let c = h.state().document().scene.bounds.center();
        let eye = Vec3::from(camera.position) - c;
        eye.x > 0.0 && eye.y.abs() < 1e-3 * eye.x && eye.z.abs() < 1e-3 * eye.x
    };
    assert!(from_x(&h), "camera {:?}", h.state().document().setup.camera);
    let view = h.get_by_label("viewport").rect();
    drag(&mut h, view.center(), Vec2::new(120.0, 40.0));
    assert!(!from_x(&h), "the drag did not orbit");
    h.key_press(Key::F);
    h.step();
    assert!(
        from_x(&h),
        "F: camera {:?}",
        h.state().document().setup.camera
    );
    // The picture shows the slab's face: most of the middle row is lit.
    settle(&mut h);
    let (size, rgb) = film_rgb(h.state());
    let row = &rgb[size[0] * (size[1] / 2)..size[0] * (size[1] / 2 + 1)];
    let lit = row.iter().filter(|p| p.max_element() > 0.0).count();
    assert!(lit > size[0] / 3, "{lit} of {} pixels lit", size[0]);
}

/// Light labels and the hover read-out sit on dark plates, so they read over bright pixels.
#[test]
fn light_labels_and_the_hover_readout_sit_on_dark_plates() {
    let (mut h, _mirror) = viewer();
    // Over the bright floor, in front of the short block.
    let view = h.get_by_label("viewport").rect();
    h.hover_at(view.lerp_inside(Vec2::new(0.5, 0.95)));
    h.run_steps(2);
    assert!(h.state().hover().is_some(), "no read-out under the pointer");
    let mut texts = Vec::new();
    let mut plates = Vec::new();
    let mut todo: Vec<egui::Shape> = h.output().shapes.iter().map(|c| c.shape.clone()).collect();
    while let Some(shape) = todo.pop() {
        match shape {
            egui::Shape::Vec(v) => todo.extend(v),
            egui::Shape::Text(t) => {
                let text = t.galley.text().to_owned();
                if text.starts_with("L1 ") || text.contains(" cd/m²   ") {
                    texts.push((text, t.galley.rect.translate(t.pos.to_vec2())));
                }
            }
            egui::Shape::Rect(r) if r.fill == egui::Color32::from_black_alpha(200) => {
                plates.push(r.rect);
            }
            _ => {}
        }
    }
    assert_eq!(
        texts.len(),
        2,
        "the light's label and the read-out: {texts:?}"
    );
    for (text, rect) in &texts {
        assert!(
            plates.iter().any(|p| p.contains_rect(*rect)),
            "no dark plate under {text:?} at {rect:?}: {plates:?}"
        );
    }
}
