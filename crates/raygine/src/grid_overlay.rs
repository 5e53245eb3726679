//! Grid readings drawn over the picture: each cell filled with the false colour of its point's
//! illuminance (log scale from Emax/1000 to Emax), its value in lx when there is room, and
//! isolux lines (marching squares over the cell centres) at round levels.

use egui::{Align2, Color32, FontId, Pos2, Shape, Stroke};
use glam::Vec3;
use tracer_core::display::{FalseColour, FalseColourQuantity, FalseColourScale};
use tracer_core::measure::isolux::{isolux_levels, isolux_segments};
use tracer_core::measure::{Grid, GridResult};

/// Draws one grid's readings; `to_screen` projects scene points (None behind the camera) and
/// `visible` says whether the camera sees a point (no surface in front of it): cells and
/// isolux lines behind objects are not drawn. Points inside objects are hatched, unlabelled.
/// `daylight_factor`: the readings are daylight factors in %, labelled to 0.1 %.
pub fn draw(
    painter: &egui::Painter,
    grid: &Grid,
    r: &GridResult,
    to_screen: &dyn Fn(Vec3) -> Option<Pos2>,
    visible: &dyn Fn(Vec3) -> bool,
    daylight_factor: bool,
) {
    let s = r.statistics();
    let max = s.e_max_lx.max(1e-6) as f32;
    let fc = FalseColour {
        quantity: FalseColourQuantity::Illuminance,
        scale: FalseColourScale::Log,
        min: max / 1000.0,
        max,
    };
    let (o, u, v) = (
        Vec3::from(grid.origin),
        Vec3::from(grid.u),
        Vec3::from(grid.v),
    );
    let (nu, nv) = (grid.nu as usize, grid.nv as usize);
    let corner = |i: f32, j: f32| o + u * (i / nu as f32) + v * (j / nv as f32);
    let labels = r.points.len() <= 64;
    for p in &r.points {
        let (i, j) = (p.i as f32, p.j as f32);
        if !visible(corner(i + 0.5, j + 0.5)) {
            continue;
        }
        let quad: Option<Vec<Pos2>> = [(i, j), (i + 1.0, j), (i + 1.0, j + 1.0), (i, j + 1.0)]
            .iter()
            .map(|&(a, b)| to_screen(corner(a, b)))
            .collect();
        let Some(quad) = quad else { continue };
        if p.buried {
            hatch(painter, &quad);
            continue;
        }
        let [cr, cg, cb, _] = fc.colour(p.illuminance_lx as f32);
        painter.add(Shape::convex_polygon(
            quad,
            Color32::from_rgba_unmultiplied(cr, cg, cb, 110),
            Stroke::new(0.5, Color32::from_black_alpha(120)),
        ));
        if labels && let Some(c) = to_screen(corner(i + 0.5, j + 0.5)) {
            painter.text(
                c,
                Align2::CENTER_CENTER,
                if daylight_factor {
                    format!("{:.1}", p.illuminance_lx)
                } else {
                    format!("{:.0}", p.illuminance_lx)
                },
                FontId::proportional(10.0),
                Color32::WHITE,
            );
        }
    }
    if r.points.len() != nu * nv {
        return;
    }
    let mut values = vec![0.0; nu * nv];
    for p in &r.points {
        // Readings of an edited grid may not fit its new size until they are measured again.
        if p.i as usize >= nu || p.j as usize >= nv {
            return;
        }
        values[p.j as usize * nu + p.i as usize] = p.illuminance_lx;
    }
    // Cell-centre coordinates to the scene: centre of cell (i, j) is corner(i + ½, j + ½).
    let centre = |(ci, cj): (f64, f64)| corner(ci as f32 + 0.5, cj as f32 + 0.5);
    for level in isolux_levels(s.e_min_lx, s.e_max_lx) {
        for [a, b] in isolux_segments(&values, nu, nv, level) {
            if !(visible(centre(a)) && visible(centre(b))) {
                continue;
            }
            if let (Some(pa), Some(pb)) = (to_screen(centre(a)), to_screen(centre(b))) {
                painter.line_segment([pa, pb], Stroke::new(1.5, Color32::WHITE));
            }
        }
    }
}

/// A cell of a point inside an object: grey, with diagonal hatching.
fn hatch(painter: &egui::Painter, quad: &[Pos2]) {
    painter.add(Shape::convex_polygon(
        quad.to_vec(),
        Color32::from_black_alpha(90),
        Stroke::new(0.5, Color32::from_black_alpha(120)),
    ));
    let stroke = Stroke::new(1.0, Color32::from_gray(170));
    if let [a, b, c, d] = quad {
        for k in 1..4 {
            let t = k as f32 / 4.0;
            painter.line_segment([a.lerp(*b, t), a.lerp(*d, t)], stroke);
            painter.line_segment([c.lerp(*b, t), c.lerp(*d, t)], stroke);
        }
        painter.line_segment([*b, *d], stroke);
    }
}

/// The grids' statistics and their colour legend in the viewport's bottom-right corner.
pub fn draw_statistics(
    painter: &egui::Painter,
    viewport: egui::Rect,
    results: &[GridResult],
    samples: u32,
    daylight_factor: bool,
) {
    let mut lines = vec![if daylight_factor {
        format!("grids, {samples} samples a point, daylight factor (CIE overcast)")
    } else {
        format!("grids, {samples} samples a point")
    }];
    for r in results {
        let s = r.statistics();
        lines.push(if daylight_factor {
            format!(
                "{}: DF min {:.2} % · avg {:.2} % · max {:.2} % · min/avg {:.2}",
                r.name, s.e_min_lx, s.e_avg_lx, s.e_max_lx, s.u0
            )
        } else {
            format!(
                "{}: Emin {:.1} · Eavg {:.1} · Emax {:.1} lx · U0 {:.2} · Emin/Emax {:.2}",
                r.name, s.e_min_lx, s.e_avg_lx, s.e_max_lx, s.u0, s.emin_over_emax
            )
        });
    }
    let galley = painter.layout(
        lines.join("\n"),
        FontId::monospace(11.0),
        Color32::WHITE,
        viewport.width() * 0.6,
    );
    let size = galley.size() + egui::Vec2::new(12.0, 30.0);
    // Bottom right: the top of the viewport carries the notices and errors.
    let plate = egui::Rect::from_min_size(
        Pos2::new(viewport.max.x - size.x - 8.0, viewport.max.y - size.y - 8.0),
        size,
    );
    painter.rect_filled(plate, 4.0, Color32::from_black_alpha(200));
    painter.galley(
        plate.min + egui::Vec2::new(6.0, 4.0),
        galley,
        Color32::WHITE,
    );
    // The cells' colours: log scale from Emax/1000 to Emax of each grid; one bar, labelled in
    // fractions of Emax.
    let bar = egui::Rect::from_min_size(
        Pos2::new(plate.min.x + 6.0, plate.max.y - 20.0),
        egui::Vec2::new(plate.width() * 0.5, 8.0),
    );
    let fc = FalseColour {
        quantity: FalseColourQuantity::Illuminance,
        scale: FalseColourScale::Log,
        min: 0.001,
        max: 1.0,
    };
    let steps = 32;
    for k in 0..steps {
        let t = (k as f32 + 0.5) / steps as f32;
        let [r, g, b, _] = fc.colour(fc.value_at(t));
        let x0 = bar.min.x + bar.width() * k as f32 / steps as f32;
        painter.rect_filled(
            egui::Rect::from_min_max(
                Pos2::new(x0, bar.min.y),
                Pos2::new(x0 + bar.width() / steps as f32 + 0.5, bar.max.y),
            ),
            0.0,
            Color32::from_rgb(r, g, b),
        );
    }
    painter.text(
        Pos2::new(bar.max.x + 6.0, bar.center().y),
        Align2::LEFT_CENTER,
        "Emax/1000 … Emax (log)",
        FontId::monospace(10.0),
        Color32::WHITE,
    );
}
