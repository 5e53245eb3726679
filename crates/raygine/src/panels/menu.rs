//! The menu bar: File, Edit, View and Help.

use crate::command::{Command, Commands};
use crate::file_ops::DialogPurpose;
use crate::shortcuts::{
    SHORTCUT_EXPORT, SHORTCUT_OPEN, SHORTCUT_QUIT, SHORTCUT_REDO, SHORTCUT_SAVE, SHORTCUT_UNDO,
};
use crate::unsaved::Switch;
use std::path::PathBuf;

/// What the menus show, and the view toggles they edit in place.
#[derive(Debug)]
pub struct MenuBar<'a> {
    pub can_undo: bool,
    pub can_redo: bool,
    pub paused: bool,
    /// Recently opened scenes, newest first.
    pub recent: &'a [PathBuf],
    pub show_controls: &'a mut bool,
    pub show_help: &'a mut bool,
    /// The Notes window's flag, and how many notes the scene has.
    pub show_notes: &'a mut bool,
    pub notes: usize,
    /// Whether the ground plane is shown.
    pub ground: bool,
}

/// The menu bar; what the user picks is a command, except the view toggles it is given.
pub fn menu_bar(ui: &mut egui::Ui, m: MenuBar<'_>, out: &mut Commands) {
    egui::Panel::top("menu").show(ui, |ui| {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| file_menu_ui(ui, m.recent, out));
            ui.menu_button("Edit", |ui| {
                let ctx = ui.ctx().clone();
                if ui
                    .add_enabled(
                        m.can_undo,
                        egui::Button::new("Undo")
                            .shortcut_text(ctx.format_shortcut(&SHORTCUT_UNDO)),
                    )
                    .clicked()
                {
                    out.push(Command::Undo);
                    ui.close();
                }
                if ui
                    .add_enabled(
                        m.can_redo,
                        egui::Button::new("Redo")
                            .shortcut_text(ctx.format_shortcut(&SHORTCUT_REDO)),
                    )
                    .clicked()
                {
                    out.push(Command::Redo);
                    ui.close();
                }
            });
            ui.menu_button("View", |ui| {
                ui.checkbox(m.show_controls, "Side panel")
                    .on_hover_text("Hide the controls to give the picture the whole window");
                ui.checkbox(m.show_notes, format!("Notes ({})", m.notes))
                    .on_hover_text("Every warning the scene's files gave when read, in full");
                let mut ground = m.ground;
                if ui
                    .checkbox(&mut ground, "Ground plane")
                    .on_hover_text(format!(
                        "A grey diffuse floor (reflectance {}) under a lone object, listed as \
                         the surface {}: it reflects light like any surface and is not saved \
                         with the scene settings",
                        tracer_core::scene::GROUND_REFLECTANCE,
                        tracer_core::scene::GROUND_NAME
                    ))
                    .changed()
                {
                    out.push(Command::SetGround(ground));
                    ui.close();
                }
                if ui
                    .add(egui::Button::new("Frame scene").shortcut_text("F"))
                    .clicked()
                {
                    out.push(Command::FrameScene);
                    ui.close();
                }
                if ui
                    .add(egui::Button::new("Reset camera").shortcut_text("Home"))
                    .on_hover_text("Back to the scene's own camera, as opened or last saved")
                    .clicked()
                {
                    out.push(Command::ResetCamera);
                    ui.close();
                }
                let label = if m.paused {
                    "Resume rendering"
                } else {
                    "Pause rendering"
                };
                if ui
                    .add(egui::Button::new(label).shortcut_text("P"))
                    .clicked()
                {
                    out.push(Command::TogglePause);
                    ui.close();
                }
            });
            ui.menu_button("Help", |ui| {
                if ui.button("Controls and shortcuts").clicked() {
                    *m.show_help = true;
                    ui.close();
                }
            });
        });
    });
}

fn file_menu_ui(ui: &mut egui::Ui, recent: &[PathBuf], out: &mut Commands) {
    let ctx = ui.ctx().clone();
    if ui
        .add(egui::Button::new("Open…").shortcut_text(ctx.format_shortcut(&SHORTCUT_OPEN)))
        .clicked()
    {
        out.push(Command::PromptPath(DialogPurpose::Open));
        ui.close();
    }
    ui.menu_button("Open recent", |ui| {
        if recent.is_empty() {
            ui.label("(none)");
        }
        for path in recent {
            if ui.button(path.display().to_string()).clicked() {
                out.push(Command::Switch(Switch::Open(path.clone())));
                ui.close();
            }
        }
    });
    if ui.button("Open built-in Cornell box").clicked() {
        out.push(Command::Switch(Switch::Builtin));
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
        out.push(Command::SaveSidecar);
        ui.close();
    }
    if ui.button("Save scene settings as…").clicked() {
        out.push(Command::PromptPath(DialogPurpose::SaveSidecar));
        ui.close();
    }
    ui.separator();
    if ui
        .add(egui::Button::new("Export PNG…").shortcut_text(ctx.format_shortcut(&SHORTCUT_EXPORT)))
        .on_hover_text("The image as displayed (exposure, tone mapping, false colour)")
        .clicked()
    {
        out.push(Command::PromptPath(DialogPurpose::ExportPng));
        ui.close();
    }
    if ui
        .button("Export EXR…")
        .on_hover_text("Linear luminance per channel, cd/m², 32-bit float")
        .clicked()
    {
        out.push(Command::PromptPath(DialogPurpose::ExportExr));
        ui.close();
    }
    if ui
        .button("Save report…")
        .on_hover_text(
            "A lighting report (PDF): settings, a view, each grid's plan and statistics, the \
             luminaire schedule and the requirements check; written in the background",
        )
        .clicked()
    {
        out.push(Command::PromptPath(DialogPurpose::SaveReport));
        ui.close();
    }
    if ui.button("Render image…").clicked() {
        out.push(Command::OpenRenderImageForm);
        ui.close();
    }
    ui.separator();
    if ui
        .add(egui::Button::new("Quit").shortcut_text(ctx.format_shortcut(&SHORTCUT_QUIT)))
        .clicked()
    {
        out.push(Command::Switch(Switch::Quit));
        ui.close();
    }
}
