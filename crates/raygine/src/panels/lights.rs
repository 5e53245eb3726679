//! Point and spot lights: kind, position (dragged at a speed scaled to the scene, finer with
//! Shift, inside the scene's bounds; typed values may go anywhere, and a light outside the
//! bounds is pointed out), intensity (cd, a drag changes it by
//! a fraction of itself), spot axis and angles, colour; add (beside the lights already there)
//! and remove. Emissive surfaces are edited with their material.

use super::widgets::{drag_hint, fine_drag, length_speed};
use crate::command::{Command, Commands, Edit};
use crate::document::Document;
use tracer_core::light::SHAPE_NAMES;
use tracer_core::scene::{
    KindTag, Light, LightKind, LuminairePlacement, LuminousShape, ShapeChoice, Spot,
};

/// More lights than this are listed one line each (a virtualised list, grouped by kind and
/// file in a summary), and only the selected one is edited: an office's 1,000 luminaires keep
/// the panel as quick as three.
pub const MANY_LIGHTS: usize = 12;

/// The lights, edited in place. `luminaire_path` is the panel's own text field for "Add
/// luminaire"; a luminaire file that cannot be read is reported as an error. `selected` is the
/// light edited when there are more than [`MANY_LIGHTS`].
pub fn lights_ui(
    ui: &mut egui::Ui,
    doc: &mut Document,
    luminaire_path: &mut String,
    selected: &mut usize,
    adding: bool,
    out: &mut Commands,
) {
    let b = doc.scene.bounds;
    // The sliders span the scene's bounds (a flat scene gets some height); typed values may go
    // anywhere.
    let pad = glam::Vec3::splat(b.extent().max_element().max(1e-3) * 0.25);
    let flat = b.extent().cmple(glam::Vec3::splat(1e-6));
    let lo = glam::Vec3::select(flat, b.min - pad, b.min);
    let hi = glam::Vec3::select(flat, b.max + pad, b.max);
    let unit = doc.setup.unit.symbol();
    let speed = length_speed(&b);
    let mut remove = None;
    let count = doc.setup.lights.len();
    let many = count > MANY_LIGHTS;
    if many {
        *selected = (*selected).min(count - 1);
        light_list(ui, &doc.setup.lights, selected, unit);
    }
    for (i, light) in doc.setup.lights.iter_mut().enumerate() {
        if many && i != *selected {
            continue;
        }
        ui.push_id(i, |ui| {
            ui.horizontal(|ui| {
                ui.strong(format!("Light {}", i + 1));
                let tag = light.tag();
                if tag == KindTag::Luminaire {
                    ui.label("luminaire");
                } else {
                    let mut chosen = tag;
                    egui::ComboBox::from_label("kind")
                        .selected_text(tag.name())
                        .show_ui(ui, |ui| {
                            ui.selectable_value(&mut chosen, KindTag::Point, "point");
                            ui.selectable_value(&mut chosen, KindTag::Spot, "spot");
                        })
                        .response
                        .on_hover_text(
                            "Point: the same intensity in every direction. Spot: a cone",
                        );
                    if chosen != tag {
                        *light = light.with_kind(chosen);
                    }
                }
                if ui
                    .small_button("Remove")
                    .on_hover_text("Remove this light")
                    .clicked()
                {
                    remove = Some(i);
                }
            });
            ui.horizontal(|ui| {
                ui.label(format!("position ({unit})"));
                for (axis, name) in ["x", "y", "z"].iter().enumerate() {
                    fine_drag(
                        ui,
                        &mut light.position[axis],
                        speed,
                        Some(lo[axis]..=hi[axis]),
                        &format!("{name} "),
                        &format!("light {name} ({unit})"),
                    )
                    .on_hover_text(format!(
                        "Light {} position along {name} ({unit}). A drag stays inside the \
                         scene's bounds; a typed value may go anywhere. {}",
                        i + 1,
                        drag_hint(speed, unit)
                    ));
                }
            });
            // A key light beside an object (the default for a lone object) is fine; a light
            // farther out than the scene's own size is probably a typing slip.
            let p = light.position();
            let reach = glam::Vec3::splat(b.extent().max_element());
            let near = tracer_core::geometry::Aabb {
                min: b.min - reach,
                max: b.max + reach,
            };
            if !near.contains(&tracer_core::geometry::Aabb { min: p, max: p }) {
                ui.colored_label(
                    egui::Color32::from_rgb(255, 210, 90),
                    "outside the scene's bounds",
                )
                .on_hover_text(
                    "This light is farther from the box around the scene's geometry than the \
                     scene is large: it may light nothing the camera sees",
                );
            }
            let is_spot = light.tag() == KindTag::Spot;
            if let Some(cd) = light.intensity_cd_mut() {
                intensity_ui(ui, cd, is_spot);
            }
            match &mut light.kind {
                LightKind::Luminaire(l) => luminaire_ui(ui, l, unit),
                LightKind::Spot(s) => spot_ui(ui, s),
                LightKind::Point { .. } => {}
            }
            ui.label(format!(
                "flux {}",
                crate::format::format_quantity(light.flux_lm(), "lm")
            ));
            ui.horizontal(|ui| {
                ui.color_edit_button_rgb(&mut light.color);
                ui.label("colour (tint, normalised to luminance 1)");
            });
            if i + 1 < count && !many {
                ui.separator();
            }
        });
    }
    if let Some(i) = remove {
        out.push(Command::Edit(Edit::RemoveLight(i)));
    }
    if ui
        .button("Add light")
        .on_hover_text("A new point light where a scene without a sidecar gets its light")
        .clicked()
    {
        out.push(Command::Edit(Edit::AddLight));
    }
    add_luminaire_ui(ui, luminaire_path, adding, out);
}

/// A summary of many lights (how many of each kind, luminaires by file) and one selectable line
/// per light, of which only the visible rows are laid out.
fn light_list(ui: &mut egui::Ui, lights: &[Light], selected: &mut usize, unit: &str) {
    let mut kinds = [0usize; 3];
    let mut files: std::collections::BTreeMap<String, usize> = std::collections::BTreeMap::new();
    let mut flux = 0.0f64;
    for l in lights {
        kinds[match l.tag() {
            KindTag::Point => 0,
            KindTag::Spot => 1,
            KindTag::Luminaire => 2,
        }] += 1;
        flux += f64::from(l.flux_lm());
        if let LightKind::Luminaire(lum) = &l.kind {
            *files.entry(file_name(&lum.luminaire.file)).or_default() += 1;
        }
    }
    ui.label(format!(
        "{} lights: {} point, {} spot, {} luminaire; total flux {}",
        lights.len(),
        kinds[0],
        kinds[1],
        kinds[2],
        crate::format::format_quantity(flux as f32, "lm")
    ));
    for (file, n) in &files {
        ui.label(format!("  {file} × {n}"));
    }
    let row = ui.text_style_height(&egui::TextStyle::Body) + ui.spacing().item_spacing.y;
    egui::ScrollArea::vertical()
        .id_salt("light list")
        .max_height(row * 10.0)
        .auto_shrink([false, true])
        .show_rows(ui, row, lights.len(), |ui, rows| {
            for i in rows {
                let l = &lights[i];
                let what = match &l.kind {
                    LightKind::Luminaire(lum) => file_name(&lum.luminaire.file),
                    LightKind::Spot(s) => format!("spot {:.4} cd", s.intensity_cd),
                    LightKind::Point { intensity_cd } => format!("point {intensity_cd:.4} cd"),
                };
                let [x, y, z] = l.position;
                let text = format!("Light {}: {what} at ({x:.3}, {y:.3}, {z:.3}) {unit}", i + 1);
                if ui.selectable_label(*selected == i, text).clicked() {
                    *selected = i;
                }
            }
        });
    ui.separator();
}

fn file_name(path: &std::path::Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// Intensity in candela: a drag changes it by about 0.5 % a point (a 20-point drag about 10 %),
/// ÷2 and ×2 take coarse steps, and a typed value applies when committed.
fn intensity_ui(ui: &mut egui::Ui, intensity_cd: &mut f32, is_spot: bool) {
    ui.horizontal(|ui| {
        let label = ui.label("intensity (cd)");
        let speed = f64::from(intensity_cd.abs().max(1e-9)) * 0.005;
        // Three significant digits at least: 0.00670 cd, not 0.01.
        let decimals = (2 - intensity_cd.abs().max(1e-9).log10().floor() as i32).clamp(2, 9);
        ui.add(
            egui::DragValue::new(intensity_cd)
                .speed(speed)
                .range(0.0..=1.0e9)
                .max_decimals(decimals as usize)
                .update_while_editing(false),
        )
        .labelled_by(label.id)
        .on_hover_text(if is_spot {
            "Luminous intensity in candela on the spot's axis. Drag for fine changes, or type"
        } else {
            "Luminous intensity in candela, the same in every direction. Drag for fine \
             changes, or type"
        });
        if ui
            .small_button("÷2")
            .on_hover_text("Halve the intensity")
            .clicked()
        {
            *intensity_cd *= 0.5;
        }
        if ui
            .small_button("×2")
            .on_hover_text("Double the intensity")
            .clicked()
        {
            *intensity_cd *= 2.0;
        }
    });
}

/// A typed path and a button that add a luminaire from an IES or EULUMDAT file (read on a
/// background job; a spinner shows while `adding`).
fn add_luminaire_ui(ui: &mut egui::Ui, text: &mut String, adding: bool, out: &mut Commands) {
    ui.horizontal(|ui| {
        let label = ui.label("luminaire file");
        ui.add(
            egui::TextEdit::singleline(text)
                .hint_text("lamp.ies or .ldt")
                .desired_width(140.0),
        )
        .labelled_by(label.id)
        .on_hover_text("An IES LM-63 or EULUMDAT file");
        if ui
            .button("Add luminaire")
            .on_hover_text("A luminaire from the file, aimed down where a new light goes")
            .clicked()
        {
            let path = std::path::PathBuf::from(text.trim());
            if text.trim().is_empty() {
                out.push(Command::Error(
                    "type the path of an IES (.ies) or EULUMDAT (.ldt) file first".into(),
                ));
                return;
            }
            out.push(Command::Edit(Edit::AddLuminaire(path)));
        }
        if adding {
            ui.spinner();
        }
    });
}

/// A luminaire's multiplier, aim, rotation, luminous opening and polar intensity diagram.
fn luminaire_ui(ui: &mut egui::Ui, light: &mut LuminairePlacement, unit: &str) {
    ui.label(format!("file {}", light.luminaire.file.display()));
    shape_ui(ui, light, unit);
    ui.add(
        egui::Slider::new(&mut light.multiplier, 0.001..=1000.0)
            .logarithmic(true)
            .clamping(egui::SliderClamping::Never)
            .text("multiplier")
            .update_while_editing(false),
    )
    .on_hover_text("Factor on the file's intensities (1: as measured)");
    aim_ui(
        ui,
        &mut light.aim,
        "aim (nadir)",
        "Direction of the photometric nadir, γ = 0 (any length)",
    );
    ui.add(
        egui::Slider::new(&mut light.rotation_deg, -180.0..=180.0)
            .text("rotation (°)")
            .update_while_editing(false),
    )
    .on_hover_text("Turn of the C planes about the aim");
    super::polar::polar_diagram(ui, &light.luminaire.photometry, light.multiplier, 240.0);
}

/// The luminous opening: the file's, a point, or a shape with its sizes in the scene unit.
fn shape_ui(ui: &mut egui::Ui, light: &mut LuminairePlacement, unit: &str) {
    let file_shape = light.luminaire.photometry.shape;
    let file_label = match file_shape {
        LuminousShape::Point => "file (point)".to_owned(),
        s => format!(
            "file ({} {})",
            s.name(),
            s.size()
                .iter()
                .map(|m| format!("{m:.3}"))
                .collect::<Vec<_>>()
                .join(" x ")
                + " m"
        ),
    };
    let current = match light.shape {
        ShapeChoice::File => file_label.clone(),
        ShapeChoice::Explicit(s) => s.name().to_owned(),
    };
    // A new explicit shape starts from the file's sizes where it has them, else 0.3 units.
    let seed = |name: &str| {
        let from_file = file_shape.size();
        let want = match name {
            "disc" => 1,
            "rectangle" | "cylinder" => 2,
            "box" => 3,
            _ => 0,
        };
        let mut size: Vec<f32> = from_file.into_iter().filter(|v| *v > 0.0).collect();
        size.resize(want, 0.3);
        LuminousShape::from_name(name, &size).unwrap_or(LuminousShape::Point)
    };
    egui::ComboBox::from_label("opening")
        .selected_text(current)
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut light.shape, ShapeChoice::File, file_label);
            for name in SHAPE_NAMES {
                let chosen = matches!(light.shape, ShapeChoice::Explicit(s) if s.name() == name);
                if ui.selectable_label(chosen, name).clicked() && !chosen {
                    light.shape = ShapeChoice::Explicit(seed(name));
                }
            }
        })
        .response
        .on_hover_text(
            "Where the light leaves: the file's luminous opening, a point (the far-field \
             model), or a shape you size. Each point of an opening emits the file's \
             distribution with luminance I/A_proj.",
        );
    if let ShapeChoice::Explicit(shape) = &mut light.shape
        && *shape != LuminousShape::Point
    {
        let names: &[&str] = match shape {
            LuminousShape::Rectangle { .. } => &["length", "width"],
            LuminousShape::Disc { .. } => &["diameter"],
            LuminousShape::Box { .. } => &["length", "width", "height"],
            _ => &["diameter", "height"],
        };
        let mut size = shape.size();
        ui.horizontal(|ui| {
            for (v, name) in size.iter_mut().zip(names) {
                ui.add(
                    egui::DragValue::new(v)
                        .speed(0.01)
                        .range(0.001..=1000.0)
                        .prefix(format!("{name} "))
                        .suffix(format!(" {unit}"))
                        .update_while_editing(false),
                )
                .on_hover_text(format!(
                    "The opening's {name} in {unit} (length along C0, width along C90)"
                ));
            }
        });
        if let Ok(resized) = LuminousShape::from_name(shape.name(), &size) {
            *shape = resized;
        }
    }
}

/// The spot's axis and angles (degrees at this edge).
fn spot_ui(ui: &mut egui::Ui, light: &mut Spot) {
    aim_ui(
        ui,
        &mut light.aim,
        "aim",
        "Direction of the spot's axis (any length)",
    );
    ui.add(
        egui::Slider::new(&mut light.cone_deg, 0.0..=180.0)
            .text("cone (°)")
            .update_while_editing(false),
    )
    .on_hover_text("Half-angle of full intensity, degrees");
    ui.add(
        egui::Slider::new(&mut light.falloff_deg, 0.0..=180.0)
            .text("falloff (°)")
            .update_while_editing(false),
    )
    .on_hover_text("Half-angle where the intensity reaches zero (smoothstep from the cone)");
    if light.falloff_deg < light.cone_deg {
        light.falloff_deg = light.cone_deg;
    }
}

/// A light's aim as three numbers; a zero aim falls back to straight down.
fn aim_ui(ui: &mut egui::Ui, aim: &mut [f32; 3], label: &str, hover: &str) {
    ui.horizontal(|ui| {
        ui.label(label);
        for (axis, name) in ["x", "y", "z"].iter().enumerate() {
            ui.add(
                egui::DragValue::new(&mut aim[axis])
                    .speed(0.01)
                    .prefix(format!("{name} "))
                    .update_while_editing(false),
            )
            .on_hover_text(hover);
        }
    });
    if glam::Vec3::from(*aim).length_squared() <= 0.0 {
        *aim = [0.0, -1.0, 0.0];
    }
}
