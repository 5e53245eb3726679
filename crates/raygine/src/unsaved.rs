//! Unsaved edits: switching scenes or quitting asks first when the setup differs from what was
//! loaded or last saved. Actions that would drop edits go through [`Switch`]; the window returns
//! the user's choice and the app applies it.

use std::path::PathBuf;
use tracer_core::scene::LengthUnit;

/// An action that replaces the scene (or ends the viewer) and would drop unsaved edits.
#[derive(Clone, Debug, PartialEq)]
pub enum Switch {
    Open(PathBuf),
    Builtin,
    Unit(LengthUnit),
    Quit,
}

impl Switch {
    fn describe(&self) -> String {
        match self {
            Switch::Open(p) => format!("open {}", p.display()),
            Switch::Builtin => "open the built-in Cornell box".to_owned(),
            Switch::Unit(u) => format!("read the scene again in {}", u.symbol()),
            Switch::Quit => "quit".to_owned(),
        }
    }
}

/// What the user chose in the unsaved-edits window.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Choice {
    /// Save the scene settings, then go on.
    Save,
    /// Drop the edits and go on.
    Discard,
    /// Stay with the edits.
    Cancel,
}

/// The window asking about unsaved edits before `switch`. `can_save` is false for a scene
/// without a file (the built-in box), whose settings need "Save scene settings as…" first.
pub fn unsaved_ui(ctx: &egui::Context, switch: &Switch, can_save: bool) -> Option<Choice> {
    let mut choice = None;
    egui::Window::new("Unsaved changes")
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
        .show(ctx, |ui| {
            ui.label(format!(
                "The lights, materials or camera changed since the scene settings were loaded \
                 or saved. Save them before you {}?",
                switch.describe()
            ));
            ui.horizontal(|ui| {
                let save = ui
                    .add_enabled(can_save, egui::Button::new("Save and continue"))
                    .on_hover_text("Write NAME.raygine.toml beside the scene, then go on")
                    .on_disabled_hover_text(
                        "This scene has no file: use File > Save scene settings as… first",
                    );
                if save.clicked() {
                    choice = Some(Choice::Save);
                }
                if ui.button("Discard changes").clicked() {
                    choice = Some(Choice::Discard);
                }
                if ui.button("Cancel").clicked() {
                    choice = Some(Choice::Cancel);
                }
            });
        });
    choice
}
