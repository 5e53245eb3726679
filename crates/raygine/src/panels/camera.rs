//! Camera: position, look-at, vertical field of view; reset to framing.

use crate::app::RaygineApp;

pub fn camera_ui(ui: &mut egui::Ui, app: &mut RaygineApp) {
    let unit = app.doc.setup.unit.symbol();
    let speed = (app.doc.scene.bounds.radius() * 0.005).max(1e-4);
    let cam = &mut app.doc.setup.camera;
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
            app.frame_scene();
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
