//! Camera: position, look-at, vertical field of view; reset to framing.

use super::widgets::{drag_hint, fine_drag, length_speed};
use crate::command::{Command, Commands};
use crate::document::Document;

/// Degrees of field of view a point of drag (Shift: a tenth).
const FOV_SPEED: f64 = 0.2;

/// The camera's numbers, edited in place; Frame scene is asked for.
pub fn camera_ui(ui: &mut egui::Ui, doc: &mut Document, out: &mut Commands) {
    let unit = doc.setup.unit.symbol();
    let speed = length_speed(&doc.scene.bounds);
    let cam = &mut doc.setup.camera;
    vec3_row(ui, "position", &mut cam.position, speed, unit);
    vec3_row(ui, "look at", &mut cam.look_at, speed, unit);
    ui.horizontal(|ui| {
        ui.label("field of view");
        let r = fine_drag(
            ui,
            &mut cam.fov_deg,
            FOV_SPEED,
            Some(5.0..=150.0),
            "",
            "field of view (°)",
        );
        cam.fov_deg = cam.fov_deg.clamp(1.0, 179.0);
        r.on_hover_text(format!(
            "Vertical field of view, degrees, from the top edge to the bottom edge. {}",
            drag_hint(FOV_SPEED, "°")
        ));
        ui.label("°");
    });
    ui.horizontal(|ui| {
        if ui
            .button("Frame scene")
            .on_hover_text("Look at the whole scene from +Z (F)")
            .clicked()
        {
            out.push(Command::FrameScene);
        }
        if ui
            .button("Reset camera")
            .on_hover_text("Back to the scene's own camera, as opened or last saved (Home)")
            .clicked()
        {
            out.push(Command::ResetCamera);
        }
    });
    ui.label("drag: orbit · shift/middle: pan · wheel: dolly");
}

fn vec3_row(ui: &mut egui::Ui, label: &str, v: &mut [f32; 3], speed: f64, unit: &str) {
    ui.horizontal(|ui| {
        ui.label(format!("{label} ({unit})"));
        for (c, axis) in v.iter_mut().zip(["x", "y", "z"]) {
            let name = format!("camera {label} {axis} ({unit})");
            fine_drag(ui, c, speed, None, &format!("{axis} "), &name)
                .on_hover_text(format!("{name}. {}", drag_hint(speed, unit)));
        }
    });
}
