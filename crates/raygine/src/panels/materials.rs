//! Materials per brep and part: Kd colour, Ks colour, glossiness; hide or isolate breps; the
//! surface clicked in the viewport is selected here.

use crate::command::{Command, Commands};
use crate::document::Document;
use tracer_core::light::EmissionSides;

/// A part's name in the list: its own name when the format gives one, else its number.
fn part_label(brep: &tracer_core::scene::Brep, part: u32) -> String {
    if brep.part_names.is_empty() {
        format!("part {part}")
    } else {
        brep.part_label(part)
    }
}

/// The breps' visibility and the selected slot's material, edited in place; a selection is asked
/// for.
pub fn materials_ui(
    ui: &mut egui::Ui,
    doc: &mut Document,
    selected_slot: Option<u32>,
    out: &mut Commands,
) {
    let scene = std::sync::Arc::clone(&doc.scene);
    egui::ScrollArea::vertical()
        .id_salt("breps")
        .max_height(220.0)
        .show(ui, |ui| {
            for (bi, brep) in scene.breps.iter().enumerate() {
                let slots = brep.first_slot..brep.first_slot + brep.part_count;
                ui.horizontal(|ui| {
                    let mut visible = slots.clone().any(|s| !doc.setup.is_hidden(s));
                    if ui
                        .checkbox(&mut visible, "")
                        .on_hover_text("Show or hide this brep")
                        .changed()
                    {
                        for s in slots.clone() {
                            doc.setup.hidden[s as usize] = !visible;
                        }
                    }
                    let selected = selected_slot.is_some_and(|s| slots.contains(&s));
                    if ui.selectable_label(selected, brep.name.as_str()).clicked() {
                        out.push(Command::Select(Some(brep.first_slot)));
                    }
                    if ui
                        .small_button("isolate")
                        .on_hover_text("Show only this brep")
                        .clicked()
                    {
                        for (s, owner) in scene.slots.iter().enumerate() {
                            doc.setup.hidden[s] = owner.brep as usize != bi;
                        }
                    }
                });
                // Parts the format names (an Integra room's 20 materials) are always listed;
                // numbered parts when their brep is selected.
                let named = !brep.part_names.is_empty();
                let selected = selected_slot.is_some_and(|s| slots.contains(&s));
                if brep.part_count > 1 && (named || selected) {
                    ui.indent(bi, |ui| {
                        ui.horizontal_wrapped(|ui| {
                            for s in slots.clone() {
                                let part = s - brep.first_slot;
                                if ui
                                    .selectable_label(
                                        selected_slot == Some(s),
                                        part_label(brep, part),
                                    )
                                    .clicked()
                                {
                                    out.push(Command::Select(Some(s)));
                                }
                            }
                        });
                    });
                }
            }
        });
    if doc.setup.hidden.iter().any(|&h| h) && ui.button("Show all").clicked() {
        doc.setup.hidden.iter_mut().for_each(|h| *h = false);
    }
    ui.separator();
    let Some(slot) = selected_slot else {
        ui.label("Click a surface or a brep name to edit its material.");
        return;
    };
    let label = scene.slot_label(slot);
    let Some(m) = doc.setup.materials.get_mut(slot as usize) else {
        return;
    };
    ui.strong(format!("Material of {label}"))
        .on_hover_text("Ctrl+S saves it in the sidecar under this key");
    super::reflectance::reflectance_ui(ui, "Kd", "Kd, diffuse reflectance", &mut m.kd);
    super::reflectance::reflectance_ui(ui, "Ks", "Ks, mirror reflectance", &mut m.ks);
    ui.add(
        egui::Slider::new(&mut m.glossiness, 0.0..=10_000.0)
            .logarithmic(true)
            .text("glossiness")
            .update_while_editing(false),
    )
    .on_hover_text(
        "Blinn-Phong exponent of the Ks lobe: 0 makes Ks a perfect mirror; in direct mode it \
         is the point lights' highlight",
    );
    ui.add(
        egui::Slider::new(&mut m.emission_cd_m2, 0.0..=1.0e6)
            .logarithmic(true)
            .clamping(egui::SliderClamping::Never)
            .text("emission (cd/m²)")
            .update_while_editing(false),
    )
    .on_hover_text("Luminance this surface emits as a Lambertian light (0: not a light)");
    if m.emission_cd_m2 > 0.0 {
        ui.horizontal(|ui| {
            ui.color_edit_button_rgb(&mut m.emission_color);
            ui.label("emission colour (tint, normalised to luminance 1)");
        });
        egui::ComboBox::from_label("emitting faces")
            .selected_text(sides_name(m.emission_sides))
            .show_ui(ui, |ui| {
                for s in [
                    EmissionSides::Both,
                    EmissionSides::Front,
                    EmissionSides::Back,
                ] {
                    ui.selectable_value(&mut m.emission_sides, s, sides_name(s));
                }
            });
    }
    let (clamped, changed) = m.clamped();
    let sums: [f32; 3] = std::array::from_fn(|c| m.kd[c] + m.ks[c] + m.kt[c]);
    if changed {
        let over: Vec<&str> = (0..3)
            .filter(|&c| sums[c] > 1.0)
            .map(|c| ["red", "green", "blue"][c])
            .collect();
        if !over.is_empty() {
            out.push(Command::Notice(format!(
                "{label}: Kd + Ks was above 1 in {} ({}); both were scaled down so they add to 1",
                over.join(", "),
                sums.map(|v| format!("{v:.2}")).join(" ")
            )));
        }
        *m = clamped;
    }
    let sums: [f32; 3] = std::array::from_fn(|c| m.kd[c] + m.ks[c] + m.kt[c]);
    let at_limit = sums.iter().any(|&v| v >= 0.999);
    let text = format!(
        "Kd + Ks = {} (at most 1 per channel)",
        sums.map(|v| format!("{v:.3}")).join(" ")
    );
    if at_limit {
        ui.colored_label(egui::Color32::YELLOW, text).on_hover_text(
            "A surface cannot reflect more light than it receives: a channel at 1 is at the \
             limit, and raising Kd or Ks further scales both down",
        );
    } else {
        ui.label(text);
    }
}

fn sides_name(s: EmissionSides) -> &'static str {
    match s {
        EmissionSides::Both => "both",
        EmissionSides::Front => "front",
        EmissionSides::Back => "back",
    }
}
