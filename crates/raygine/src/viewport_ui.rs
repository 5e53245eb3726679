//! The viewport: the live film, mouse camera control, hover read-outs, picking and the luminance
//! meter. What is drawn over the picture is in [`crate::viewport_draw`].

use crate::camera_control::{dolly, orbit_about, pan};
use crate::command::{Command, Commands};
use crate::document::Document;
use crate::file_ops::PendingLoad;
use crate::luminance_meter::Meter;
use crate::measure_worker::MeasureWorker;
use crate::render_worker::RenderWorker;
use crate::viewport_draw::{
    Overlays, draw_axis_triad, draw_grid_readings, draw_legend, draw_light_markers, draw_overlays,
};
use egui::{Color32, Pos2, Rect, Sense, Vec2};
use tracer_core::display::DisplaySettings;
use tracer_core::scene::luminance;

pub use crate::viewport_draw::{HoverInfo, legend_rows};

/// What the viewport draws and edits. The camera is edited in place (orbit, pan, dolly); the
/// rest of the document is read. The `&mut` fields from `viewport_px` on are the viewport's own
/// state, which the app keeps from frame to frame.
#[derive(Debug)]
pub struct Viewport<'a> {
    pub worker: &'a mut RenderWorker,
    pub doc: &'a mut Document,
    pub measure: &'a MeasureWorker,
    pub glare: &'a crate::glare_worker::GlareWorker,
    /// The display mapping in force (false colour included).
    pub display: DisplaySettings,
    /// Film pixels per screen pixel (0.25 ..= 1).
    pub resolution_scale: f32,
    pub show_grids: bool,
    /// The light the Lights panel has selected (labelled alone when there are many).
    pub selected_light: usize,
    pub loading: Option<&'a PendingLoad>,
    /// Why the picture is black, when it is.
    pub picture_hint: Option<&'a str>,
    pub error: Option<&'a str>,
    pub notice: Option<&'a str>,
    /// Film size of the viewport, pixels.
    pub viewport_px: &'a mut [u32; 2],
    /// The viewport's screen rectangle (points), for reports.
    pub viewport_rect: &'a mut Option<Rect>,
    /// Whether this frame drew a picture.
    pub picture_drawn: &'a mut bool,
    pub hover: &'a mut Option<HoverInfo>,
    /// The luminance meter's rectangle (Ctrl+drag over the picture), film pixels.
    pub meter: &'a mut Option<Meter>,
    /// Where the current Ctrl+drag started (film position).
    pub meter_anchor: &'a mut Option<(f32, f32)>,
    /// What the current orbit turns about: the surface point under the cursor where the drag
    /// started, else the look-at point.
    pub orbit_pivot: &'a mut Option<glam::Vec3>,
}

/// The viewport; a click selects the surface under the pointer, a banner's ✖ dismisses it.
pub fn viewport_ui(ui: &mut egui::Ui, mut v: Viewport<'_>, out: &mut Commands) {
    let rect = ui.available_rect_before_wrap();
    let ppp = ui.ctx().pixels_per_point();
    let scale = v.resolution_scale.clamp(0.25, 1.0);
    *v.viewport_px = [
        ((rect.width() * ppp * scale).round() as u32).clamp(1, 8192),
        ((rect.height() * ppp * scale).round() as u32).clamp(1, 8192),
    ];
    *v.viewport_rect = Some(rect);
    let response = ui.allocate_rect(rect, Sense::click_and_drag());
    // A name for screen readers and UI tests.
    response
        .widget_info(|| egui::WidgetInfo::labeled(egui::accesskit::Role::Image, true, "viewport"));
    let display = v.display;
    *v.picture_drawn = false;
    if let Some(texture) = v.worker.update_texture(ui.ctx(), &display, &v.doc.scene) {
        let uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));
        ui.painter().image(texture.id(), rect, uv, Color32::WHITE);
        *v.picture_drawn = true;
    }
    handle_mouse(ui, &mut v, &response, rect, out);
    let basis = v.worker.basis();
    if let Some(b) = &basis {
        crate::viewport_draw::draw_image_circle(ui, b, rect);
        let size = v.doc.scene.bounds.extent().length();
        crate::viewport_draw::draw_observers(ui, &v.doc.setup.observers, b, rect, size);
        draw_light_markers(ui, v.doc, b, rect, v.selected_light);
        if let Some(readings) = v.glare.readings() {
            crate::viewport_draw::draw_glare_sources(ui, &v.doc.setup, &readings, b, rect);
        }
        if let Some(pivot) = *v.orbit_pivot {
            crate::viewport_draw::draw_pivot(ui, b, rect, pivot);
        }
        if v.show_grids
            && let Some(readings) = v.measure.readings()
        {
            draw_grid_readings(ui, v.doc, &readings, b, rect);
        }
    }
    draw_meter(ui, &v, rect);
    draw_axis_triad(ui, &v.doc.setup, rect);
    if let Some(fc) = display.false_colour {
        draw_legend(ui, &fc, rect);
    }
    let overlays = Overlays {
        loading: v.loading,
        picture_hint: v.picture_hint,
        error: v.error,
        notice: v.notice,
        hover: v.hover.as_ref(),
    };
    draw_overlays(ui, &overlays, rect, out);
    // Keep repainting (about 30 frames a second) while the engine refines; idle once converged.
    if v.worker.busy() || v.worker.shown_generation() != v.worker.generation() {
        ui.ctx()
            .request_repaint_after(std::time::Duration::from_millis(33));
    }
}

/// Film pixel under a screen position.
fn film_pixel(worker: &RenderWorker, rect: Rect, pos: Pos2) -> Option<(f32, f32)> {
    if !rect.contains(pos) {
        return None;
    }
    let settings = worker.current()?.settings;
    let (w, h) = (settings.width, settings.height);
    let fx = (pos.x - rect.min.x) / rect.width() * w as f32;
    let fy = (pos.y - rect.min.y) / rect.height() * h as f32;
    Some((fx, fy))
}

fn handle_mouse(
    ui: &egui::Ui,
    v: &mut Viewport<'_>,
    response: &egui::Response,
    rect: Rect,
    out: &mut Commands,
) {
    let handedness = v.doc.setup.handedness;
    let camera = v.doc.setup.camera;
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
        meter_drag(v, response, rect);
    } else {
        *v.meter_anchor = None;
    }
    let panning = response.dragged_by(egui::PointerButton::Middle)
        || (response.dragged_by(egui::PointerButton::Primary) && shift);
    let orbiting = response.dragged_by(egui::PointerButton::Primary) && !shift && !metering;
    if !orbiting {
        *v.orbit_pivot = None;
    } else if v.orbit_pivot.is_none() {
        let origin = ui.input(|i| i.pointer.press_origin());
        *v.orbit_pivot = Some(
            origin
                .and_then(|pos| film_pixel(v.worker, rect, pos))
                .and_then(|(fx, fy)| surface_point(v.worker, fx, fy))
                .unwrap_or(glam::Vec3::from(camera.look_at)),
        );
    }
    if delta != Vec2::ZERO && !metering {
        let size_px = [rect.width(), rect.height()];
        v.doc.setup.camera = if panning {
            pan(&camera, handedness, delta.x, delta.y, size_px)
        } else if let Some(pivot) = *v.orbit_pivot {
            orbit_about(&camera, handedness, pivot, delta.x, delta.y)
        } else {
            camera
        };
    }
    if response.hovered() && scroll != 0.0 {
        let aspect = rect.width() / rect.height().max(1.0);
        v.doc.setup.camera = dolly(&v.doc.setup.camera, scroll * 0.002, aspect);
    }
    *v.hover = response
        .hover_pos()
        .and_then(|pos| film_pixel(v.worker, rect, pos))
        .and_then(|(fx, fy)| hover_info(v.worker, v.doc, fx, fy));
    if response.clicked()
        && let Some(pos) = response.interact_pointer_pos()
        && let Some((fx, fy)) = film_pixel(v.worker, rect, pos)
    {
        out.push(Command::Select(pick_slot(v.worker, fx, fy)));
    }
}

/// Updates the meter's rectangle while Ctrl+dragging.
fn meter_drag(v: &mut Viewport<'_>, response: &egui::Response, rect: Rect) {
    let Some(pos) = response.interact_pointer_pos() else {
        return;
    };
    let Some(here) = film_pixel(v.worker, rect, pos) else {
        return;
    };
    let Some(settings) = v.worker.current().map(|k| k.settings) else {
        return;
    };
    let anchor = match *v.meter_anchor {
        Some(a) => a,
        None => {
            let start = pos - response.drag_delta();
            let a = film_pixel(v.worker, rect, start).unwrap_or(here);
            *v.meter_anchor = Some(a);
            a
        }
    };
    *v.meter = Some(Meter::from_corners(
        anchor,
        here,
        settings.width,
        settings.height,
    ));
}

/// The meter's rectangle and reading over the picture.
fn draw_meter(ui: &egui::Ui, v: &Viewport<'_>, rect: Rect) {
    let Some(m) = *v.meter else {
        return;
    };
    let Some(settings) = v.worker.current().map(|k| k.settings) else {
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
    let basis = v.worker.basis();
    let outside = |x, y| basis.as_ref().is_some_and(|b| b.pixel_outside(x, y));
    let reading = v.worker.with_film(|f| f.and_then(|f| m.read(f, outside)));
    crate::luminance_meter::draw(&ui.painter_at(rect), screen, reading);
}

/// The point of the closest drawn surface seen at film position (`fx`, `fy`).
fn surface_point(worker: &RenderWorker, fx: f32, fy: f32) -> Option<glam::Vec3> {
    let key = worker.current()?;
    let basis = key.setup.camera.basis(
        key.setup.handedness,
        key.settings.width,
        key.settings.height,
    );
    let ray = basis.ray(fx, fy)?;
    let hit = key.scene.closest_drawn(&ray, &key.setup.hidden)?;
    Some(ray.origin + ray.dir * hit.t)
}

/// The material slot of the surface seen at film position (`fx`, `fy`).
pub fn pick_slot(worker: &RenderWorker, fx: f32, fy: f32) -> Option<u32> {
    let key = worker.current()?;
    let basis = key.setup.camera.basis(
        key.setup.handedness,
        key.settings.width,
        key.settings.height,
    );
    key.scene.pick_slot(&basis.ray(fx, fy)?, &key.setup.hidden)
}

fn hover_info(worker: &RenderWorker, doc: &Document, fx: f32, fy: f32) -> Option<HoverInfo> {
    let (x, y) = (fx as u32, fy as u32);
    // Outside a fisheye's image circle the camera sees nothing: no readout.
    if worker.basis().is_some_and(|b| b.pixel_outside(x, y)) {
        return None;
    }
    let (lum, lx) = worker.with_film(|f| {
        let f = f?;
        if x >= f.width() || y >= f.height() {
            return None;
        }
        let i = f.accum.index(x, y);
        let lx = f.illuminance_measured(i).then(|| f.shown_illuminance(i));
        Some((luminance(f.shown_rgb(i)), lx))
    })?;
    let surface = pick_slot(worker, fx, fy).map(|s| {
        let label = doc.scene.slot_label(s);
        match doc.setup.materials.get(s as usize) {
            Some(m) => format!("{label}: {}", crate::panels::materials::summary(m)),
            None => label,
        }
    });
    Some(HoverInfo {
        luminance: lum,
        illuminance: lx,
        surface,
        pixel: [x, y],
    })
}
