//! The viewer's tests through egui_kittest, built as one test binary (the GUI stack is linked
//! once): `viewer` (widgets, files, rendering), `commands` (the command path), `environment`
//! (the Environment section), `denoise` and `first_view` (previews, status figures and exposure
//! in a scene's first seconds).

#![allow(clippy::unwrap_used, clippy::expect_used)]

mod cameras;
mod commands;
mod denoise;
mod environment;
mod first_view;
mod materials;
mod rough_edges;
mod viewer;

/// The app on the built-in box in a `width` x `height` window, 2 render threads, the last
/// scene ignored, with `integrator`, `target_spp` and `scale` (film pixels per screen pixel).
fn box_viewer(
    size: egui::Vec2,
    integrator: tracer_core::integrator::IntegratorKind,
    target_spp: u32,
    scale: f32,
) -> egui_kittest::Harness<'static, raygine::app::RaygineApp> {
    let mut h = egui_kittest::Harness::builder()
        .with_size(size)
        .with_accessibility_check(false)
        .build_eframe(|cc| {
            raygine::app::RaygineApp::new(
                cc,
                raygine::app::AppOptions {
                    threads: 2,
                    ignore_last_scene: true,
                    ..raygine::app::AppOptions::default()
                },
            )
            .expect("the app starts")
        });
    h.state_mut().render_prefs_mut().integrator = integrator;
    h.state_mut().render_prefs_mut().target_spp = target_spp;
    h.state_mut().render_prefs_mut().resolution_scale = scale;
    h
}
