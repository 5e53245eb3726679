//! The viewport: the live film, mouse camera control, hover read-outs, picking, light markers,
//! the axis triad and the false-colour legend.

use crate::app::{HoverInfo, RaygineApp};
use crate::camera_control::{dolly, orbit, pan};
use egui::{Align2, Color32, FontId, Pos2, Rect, Sense, Stroke, Vec2};
use glam::Vec3;
use tracer_core::scene::LightKind;
use tracer_core::scene::{CameraBasis, luminance};

pub fn viewport_ui(ui: &mut egui::Ui, app: &mut RaygineApp) {
    let rect = ui.available_rect_before_wrap();
    let ppp = ui.ctx().pixels_per_point();
    let scale = app.render.resolution_scale.clamp(0.25, 1.0);
    app.viewport_px = [
        ((rect.width() * ppp * scale).round() as u32).clamp(1, 8192),
        ((rect.height() * ppp * scale).round() as u32).clamp(1, 8192),
    ];
    app.viewport_rect = Some(rect);
    let response = ui.allocate_rect(rect, Sense::click_and_drag());
    // A name for screen readers and UI tests.
    response
        .widget_info(|| egui::WidgetInfo::labeled(egui::accesskit::Role::Image, true, "viewport"));
    let display = app.effective_display();
    app.picture_drawn = false;
    if let Some(texture) = app
        .worker
        .update_texture(ui.ctx(), &display, &app.doc.scene)
    {
        let uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));
        ui.painter().image(texture.id(), rect, uv, Color32::WHITE);
        app.picture_drawn = true;
    }
    handle_mouse(ui, app, &response, rect);
    let basis = app.worker.basis();
    if let Some(b) = &basis {
        draw_light_markers(ui, app, b, rect);
        if app.show_grids {
            draw_grid_readings(ui, app, b, rect);
        }
    }
    draw_meter(ui, app, rect);
    draw_axis_triad(ui, app, rect);
    if let Some(fc) = display.false_colour {
        draw_legend(ui, &fc, rect);
    }
    draw_overlays(ui, app, rect);
    // Keep repainting (about 30 frames a second) while the engine refines; idle once converged.
    if app.worker.busy() || app.worker.shown_generation() != app.worker.generation() {
        ui.ctx()
            .request_repaint_after(std::time::Duration::from_millis(33));
    }
}

/// Film pixel under a screen position.
fn film_pixel(app: &RaygineApp, rect: Rect, pos: Pos2) -> Option<(f32, f32)> {
    if !rect.contains(pos) {
        return None;
    }
    let settings = app.worker.current()?.settings;
    let (w, h) = (settings.width, settings.height);
    let fx = (pos.x - rect.min.x) / rect.width() * w as f32;
    let fy = (pos.y - rect.min.y) / rect.height() * h as f32;
    Some((fx, fy))
}

fn handle_mouse(ui: &egui::Ui, app: &mut RaygineApp, response: &egui::Response, rect: Rect) {
    let handedness = app.doc.setup.handedness;
    let camera = app.doc.setup.camera;
    let (shift, command, scroll) = ui.input(|i| {
        (
            i.modifiers.shift,
            i.modifiers.command,
            i.smooth_scroll_delta.y,
        )
    });
    let delta = response.drag_delta();
    // Ctrl+drag: the luminance meter's rectangle instead of orbiting.
    let metering = command && response.dragged_by(egui::PointerButton::Primary);
    if metering {
        meter_drag(app, response, rect);
    } else {
        app.meter_anchor = None;
    }
    if delta != Vec2::ZERO && !metering {
        let panning = response.dragged_by(egui::PointerButton::Middle)
            || (response.dragged_by(egui::PointerButton::Primary) && shift);
        let height_px = rect.height();
        app.doc.setup.camera = if panning {
            pan(&camera, handedness, delta.x, delta.y, height_px)
        } else if response.dragged_by(egui::PointerButton::Primary) {
            orbit(&camera, handedness, delta.x, delta.y)
        } else {
            camera
        };
    }
    if response.hovered() && scroll != 0.0 {
        app.doc.setup.camera = dolly(&app.doc.setup.camera, scroll * 0.002);
    }
    app.hover = response
        .hover_pos()
        .and_then(|pos| film_pixel(app, rect, pos))
        .and_then(|(fx, fy)| hover_info(app, fx, fy));
    if response.clicked()
        && let Some(pos) = response.interact_pointer_pos()
        && let Some((fx, fy)) = film_pixel(app, rect, pos)
    {
        app.selected_slot = pick_slot(app, fx, fy);
    }
}

/// Updates the meter's rectangle while Ctrl+dragging.
fn meter_drag(app: &mut RaygineApp, response: &egui::Response, rect: Rect) {
    let Some(pos) = response.interact_pointer_pos() else {
        return;
    };
    let Some(here) = film_pixel(app, rect, pos) else {
        return;
    };
    let Some(settings) = app.worker.current().map(|k| k.settings) else {
        return;
    };
    let anchor = match app.meter_anchor {
        Some(a) => a,
        None => {
            let start = pos - response.drag_delta();
            let a = film_pixel(app, rect, start).unwrap_or(here);
            app.meter_anchor = Some(a);
            a
        }
    };
    app.meter = Some(crate::luminance_meter::Meter::from_corners(
        anchor,
        here,
        settings.width,
        settings.height,
    ));
}

/// The meter's rectangle and reading over the picture.
fn draw_meter(ui: &egui::Ui, app: &RaygineApp, rect: Rect) {
    let Some(m) = app.meter else {
        return;
    };
    let Some(settings) = app.worker.current().map(|k| k.settings) else {
        return;
    };
    let (w, h) = (settings.width as f32, settings.height as f32);
    let to_screen = |x: u32, y: u32| {
        Pos2::new(
            rect.min.x + x as f32 / w * rect.width(),
            rect.min.y + y as f32 / h * rect.height(),
        )
    };
    let screen = Rect::from_min_max(to_screen(m.x0, m.y0), to_screen(m.x1, m.y1));
    let reading = app.worker.with_film(|f| f.and_then(|f| m.read(f)));
    crate::luminance_meter::draw(&ui.painter_at(rect), screen, reading);
}

/// The material slot of the surface seen at film position (`fx`, `fy`).
pub fn pick_slot(app: &RaygineApp, fx: f32, fy: f32) -> Option<u32> {
    let key = app.worker.current()?;
    let basis = key.setup.camera.basis(
        key.setup.handedness,
        key.settings.width,
        key.settings.height,
    );
    key.scene.pick_slot(&basis.ray(fx, fy), &key.setup.hidden)
}

fn hover_info(app: &RaygineApp, fx: f32, fy: f32) -> Option<HoverInfo> {
    let (x, y) = (fx as u32, fy as u32);
    let (lum, lx) = app.worker.with_film(|f| {
        let f = f?;
        if x >= f.width() || y >= f.height() {
            return None;
        }
        let i = f.accum.index(x, y);
        Some((luminance(f.shown_rgb(i)), f.shown_illuminance(i)))
    })?;
    let surface = pick_slot(app, fx, fy).map(|s| app.doc.scene.slot_label(s));
    Some(HoverInfo {
        luminance: lum,
        illuminance: lx,
        surface,
        pixel: [x, y],
    })
}

fn to_screen(rect: Rect, basis: &CameraBasis, p: Vec3) -> Option<Pos2> {
    let (x, y) = basis.project(p)?;
    Some(Pos2::new(
        rect.min.x + x / basis.width as f32 * rect.width(),
        rect.min.y + y / basis.height as f32 * rect.height(),
    ))
}

fn draw_light_markers(ui: &egui::Ui, app: &RaygineApp, basis: &CameraBasis, rect: Rect) {
    let painter = ui.painter_at(rect);
    for (i, light) in app.doc.setup.lights.iter().enumerate() {
        if let Some(pos) = to_screen(rect, basis, light.position()) {
            let c = light.color.map(|v| (v.clamp(0.0, 1.0) * 255.0) as u8);
            painter.circle(
                pos,
                6.0,
                Color32::from_rgb(c[0], c[1], c[2]),
                Stroke::new(2.0, Color32::BLACK),
            );
            let label = match light.kind {
                LightKind::Luminaire => format!("L{} {:.0} lm", i + 1, light.flux_lm()),
                _ => format!("L{} {:.0} cd", i + 1, light.intensity_cd),
            };
            // On a dark plate, so the label reads over bright pixels.
            let galley = painter.layout_no_wrap(label, FontId::proportional(12.0), Color32::YELLOW);
            let at = pos + Vec2::new(9.0, -9.0 - galley.size().y);
            painter.rect_filled(
                Rect::from_min_size(
                    at - Vec2::new(3.0, 1.0),
                    galley.size() + Vec2::new(6.0, 2.0),
                ),
                3.0,
                Color32::from_black_alpha(200),
            );
            painter.galley(at, galley, Color32::YELLOW);
            // Spots and luminaires: their aim, a tenth of the scene's size long.
            if light.kind != LightKind::Point {
                let reach = app.doc.scene.bounds.radius() * 0.2;
                let tip = light.position() + Vec3::from(light.aim).normalize_or_zero() * reach;
                if let Some(end) = to_screen(rect, basis, tip) {
                    painter.arrow(pos, end - pos, Stroke::new(2.0, Color32::YELLOW));
                }
            }
        }
    }
}

/// The grids' readings over the picture: false-colour cells, values and isolux lines.
fn draw_grid_readings(ui: &egui::Ui, app: &RaygineApp, basis: &CameraBasis, rect: Rect) {
    let Some(readings) = app.measure.readings() else {
        return;
    };
    let painter = ui.painter_at(rect);
    let project = |p: Vec3| to_screen(rect, basis, p);
    for r in &readings.results {
        if let Some(grid) = app.doc.setup.grids.iter().find(|g| g.name == r.name) {
            crate::grid_overlay::draw(&painter, grid, r, &project);
        }
    }
    crate::grid_overlay::draw_statistics(&painter, rect, &readings.results, readings.samples);
}

/// X (red), Y (green), Z (blue) in the bottom-left corner, drawn with the camera's basis so the
/// triad agrees with the picture (mirrored for left-handed scenes).
fn draw_axis_triad(ui: &egui::Ui, app: &RaygineApp, rect: Rect) {
    let basis = app.doc.setup.camera.basis(app.doc.setup.handedness, 1, 1);
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

fn draw_legend(ui: &egui::Ui, fc: &tracer_core::display::FalseColour, rect: Rect) {
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

/// A value with 3 significant digits.
pub fn format_value(v: f32) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let digits = (2 - v.abs().log10().floor() as i32).max(0) as usize;
    format!("{v:.digits$}")
}

fn draw_overlays(ui: &mut egui::Ui, app: &mut RaygineApp, rect: Rect) {
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
    if let Some(l) = &app.loading {
        line(
            format!(
                "Loading {} … {:.1} s",
                l.path.display(),
                l.started.elapsed().as_secs_f32()
            ),
            Color32::LIGHT_BLUE,
        );
    }
    if let Some(hint) = &app.picture_hint {
        line(hint.clone(), Color32::from_rgb(255, 210, 90));
    }
    let top = Rect::from_min_max(
        Pos2::new(rect.min.x + 8.0, y),
        Pos2::new(rect.max.x - 8.0, rect.max.y),
    );
    let dismissed = ui
        .scope_builder(egui::UiBuilder::new().max_rect(top), |ui| {
            crate::banners::banners_ui(ui, app.error.as_deref(), app.notice.as_deref())
        })
        .inner;
    match dismissed {
        Some(crate::banners::BannerKind::Error) => app.error = None,
        Some(crate::banners::BannerKind::Notice) => app.notice = None,
        None => {}
    }
    if let Some(h) = &app.hover {
        let text = format!(
            "{} cd/m²   {} lx   {}",
            format_value(h.luminance),
            format_value(h.illuminance),
            h.surface.as_deref().unwrap_or("(background)")
        );
        // On a dark plate, like the light labels: white text over a bright floor was lost.
        let galley = painter.layout_no_wrap(text, FontId::monospace(13.0), Color32::WHITE);
        let at = Pos2::new(rect.min.x + 8.0, rect.max.y - 90.0 - galley.size().y);
        painter.rect_filled(
            Rect::from_min_size(
                at - Vec2::new(3.0, 1.0),
                galley.size() + Vec2::new(6.0, 2.0),
            ),
            3.0,
            Color32::from_black_alpha(200),
        );
        painter.galley(at, galley, Color32::WHITE);
    }
}
