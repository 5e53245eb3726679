//! The scene's frame: its length unit (reads the scene again) and handedness (a setup edit).

use tracer_core::scene::{Handedness, LengthUnit, Setup};

/// Draws the unit and handedness choices; returns the unit the user picked, if it changed (and
/// no scene is being loaded).
pub fn frame_ui(ui: &mut egui::Ui, setup: &mut Setup, loading: bool) -> Option<LengthUnit> {
    let mut unit = setup.unit;
    ui.horizontal(|ui| {
        egui::ComboBox::from_label("unit")
            .selected_text(unit.symbol())
            .show_ui(ui, |ui| {
                for u in LengthUnit::ALL {
                    ui.selectable_value(&mut unit, u, u.symbol());
                }
            })
            .response
            .on_hover_text(
                "The unit of the file's coordinates. Changing it reads the scene again (the \
                 default light and camera follow; unsaved edits are dropped)",
            );
        let h = &mut setup.handedness;
        egui::ComboBox::from_label("handedness")
            .selected_text(handedness_name(*h))
            .show_ui(ui, |ui| {
                for k in [Handedness::Left, Handedness::Right] {
                    ui.selectable_value(h, k, handedness_name(k));
                }
            })
            .response
            .on_hover_text(
                "Left-handed (Lumicept's files): a camera at +Z looking towards -Z sees +X on \
                 the left. Right-handed: +X on the right. Only the camera's picture changes",
            );
    });
    (unit != setup.unit && !loading).then_some(unit)
}

fn handedness_name(h: Handedness) -> &'static str {
    match h {
        Handedness::Left => "left-handed",
        Handedness::Right => "right-handed",
    }
}
