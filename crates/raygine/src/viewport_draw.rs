//! What the viewport draws over the picture: light markers, the grids' readings, the axis
//! triad, the false-colour legend, and the text overlays (load, hint, banners, read-out).

use crate::banners::BannerKind;
use crate::command::{Command, Commands};
use crate::document::Document;
use crate::file_ops::PendingLoad;
use crate::format::format_value;
use crate::measure_worker::Readings;
use egui::{Align2, Color32, FontId, Pos2, Rect, Stroke, Vec2};
use glam::Vec3;
use tracer_core::scene::{CameraBasis, Setup};

/// What the mouse points at in the viewport.
#[derive(Clone, Debug, Default)]
pub struct HoverInfo {
    pub luminance: f32,
    /// None until the render measures it (from the first readout on).
    pub illuminance: Option<f32>,
    pub surface: Option<String>,
    pub pixel: [u32; 2],
}

/// The text drawn over the picture.
#[derive(Debug)]
pub struct Overlays<'a> {
    pub loading: Option<&'a PendingLoad>,
    pub picture_hint: Option<&'a str>,
    pub error: Option<&'a str>,
    pub notice: Option<&'a str>,
    pub hover: Option<&'a HoverInfo>,
}

fn to_screen(rect: Rect, basis: &CameraBasis, p: Vec3) -> Option<Pos2> {
    let (x, y) = basis.project(p)?;
    Some(Pos2::new(
        rect.min.x + x / basis.width as f32 * rect.width(),
        rect.min.y + y / basis.height as f32 * rect.height(),
    ))
}

/// A fisheye's image circle, outlined: outside it the camera sees nothing.
pub fn draw_image_circle(ui: &egui::Ui, basis: &CameraBasis, rect: Rect) {
    let tracer_core::scene::Lens::Fisheye {
        centre, radius_px, ..
    } = basis.lens
    else {
        return;
    };
    let sx = rect.width() / basis.width as f32;
    let sy = rect.height() / basis.height as f32;
    let centre = Pos2::new(rect.min.x + centre.0 * sx, rect.min.y + centre.1 * sy);
    let stroke = Stroke::new(1.0, Color32::from_gray(110));
    ui.painter_at(rect)
        .circle_stroke(centre, radius_px * sx.min(sy), stroke);
}

/// Each observer as a small cyan ring with its name and a short line along its view.
pub fn draw_observers(
    ui: &egui::Ui,
    observers: &[tracer_core::scene::Observer],
    basis: &CameraBasis,
    rect: Rect,
    scene_size: f32,
) {
    let painter = ui.painter_at(rect);
    let colour = Color32::from_rgb(120, 220, 255);
    for o in observers {
        let eye = Vec3::from(o.position);
        let Some(pos) = to_screen(rect, basis, eye) else {
            continue;
        };
        painter.circle_stroke(pos, 5.0, Stroke::new(1.5, colour));
        let dir = Vec3::from(o.direction).normalize_or_zero();
        if let Some(tip) = to_screen(rect, basis, eye + dir * 0.08 * scene_size) {
            painter.line_segment([pos, tip], Stroke::new(1.5, colour));
        }
        painter.text(
            pos + Vec2::new(8.0, -8.0),
            Align2::LEFT_BOTTOM,
            &o.name,
            FontId::proportional(12.0),
            colour,
        );
    }
}

/// When the camera looks through an observer's fisheye ("View from observer"), that observer's
/// glare sources: the image's outlined pixel by pixel (orange), the luminaires' as circles of
/// their solid angle (cyan), each labelled with its luminance; UGR and DGP in the corner.
pub fn draw_glare_sources(
    ui: &egui::Ui,
    setup: &tracer_core::scene::Setup,
    readings: &crate::glare_worker::GlareReadings,
    basis: &CameraBasis,
    rect: Rect,
) {
    let Some(observer) = setup
        .observers
        .iter()
        .find(|o| o.fisheye_camera() == setup.camera)
    else {
        return;
    };
    let Some(Ok(judged)) = readings
        .observers
        .iter()
        .find(|r| r.name == observer.name)
        .map(|r| &r.result)
    else {
        return;
    };
    let painter = ui.painter_at(rect);
    let [right, up, forward] = judged.frame;
    let to_world = |d: glam::DVec3| {
        (right * d.x as f32 + up * d.y as f32 + forward * d.z as f32).normalize_or_zero()
    };
    let sx = rect.width() / basis.width as f32;
    let sy = rect.height() / basis.height as f32;
    let screen = |d: glam::DVec3| {
        basis
            .film_position(to_world(d))
            .map(|(x, y)| Pos2::new(rect.min.x + x * sx, rect.min.y + y * sy))
    };
    let orange = Color32::from_rgb(255, 150, 40);
    let cyan = Color32::from_rgb(120, 220, 255);
    for (s, edge) in judged.from_image.sources.iter().zip(&judged.outlines) {
        for &d in edge {
            if let Some(p) = screen(d) {
                painter.rect_filled(Rect::from_center_size(p, Vec2::splat(1.5)), 0.0, orange);
            }
        }
        if let Some(p) = screen(s.direction) {
            painter.text(
                p,
                Align2::CENTER_CENTER,
                format!("{:.0} cd/m²", s.luminance),
                FontId::proportional(11.0),
                orange,
            );
        }
    }
    if let Some(a) = &judged.analytic {
        for s in &a.sources {
            // A cone of the source's solid angle about its direction.
            let half = (1.0 - s.solid_angle / std::f64::consts::TAU)
                .clamp(-1.0, 1.0)
                .acos();
            let d = s.direction;
            let helper = if d.y.abs() < 0.9 {
                glam::DVec3::Y
            } else {
                glam::DVec3::X
            };
            let (u, v) = {
                let u = d.cross(helper).normalize();
                (u, d.cross(u))
            };
            let ring: Vec<Pos2> = (0..=48)
                .filter_map(|k| {
                    let phi = std::f64::consts::TAU * f64::from(k) / 48.0;
                    let dir = d * half.cos() + (u * phi.cos() + v * phi.sin()) * half.sin();
                    screen(dir)
                })
                .collect();
            painter.add(egui::Shape::line(ring, Stroke::new(1.5, cyan)));
        }
    }
    let f = &judged.from_image;
    let pm = crate::glare_worker::plus_minus;
    let ugr = f.ugr.map_or("—".to_owned(), |u| pm(u, f.ugr_se, 1));
    painter.text(
        rect.left_top() + Vec2::new(8.0, 24.0),
        Align2::LEFT_TOP,
        format!(
            "{}: UGR {ugr}, DGP {}, Ev {} lx ({} spp; glare sources outlined)",
            observer.name,
            pm(f.dgp, f.dgp_se, 3),
            pm(f.ev, f.ev_se, 0),
            readings.samples
        ),
        FontId::proportional(13.0),
        orange,
    );
}

/// The point an orbit turns about: a small ring with a cross.
pub fn draw_pivot(ui: &egui::Ui, basis: &CameraBasis, rect: Rect, pivot: Vec3) {
    let Some(pos) = to_screen(rect, basis, pivot) else {
        return;
    };
    let painter = ui.painter_at(rect);
    let stroke = egui::Stroke::new(1.5, Color32::from_rgb(255, 230, 120));
    painter.circle_stroke(pos, 7.0, stroke);
    painter.line_segment(
        [pos - egui::vec2(4.0, 0.0), pos + egui::vec2(4.0, 0.0)],
        stroke,
    );
    painter.line_segment(
        [pos - egui::vec2(0.0, 4.0), pos + egui::vec2(0.0, 4.0)],
        stroke,
    );
}

/// Each light as a dot in its colour with its label; spots and luminaires with their aim. With
/// more than the Lights panel lists in full, small unlabelled dots, and the `selected` light
/// marked in full: a thousand labels would hide the picture and slow every frame.
pub fn draw_light_markers(
    ui: &egui::Ui,
    doc: &Document,
    basis: &CameraBasis,
    rect: Rect,
    selected: usize,
) {
    let painter = ui.painter_at(rect);
    let many = doc.setup.lights.len() > crate::panels::MANY_LIGHTS;
    for (i, light) in doc.setup.lights.iter().enumerate() {
        if many && i != selected {
            if let Some(pos) = to_screen(rect, basis, light.position()) {
                painter.circle_filled(pos, 2.5, Color32::YELLOW);
            }
            continue;
        }
        if let Some(pos) = to_screen(rect, basis, light.position()) {
            let c = light.color.map(|v| (v.clamp(0.0, 1.0) * 255.0) as u8);
            painter.circle(
                pos,
                6.0,
                Color32::from_rgb(c[0], c[1], c[2]),
                Stroke::new(2.0, Color32::BLACK),
            );
            // One quantity for every kind: the (peak) intensity in cd; flux is in the panel.
            let cd = light.peak_cd();
            let label = format!("L{} {}", i + 1, crate::format::format_quantity(cd, "cd"));
            // On a dark plate, so the label reads over bright pixels.
            let galley = painter.layout_no_wrap(label, FontId::proportional(12.0), Color32::YELLOW);
            let at = pos + Vec2::new(9.0, -9.0 - galley.size().y);
            text_on_plate(&painter, at, galley, Color32::YELLOW);
            draw_opening(&painter, doc, basis, rect, light);
            // Spots and luminaires: their aim, a tenth of the scene's size long.
            if let Some(aim) = light.aim() {
                let reach = doc.scene.bounds.radius() * 0.2;
                let tip = light.position() + Vec3::from(aim).normalize_or_zero() * reach;
                if let Some(end) = to_screen(rect, basis, tip) {
                    painter.arrow(pos, end - pos, Stroke::new(2.0, Color32::YELLOW));
                }
            }
        }
    }
}

/// A luminaire's luminous opening as a thin outline (it is not geometry, so the picture does
/// not show it).
fn draw_opening(
    painter: &egui::Painter,
    doc: &Document,
    basis: &CameraBasis,
    rect: Rect,
    light: &tracer_core::scene::Light,
) {
    let tracer_core::scene::LightKind::Luminaire(placement) = &light.kind else {
        return;
    };
    let sign = match doc.setup.handedness {
        tracer_core::scene::Handedness::Right => 1.0,
        tracer_core::scene::Handedness::Left => -1.0,
    };
    let Some(frame) = light.luminaire_frame(sign) else {
        return;
    };
    let shape = placement.opening(doc.setup.unit.metres_per_unit());
    let stroke = Stroke::new(1.5, Color32::from_rgb(255, 230, 120));
    for [a, b] in shape.outline(24) {
        let a = to_screen(rect, basis, light.position() + frame.to_scene(a));
        let b = to_screen(rect, basis, light.position() + frame.to_scene(b));
        if let (Some(a), Some(b)) = (a, b) {
            painter.line_segment([a, b], stroke);
        }
    }
}

/// The grids' readings over the picture: false-colour cells, values and isolux lines.
pub fn draw_grid_readings(
    ui: &egui::Ui,
    doc: &Document,
    readings: &Readings,
    basis: &CameraBasis,
    rect: Rect,
) {
    let painter = ui.painter_at(rect);
    let project = |p: Vec3| to_screen(rect, basis, p);
    // Depth test against the scene: a point is seen when no drawn surface lies between it and
    // the eye (the grid floats 0.1 % of the scene's size over its surface).
    let visible = |p: Vec3| seen_from(&doc.scene, &doc.setup.hidden, basis.eye_for(p), p);
    for r in &readings.results {
        if let Some(grid) = doc.setup.grids.iter().find(|g| g.name == r.name) {
            crate::grid_overlay::draw(
                &painter,
                grid,
                r,
                &project,
                &visible,
                readings.daylight_factor,
            );
        }
    }
    crate::grid_overlay::draw_statistics(
        &painter,
        rect,
        &readings.results,
        readings.samples,
        readings.daylight_factor,
    );
}

/// Whether `p` is seen from `eye`: no drawn surface lies between them (within twice the ray
/// epsilon of `p`, so a grid floating just over its surface is seen).
pub fn seen_from(scene: &tracer_core::scene::Scene, hidden: &[bool], eye: Vec3, p: Vec3) -> bool {
    let to = p - eye;
    let distance = to.length();
    let Some(dir) = to.try_normalize() else {
        return true;
    };
    let ray = tracer_core::geometry::Ray::new(eye, dir);
    scene
        .closest_drawn(&ray, hidden)
        .is_none_or(|hit| hit.t >= distance - 2.0 * scene.ray_epsilon())
}

/// X (red), Y (green), Z (blue) in the bottom-left corner, drawn with the camera's basis so the
/// triad agrees with the picture (mirrored for left-handed scenes); with daylight, the sun's
/// direction in yellow.
pub fn draw_axis_triad(ui: &egui::Ui, setup: &Setup, rect: Rect) {
    let basis = setup.camera.basis(setup.handedness, 1, 1);
    let origin = Pos2::new(rect.min.x + 40.0, rect.max.y - 40.0);
    let painter = ui.painter_at(rect);
    for (axis, colour, name) in [
        (Vec3::X, Color32::from_rgb(230, 60, 60), "X"),
        (Vec3::Y, Color32::from_rgb(60, 200, 60), "Y"),
        (Vec3::Z, Color32::from_rgb(80, 120, 255), "Z"),
    ] {
        let d = Vec2::new(axis.dot(basis.right), -axis.dot(basis.up)) * 28.0;
        painter.line_segment([origin, origin + d], Stroke::new(2.0, colour));
        painter.text(
            origin + d * 1.25,
            Align2::CENTER_CENTER,
            name,
            FontId::proportional(12.0),
            colour,
        );
    }
    // Daylight: where the sun is, in yellow (dashed below the horizon).
    if let Some(d) = &setup.daylight {
        let sun = d.sun_direction(setup.handedness == tracer_core::scene::Handedness::Right);
        let v = Vec2::new(sun.dot(basis.right), -sun.dot(basis.up)) * 28.0;
        let colour = Color32::from_rgb(255, 210, 60);
        if d.sun().altitude_deg > 0.0 {
            painter.line_segment([origin, origin + v], Stroke::new(2.0, colour));
        } else {
            painter.add(egui::Shape::dashed_line(
                &[origin, origin + v],
                Stroke::new(1.5, colour),
                3.0,
                3.0,
            ));
        }
        painter.circle_filled(origin + v * 1.25, 4.0, colour);
        painter.text(
            origin + v * 1.25 + Vec2::new(8.0, -8.0),
            Align2::LEFT_CENTER,
            "sun",
            FontId::proportional(11.0),
            colour,
        );
    }
}

/// The legend's rows, top to bottom: above the range (white), the palette's values, and below
/// the range (black), which on a log scale includes 0.
pub fn legend_rows(fc: &tracer_core::display::FalseColour) -> Vec<(String, [u8; 4])> {
    let legend = fc.legend(8);
    let mut rows = vec![(
        format!("> {}", format_value(fc.max)),
        fc.colour(f32::INFINITY),
    )];
    rows.extend(
        legend
            .entries
            .iter()
            .rev()
            .map(|e| (format_value(e.value), e.rgba)),
    );
    let below = match fc.scale {
        tracer_core::display::FalseColourScale::Log => format!("< {}, 0", format_value(fc.min)),
        tracer_core::display::FalseColourScale::Linear => {
            format!("< {}", format_value(fc.min))
        }
    };
    rows.push((below, fc.colour(f32::NEG_INFINITY)));
    rows
}

/// The false-colour legend in the top-right corner.
pub fn draw_legend(ui: &egui::Ui, fc: &tracer_core::display::FalseColour, rect: Rect) {
    let rows = legend_rows(fc);
    let unit = fc.quantity.unit();
    let painter = ui.painter_at(rect);
    let (w, row) = (22.0, 18.0);
    let top = rect.min.y + 12.0;
    let x = rect.max.x - 130.0;
    painter.rect_filled(
        Rect::from_min_size(
            Pos2::new(x - 8.0, top - 8.0),
            Vec2::new(130.0, row * rows.len() as f32 + 30.0),
        ),
        4.0,
        Color32::from_black_alpha(170),
    );
    for (k, (label, [r, g, b, _])) in rows.iter().enumerate() {
        let y = top + k as f32 * row;
        let swatch = Rect::from_min_size(Pos2::new(x, y), Vec2::new(w, row - 2.0));
        painter.rect_filled(swatch, 0.0, Color32::from_rgb(*r, *g, *b));
        // Black and white swatches get an outline so they read against the backdrop.
        painter.rect_stroke(
            swatch,
            0.0,
            Stroke::new(1.0, Color32::from_gray(140)),
            egui::StrokeKind::Inside,
        );
        painter.text(
            Pos2::new(x + w + 6.0, y + row * 0.5),
            Align2::LEFT_CENTER,
            label,
            FontId::monospace(12.0),
            Color32::WHITE,
        );
    }
    painter.text(
        Pos2::new(x, top + row * rows.len() as f32 + 4.0),
        Align2::LEFT_TOP,
        unit,
        FontId::proportional(12.0),
        Color32::WHITE,
    );
}

/// Text over the picture: a load in progress, the picture hint, the error and notice banners
/// (their ✖ asks for them to be dismissed), and the read-out under the pointer.
pub fn draw_overlays(ui: &mut egui::Ui, v: &Overlays<'_>, rect: Rect, out: &mut Commands) {
    let painter = ui.painter_at(rect);
    let mut y = rect.min.y + 8.0;
    let mut line = |text: String, colour: Color32| {
        let galley = painter.layout(
            text,
            FontId::proportional(14.0),
            colour,
            rect.width() - 40.0,
        );
        let r = Rect::from_min_size(
            Pos2::new(rect.min.x + 8.0, y),
            galley.size() + Vec2::new(12.0, 8.0),
        );
        painter.rect_filled(r, 4.0, Color32::from_black_alpha(190));
        painter.galley(r.min + Vec2::new(6.0, 4.0), galley, colour);
        y = r.max.y + 6.0;
    };
    if let Some(l) = v.loading {
        line(
            format!(
                "Loading {} … {:.1} s",
                l.path.display(),
                l.started.elapsed().as_secs_f32()
            ),
            Color32::LIGHT_BLUE,
        );
    }
    if let Some(hint) = v.picture_hint {
        line(hint.to_owned(), Color32::from_rgb(255, 210, 90));
    }
    let top = Rect::from_min_max(
        Pos2::new(rect.min.x + 8.0, y),
        Pos2::new(rect.max.x - 8.0, rect.max.y),
    );
    let dismissed = ui
        .scope_builder(egui::UiBuilder::new().max_rect(top), |ui| {
            crate::banners::banners_ui(ui, v.error, v.notice)
        })
        .inner;
    match dismissed {
        Some(BannerKind::Error) => out.push(Command::DismissError),
        Some(BannerKind::Notice) => out.push(Command::DismissNotice),
        None => {}
    }
    if let Some(h) = v.hover {
        let lx = h
            .illuminance
            .map_or_else(|| "(measuring)".to_owned(), format_value);
        let text = format!(
            "{} cd/m²   {} lx   {}",
            format_value(h.luminance),
            lx,
            h.surface.as_deref().unwrap_or("(background)")
        );
        // On a dark plate, like the light labels: white text over a bright floor was lost.
        let galley = painter.layout_no_wrap(text, FontId::monospace(13.0), Color32::WHITE);
        let at = Pos2::new(rect.min.x + 8.0, rect.max.y - 90.0 - galley.size().y);
        text_on_plate(&painter, at, galley, Color32::WHITE);
    }
}

/// Laid-out text at `at` on a dark, rounded plate, so it reads over bright pixels.
fn text_on_plate(
    painter: &egui::Painter,
    at: Pos2,
    galley: std::sync::Arc<egui::Galley>,
    colour: Color32,
) {
    painter.rect_filled(
        Rect::from_min_size(
            at - Vec2::new(3.0, 1.0),
            galley.size() + Vec2::new(6.0, 2.0),
        ),
        3.0,
        Color32::from_black_alpha(200),
    );
    painter.galley(at, galley, colour);
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    /// In the built-in box, a floor point behind the tall block (seen from the camera) is hidden
    /// by it; the same point seen from straight above is not, nor is a point just over the open
    /// floor.
    #[test]
    fn grid_points_behind_objects_are_not_seen() {
        let loaded = tracer_core::scene::builtin_cornell_box(None).unwrap();
        let scene = &loaded.scene;
        let eye = Vec3::from(loaded.setup.camera.position);
        let floor = |x: f32, z: f32| Vec3::new(x, scene.bounds.min.y + 0.5, z);
        // The floor just behind the tall block (x 314..472, back face near z = -456), which
        // stands 330 mm high, taller than the eye at 273 mm.
        let behind: Vec<Vec3> = (0..10)
            .map(|k| floor(400.0, -470.0 - 8.0 * k as f32))
            .collect();
        let hidden: Vec<&Vec3> = behind
            .iter()
            .filter(|&&p| !seen_from(scene, &[], eye, p))
            .collect();
        assert!(
            hidden.len() >= 5,
            "only {} of the points behind the block are hidden",
            hidden.len()
        );
        for p in hidden {
            assert!(
                seen_from(scene, &[], *p + Vec3::Y * 540.0, *p),
                "{p} from above"
            );
        }
        assert!(seen_from(scene, &[], eye, floor(450.0, -100.0)));
    }
}
