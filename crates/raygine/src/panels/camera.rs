//! Camera: projection, position, look-at, field of view or orthographic width; reset to
//! framing.

use super::widgets::{drag_hint, fine_drag, length_speed, refusable_choice};
use crate::command::{Command, Commands};
use crate::document::Document;
use tracer_core::integrator::IntegratorKind;
use tracer_core::scene::{MAX_FISHEYE_FOV_DEG, Projection};

/// Degrees of field of view a point of drag (Shift: a tenth).
const FOV_SPEED: f64 = 0.2;

/// The camera's numbers, edited in place; Frame scene is asked for. `integrator` is the render
/// panel's: the light tracer cannot render an orthographic view, so that entry is disabled
/// while it is chosen. `aspect` (the viewport's width over height) gives an orthographic
/// width its starting value.
pub fn camera_ui(
    ui: &mut egui::Ui,
    doc: &mut Document,
    integrator: IntegratorKind,
    aspect: f32,
    out: &mut Commands,
) {
    let unit = doc.setup.unit.symbol();
    let speed = length_speed(&doc.scene.bounds);
    let cam = &mut doc.setup.camera;
    // One row: the projection and its one number (field of view, or width).
    ui.horizontal(|ui| {
        projection_ui(ui, cam, integrator, aspect);
        match cam.projection {
            Projection::Orthographic => {
                let mut width = cam.orthographic_width(aspect);
                let r = fine_drag(
                    ui,
                    &mut width,
                    speed,
                    Some(1e-3..=1e9),
                    "width ",
                    &format!("orthographic width ({unit})"),
                );
                if r.changed() {
                    cam.width = Some(width.max(1e-4));
                }
                r.on_hover_text(format!(
                    "What the orthographic view shows across, in scene units; the wheel \
                     changes it too. {}",
                    drag_hint(speed, unit)
                ));
                ui.label(unit);
            }
            Projection::Equirectangular => {
                ui.label("360° x 180°").on_hover_text(
                    "Azimuth across, elevation down; the view direction at the centre",
                );
            }
            p => {
                let (max, hint) = if p.is_fisheye() {
                    (
                        MAX_FISHEYE_FOV_DEG,
                        "Field of view across the image circle, degrees (at most 180°: a \
                         hemisphere).",
                    )
                } else {
                    (
                        179.0,
                        "Vertical field of view, degrees, from the top edge to the bottom edge.",
                    )
                };
                let r = fine_drag(
                    ui,
                    &mut cam.fov_deg,
                    FOV_SPEED,
                    Some(5.0..=max),
                    "",
                    "field of view (°)",
                );
                cam.fov_deg = cam.fov_deg.clamp(1.0, max);
                r.on_hover_text(format!("{hint} {}", drag_hint(FOV_SPEED, "°")));
                ui.label("°");
            }
        }
    });
    vec3_row(ui, "position", &mut cam.position, speed, unit);
    vec3_row(ui, "look at", &mut cam.look_at, speed, unit);
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

/// The projection menu. Switching to a fisheye opens it to 180°; back to perspective, a field
/// of view a pinhole can show.
fn projection_ui(
    ui: &mut egui::Ui,
    cam: &mut tracer_core::scene::Camera,
    integrator: IntegratorKind,
    aspect: f32,
) {
    let before = cam.projection;
    egui::ComboBox::from_label("projection")
        .selected_text(short_label(cam.projection))
        .show_ui(ui, |ui| {
            for p in Projection::ALL {
                let refused = integrator.check_projection(p).err();
                refusable_choice(ui, &mut cam.projection, p, p.label(), refused);
            }
        })
        .response
        .on_hover_text(
            "Perspective: a pinhole. Fisheyes (up to 180°): equidistant is Radiance's -vta and \
             evalglare's input, hemispherical (-vth) weighs the film by projected solid angle. \
             Equirectangular: a 360° panorama. Orthographic: parallel rays, for plans and \
             elevations.",
        );
    if cam.projection == before {
        return;
    }
    if cam.projection.is_fisheye() && !before.is_fisheye() {
        cam.fov_deg = MAX_FISHEYE_FOV_DEG;
    } else if before.is_fisheye() && !cam.projection.is_fisheye() {
        // A fisheye's angle means nothing to a pinhole (nor to the orthographic width).
        cam.fov_deg = tracer_core::scene::DEFAULT_FOV_DEG;
    }
    if cam.projection == Projection::Orthographic && cam.width.is_none() {
        // Start where the perspective view was, at the look-at point.
        cam.width = Some(cam.orthographic_width(aspect));
    }
}

/// The projection's name in the closed menu (the open menu says more).
fn short_label(p: Projection) -> &'static str {
    match p {
        Projection::Perspective => "Perspective",
        Projection::FisheyeEquidistant => "Fisheye -vta",
        Projection::FisheyeEquisolid => "Equisolid",
        Projection::Hemispherical => "Hemisph. -vth",
        Projection::Equirectangular => "360°",
        Projection::Orthographic => "Orthographic",
    }
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
