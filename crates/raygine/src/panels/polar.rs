//! A luminaire's polar intensity diagram as datasheets draw it: the nadir (γ = 0°) down, a
//! spoke every 30° labelled with its γ, circles at round candela values labelled in cd, the
//! C0-C180 plane solid (C0 to the right) and the C90-C270 plane dashed (C90 to the right).

use egui::{Align2, Color32, FontId, Pos2, Sense, Stroke, Vec2};
use tracer_core::light::Photometry;

const C0_COLOUR: Color32 = Color32::from_rgb(230, 90, 70);
const C90_COLOUR: Color32 = Color32::from_rgb(80, 150, 240);

/// A "nice" step for `n` circles up to `max`: 1, 2 or 5 times a power of ten.
pub fn ring_step(max: f32, n: f32) -> f32 {
    if !(max > 0.0 && max.is_finite()) {
        return 1.0;
    }
    let raw = max / n;
    let p = 10f32.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&s| s >= raw)
        .unwrap_or(10.0 * p)
}

/// Draws the diagram of `p` times `multiplier`, `size` points square.
pub fn polar_diagram(ui: &mut egui::Ui, p: &Photometry, multiplier: f32, size: f32) {
    let sample = |c: f32| -> Vec<(f32, f32)> {
        (0..=180)
            .map(|g| (g as f32, p.intensity(c, g as f32) * multiplier))
            .collect()
    };
    let planes = [
        (sample(0.0), sample(180.0), C0_COLOUR, false),
        (sample(90.0), sample(270.0), C90_COLOUR, true),
    ];
    let peak = planes
        .iter()
        .flat_map(|(a, b, _, _)| a.iter().chain(b).map(|&(_, v)| v))
        .fold(0.0_f32, f32::max);
    let step = ring_step(peak, 4.0);
    let rings = (peak / step).ceil().max(1.0);
    let scale_max = rings * step;

    let (response, painter) = ui.allocate_painter(Vec2::splat(size), Sense::hover());
    let rect = response.rect;
    let centre = rect.center();
    let radius = 0.5 * size - 16.0;
    let faint = Stroke::new(1.0, Color32::from_gray(90));
    let text = ui.visuals().text_color();
    let font = FontId::proportional(10.0);
    // γ measured from the nadir (down); right half C0 (or C90), left half C180 (or C270).
    let at = |gamma_deg: f32, r: f32, right: bool| {
        let g = gamma_deg.to_radians();
        let x = if right { g.sin() } else { -g.sin() };
        centre + Vec2::new(x, g.cos()) * r
    };
    for k in 1..=rings as u32 {
        let r = radius * (k as f32 * step / scale_max);
        painter.circle_stroke(centre, r, faint);
        // Along the 165° spoke, clear of the 180° label at the top.
        painter.text(
            at(165.0, r, true) + Vec2::new(2.0, 0.0),
            Align2::LEFT_CENTER,
            crate::format::format_quantity(k as f32 * step, "cd"),
            font.clone(),
            text,
        );
    }
    for gamma in (0..=180).step_by(30) {
        for right in [true, false] {
            painter.line_segment([centre, at(gamma as f32, radius, right)], faint);
        }
        if gamma > 0 && gamma < 180 {
            for right in [true, false] {
                let pos = at(gamma as f32, radius + 8.0, right);
                painter.text(
                    pos,
                    Align2::CENTER_CENTER,
                    format!("{gamma}°"),
                    font.clone(),
                    text,
                );
            }
        }
    }
    painter.text(
        at(0.0, radius + 8.0, true),
        Align2::CENTER_CENTER,
        "0°",
        font.clone(),
        text,
    );
    painter.text(
        at(180.0, radius + 8.0, true),
        Align2::CENTER_CENTER,
        "180°",
        font.clone(),
        text,
    );
    for (a, b, colour, dashed) in &planes {
        let curve: Vec<Pos2> = a
            .iter()
            .map(|&(g, v)| at(g, radius * v / scale_max, true))
            .chain(
                b.iter()
                    .rev()
                    .map(|&(g, v)| at(g, radius * v / scale_max, false)),
            )
            .collect();
        let stroke = Stroke::new(2.0, *colour);
        if *dashed {
            painter.extend(egui::Shape::dashed_line(&curve, stroke, 5.0, 3.0));
        } else {
            painter.add(egui::Shape::line(curve, stroke));
        }
    }
    ui.horizontal(|ui| {
        ui.colored_label(C0_COLOUR, "— C0-C180");
        ui.colored_label(C90_COLOUR, "- - C90-C270");
        ui.label(format!(
            "(right: C0, C90; peak {})",
            crate::format::format_quantity(peak, "cd")
        ));
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rings_fall_on_round_values() {
        assert_eq!(ring_step(330.0, 4.0), 100.0);
        assert_eq!(ring_step(100.0, 4.0), 50.0);
        assert_eq!(ring_step(7.0, 4.0), 2.0);
        assert_eq!(ring_step(0.0, 4.0), 1.0);
    }
}
