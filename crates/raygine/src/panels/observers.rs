//! Observers: the eyes where glare is judged (`[[observers]]`). Each can be looked through (a
//! 180° equidistant fisheye at the eye, the view glare is computed from), edited number by
//! number (an edit that makes it invalid is refused, its reason shown for a few seconds) or
//! removed; one can be added where the camera stands. Edits the setup in place, like the camera's numbers.

use crate::document::Document;
use tracer_core::scene::Observer;

/// How long a refused edit's reason stays under the observer, seconds.
const REFUSAL_SECS: f64 = 8.0;

/// The observer's numbers as editable fields; the edited observer when it changed and is valid
/// (else the observer is kept, and the reason shown for a few seconds).
fn edit_ui(ui: &mut egui::Ui, o: &Observer, unit: &str, speed: f64) -> Option<Observer> {
    let mut e = o.clone();
    egui::CollapsingHeader::new(format!("edit {}", o.name))
        .default_open(false)
        .show(ui, |ui| {
            for (label, v, step) in [
                (format!("eye ({unit})"), &mut e.position, speed),
                ("line of sight".to_owned(), &mut e.direction, 0.01),
                ("up".to_owned(), &mut e.up, 0.01),
            ] {
                ui.horizontal(|ui| {
                    let name = ui.label(label);
                    for (axis, c) in v.iter_mut().enumerate() {
                        ui.add(
                            egui::DragValue::new(c)
                                .speed(step)
                                .prefix(["x ", "y ", "z "][axis])
                                .update_while_editing(false),
                        )
                        .labelled_by(name.id);
                    }
                });
            }
        });
    // The last refusal (reason, when) lives in egui's memory: the edit itself reverts at once.
    let id = ui.make_persistent_id("refused");
    let now = ui.input(|i| i.time);
    let mut accepted = None;
    if e != *o {
        match e.check() {
            Ok(()) => {
                ui.data_mut(|d| d.remove::<(String, f64)>(id));
                accepted = Some(e);
            }
            Err(reason) => {
                ui.data_mut(|d| d.insert_temp(id, (reason, now)));
            }
        }
    }
    if let Some((reason, at)) = ui.data(|d| d.get_temp::<(String, f64)>(id)) {
        if now - at < REFUSAL_SECS {
            ui.colored_label(
                egui::Color32::from_rgb(255, 120, 100),
                format!("edit refused: {reason}"),
            );
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_secs_f64(
                    REFUSAL_SECS - (now - at),
                ));
        } else {
            ui.data_mut(|d| d.remove::<(String, f64)>(id));
        }
    }
    accepted
}

pub fn observers_ui(ui: &mut egui::Ui, doc: &mut Document) {
    let unit = doc.setup.unit.symbol();
    ui.strong("Observers");
    if doc.setup.observers.is_empty() {
        ui.label("None yet: add one where the camera stands, or [[observers]] in the sidecar.");
    }
    let (mut view, mut remove, mut edited) = (None, None, None);
    // Lengths drag at a 400th of the scene's size a point, as the camera's.
    let speed = f64::from(doc.scene.bounds.extent().max_element().max(1e-6)) / 400.0;
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
        ui.push_id(("observer", i), |ui| {
            if let Some(changed) = edit_ui(ui, o, unit, speed) {
                edited = Some((i, changed));
            }
        });
    }
    if let Some((i, o)) = edited {
        doc.setup.observers[i] = o;
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
