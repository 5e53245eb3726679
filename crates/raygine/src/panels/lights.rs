//! Point lights: position (slider over the scene bounds and out to the camera, or typed), intensity (logarithmic, cd),
//! colour; add and remove.

use crate::app::RaygineApp;
use tracer_core::scene::{PointLight, default_light};

pub fn lights_ui(ui: &mut egui::Ui, app: &mut RaygineApp) {
    let b = app.doc.scene.bounds;
    let margin = b.extent() * 0.5;
    // Over the bounds with a margin, and out to the camera: the default light of an object
    // sits between it and the camera.
    let eye = glam::Vec3::from_array(app.doc.setup.camera.position);
    let (lo, hi) = ((b.min - margin).min(eye), (b.max + margin).max(eye));
    let unit = app.doc.setup.unit.symbol();
    let mut remove = None;
    let count = app.doc.setup.lights.len();
    for (i, light) in app.doc.setup.lights.iter_mut().enumerate() {
        ui.push_id(i, |ui| {
            ui.horizontal(|ui| {
                ui.strong(format!("Light {}", i + 1));
                if ui
                    .small_button("Remove")
                    .on_hover_text("Remove this light")
                    .clicked()
                {
                    remove = Some(i);
                }
            });
            for (axis, name) in ["x", "y", "z"].iter().enumerate() {
                ui.add(
                    egui::Slider::new(&mut light.position[axis], lo[axis]..=hi[axis])
                        .text(format!("light {name} ({unit})"))
                        .clamping(egui::SliderClamping::Never),
                )
                .on_hover_text(format!(
                    "Light {} position along {name}, scene units ({unit}); type any value",
                    i + 1
                ));
            }
            ui.add(
                egui::Slider::new(&mut light.intensity_cd, 0.01..=1.0e6)
                    .logarithmic(true)
                    .clamping(egui::SliderClamping::Never)
                    .text("intensity (cd)"),
            )
            .on_hover_text("Luminous intensity in candela, the same in every direction");
            ui.horizontal(|ui| {
                ui.color_edit_button_rgb(&mut light.color);
                ui.label("colour (tint, normalised to luminance 1)");
            });
            if i + 1 < count {
                ui.separator();
            }
        });
    }
    if let Some(i) = remove {
        app.doc.setup.lights.remove(i);
    }
    if ui
        .button("Add light")
        .on_hover_text("A new point light where a scene without a sidecar gets its light")
        .clicked()
    {
        let light: PointLight = default_light(
            &app.doc.scene,
            app.doc.setup.unit,
            app.doc.setup.camera.position,
        );
        app.doc.setup.lights.push(light);
    }
}
