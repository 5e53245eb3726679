//! The Glare section: the observers (where glare is judged), and per observer UGR and DGP with
//! their standard errors as the background judgement refines, both ways of finding sources;
//! the image rule's threshold and DGP's low-light correction.

use crate::document::Document;
use crate::glare_worker::{GlareReadings, Judged, REFINEMENTS, plus_minus as pm};
use egui::Color32;
use tracer_core::glare::{GlareFigures, GlareOptions};

fn figures_ui(ui: &mut egui::Ui, way: &str, f: &GlareFigures) {
    let ugr = f.ugr.map_or("—".to_owned(), |u| pm(u, f.ugr_se, 1));
    let low = if f.low_light_applied {
        ", low-light corrected"
    } else {
        ""
    };
    let n = f.sources.len();
    ui.label(format!(
        "{way}: UGR {ugr}, DGP {}{low} ({n} source{})",
        pm(f.dgp, f.dgp_se, 3),
        if n == 1 { "" } else { "s" }
    ))
    .on_hover_text(sources_text(f));
}

/// Each source on its own line, for the hover.
fn sources_text(f: &GlareFigures) -> String {
    let mut lines = vec![format!(
        "Lb {} cd/m² (background), Ev {} lx",
        pm(f.lb, f.lb_se, 1),
        pm(f.ev, f.ev_se, 1)
    )];
    lines.push(match f.error_batches {
        Some(k) => format!("± from the spread of {k} independent batches of samples"),
        None => "± from the pixels' own errors".to_owned(),
    });
    for s in &f.sources {
        let (up, right) = s.angles_deg();
        lines.push(format!(
            "{}: L {:.0} cd/m², ω {:.4} sr, p {:.2} ({}), {up:+.0}° up, {right:+.0}° right{}",
            s.label,
            s.luminance,
            s.solid_angle,
            s.position_index,
            s.index_rule.label(),
            if s.outside_cie117() {
                " — outside CIE 117's 0.0003–0.1 sr"
            } else {
                ""
            }
        ));
    }
    lines.extend(f.notes());
    lines.join("\n")
}

fn judged_ui(ui: &mut egui::Ui, j: &Judged) {
    ui.label(format!(
        "Ev {} lx at the eye",
        pm(j.from_image.ev, j.from_image.ev_se, 0)
    ));
    figures_ui(ui, "Image", &j.from_image);
    if let Some(a) = &j.analytic {
        figures_ui(ui, "Luminaires", a);
    }
}

/// The section: observers, their glare, the options.
pub fn glare_ui(
    ui: &mut egui::Ui,
    doc: &mut Document,
    readings: Option<GlareReadings>,
    options: &mut GlareOptions,
) {
    super::observers::observers_ui(ui, doc);
    if doc.setup.observers.is_empty() {
        return;
    }
    ui.separator();
    match &readings {
        None => {
            ui.label(format!(
                "Judging glare ({} spp fisheye at each eye)…",
                REFINEMENTS[0]
            ));
        }
        Some(r) => {
            let status = if r.finished {
                format!("{} spp a pixel (done)", r.samples)
            } else {
                format!("{} spp a pixel, refining…", r.samples)
            };
            ui.weak(status);
            for o in &r.observers {
                ui.strong(&o.name);
                match &o.result {
                    Ok(j) => judged_ui(ui, j),
                    Err(e) => {
                        ui.colored_label(Color32::from_rgb(255, 120, 100), e);
                    }
                }
            }
        }
    }
    ui.horizontal(|ui| {
        ui.label("Glare pixels above");
        ui.add(
            egui::DragValue::new(&mut options.detection.threshold)
                .range(0.5..=1e9)
                .speed(0.1),
        )
        .on_hover_text(
            "evalglare's -b: up to 100 a factor of the image's mean luminance, above 100 a \
             luminance in cd/m²",
        );
        ui.label(if options.detection.threshold > 100.0 {
            "cd/m²"
        } else {
            "× mean"
        });
    });
    ui.checkbox(
        &mut options.low_light,
        "DGP low-light correction (Ev < 1000 lx)",
    )
    .on_hover_text("evalglare's -C l+: DGP · e^(0.024 Ev − 4) / (1 + e^(0.024 Ev − 4))");
}
