//! The scene's frame: its length unit (reads the scene again) and handedness (a setup edit).

use tracer_core::scene::{Handedness, LengthUnit, Setup};

/// Draws the unit and handedness choices, and the scene's size with a one-click unit change when
/// the size looks like another unit's (`diagonal`: the bounds' diagonal in file units); returns
/// the unit the user picked, if it changed (and no scene is being loaded).
pub fn frame_ui(
    ui: &mut egui::Ui,
    setup: &mut Setup,
    diagonal: f32,
    loading: bool,
) -> Option<LengthUnit> {
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
    let size = crate::format::format_quantity(diagonal * setup.unit.metres_per_unit(), "m");
    match setup.unit.suggested_unit(diagonal) {
        Some(better) => {
            ui.horizontal_wrapped(|ui| {
                ui.colored_label(
                    egui::Color32::from_rgb(255, 210, 90),
                    format!(
                        "{size} across in {}: written in {}?",
                        setup.unit.symbol(),
                        better.symbol()
                    ),
                )
                .on_hover_text(
                    "Rooms and objects people light are 5 cm to 500 m across; this scene's size \
                     in its unit is outside that",
                );
                if ui
                    .button(format!("Use {}", better.symbol()))
                    .on_hover_text("Read the scene again with this unit")
                    .clicked()
                {
                    unit = better;
                }
            });
        }
        None => {
            ui.label(format!("{size} across"))
                .on_hover_text("The diagonal of the box around the scene's geometry");
        }
    }
    (unit != setup.unit && !loading).then_some(unit)
}

fn handedness_name(h: Handedness) -> &'static str {
    match h {
        Handedness::Left => "left-handed",
        Handedness::Right => "right-handed",
    }
}
