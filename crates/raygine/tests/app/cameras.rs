//! The Camera section's projection menu: a fisheye re-renders with black corners and a lit
//! centre; the light tracer and the orthographic view exclude each other in the menus; the
//! wheel narrows an orthographic view instead of moving the eye; the sidecar keeps it all.

use egui::accesskit::Role;
use egui::{Modifiers, Vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use raygine::app::RaygineApp;
use std::time::{Duration, Instant};
use tracer_core::integrator::IntegratorKind;
use tracer_core::scene::Projection;

const TIMEOUT: Duration = Duration::from_secs(20);

type Viewer = Harness<'static, RaygineApp>;

fn step_until(h: &mut Viewer, what: &str, done: impl Fn(&RaygineApp) -> bool) {
    let deadline = Instant::now() + TIMEOUT;
    while !done(h.state()) {
        assert!(Instant::now() < deadline, "timed out waiting for {what}");
        h.step();
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn choose_projection(h: &mut Viewer, label: &str) {
    h.get_by_role_and_label(Role::ComboBox, "projection")
        .click();
    h.run_steps(2);
    h.get_by_label(label).click();
    h.run_steps(2);
}

/// The current generation's film mean luminance at pixel (x, y) once every pixel has a sample.
fn film_luminance(h: &Viewer, x: u32, y: u32) -> Option<f64> {
    let generation = h.state().worker().generation();
    h.state().worker().with_film(|f| {
        let f = f.filter(|f| f.generation == generation)?;
        (f.accum.min_samples() >= 1).then(|| f.accum.mean_luminance(f.accum.index(x, y)))
    })
}

#[test]
fn a_fisheye_renders_black_corners_and_the_menus_keep_light_tracing_from_orthographic() {
    let mut h = crate::box_viewer(Vec2::new(960.0, 900.0), IntegratorKind::Direct, 1, 0.25);
    h.run_steps(2);
    // Inside the box, so the whole hemisphere sees lit walls.
    h.state_mut().setup_mut().camera.position = [278.0, 273.0, -150.0];
    h.run_steps(2);
    let generation = h.state().worker().generation();
    choose_projection(&mut h, "Fisheye, equidistant (-vta)");
    let camera = h.state().document().setup.camera;
    assert_eq!(camera.projection, Projection::FisheyeEquidistant);
    assert_eq!(camera.fov_deg, 180.0, "a fisheye opens at 180°");
    assert!(h.state().worker().generation() > generation, "no restart");
    step_until(&mut h, "a fisheye film", |app| {
        let generation = app.worker().generation();
        app.worker()
            .current()
            .is_some_and(|k| k.setup.camera.projection == Projection::FisheyeEquidistant)
            && app.worker().with_film(|f| {
                f.is_some_and(|f| f.generation == generation && f.accum.min_samples() >= 1)
            })
    });
    let key = h.state().worker().current().unwrap();
    let (w, hgt) = (key.settings.width, key.settings.height);
    assert_eq!(film_luminance(&h, 0, 0), Some(0.0), "the corner is black");
    let centre = film_luminance(&h, w / 2, hgt / 2).unwrap();
    assert!(centre > 0.0, "the centre sees the lit box: {centre}");
    // The hover readout says nothing outside the circle.
    let basis = h.state().worker().basis().unwrap();
    assert!(basis.pixel_outside(0, 0) && !basis.pixel_outside(w / 2, hgt / 2));

    // Light tracing: the orthographic entry is disabled (a click does nothing).
    h.state_mut().render_prefs_mut().integrator = IntegratorKind::Light;
    h.run_steps(2);
    choose_projection(&mut h, "Orthographic");
    assert_eq!(
        h.state().document().setup.camera.projection,
        Projection::FisheyeEquidistant,
        "the light tracer took an orthographic camera"
    );
    h.key_press(egui::Key::Escape);
    h.run_steps(2);

    // Bidirectional: orthographic is taken, starting at the width the view had.
    h.state_mut().render_prefs_mut().integrator = IntegratorKind::Bidirectional;
    h.run_steps(2);
    choose_projection(&mut h, "Orthographic");
    let camera = h.state().document().setup.camera;
    assert_eq!(camera.projection, Projection::Orthographic);
    let width = camera.width.expect("a width to start from");
    // What a 45° pinhole shows across at the look-at point, not the fisheye's 180° (which
    // made it hundreds of metres): within the box's size.
    assert_eq!(camera.fov_deg, tracer_core::scene::DEFAULT_FOV_DEG);
    let key = h.state().worker().current().unwrap();
    let aspect = key.settings.width as f32 / key.settings.height as f32;
    let distance = (glam::Vec3::from(camera.look_at) - glam::Vec3::from(camera.position)).length();
    let want = 2.0 * distance * 22.5f32.to_radians().tan() * aspect;
    assert!((width / want - 1.0).abs() < 0.02, "{width} vs {want} mm");
    // The wheel over the viewport narrows it and leaves the eye.
    let view = h.get_by_label("viewport").rect().center();
    h.hover_at(view);
    for _ in 0..3 {
        h.event(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Point,
            delta: Vec2::new(0.0, 60.0),
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Unknown,
            modifiers: Modifiers::NONE,
        });
        h.step();
    }
    h.run_steps(2);
    let after = h.state().document().setup.camera;
    assert_eq!(after.position, camera.position, "the eye stayed");
    assert!(after.width.unwrap() < width, "{:?} vs {width}", after.width);
    // With an orthographic camera the light tracer's entry is disabled in the Render section.
    h.get_by_role_and_label(Role::ComboBox, "light transport")
        .click();
    h.run_steps(2);
    h.get_by_label("Global illumination (light tracing)")
        .click();
    h.run_steps(2);
    assert_eq!(
        h.state().render_prefs().integrator,
        IntegratorKind::Bidirectional
    );
}

/// A scene that opens with an orthographic camera while the light tracer is chosen renders
/// bidirectionally and says why.
#[test]
fn an_orthographic_scene_under_the_light_tracer_switches_to_bidirectional_with_a_notice() {
    let mut h = crate::box_viewer(Vec2::new(960.0, 900.0), IntegratorKind::Light, 1, 0.25);
    h.run_steps(2);
    h.state_mut().setup_mut().camera.projection = Projection::Orthographic;
    h.run_steps(3);
    assert_eq!(
        h.state().render_prefs().integrator,
        IntegratorKind::Bidirectional
    );
    assert!(
        h.query_by_label_contains("Switched to bidirectional")
            .is_some(),
        "no notice"
    );
}

/// The box in `integrator` mode with the side panel's other groups closed and Glare open.
fn glare_section(
    integrator: IntegratorKind,
) -> egui_kittest::Harness<'static, raygine::app::RaygineApp> {
    let mut h = crate::box_viewer(Vec2::new(960.0, 900.0), integrator, 1, 0.25);
    h.run_steps(2);
    for group in ["Lights", "Camera", "Materials", "Render"] {
        h.get_by_label(group).click();
        h.step();
    }
    h.get_by_label("Glare").click();
    h.run_steps(2);
    h
}

fn add_observer_at_camera(h: &mut egui_kittest::Harness<'static, raygine::app::RaygineApp>) {
    h.get_by_role_and_label(Role::Button, "Add observer at camera")
        .click();
    h.run_steps(2);
}

/// The Glare section's observers: one added where the camera stands, its glare judged in the
/// background and shown (UGR and DGP with their errors), then "View from observer" looks
/// through a 180° equidistant fisheye from it; the eye stays where the camera was.
#[test]
fn an_observer_is_added_at_the_camera_and_viewed_through_a_fisheye() {
    let mut h = glare_section(IntegratorKind::Direct);
    let before = h.state().document().setup.camera;
    add_observer_at_camera(&mut h);
    let observers = h.state().document().setup.observers.clone();
    assert_eq!(observers.len(), 1);
    assert_eq!(observers[0].name, "observer1");
    assert_eq!(observers[0].position, before.position);
    // The glare worker's first refinement (4 spp at 400 x 400 on one thread).
    let started = std::time::Instant::now();
    while h.state().glare_readings().is_none() && started.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(50));
        h.step();
    }
    let readings = h.state().glare_readings().expect("glare within a minute");
    let judged = readings.observers[0].result.as_ref().expect("the eye sees");
    // The box's light is in view from the default camera: one source, a UGR and a DGP.
    assert!(!judged.from_image.sources.is_empty());
    assert!(judged.from_image.ugr.is_some_and(|u| u.is_finite()));
    assert!(judged.from_image.dgp > 0.16 && judged.from_image.dgp < 1.0);
    h.run_steps(2);
    assert!(
        h.query_by_label_contains("Image: UGR").is_some(),
        "the Glare section shows the image's UGR"
    );
    h.get_by_role_and_label(Role::Button, "View from observer")
        .click();
    h.run_steps(2);
    let camera = h.state().document().setup.camera;
    assert_eq!(camera.projection, Projection::FisheyeEquidistant);
    assert_eq!((camera.fov_deg, camera.position), (180.0, before.position));
}

/// In bidirectional mode the Glare section's errors come from independent batches of samples
/// (one a sample: four at the first refinement), since light subpaths splat into many pixels.
#[test]
fn bidirectional_glare_errors_come_from_independent_batches() {
    let mut h = glare_section(IntegratorKind::Bidirectional);
    add_observer_at_camera(&mut h);
    let started = std::time::Instant::now();
    while h.state().glare_readings().is_none() && started.elapsed().as_secs() < 90 {
        std::thread::sleep(std::time::Duration::from_millis(50));
        h.step();
    }
    let readings = h.state().glare_readings().expect("glare within 90 s");
    assert_eq!(readings.samples, 4);
    let judged = readings.observers[0].result.as_ref().expect("the eye sees");
    assert_eq!(judged.from_image.error_batches, Some(4));
    assert!(judged.from_image.ugr_se.is_finite() && judged.from_image.ugr_se > 0.0);
}

/// An observer edit that would make it invalid (a zero line of sight) is refused: the observer
/// keeps its numbers and the reason stays on screen, not for one frame only.
#[test]
fn a_refused_observer_edit_keeps_the_observer_and_says_why() {
    let mut h = glare_section(IntegratorKind::Direct);
    add_observer_at_camera(&mut h);
    let before = h.state().document().setup.observers[0].clone();
    assert_eq!(
        before.direction,
        [0.0, 0.0, -1.0],
        "the box camera looks along -z"
    );
    h.get_by_label("edit observer1").click();
    h.run_steps(2);
    let fields = h
        .get_all_by_role_and_label(Role::SpinButton, "line of sight")
        .count();
    assert_eq!(fields, 3, "x, y and z of the line of sight");
    // z from -1 to 0: a zero line of sight.
    h.get_all_by_role_and_label(Role::SpinButton, "line of sight")
        .nth(2)
        .unwrap()
        .set_value_accesskit(0.0);
    h.run_steps(3);
    assert_eq!(
        h.state().document().setup.observers[0],
        before,
        "the edit was kept"
    );
    for _ in 0..10 {
        h.step();
    }
    assert!(
        h.query_by_label_contains("edit refused").is_some(),
        "the reason is not on screen ten frames later"
    );
}
