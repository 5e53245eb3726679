//! Floating windows: the path prompt (typed path plus the native dialog), "Render image...",
//! and the help window. Each owns the values it edits; what the user confirms is a command.

use crate::command::{Command, Commands};
use crate::file_ops::DialogPurpose;
use crate::render_image::RenderImageJob;
use std::path::PathBuf;

/// What the path window (typed path, with a Browse... button for the native dialog) is for.
#[derive(Clone, Debug)]
pub struct PathPrompt {
    pub purpose: DialogPurpose,
    pub text: String,
    /// Set when the file exists and the user must confirm overwriting it.
    pub confirm_overwrite: bool,
    /// The path field takes keyboard focus on the next frame (set when the window opens).
    pub focus_field: bool,
    /// Why Browse… did not help (no desktop file dialog), shown in the window.
    pub note: Option<String>,
}

impl PathPrompt {
    /// A path window for `purpose` with `text` typed in; its field takes the focus.
    pub fn new(purpose: DialogPurpose, text: String) -> Self {
        Self {
            purpose,
            text,
            confirm_overwrite: false,
            focus_field: true,
            note: None,
        }
    }
}

/// Values the "Render image..." window edits.
#[derive(Clone, Debug)]
pub struct RenderImageForm {
    pub width: u32,
    pub height: u32,
    pub samples: u32,
    pub path: String,
}

/// The floating windows' state: each is shown while its value is there (or its flag is set).
#[derive(Debug)]
pub struct Windows<'a> {
    pub prompt: &'a mut Option<PathPrompt>,
    pub render_image_form: &'a mut Option<RenderImageForm>,
    /// The running "Render image..." job, whose progress is shown instead of the form.
    pub render_image_job: Option<&'a RenderImageJob>,
    pub show_help: &'a mut bool,
}

pub fn windows_ui(ctx: &egui::Context, w: Windows<'_>, out: &mut Commands) {
    path_prompt_ui(ctx, w.prompt, out);
    render_image_ui(ctx, w.render_image_form, w.render_image_job, out);
    help_ui(ctx, w.show_help);
}

fn title(purpose: DialogPurpose) -> &'static str {
    match purpose {
        DialogPurpose::Open => "Open scene",
        DialogPurpose::ExportPng => "Export PNG",
        DialogPurpose::ExportExr => "Export EXR",
        DialogPurpose::SaveSidecar => "Save scene settings",
        DialogPurpose::RenderImage => "Render image to",
        DialogPurpose::EnvironmentMap => "Load environment map",
        DialogPurpose::SaveReport => "Save report (PDF)",
    }
}

fn path_prompt_ui(ctx: &egui::Context, shown: &mut Option<PathPrompt>, out: &mut Commands) {
    let Some(mut prompt) = shown.take() else {
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
                    prompt.note = None;
                    out.push(Command::Browse {
                        purpose: prompt.purpose,
                        suggested: PathBuf::from(&prompt.text),
                    });
                }
            });
            if let Some(note) = &prompt.note {
                ui.colored_label(egui::Color32::from_rgb(255, 210, 90), note);
            }
            let path = PathBuf::from(prompt.text.trim());
            let writes = prompt.purpose.writes();
            if prompt.confirm_overwrite {
                ui.colored_label(
                    egui::Color32::YELLOW,
                    format!("{} exists. Replace it?", path.display()),
                );
            }
            let label = match (prompt.purpose, prompt.confirm_overwrite) {
                (DialogPurpose::Open, _) => "Open",
                (DialogPurpose::EnvironmentMap, _) => "Load",
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
        Some(path) => out.push(Command::RunPathAction(prompt.purpose, path)),
        None if open => *shown = Some(prompt),
        None => {}
    }
}

fn render_image_ui(
    ctx: &egui::Context,
    shown: &mut Option<RenderImageForm>,
    job: Option<&RenderImageJob>,
    out: &mut Commands,
) {
    if let Some(job) = job {
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
            out.push(Command::CancelRenderImage);
        }
        return;
    }
    let Some(mut form) = shown.take() else {
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
        *shown = Some(form);
        out.push(Command::StartRenderImage(path));
    } else if open {
        *shown = Some(form);
    }
}

fn help_ui(ctx: &egui::Context, show_help: &mut bool) {
    egui::Window::new("Controls and shortcuts")
        .open(show_help)
        .show(ctx, |ui| {
            egui::Grid::new("keys").striped(true).show(ui, |ui| {
                for (k, what) in [
                    (
                        "Ctrl+O",
                        "open a scene (.shp, .brs, .obj, .gltf/.glb, .usda/.usdc/.usdz) or its NAME.raygine.toml (or drop one on the window)",
                    ),
                    (
                        "Ctrl+S",
                        "save materials, lights, camera (NAME.raygine.toml)",
                    ),
                    ("Ctrl+E", "export the image as displayed (PNG)"),
                    ("Ctrl+Z / Ctrl+Shift+Z", "undo / redo scene edits"),
                    ("F", "frame the scene"),
                    ("Home", "reset the camera to the scene's own"),
                    ("P", "pause / resume rendering"),
                    ("D", "denoised / raw picture (readouts always raw)"),
                    ("Ctrl+Q", "quit (settings and recent files are kept)"),
                    (
                        "drag",
                        "orbit about the surface point under the cursor (each finished drag \
                         or wheel turn is one undo step)",
                    ),
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
