//! The Measure panel: the scene's calculation grids, a work plane to add, their statistics as
//! they refine, and export of the readings to CSV and JSON beside the scene.

use crate::command::{Command, Commands, Edit};
use crate::document::Document;
use crate::measure_cmd::{csv, json_report};
use crate::measure_worker::Readings;
use tracer_core::integrator::IntegratorKind;
use tracer_core::measure::rounding::Precision;

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
    daylight_factor: &mut bool,
    out: &mut Commands,
) {
    let readings = view.readings;
    if let Some(e) = readings.as_ref().and_then(|r| r.error.as_ref()) {
        ui.colored_label(egui::Color32::from_rgb(255, 120, 100), e);
    }
    let df = readings.as_ref().is_some_and(|r| r.daylight_factor);
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
                Some(r) if df => {
                    let s = r.statistics();
                    ui.label(format!(
                        "DF min {:.2} % · avg {:.2} % · max {:.2} %",
                        s.e_min_lx, s.e_avg_lx, s.e_max_lx
                    ));
                    ui.label(format!("uniformity (min/avg) {:.2}", s.u0));
                }
                Some(r) => {
                    let s = r.statistics();
                    ui.label(format!(
                        "Emin {:.1} lx · Eavg {:.1} lx · Emax {:.1} lx",
                        s.e_min_lx, s.e_avg_lx, s.e_max_lx
                    ));
                    let buried = r.buried_count();
                    if buried > 0 {
                        ui.colored_label(
                            egui::Color32::from_rgb(255, 210, 90),
                            format!(
                                "{buried} of {} points inside objects (hatched), left out",
                                r.points.len()
                            ),
                        )
                        .on_hover_text(
                            "Points whose every view ends on the inside of a surface (in a \
                             block, under a cabinet) read 0 lx; Emin, Eavg, U0 leave them out",
                        );
                    }
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
        out.push(Command::Edit(Edit::ReplaceGrid(i, Box::new(g))));
    }
    if let Some(i) = remove {
        out.push(Command::Edit(Edit::RemoveGrid(i)));
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
            out.push(Command::Edit(Edit::AddWorkPlane));
        }
        ui.checkbox(show_grids, "show on picture");
        ui.checkbox(daylight_factor, "DF (%)").on_hover_text(
            "Daylight factor: measure DF = E_in / E_out,h under the CIE overcast sky without \
             sun, lights or glowing surfaces, whatever the scene's sky (E_out,h computed)",
        );
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
        out.push(Command::Edit(Edit::AddGridOnSurface(slot)));
    }
    ui.add_enabled_ui(
        readings.as_ref().is_some_and(|r| !r.results.is_empty()),
        |ui| {
            ui.horizontal(|ui| {
                if ui.button("Export CSV").clicked()
                    && let Some(r) = &readings
                {
                    out.push(export(
                        doc,
                        "grids.csv",
                        csv(&r.results, None, Precision::Rounded),
                    ));
                }
                if ui.button("Export JSON").clicked()
                    && let Some(r) = &readings
                {
                    let unit = doc.setup.unit.symbol();
                    let text = json_report(
                        &r.results,
                        unit,
                        view.integrator.name(),
                        r.samples,
                        None,
                        Precision::Rounded,
                    );
                    out.push(export(doc, "grids.json", text));
                }
            });
            if ui
                .button("Save view + CSV")
                .on_hover_text(
                    "The view with the grids, their statistics and legend as a PNG, and the \
                     CSV beside it (File > Save report… writes the PDF report)",
                )
                .clicked()
                && let Some(r) = &readings
            {
                out.push(Command::SaveReport {
                    png: report_path(doc, "report.png"),
                    csv: report_path(doc, "grids.csv"),
                    csv_text: csv(&r.results, None, Precision::Rounded),
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
    // Room for the widest tick label ("1200", "0.05") beside the axis title, so none is cut.
    let top = pts.iter().map(|p| p[1]).fold(0.0_f64, f64::max);
    let digits = top.abs().max(1.0).log10().floor() as usize + 1;
    let char_w = ui.fonts_mut(|f| f.glyph_width(&egui::TextStyle::Body.resolve(ui.style()), '0'));
    // Inside the panel's visible width, with room past the last point for the x axis's last
    // tick label ("400", which the panel's edge used to cut to "40").
    let width = (ui.clip_rect().right() - ui.cursor().left() - 12.0).clamp(160.0, 480.0);
    Plot::new(ui.make_persistent_id("profile-plot"))
        .height(140.0)
        .width(width)
        .set_margin_fraction(egui::vec2(0.08, 0.1))
        .y_axis_min_width(char_w * (digits as f32 + 2.0))
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
