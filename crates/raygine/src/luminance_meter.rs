//! The luminance meter: Ctrl+drag a rectangle over the picture to read its mean luminance
//! (cd/m²) ± the standard error, from the film's exact sums, as the picture refines.

use egui::{Color32, FontId, Pos2, Rect, Stroke};
use tracer_core::render::ProgressiveFilm;

/// A rectangle on the film (film pixels, half-open) and its reading.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Meter {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

/// What the meter reads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeterReading {
    /// Mean of the pixels' mean luminance, cd/m².
    pub mean_cd_m2: f64,
    /// Standard error of that mean (pixels independent), cd/m²; None before two samples.
    pub std_error_cd_m2: Option<f64>,
    pub pixels: usize,
}

impl Meter {
    /// The rectangle spanned by two film positions, clipped to a `width` x `height` film.
    pub fn from_corners(a: (f32, f32), b: (f32, f32), width: u32, height: u32) -> Meter {
        let clip = |v: f32, max: u32| (v.max(0.0) as u32).min(max);
        Meter {
            x0: clip(a.0.min(b.0), width),
            y0: clip(a.1.min(b.1), height),
            x1: clip(a.0.max(b.0).ceil(), width),
            y1: clip(a.1.max(b.1).ceil(), height),
        }
    }

    /// The reading over the film's accumulated samples (None for an empty rectangle or a film of
    /// another size), leaving out pixels for which `outside` says the camera sees nothing (a
    /// fisheye's corners); None when no pixel is left.
    pub fn read(
        &self,
        film: &ProgressiveFilm,
        outside: impl Fn(u32, u32) -> bool,
    ) -> Option<MeterReading> {
        if self.x1 > film.width()
            || self.y1 > film.height()
            || self.x0 >= self.x1
            || self.y0 >= self.y1
        {
            return None;
        }
        let (mut sum, mut var, mut n, mut all_se) = (0.0f64, 0.0f64, 0usize, true);
        for y in self.y0..self.y1 {
            for x in self.x0..self.x1 {
                if outside(x, y) {
                    continue;
                }
                // Film-level: under adaptive sampling the splats go over the film's light
                // subpaths, not the pixel's own count.
                let i = film.accum.index(x, y);
                sum += film.accum.mean_luminance(i);
                match film.accum.luminance_std_error(i) {
                    Some(se) => var += se * se,
                    None => all_se = false,
                }
                n += 1;
            }
        }
        if n == 0 {
            return None;
        }
        let nf = n as f64;
        Some(MeterReading {
            mean_cd_m2: sum / nf,
            std_error_cd_m2: all_se.then(|| var.sqrt() / nf),
            pixels: n,
        })
    }
}

/// Draws the meter's rectangle (screen `rect` of the film) and its reading beside it.
pub fn draw(painter: &egui::Painter, screen: Rect, reading: Option<MeterReading>) {
    painter.rect_stroke(
        screen,
        0.0,
        Stroke::new(1.5, Color32::from_rgb(255, 220, 0)),
        egui::StrokeKind::Middle,
    );
    let text = match reading {
        Some(MeterReading {
            mean_cd_m2,
            std_error_cd_m2: Some(se),
            pixels,
        }) => format!("{mean_cd_m2:.2} ± {se:.2} cd/m² ({pixels} px)"),
        Some(r) => format!("{:.2} cd/m² ({} px)", r.mean_cd_m2, r.pixels),
        None => "…".into(),
    };
    // On a dark plate: the picture under it may be white.
    let galley = painter.layout_no_wrap(
        text,
        FontId::monospace(13.0),
        Color32::from_rgb(255, 220, 0),
    );
    let at = Pos2::new(screen.min.x, screen.max.y + 4.0);
    let plate = Rect::from_min_size(at, galley.size() + egui::Vec2::new(8.0, 4.0));
    painter.rect_filled(plate, 3.0, Color32::from_black_alpha(200));
    painter.galley(
        at + egui::Vec2::new(4.0, 2.0),
        galley,
        Color32::from_rgb(255, 220, 0),
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corners_in_any_order_give_the_same_clipped_rectangle() {
        let a = Meter::from_corners((10.4, 5.0), (2.0, 20.5), 16, 16);
        let b = Meter::from_corners((2.0, 20.5), (10.4, 5.0), 16, 16);
        assert_eq!(a, b);
        assert_eq!((a.x0, a.y0, a.x1, a.y1), (2, 5, 11, 16));
    }
}
