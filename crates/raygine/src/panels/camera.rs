//! Camera: position, look-at, vertical field of view; reset to framing.

use crate::command::{Command, Commands};
use crate::document::Document;

/// The camera's numbers, edited in place; Frame scene is asked for.
pub fn camera_ui(ui: &mut egui::Ui, doc: &mut Document, out: &mut Commands) {
    let unit = doc.setup.unit.symbol();
    let speed = (doc.scene.bounds.radius() * 0.005).max(1e-4);
    let cam = &mut doc.setup.camera;
    vec3_row(ui, "position", &mut cam.position, speed, unit);
    vec3_row(ui, "look at", &mut cam.look_at, speed, unit);
    ui.add(
        egui::Slider::new(&mut cam.fov_deg, 5.0..=150.0)
            .text("field of view (°)")
            .update_while_editing(false),
    )
    .on_hover_text("Vertical field of view, degrees, from the top edge to the bottom edge");
    ui.horizontal(|ui| {
        if ui
            .button("Frame scene")
            .on_hover_text("Look at the whole scene from +Z (F)")
            .clicked()
        {
            out.push(Command::FrameScene);
        }
        ui.label("drag: orbit · shift/middle: pan · wheel: dolly");
    });
}

fn vec3_row(ui: &mut egui::Ui, label: &str, v: &mut [f32; 3], speed: f32, unit: &str) {
    ui.horizontal(|ui| {
        ui.label(format!("{label} ({unit})"));
        for (c, axis) in v.iter_mut().zip(["x", "y", "z"]) {
            ui.add(
                egui::DragValue::new(c)
                    .speed(speed)
                    .max_decimals(3)
                    .update_while_editing(false),
            )
            .on_hover_text(format!("camera {label} {axis} ({unit})"));
        }
    });
}
