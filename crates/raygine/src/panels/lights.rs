//! Point and spot lights: kind, position (slider over the scene bounds and out to the camera,
//! or typed), intensity (logarithmic, cd), spot axis and angles, colour; add and remove.
//! Emissive surfaces are edited with their material.

use crate::app::RaygineApp;
use tracer_core::scene::{Light, LightKind, default_light};

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
                egui::ComboBox::from_id_salt("kind")
                    .selected_text(match light.kind {
                        LightKind::Point => "point",
                        LightKind::Spot => "spot",
                    })
                    .show_ui(ui, |ui| {
                        ui.selectable_value(&mut light.kind, LightKind::Point, "point");
                        ui.selectable_value(&mut light.kind, LightKind::Spot, "spot");
                    })
                    .response
                    .on_hover_text("Point: the same intensity in every direction. Spot: a cone");
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
            .on_hover_text(match light.kind {
                LightKind::Point => "Luminous intensity in candela, the same in every direction",
                LightKind::Spot => "Luminous intensity in candela on the spot's axis",
            });
            if light.kind == LightKind::Spot {
                spot_ui(ui, light);
            }
            ui.label(format!("flux {:.0} lm", light.flux_lm()));
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
        let light: Light = default_light(
            &app.doc.scene,
            app.doc.setup.unit,
            app.doc.setup.camera.position,
        );
        app.doc.setup.lights.push(light);
    }
}

/// The spot's axis and angles (degrees at this edge).
fn spot_ui(ui: &mut egui::Ui, light: &mut Light) {
    ui.horizontal(|ui| {
        ui.label("aim");
        for (axis, name) in ["x", "y", "z"].iter().enumerate() {
            ui.add(
                egui::DragValue::new(&mut light.aim[axis])
                    .speed(0.01)
                    .prefix(format!("{name} ")),
            )
            .on_hover_text("Direction of the spot's axis (any length)");
        }
    });
    if glam::Vec3::from(light.aim).length_squared() <= 0.0 {
        light.aim = [0.0, -1.0, 0.0];
    }
    ui.add(egui::Slider::new(&mut light.cone_deg, 0.0..=180.0).text("cone (°)"))
        .on_hover_text("Half-angle of full intensity, degrees");
    ui.add(egui::Slider::new(&mut light.falloff_deg, 0.0..=180.0).text("falloff (°)"))
        .on_hover_text("Half-angle where the intensity reaches zero (smoothstep from the cone)");
    if light.falloff_deg < light.cone_deg {
        light.falloff_deg = light.cone_deg;
    }
}
