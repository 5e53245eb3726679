//! The Measure panel: the scene's calculation grids, a work plane to add, their statistics as
//! they refine, and export of the readings to CSV and JSON beside the scene.

use crate::command::{Command, Commands};
use crate::document::Document;
use crate::measure_cmd::{csv, json_report};
use crate::measure_worker::Readings;
use tracer_core::integrator::IntegratorKind;
use tracer_core::scene::{GridContext, GridSpec};

/// What the Measure panel shows besides the document.
#[derive(Debug)]
pub struct MeasureView {
    /// The grids' latest readings (None while the first refinement runs).
    pub readings: Option<Readings>,
    pub selected_slot: Option<u32>,
    /// The light transport the readings were measured with (named in the JSON).
    pub integrator: IntegratorKind,
}

/// The grids, edited in place; exports and the report are asked for.
pub fn measure_ui(
    ui: &mut egui::Ui,
    doc: &mut Document,
    view: MeasureView,
    show_grids: &mut bool,
    out: &mut Commands,
) {
    let readings = view.readings;
    let unit = doc.setup.unit.symbol();
    let mut remove = None;
    if doc.setup.grids.is_empty() {
        ui.label("No calculation grids. Add a work plane, or [[grids]] in the sidecar.");
    }
    let mut edited = None;
    for (i, grid) in doc.setup.grids.iter().enumerate() {
        ui.push_id(i, |ui| {
            if let Some(g) = edit_ui(ui, grid, unit) {
                edited = Some((i, g));
            }
            ui.horizontal(|ui| {
                ui.strong(format!("{} ({}x{} points)", grid.name, grid.nu, grid.nv));
                if ui
                    .small_button("Remove")
                    .on_hover_text("Remove this grid")
                    .clicked()
                {
                    remove = Some(i);
                }
            });
            let result = readings
                .as_ref()
                .and_then(|r| r.results.iter().find(|g| g.name == grid.name));
            match result {
                Some(r) => {
                    let s = r.statistics();
                    ui.label(format!(
                        "Emin {:.1} lx · Eavg {:.1} lx · Emax {:.1} lx",
                        s.e_min_lx, s.e_avg_lx, s.e_max_lx
                    ));
                    ui.label(format!(
                        "U0 {:.2} · Emin/Emax {:.2}",
                        s.u0, s.emin_over_emax
                    ));
                    profile_ui(ui, grid, r, unit);
                }
                None => {
                    ui.horizontal(|ui| {
                        ui.spinner();
                        ui.label("measuring…");
                    });
                }
            }
        });
    }
    if let Some((i, g)) = edited {
        doc.setup.grids[i] = g;
    }
    if let Some(i) = remove {
        doc.setup.grids.remove(i);
    }
    if let Some(r) = &readings
        && !doc.setup.grids.is_empty()
    {
        let state = if r.finished { "done" } else { "refining" };
        ui.label(format!(
            "{} samples a point ({state}){}",
            r.samples,
            if doc.setup.maintenance_factor != 1.0 {
                format!(", maintenance factor {}", doc.setup.maintenance_factor)
            } else {
                String::new()
            }
        ));
    }
    ui.horizontal(|ui| {
        if ui
            .button("Add work plane")
            .on_hover_text("0.75 m over the floor, 0.5 m from the walls, EN 12464-1 spacing")
            .clicked()
        {
            add_work_plane(doc, out);
        }
        ui.checkbox(show_grids, "show on picture");
    });
    let selected = view.selected_slot;
    if ui
        .add_enabled(
            selected.is_some(),
            egui::Button::new("Add grid on selected surface"),
        )
        .on_hover_text("A grid over the clicked surface's plane, just in front of it")
        .clicked()
        && let Some(slot) = selected
    {
        add_surface_grid(doc, slot, out);
    }
    ui.add_enabled_ui(
        readings.as_ref().is_some_and(|r| !r.results.is_empty()),
        |ui| {
            ui.horizontal(|ui| {
                if ui.button("Export CSV").clicked()
                    && let Some(r) = &readings
                {
                    out.push(export(doc, "grids.csv", csv(&r.results)));
                }
                if ui.button("Export JSON").clicked()
                    && let Some(r) = &readings
                {
                    let unit = doc.setup.unit.symbol();
                    let text = json_report(&r.results, unit, view.integrator.name(), r.samples);
                    out.push(export(doc, "grids.json", text));
                }
            });
            if ui
                .button("Save report")
                .on_hover_text(
                    "The view with the grids, their statistics and legend as a PNG, and the \
                     CSV beside it",
                )
                .clicked()
                && let Some(r) = &readings
            {
                out.push(Command::SaveReport {
                    png: report_path(doc, "report.png"),
                    csv: report_path(doc, "grids.csv"),
                    csv_text: csv(&r.results),
                });
            }
        },
    );
}

/// The grid's numbers as editable fields; returns the edited grid when it changed and is valid.
fn edit_ui(
    ui: &mut egui::Ui,
    grid: &tracer_core::measure::Grid,
    unit: &str,
) -> Option<tracer_core::measure::Grid> {
    let mut g = grid.clone();
    egui::CollapsingHeader::new(format!("edit {}", grid.name))
        .default_open(false)
        .show(ui, |ui| {
            for (label, v) in [
                ("origin", &mut g.origin),
                ("u", &mut g.u),
                ("v", &mut g.v),
                ("normal", &mut g.normal),
            ] {
                ui.horizontal(|ui| {
                    let name = ui.label(if label == "normal" {
                        label.to_owned()
                    } else {
                        format!("{label} ({unit})")
                    });
                    for (axis, c) in v.iter_mut().enumerate() {
                        ui.add(
                            egui::DragValue::new(c)
                                .speed(1.0)
                                .prefix(["x ", "y ", "z "][axis])
                                .update_while_editing(false),
                        )
                        .labelled_by(name.id);
                    }
                });
            }
            ui.horizontal(|ui| {
                let name = ui.label("points nu × nv");
                ui.add(
                    egui::DragValue::new(&mut g.nu)
                        .range(1..=1000)
                        .update_while_editing(false),
                )
                .labelled_by(name.id);
                ui.add(
                    egui::DragValue::new(&mut g.nv)
                        .range(1..=1000)
                        .update_while_editing(false),
                )
                .labelled_by(name.id);
            });
        });
    if g == *grid {
        return None;
    }
    tracer_core::measure::Grid::new(&g.name, g.origin, g.u, g.v, g.nu, g.nv, Some(g.normal)).ok()
}

/// Illuminance along one row of the grid (j chosen with a slider), against the distance along u.
fn profile_ui(
    ui: &mut egui::Ui,
    grid: &tracer_core::measure::Grid,
    r: &tracer_core::measure::GridResult,
    unit: &str,
) {
    use egui_plot::{Line, Plot, PlotPoints};
    if grid.nu < 2 {
        return;
    }
    let id = ui.make_persistent_id("profile-row");
    let mut row: u32 = ui.data_mut(|d| d.get_temp(id).unwrap_or(grid.nv / 2));
    row = row.min(grid.nv - 1);
    if grid.nv > 1 {
        ui.add(egui::Slider::new(&mut row, 0..=grid.nv - 1).text("profile row j"))
            .on_hover_text("The row of points (along u) whose illuminance is plotted");
    }
    ui.data_mut(|d| d.insert_temp(id, row));
    let length = glam::Vec3::from(grid.u).length();
    let pts: Vec<[f64; 2]> = r
        .points
        .iter()
        .filter(|p| p.j == row)
        .map(|p| {
            let along = (f64::from(p.i) + 0.5) / f64::from(grid.nu) * f64::from(length);
            [along, p.illuminance_lx]
        })
        .collect();
    Plot::new(ui.make_persistent_id("profile-plot"))
        .height(120.0)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .include_y(0.0)
        .x_axis_label(format!("along u ({unit})"))
        .y_axis_label("E (lx)")
        .show(ui, |plot| {
            plot.line(Line::new(format!("row {row} (lx)"), PlotPoints::from(pts)));
        });
}

/// A grid over the plane of material slot `slot`'s largest triangle, covering the slot's
/// triangles in that plane, 0.1 % of the scene's size in front of it (towards the camera).
fn add_surface_grid(doc: &mut Document, slot: u32, out: &mut Commands) {
    use glam::Vec3;
    let scene = &doc.scene;
    let tris: Vec<usize> = (0..scene.triangles.len())
        .filter(|&t| scene.triangle_slots[t] == slot)
        .collect();
    let area = |t: usize| {
        let [a, b, c] = scene.triangles[t];
        (b - a).cross(c - a).length()
    };
    let Some(&largest) = tris.iter().max_by(|&&a, &&b| area(a).total_cmp(&area(b))) else {
        return;
    };
    let [a, b, c] = scene.triangles[largest];
    let Some(mut n) = (b - a).cross(c - a).try_normalize() else {
        out.push(Command::Error("the selected surface has no area".into()));
        return;
    };
    let eye = Vec3::from(doc.setup.camera.position);
    if n.dot(eye - a) < 0.0 {
        n = -n;
    }
    // The slot's triangles in this plane (parallel, and on it within 0.1 % of the scene).
    let tol = 1e-3 * scene.bounds.radius().max(1e-6);
    let mut points = Vec::new();
    for &t in &tris {
        let [p, q, r] = scene.triangles[t];
        let m = (q - p).cross(r - p).normalize_or_zero();
        if m.cross(n).length() < 0.02 && [p, q, r].iter().all(|v| (v - a).dot(n).abs() < tol) {
            points.extend([p, q, r]);
        }
    }
    let reference = if n.cross(Vec3::X).length() > 0.5 {
        Vec3::X
    } else {
        Vec3::Z
    };
    let e1 = (reference - n * n.dot(reference)).normalize();
    let e2 = n.cross(e1);
    let (mut lo, mut hi) = (
        glam::Vec2::splat(f32::INFINITY),
        glam::Vec2::splat(f32::NEG_INFINITY),
    );
    for p in &points {
        let q = glam::Vec2::new((p - a).dot(e1), (p - a).dot(e2));
        lo = lo.min(q);
        hi = hi.max(q);
    }
    let size = hi - lo;
    let origin = a + e1 * lo.x + e2 * lo.y + n * tol;
    // Grid names are A-Z, a-z, 0-9, _ and -: anything else in a brep's name becomes _.
    let label: String = scene
        .slot_label(slot)
        .chars()
        .map(|c| match c {
            '/' => '-',
            c if c.is_ascii_alphanumeric() || c == '_' || c == '-' => c,
            _ => '_',
        })
        .collect();
    let name = (1..)
        .map(|k| format!("{label}{k}"))
        .find(|name| doc.setup.grids.iter().all(|g| &g.name != name))
        .unwrap_or(label);
    let mpu = doc.setup.unit.metres_per_unit();
    let p = tracer_core::scene::en12464_spacing_m(size.max_element() * mpu) / mpu;
    let count = |l: f32| ((l / p).ceil() as u32).clamp(1, 1000);
    match tracer_core::measure::Grid::new(
        &name,
        origin.to_array(),
        (e1 * size.x).to_array(),
        (e2 * size.y).to_array(),
        count(size.x),
        count(size.y),
        Some(n.to_array()),
    ) {
        Ok(g) => doc.setup.grids.push(g),
        Err(e) => out.push(Command::Error(e.to_string())),
    }
}

fn add_work_plane(doc: &mut Document, out: &mut Commands) {
    let n = (1..)
        .map(|k| format!("workplane{k}"))
        .find(|name| doc.setup.grids.iter().all(|g| &g.name != name))
        .unwrap_or_else(|| "workplane".into());
    // 0.75 m up and 0.5 m in, unless the scene is smaller than that (a model box): then half
    // its height and a tenth of its shorter side, and say so.
    let b = doc.scene.bounds;
    let per_m = 1.0 / doc.setup.unit.metres_per_unit();
    let (height, margin) = (0.75 * per_m, 0.5 * per_m);
    let fit_height = height.min(0.5 * b.extent().y);
    let fit_margin = margin.min(0.1 * b.extent().x.min(b.extent().z));
    if fit_height < height || fit_margin < margin {
        let unit = doc.setup.unit.symbol();
        out.push(Command::Notice(format!(
            "the scene is small for a 0.75 m work plane 0.5 m from the walls: placed at \
             {fit_height:.0} {unit}, {fit_margin:.0} {unit} from the walls"
        )));
    }
    let spec = GridSpec {
        name: n,
        work_plane: Some(true),
        height: Some(fit_height),
        margin: Some(fit_margin),
        ..GridSpec::default()
    };
    let context = GridContext {
        bounds: b,
        metres_per_unit: doc.setup.unit.metres_per_unit(),
    };
    match spec.to_grid(Some(context)) {
        Ok(Some(grid)) => doc.setup.grids.push(grid),
        Ok(None) => {}
        Err(e) => out.push(Command::Error(e)),
    }
}

/// NAME.`suffix` beside the scene (the current folder for the built-in scene).
fn report_path(doc: &Document, suffix: &str) -> std::path::PathBuf {
    match &doc.path {
        Some(p) => p.with_extension(suffix),
        None => std::path::PathBuf::from(format!("cornell_box.{suffix}")),
    }
}

/// Asks for `text` to be written beside the scene as NAME.`suffix` (the current folder for the
/// built-in scene).
fn export(doc: &Document, suffix: &str, text: String) -> Command {
    Command::WriteText {
        path: report_path(doc, suffix),
        text,
    }
}
