//! The Environment section: a sky set through its widgets re-renders, is one undo step at a
//! time and is saved in the sidecar; a map is read in the background, and one that cannot be
//! read is reported and leaves the sky as it was.

use egui::accesskit::Role;
use egui::{Key, Modifiers, Vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use raygine::app::RaygineApp;
use raygine::panels::new_sky_cd_m2;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use tracer_core::integrator::IntegratorKind;
use tracer_core::light::EnvironmentSource;

const TIMEOUT: Duration = Duration::from_secs(15);

type Viewer = Harness<'static, RaygineApp>;

/// The built-in box in direct mode at 1 sample, a quarter of the pixels (no picture is
/// checked), its exposure set, the Environment section opened.
fn viewer() -> Viewer {
    let mut h = crate::box_viewer(Vec2::new(960.0, 900.0), IntegratorKind::Direct, 1, 0.25);
    // The exposure a new sky is made for is set on the first view.
    step_until(
        &mut h,
        "the first view's exposure",
        RaygineApp::exposure_held,
    );
    h.get_by_label("Environment").click();
    h.run_steps(2);
    h
}

fn step_until(h: &mut Viewer, what: &str, done: impl Fn(&RaygineApp) -> bool) {
    let deadline = Instant::now() + TIMEOUT;
    while !done(h.state()) {
        assert!(Instant::now() < deadline, "timed out waiting for {what}");
        h.step();
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn scratch_dir(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("environment-{test}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The uniform sky's luminance, if the environment is one.
fn sky_cd_m2(app: &RaygineApp) -> Option<f32> {
    match app.document().setup.environment.as_ref().map(|e| &e.source) {
        Some(EnvironmentSource::Uniform {
            luminance_cd_m2, ..
        }) => Some(*luminance_cd_m2),
        _ => None,
    }
}

/// Uniform, then a typed luminance: each re-renders and is one undo step; undo goes back to
/// no environment; the light tracer says it leaves the sky out (bdpt does not); the sidecar
/// keeps it.
#[test]
fn a_uniform_sky_set_in_the_section_renders_undoes_and_saves() {
    let mut h = viewer();
    assert_eq!(h.state().document().setup.environment, None);
    let generation = h.state().worker().generation();
    let new_sky = new_sky_cd_m2(h.state().display().exposure_stops);
    h.get_by_role_and_label(Role::RadioButton, "Uniform")
        .click();
    h.run_steps(2);
    assert_eq!(sky_cd_m2(h.state()), Some(new_sky));
    assert!(
        h.state().worker().generation() > generation,
        "the render did not restart"
    );
    h.get_by_role_and_label(Role::SpinButton, "luminance")
        .set_value_accesskit(250.0);
    h.run_steps(2);
    assert_eq!(sky_cd_m2(h.state()), Some(250.0));

    let path = scratch_dir("uniform").join("box.raygine.toml");
    let ctx = h.state().context().clone();
    h.state_mut().save_sidecar(&ctx, path.clone());
    step_until(&mut h, "the sidecar write", |app| !app.writing());
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.contains("[environment]") && text.contains("luminance_cd_m2 = 250"),
        "{text}"
    );

    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    assert_eq!(sky_cd_m2(h.state()), Some(new_sky));
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    assert_eq!(
        h.state().document().setup.environment,
        None,
        "undo did not take the sky away"
    );
    h.run_steps(2);
    let rendered = h.state().worker().current().unwrap();
    assert_eq!(rendered.setup.environment, None, "renders without the sky");
}

/// Writes a `width` x `width / 2` Radiance map: a bright upper half over a dim lower one.
fn write_map(path: &Path, width: u32, height: u32) {
    let image = image::Rgb32FImage::from_fn(width, height, |_, y| {
        image::Rgb(if y < height / 2 { [4.0; 3] } else { [0.5; 3] })
    });
    image.save(path).unwrap();
}

/// Map without a map read yet asks for a file; the map typed there is read in the background,
/// shown with a thumbnail, keeps the turn and is saved relative to the sidecar. A file that is
/// not a map is reported and the map stays.
#[test]
fn a_map_is_read_in_the_background_and_a_bad_one_keeps_the_sky() {
    let mut h = viewer();
    let dir = scratch_dir("map");
    let sky = dir.join("sky.hdr");
    write_map(&sky, 16, 8);
    let square = dir.join("square.hdr");
    write_map(&square, 8, 8);

    h.get_by_role_and_label(Role::RadioButton, "Uniform")
        .click();
    h.run_steps(2);
    let new_sky = sky_cd_m2(h.state()).expect("a uniform sky");
    h.get_by_role_and_label(Role::Slider, "rotation (°)")
        .set_value_accesskit(30.0);
    h.run_steps(2);
    h.get_by_role_and_label(Role::RadioButton, "Map").click();
    h.run_steps(2);
    assert!(
        sky_cd_m2(h.state()).is_some(),
        "the sky changed before a map was read"
    );
    let field = h.get_by_role_and_label(Role::TextInput, "Path:");
    field.focus();
    field.type_text(&sky.display().to_string());
    h.step();
    h.get_by_role_and_label(Role::Button, "Load").click();
    h.step();
    step_until(&mut h, "the map's thumbnail", |app| {
        app.map_thumbnail_size().is_some()
    });
    let app = h.state();
    assert!(app.error().is_none(), "{:?}", app.error());
    let env = app.document().setup.environment.clone().unwrap();
    let EnvironmentSource::Map(map) = &env.source else {
        panic!("not a map: {env:?}");
    };
    assert_eq!((map.width, map.height), (16, 8));
    assert_eq!(env.rotation_deg, 30.0, "the turn was not kept");
    assert_eq!(app.map_thumbnail_size(), Some([16, 8]));
    assert!(h.query_by_label_contains("sky.hdr, 16 × 8 px").is_some());
    // The sidecar beside the map names it relative to itself.
    let ctx = h.state().context().clone();
    h.state_mut()
        .save_sidecar(&ctx, dir.join("box.raygine.toml"));
    step_until(&mut h, "the sidecar write", |app| !app.writing());
    let text = std::fs::read_to_string(dir.join("box.raygine.toml")).unwrap();
    assert!(text.contains("file = \"sky.hdr\""), "{text}");
    assert!(text.contains("rotation_deg = 30"), "{text}");

    h.state_mut().apply(raygine::command::Command::Edit(
        raygine::command::Edit::LoadEnvironmentMap(square),
    ));
    step_until(&mut h, "the bad map", |app| !app.loading_environment());
    h.step();
    let app = h.state();
    let error = app.error().unwrap_or_default();
    assert!(error.contains("square.hdr"), "{error}");
    assert_eq!(
        app.document().setup.environment.as_ref(),
        Some(&env),
        "a bad map replaced the sky"
    );
    // One undo takes the map away again, back to the turned uniform sky.
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    assert_eq!(sky_cd_m2(h.state()), Some(new_sky));
}

/// Daylight, in the Environment section: "Add daylight" puts an overcast sky of 10,000 lx for a
/// place and time into the scene (the render restarts); the time-of-day slider moves the sun
/// (07:30 puts it in the south-east, low); a date that does not exist is shown in red and the
/// scene keeps its daylight; the sidecar saves `[daylight]`; "Remove daylight" takes the sky
/// away and undo brings it back.
#[test]
fn daylight_is_added_its_sun_moves_and_it_is_saved() {
    let mut h = viewer();
    assert!(h.state().document().setup.daylight.is_none());
    let generation = h.state().worker().generation();
    h.get_by_role_and_label(Role::Button, "Add daylight")
        .click();
    h.run_steps(2);
    let setup = &h.state().document().setup;
    let d = setup.daylight.as_ref().expect("daylight added");
    assert_eq!(d.spec.sky.as_deref(), Some("cie-overcast"));
    assert!(matches!(
        setup.environment.as_ref().map(|e| &e.source),
        Some(EnvironmentSource::Map(_))
    ));
    assert!(h.state().worker().generation() > generation, "no restart");
    let noon = d.sun();

    h.get_by_role_and_label(Role::Slider, "local time")
        .set_value_accesskit(450.0);
    h.run_steps(2);
    let d = h.state().document().setup.daylight.clone().unwrap();
    assert_eq!(d.spec.time, "07:30");
    let morning = d.sun();
    assert!(
        morning.altitude_deg < noon.altitude_deg - 30.0 && morning.azimuth_deg < 120.0,
        "{morning:?} vs {noon:?}"
    );

    let path = scratch_dir("daylight").join("box.raygine.toml");
    let ctx = h.state().context().clone();
    h.state_mut().save_sidecar(&ctx, path.clone());
    step_until(&mut h, "the sidecar write", |app| !app.writing());
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.contains("[daylight]")
            && text.contains("time = \"07:30\"")
            && !text.contains("[environment]"),
        "{text}"
    );

    h.get_by_role_and_label(Role::Button, "Remove daylight")
        .click();
    h.run_steps(2);
    assert!(h.state().document().setup.daylight.is_none());
    assert_eq!(h.state().document().setup.environment, None);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.step();
    assert!(h.state().document().setup.daylight.is_some(), "undo");
}

/// The Measure section's "DF (%)" (daylight factor): the grids are measured under the overcast sky
/// alone and read in %. The built-in box is open at the front, so some daylight gets in: DF
/// between 0 and 100 %, more near the opening than at the back wall.
#[test]
fn grids_read_daylight_factors_when_asked() {
    let mut h = viewer();
    h.get_by_label("Measure").click();
    h.run_steps(2);
    h.get_by_role_and_label(Role::Button, "Add work plane")
        .click();
    h.step();
    step_until(&mut h, "the first refinement", |app| {
        app.measure().readings().is_some_and(|r| r.samples >= 16)
    });
    let lit = h.state().measure().readings().unwrap();
    assert!(!lit.daylight_factor);
    assert!(lit.results[0].statistics().e_avg_lx > 0.0);
    // Scroll the side panel down to the row under the grid (wheel over the panel).
    let panel = h.get_by_label("Measure").rect().center();
    h.hover_at(panel);
    for _ in 0..4 {
        h.event(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Point,
            delta: Vec2::new(0.0, -120.0),
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Unknown,
            modifiers: Modifiers::NONE,
        });
        h.step();
    }
    h.run_steps(2);
    h.get_by_role_and_label(Role::CheckBox, "DF (%)").click();
    h.step();
    step_until(&mut h, "the daylight factors", |app| {
        app.measure()
            .readings()
            .is_some_and(|r| r.daylight_factor && r.samples >= 16)
    });
    let df = h.state().measure().readings().unwrap();
    let s = df.results[0].statistics();
    assert!(
        s.e_min_lx >= 0.0 && s.e_max_lx > 0.0 && s.e_max_lx < 100.0,
        "{s:?}"
    );
    assert!(s.e_max_lx > 2.0 * s.e_min_lx, "{s:?}");
}
