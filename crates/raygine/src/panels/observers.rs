//! Observers: the eyes where glare is judged (`[[observers]]`). Each can be looked through (a
//! 180° equidistant fisheye at the eye, the view glare is computed from) or removed; one can be
//! added where the camera stands. Edits the setup in place, like the camera's numbers.

use crate::document::Document;
use tracer_core::scene::Observer;

pub fn observers_ui(ui: &mut egui::Ui, doc: &mut Document) {
    let unit = doc.setup.unit.symbol();
    ui.strong("Observers");
    if doc.setup.observers.is_empty() {
        ui.label("None yet: add one where the camera stands, or [[observers]] in the sidecar.");
    }
    let (mut view, mut remove) = (None, None);
    for (i, o) in doc.setup.observers.iter().enumerate() {
        ui.horizontal(|ui| {
            // The name only, so the row's buttons fit the panel; where it stands on hover.
            ui.label(&o.name).on_hover_text(format!(
                "at ({:.0}, {:.0}, {:.0}) {unit}, looking along ({:.2}, {:.2}, {:.2})",
                o.position[0],
                o.position[1],
                o.position[2],
                o.direction[0],
                o.direction[1],
                o.direction[2]
            ));
            if ui
                .button("View from observer")
                .on_hover_text(
                    "Look through a 180° equidistant fisheye from this eye (Radiance -vta, what \
                     glare is judged from)",
                )
                .clicked()
            {
                view = Some(i);
            }
            if ui.small_button("Remove").clicked() {
                remove = Some(i);
            }
        });
    }
    if let Some(i) = view {
        doc.setup.camera = doc.setup.observers[i].fisheye_camera();
    }
    if let Some(i) = remove {
        doc.setup.observers.remove(i);
    }
    if ui
        .button("Add observer at camera")
        .on_hover_text("An observer at the camera's eye, looking where it looks")
        .clicked()
    {
        let taken = |n: &str| doc.setup.observers.iter().any(|o| o.name == n);
        let name = (1..)
            .map(|k| format!("observer{k}"))
            .find(|n| !taken(n))
            .unwrap_or_default();
        let o = Observer::at_camera(&name, &doc.setup.camera);
        doc.setup.observers.push(o);
    }
}
