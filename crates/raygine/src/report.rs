//! The measurement report: the viewport as shown (picture, grid cells, isolux lines, the grids'
//! statistics and colour legend) saved as one PNG, with the readings as CSV beside it.
//!
//! The picture comes from the window's own pixels (egui's screenshot), so the report is exactly
//! what the user sees; it arrives a frame later, on the integration's callback.

use egui::{ColorImage, Rect};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// What became of a report: `Ok(message)` or `Err(reason)`, once the screenshot arrived.
pub type ReportStatus = Arc<Mutex<Option<Result<String, String>>>>;

/// The part of `image` (pixels) under `rect` (points, `pixels_per_point` pixels each), clipped
/// to the image; RGBA8, row-major, with its size.
pub fn crop(image: &ColorImage, rect: Rect, pixels_per_point: f32) -> (Vec<u8>, u32, u32) {
    let [w, h] = image.size;
    let clip = |v: f32, max: usize| ((v * pixels_per_point).round().max(0.0) as usize).min(max);
    let (x0, y0) = (clip(rect.min.x, w), clip(rect.min.y, h));
    let (x1, y1) = (clip(rect.max.x, w), clip(rect.max.y, h));
    let (cw, ch) = (x1.saturating_sub(x0), y1.saturating_sub(y0));
    let mut rgba = Vec::with_capacity(cw * ch * 4);
    for y in y0..y0 + ch {
        for x in x0..x0 + cw {
            rgba.extend_from_slice(&image.pixels[y * w + x].to_array());
        }
    }
    (rgba, cw as u32, ch as u32)
}

/// Writes the CSV now and asks for a screenshot; the PNG of `viewport` is written when it
/// arrives. Poll the returned status.
pub fn save(
    ctx: &egui::Context,
    viewport: Rect,
    png: PathBuf,
    csv_path: PathBuf,
    csv_text: &str,
) -> ReportStatus {
    let status: ReportStatus = Arc::new(Mutex::new(None));
    if let Err(e) = tracer_core::export::write_text(&csv_path, csv_text) {
        if let Ok(mut s) = status.lock() {
            *s = Some(Err(format!("{}: {e}", csv_path.display())));
        }
        return status;
    }
    let ppp = ctx.pixels_per_point();
    let done = Arc::clone(&status);
    let repaint = ctx.clone();
    ctx.request_screenshot(move |image| {
        let (rgba, w, h) = crop(&image, viewport, ppp);
        let result = if w == 0 || h == 0 {
            Err("the viewport is empty: nothing to save".to_owned())
        } else {
            tracer_core::export::write_png(&png, rgba, w, h)
                .map(|()| format!("wrote {} and {}", png.display(), csv_path.display()))
                .map_err(|e| format!("{}: {e}", png.display()))
        };
        if let Ok(mut s) = done.lock() {
            *s = Some(result);
        }
        repaint.request_repaint();
    });
    status
}

#[cfg(test)]
mod tests {
    use super::*;
    use egui::{Color32, Pos2};

    #[test]
    fn crop_takes_the_viewport_pixels_at_the_scale() {
        let mut image = ColorImage::new([8, 4], vec![Color32::BLACK; 32]);
        image.pixels[8 + 4] = Color32::RED; // (4, 1)
        // Points (2, 0)..(4, 2) at 2 pixels a point: pixels (4, 0)..(8, 4).
        let (rgba, w, h) = crop(
            &image,
            Rect::from_min_max(Pos2::new(2.0, 0.0), Pos2::new(4.0, 2.0)),
            2.0,
        );
        assert_eq!((w, h), (4, 4));
        assert_eq!(&rgba[(4) * 4..(4) * 4 + 4], &[255, 0, 0, 255]);
        let (_, w, h) = crop(
            &image,
            Rect::from_min_max(Pos2::new(3.0, 1.0), Pos2::new(40.0, 40.0)),
            2.0,
        );
        assert_eq!((w, h), (2, 2));
    }
}
