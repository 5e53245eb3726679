//! The side panel, menu bar, status bar and windows of the viewer.

mod camera;
mod frame;
mod lights;
mod materials;
mod measure;
mod reflectance;
mod render;
mod windows;

pub use windows::windows_ui;

use frame::frame_ui;

use crate::app::{
    RaygineApp, SHORTCUT_EXPORT, SHORTCUT_OPEN, SHORTCUT_REDO, SHORTCUT_SAVE, SHORTCUT_UNDO,
};
use crate::file_ops::DialogPurpose;

/// All control groups of the side panel.
pub fn controls_ui(ui: &mut egui::Ui, app: &mut RaygineApp) {
    ui.heading(app.doc.scene.name.clone());
    ui.label(format!(
        "{} triangles, {} breps",
        app.doc.scene.triangle_count(),
        app.doc.scene.breps.len(),
    ));
    if let Some(unit) = frame_ui(ui, app) {
        app.request(crate::unsaved::Switch::Unit(unit));
    }
    ui.separator();
    egui::CollapsingHeader::new("Lights")
        .default_open(true)
        .show(ui, |ui| lights::lights_ui(ui, app));
    egui::CollapsingHeader::new("Camera")
        .default_open(true)
        .show(ui, |ui| camera::camera_ui(ui, app));
    egui::CollapsingHeader::new("Materials")
        .default_open(true)
        .show(ui, |ui| materials::materials_ui(ui, app));
    egui::CollapsingHeader::new("Measure")
        .default_open(false)
        .show(ui, |ui| measure::measure_ui(ui, app));
    egui::CollapsingHeader::new("Render")
        .default_open(true)
        .show(ui, |ui| render::render_ui(ui, app));
}

pub fn menu_bar(ui: &mut egui::Ui, app: &mut RaygineApp) {
    egui::Panel::top("menu").show(ui, |ui| {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| file_menu_ui(ui, app));
            ui.menu_button("Edit", |ui| {
                let ctx = ui.ctx().clone();
                if ui
                    .add_enabled(
                        app.history.can_undo_from(&app.doc.setup),
                        egui::Button::new("Undo")
                            .shortcut_text(ctx.format_shortcut(&SHORTCUT_UNDO)),
                    )
                    .clicked()
                {
                    app.undo();
                    ui.close();
                }
                if ui
                    .add_enabled(
                        app.history.can_redo(),
                        egui::Button::new("Redo")
                            .shortcut_text(ctx.format_shortcut(&SHORTCUT_REDO)),
                    )
                    .clicked()
                {
                    app.redo();
                    ui.close();
                }
            });
            ui.menu_button("View", |ui| {
                ui.checkbox(&mut app.show_controls, "Side panel")
                    .on_hover_text("Hide the controls to give the picture the whole window");
                if ui
                    .add(egui::Button::new("Frame scene").shortcut_text("F"))
                    .clicked()
                {
                    app.frame_scene();
                    ui.close();
                }
                let label = if app.paused {
                    "Resume rendering"
                } else {
                    "Pause rendering"
                };
                if ui
                    .add(egui::Button::new(label).shortcut_text("P"))
                    .clicked()
                {
                    app.paused = !app.paused;
                    app.worker.set_paused(app.paused);
                    ui.close();
                }
            });
            ui.menu_button("Help", |ui| {
                if ui.button("Controls and shortcuts").clicked() {
                    app.show_help = true;
                    ui.close();
                }
            });
        });
    });
}

fn file_menu_ui(ui: &mut egui::Ui, app: &mut RaygineApp) {
    let ctx = ui.ctx().clone();
    if ui
        .add(egui::Button::new("Open…").shortcut_text(ctx.format_shortcut(&SHORTCUT_OPEN)))
        .clicked()
    {
        app.prompt_path(DialogPurpose::Open);
        ui.close();
    }
    ui.menu_button("Open recent", |ui| {
        if app.prefs.recent.is_empty() {
            ui.label("(none)");
        }
        for path in app.prefs.recent.clone() {
            if ui.button(path.display().to_string()).clicked() {
                app.request(crate::unsaved::Switch::Open(path));
                ui.close();
            }
        }
    });
    if ui.button("Open built-in Cornell box").clicked() {
        app.request(crate::unsaved::Switch::Builtin);
        ui.close();
    }
    ui.separator();
    if ui
        .add(
            egui::Button::new("Save scene settings")
                .shortcut_text(ctx.format_shortcut(&SHORTCUT_SAVE)),
        )
        .on_hover_text("Materials, lights and camera, saved as NAME.raygine.toml next to the scene")
        .clicked()
    {
        match app.doc.path.clone() {
            Some(p) => app.save_sidecar(&ctx, tracer_core::scene::sidecar_path(&p)),
            None => app.prompt_path(DialogPurpose::SaveSidecar),
        }
        ui.close();
    }
    if ui.button("Save scene settings as…").clicked() {
        app.prompt_path(DialogPurpose::SaveSidecar);
        ui.close();
    }
    ui.separator();
    if ui
        .add(egui::Button::new("Export PNG…").shortcut_text(ctx.format_shortcut(&SHORTCUT_EXPORT)))
        .on_hover_text("The image as displayed (exposure, tone mapping, false colour)")
        .clicked()
    {
        app.prompt_path(DialogPurpose::ExportPng);
        ui.close();
    }
    if ui
        .button("Export EXR…")
        .on_hover_text("Linear luminance per channel, cd/m², 32-bit float")
        .clicked()
    {
        app.prompt_path(DialogPurpose::ExportExr);
        ui.close();
    }
    if ui.button("Render image…").clicked() {
        let [w, h] = app.viewport_px;
        app.render_image_form = Some(crate::app::RenderImageForm {
            width: w.max(640),
            height: h.max(360),
            samples: 64,
            path: app
                .suggested_path(DialogPurpose::RenderImage)
                .display()
                .to_string(),
        });
        ui.close();
    }
    ui.separator();
    if ui
        .add(
            egui::Button::new("Quit")
                .shortcut_text(ctx.format_shortcut(&crate::app::SHORTCUT_QUIT)),
        )
        .clicked()
    {
        app.request(crate::unsaved::Switch::Quit);
        ui.close();
    }
}

/// One line at the bottom; what does not fit is cut off at the window's edge. It never wraps:
/// a second line would shrink the viewport, whose new size restarts the render, whose new
/// figures could unwrap it again (a narrow window restarted the render every frame).
pub fn status_bar(ui: &mut egui::Ui, app: &mut RaygineApp) {
    egui::Panel::bottom("status").show(ui, |ui| {
        ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Extend);
        ui.horizontal(|ui| {
            let s = app.worker.stats();
            let state = if app.paused {
                "paused"
            } else if s.finished {
                "converged"
            } else {
                "rendering"
            };
            ui.label(format!(
                "{state} · {} · {}/{} spp · {} · {:.1} Mrays/s · {:.1} s",
                app.render.integrator.label(),
                s.samples_per_pixel,
                s.target_spp,
                s.pass,
                s.mrays_per_sec(),
                s.elapsed_secs
            ));
            if let Some(noise) = s.relative_noise {
                ui.label(format!("noise ±{:.1} %", noise * 100.0))
                    .on_hover_text(
                        "Remaining noise: RMS standard error of the pixels' luminance over the \
                     mean luminance, from the summed squares of the samples",
                    );
            }
            ui.separator();
            ui.label(format!(
                "{} tris · BVH {:.0} ms · parse {:.0} ms",
                app.doc.scene.triangle_count(),
                app.doc.scene.bvh_build_secs * 1e3,
                app.doc.parse_secs * 1e3
            ));
            ui.separator();
            ui.label(format!(
                "{}x{} px · {} threads",
                app.viewport_px[0], app.viewport_px[1], s.threads
            ));
            if let Some(l) = &app.loading {
                ui.separator();
                ui.spinner();
                ui.label(format!(
                    "loading {} ({:.1} s)",
                    l.path.file_name().map_or_else(
                        || l.path.display().to_string(),
                        |n| n.to_string_lossy().into_owned()
                    ),
                    l.started.elapsed().as_secs_f32()
                ));
                if ui
                    .button("Cancel")
                    .on_hover_text("Keep the current scene")
                    .clicked()
                {
                    app.loading = None;
                }
            }
            if let Some(p95) = app.p95_frame_ms() {
                ui.separator();
                ui.label(format!("UI p95 {p95:.0} ms"));
            }
        });
    });
}
