//! Floating windows: the path prompt (typed path plus the native dialog), "Render image...",
//! and the help window.

use crate::app::RaygineApp;
use crate::file_ops::{DialogPurpose, PendingDialog};
use std::path::PathBuf;

pub fn windows_ui(ctx: &egui::Context, app: &mut RaygineApp) {
    path_prompt_ui(ctx, app);
    render_image_ui(ctx, app);
    help_ui(ctx, app);
}

fn title(purpose: DialogPurpose) -> &'static str {
    match purpose {
        DialogPurpose::Open => "Open scene",
        DialogPurpose::ExportPng => "Export PNG",
        DialogPurpose::ExportExr => "Export EXR",
        DialogPurpose::SaveSidecar => "Save scene settings",
        DialogPurpose::RenderImage => "Render image to",
    }
}

fn path_prompt_ui(ctx: &egui::Context, app: &mut RaygineApp) {
    let Some(mut prompt) = app.prompt.take() else {
        return;
    };
    let mut open = true;
    let mut confirmed: Option<PathBuf> = None;
    let mut closed_by_key = false;
    egui::Window::new(title(prompt.purpose))
        .collapsible(false)
        .open(&mut open)
        .show(ctx, |ui| {
            let mut submitted = false;
            ui.horizontal(|ui| {
                let label = ui.label("Path:");
                let edit = ui
                    .add(egui::TextEdit::singleline(&mut prompt.text).desired_width(360.0))
                    .labelled_by(label.id);
                if std::mem::take(&mut prompt.focus_field) {
                    edit.request_focus();
                }
                if edit.changed() {
                    prompt.confirm_overwrite = false;
                }
                if edit.lost_focus() {
                    let (enter, escape) = ui.input(|i| {
                        (
                            i.key_pressed(egui::Key::Enter),
                            i.key_pressed(egui::Key::Escape),
                        )
                    });
                    submitted = enter;
                    if escape {
                        closed_by_key = true;
                    }
                }
                if ui
                    .button("Browse…")
                    .on_hover_text("Native file dialog (if the desktop has one)")
                    .clicked()
                {
                    let suggested = PathBuf::from(&prompt.text);
                    prompt.note = None;
                    app.dialog = Some(PendingDialog::start(prompt.purpose, Some(&suggested), ctx));
                }
            });
            if let Some(note) = &prompt.note {
                ui.colored_label(egui::Color32::from_rgb(255, 210, 90), note);
            }
            let path = PathBuf::from(prompt.text.trim());
            let writes = prompt.purpose != DialogPurpose::Open;
            if prompt.confirm_overwrite {
                ui.colored_label(
                    egui::Color32::YELLOW,
                    format!("{} exists. Replace it?", path.display()),
                );
            }
            let label = match (prompt.purpose, prompt.confirm_overwrite) {
                (DialogPurpose::Open, _) => "Open",
                (_, true) => "Replace",
                _ => "Save",
            };
            submitted |= ui.button(label).clicked();
            if submitted && !prompt.text.trim().is_empty() {
                if writes && path.exists() && !prompt.confirm_overwrite {
                    prompt.confirm_overwrite = true;
                    // Enter again (or the button) replaces the file.
                    prompt.focus_field = true;
                } else {
                    confirmed = Some(path);
                }
            }
        });
    if closed_by_key {
        open = false;
    }
    match confirmed {
        Some(path) => app.run_path_action(ctx, prompt.purpose, path),
        None if open => app.prompt = Some(prompt),
        None => {}
    }
}

fn render_image_ui(ctx: &egui::Context, app: &mut RaygineApp) {
    if let Some(job) = &app.render_image_job {
        let stats = job.worker.stats();
        let mut cancel = false;
        egui::Window::new("Rendering image")
            .collapsible(false)
            .show(ctx, |ui| {
                let done = stats.samples_per_pixel as f32 / stats.target_spp.max(1) as f32;
                ui.label(format!("{}, writing {}", stats.pass, job.path.display()));
                ui.add(egui::ProgressBar::new(done).show_percentage());
                ui.label(format!(
                    "{:.1} s, {:.1} Mrays/s",
                    stats.elapsed_secs,
                    stats.mrays_per_sec()
                ));
                cancel = ui.button("Cancel").clicked();
            });
        if cancel {
            app.render_image_job = None;
            app.notice = Some("render cancelled".to_owned());
        }
        return;
    }
    let Some(mut form) = app.render_image_form.take() else {
        return;
    };
    let mut open = true;
    let mut start = false;
    egui::Window::new("Render image")
        .collapsible(false)
        .open(&mut open)
        .show(ctx, |ui| {
            ui.horizontal(|ui| {
                ui.label("size (px)");
                ui.add(egui::DragValue::new(&mut form.width).range(1..=16_384));
                ui.label("×");
                ui.add(egui::DragValue::new(&mut form.height).range(1..=16_384));
            });
            ui.add(
                egui::Slider::new(&mut form.samples, 1..=4096)
                    .logarithmic(true)
                    .text("samples per pixel"),
            );
            ui.horizontal(|ui| {
                ui.label("PNG:");
                ui.text_edit_singleline(&mut form.path);
            });
            start = ui.button("Render").clicked();
        });
    if start && !form.path.trim().is_empty() {
        let path = PathBuf::from(form.path.trim());
        app.render_image_form = Some(form);
        app.start_render_image(path);
    } else if open {
        app.render_image_form = Some(form);
    }
}

fn help_ui(ctx: &egui::Context, app: &mut RaygineApp) {
    egui::Window::new("Controls and shortcuts")
        .open(&mut app.show_help)
        .show(ctx, |ui| {
            egui::Grid::new("keys").striped(true).show(ui, |ui| {
                for (k, what) in [
                    ("Ctrl+O", "open a .shp scene (or drop one on the window)"),
                    (
                        "Ctrl+S",
                        "save materials, lights, camera (NAME.raygine.toml)",
                    ),
                    ("Ctrl+E", "export the image as displayed (PNG)"),
                    ("Ctrl+Z / Ctrl+Shift+Z", "undo / redo scene edits"),
                    ("F", "frame the scene"),
                    ("P", "pause / resume rendering"),
                    ("Ctrl+Q", "quit (settings and recent files are kept)"),
                    ("drag", "orbit about the look-at point"),
                    ("shift-drag, middle-drag", "pan"),
                    ("wheel", "dolly"),
                    ("click", "select the surface's material"),
                ] {
                    ui.monospace(k);
                    ui.label(what);
                    ui.end_row();
                }
            });
            ui.label("Units: intensity cd, illuminance lx, luminance cd/m² (Rec. 709 Y).");
        });
}
