//! Materials per brep and part: Kd colour, Ks colour, glossiness (or base colour, metallic and
//! roughness); hide or isolate breps; the
//! surface clicked in the viewport is selected here.

use crate::command::{Command, Commands, Edit};
use crate::document::Document;
use tracer_core::light::EmissionSides;
use tracer_core::scene::{Material, Pbr};

/// A part's name in the list: its own name when the format gives one, else its number, and
/// beside it its material's name in the file ("proom2_0003 · wood").
fn part_label(brep: &tracer_core::scene::Brep, part: u32) -> String {
    let name = if brep.part_names.is_empty() {
        format!("part {part}")
    } else {
        brep.part_label(part)
    };
    match brep.part_material(part) {
        Some(m) => format!("{name} · {m}"),
        None => name,
    }
}

/// Whether `text` holds `filter` (ignoring case; an empty filter matches everything).
fn matches(text: &str, filter: &str) -> bool {
    filter.is_empty() || text.to_lowercase().contains(&filter.to_lowercase())
}

/// The breps' visibility and the selected slot's material, edited in place; a selection is asked
/// for.
pub fn materials_ui(
    ui: &mut egui::Ui,
    doc: &mut Document,
    selected_slot: Option<u32>,
    filter: &mut String,
    thumbnails: &mut super::texture_maps::TextureThumbnails,
    out: &mut Commands,
) {
    let scene = std::sync::Arc::clone(&doc.scene);
    let many = scene.breps.len() > 6 || scene.slots.len() > 6;
    if many || !filter.is_empty() {
        ui.horizontal(|ui| {
            let label = ui.label("filter");
            ui.add(
                egui::TextEdit::singleline(filter)
                    .hint_text("brep, part or material name")
                    .desired_width(160.0),
            )
            .labelled_by(label.id)
            .on_hover_text("List only the breps and parts whose name or material holds this");
            if !filter.is_empty()
                && ui
                    .small_button("✖")
                    .on_hover_text("Clear the filter")
                    .clicked()
            {
                filter.clear();
            }
        });
    }
    let filter = filter.trim().to_owned();
    egui::ScrollArea::vertical()
        .id_salt("breps")
        .max_height(220.0)
        .show(ui, |ui| {
            for (bi, brep) in scene.breps.iter().enumerate() {
                let slots = brep.first_slot..brep.first_slot + brep.part_count;
                let brep_matches = matches(&brep.name, &filter);
                let part_matches =
                    |s: u32| matches(&part_label(brep, s - brep.first_slot), &filter);
                if !brep_matches && !slots.clone().any(part_matches) {
                    continue;
                }
                ui.horizontal(|ui| {
                    let mut visible = slots.clone().any(|s| !doc.setup.is_hidden(s));
                    if ui
                        .checkbox(&mut visible, "")
                        .on_hover_text("Show or hide this brep")
                        .changed()
                    {
                        out.push(Command::Edit(Edit::SetHidden {
                            slots: slots.clone().collect(),
                            hidden: !visible,
                        }));
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
                        let (own, others): (Vec<u32>, Vec<u32>) = (0..scene.slots.len() as u32)
                            .partition(|&s| scene.slots[s as usize].brep as usize == bi);
                        out.push(Command::Edit(Edit::SetHidden {
                            slots: others,
                            hidden: true,
                        }));
                        out.push(Command::Edit(Edit::SetHidden {
                            slots: own,
                            hidden: false,
                        }));
                    }
                });
                // Parts the format names (an Integra room's 20 materials) are always listed;
                // numbered parts when their brep is selected.
                let named = !brep.part_names.is_empty();
                let selected = selected_slot.is_some_and(|s| slots.contains(&s));
                let filtering = !filter.is_empty() && !brep_matches;
                if brep.part_count > 1 && (named || selected || filtering) {
                    ui.indent(bi, |ui| {
                        ui.horizontal_wrapped(|ui| {
                            for s in slots.clone() {
                                let part = s - brep.first_slot;
                                if filtering && !part_matches(s) {
                                    continue;
                                }
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
        out.push(Command::Edit(Edit::ShowAll));
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
    model_ui(ui, m);
    if let Some(pbr) = &mut m.pbr {
        metal_rough_ui(ui, pbr, &mut m.ior);
    } else {
        super::reflectance::reflectance_ui(ui, "Kd", "Kd, diffuse reflectance", &mut m.kd);
        super::reflectance::reflectance_ui(ui, "Ks", "Ks, mirror reflectance", &mut m.ks);
        ui.add(
            egui::Slider::new(&mut m.glossiness, 0.0..=10_000.0)
                .logarithmic(true)
                .text("glossiness")
                .update_while_editing(false),
        )
        .on_hover_text(
            "Blinn-Phong exponent of the Ks lobe: 0 makes Ks a perfect mirror; in direct mode \
             it is the point lights' highlight",
        );
    }
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
    super::texture_maps::texture_maps_ui(ui, &scene, m, thumbnails);
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
    if m.pbr.is_some() {
        return;
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

/// The model menu: switching converts the values (glTF's reader's Blinn-Phong approximation one
/// way, its inverse the other), so the surface keeps about its look.
fn model_ui(ui: &mut egui::Ui, m: &mut Material) {
    const CLASSIC: &str = "Lambert + Blinn-Phong";
    const GLTF: &str = "metallic-roughness (glTF)";
    let mut pbr = m.pbr.is_some();
    egui::ComboBox::from_label("model")
        .selected_text(if pbr { GLTF } else { CLASSIC })
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut pbr, false, CLASSIC);
            ui.selectable_value(&mut pbr, true, GLTF);
        });
    match (pbr, m.pbr) {
        (true, None) => {
            // α from the Beckmann-equivalent exponent g = 2/α² − 2; roughness = √α.
            let alpha = (2.0 / (m.glossiness.max(0.0) + 2.0)).sqrt();
            let roughness = if m.glossiness > 0.0 {
                alpha.sqrt()
            } else {
                0.0
            };
            let metal = m.ks.iter().sum::<f32>() > m.kd.iter().sum::<f32>();
            *m = Material {
                pbr: Some(Pbr {
                    base_color: if metal { m.ks } else { m.kd },
                    metallic: if metal { 1.0 } else { 0.0 },
                    roughness: if metal || m.glossiness > 0.0 {
                        roughness
                    } else {
                        1.0
                    },
                    transmission: 0.0,
                }),
                kd: [0.0; 3],
                ks: [0.0; 3],
                glossiness: 0.0,
                kt: [0.0; 3],
                ..*m
            };
        }
        (false, Some(p)) => {
            let alpha = p.roughness * p.roughness;
            let g = if alpha > 0.0 {
                2.0 / (alpha * alpha) - 2.0
            } else {
                0.0
            };
            *m = Material {
                kd: p.base_color.map(|c| c * (1.0 - p.metallic) * 0.96),
                ks: p
                    .base_color
                    .map(|c| c * p.metallic + 0.04 * (1.0 - p.metallic)),
                glossiness: if g > 10_000.0 { 0.0 } else { g.max(1.0) },
                pbr: None,
                ..*m
            };
        }
        _ => {}
    }
}

/// A material's values on one line, for the viewport's hover read-out.
pub fn summary(m: &Material) -> String {
    let rgb = |c: [f32; 3]| format!("{:.2} {:.2} {:.2}", c[0], c[1], c[2]);
    let mut s = match &m.pbr {
        Some(p) => {
            let mut s = format!(
                "base colour {}, metallic {:.2}, roughness {:.2}",
                rgb(p.base_color),
                p.metallic,
                p.roughness
            );
            if p.transmission > 0.0 {
                s += &format!(", transmission {:.2}, ior {:.2}", p.transmission, m.ior);
            }
            s
        }
        None => {
            let mut s = format!("Kd {}", rgb(m.kd));
            if m.ks.iter().any(|&k| k > 0.0) {
                s += &format!(", Ks {}, glossiness {:.0}", rgb(m.ks), m.glossiness);
            }
            if m.kt.iter().any(|&k| k > 0.0) {
                s += &format!(", Kt {}, ior {:.2}", rgb(m.kt), m.ior);
            }
            s
        }
    };
    if m.emission_cd_m2 > 0.0 {
        s += &format!(
            ", emits {} cd/m²",
            crate::format::format_value(m.emission_cd_m2)
        );
    }
    s
}

/// A metallic-roughness material's base colour, metallic, roughness, transmission and the
/// dielectric's index (glTF's model).
fn metal_rough_ui(ui: &mut egui::Ui, pbr: &mut Pbr, ior: &mut f32) {
    super::reflectance::reflectance_ui(
        ui,
        "base colour",
        "base colour (metals: F0; others: diffuse)",
        &mut pbr.base_color,
    );
    ui.add(
        egui::Slider::new(&mut pbr.metallic, 0.0..=1.0)
            .text("metallic")
            .update_while_editing(false),
    )
    .on_hover_text("0: a dielectric over a diffuse base; 1: a metal tinted by the base colour");
    ui.add(
        egui::Slider::new(&mut pbr.roughness, 0.0..=1.0)
            .text("roughness")
            .update_while_editing(false),
    )
    .on_hover_text("Perceptual roughness: GGX α = roughness²");
    ui.add(
        egui::Slider::new(&mut pbr.transmission, 0.0..=1.0)
            .text("transmission")
            .update_while_editing(false),
    )
    .on_hover_text(
        "glTF's thin-walled transmission: light passes through the dielectric, tinted by the \
         base colour (traced in path, bdpt and light-tracing modes)",
    );
    ui.add(
        egui::Slider::new(ior, 1.0..=3.0)
            .text("ior")
            .update_while_editing(false),
    )
    .on_hover_text(
        "Refractive index of the dielectric layer: F0 = ((ior − 1)/(ior + 1))², 0.04 at 1.5",
    );
}

fn sides_name(s: EmissionSides) -> &'static str {
    match s {
        EmissionSides::Both => "both",
        EmissionSides::Front => "front",
        EmissionSides::Back => "back",
    }
}
