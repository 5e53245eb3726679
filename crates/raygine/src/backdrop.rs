//! The viewport's backdrop: where the camera ray hit nothing, the viewer draws a dark slate
//! gradient instead of black, so the background is told apart from unlit surfaces (0 cd/m²,
//! black). Display only: the film keeps 0 cd/m² there, and exports and the CLI are unchanged.

use egui::{Color32, ColorImage};
use tracer_core::display::DisplayMapper;
use tracer_core::render::{ProgressiveFilm, Tile};

/// The backdrop's colour at the top and at the bottom of the picture (sRGB).
pub const TOP: [u8; 3] = [58, 64, 78];
pub const BOTTOM: [u8; 3] = [28, 31, 38];

/// The backdrop's colour in row `y` of a picture `height` rows tall.
pub fn colour_at(y: u32, height: u32) -> Color32 {
    let t = y as f32 / height.saturating_sub(1).max(1) as f32;
    let [r, g, b] = lerp(TOP, BOTTOM, t);
    Color32::from_rgb(r, g, b)
}

fn lerp(a: [u8; 3], b: [u8; 3], t: f32) -> [u8; 3] {
    let t = t.clamp(0.0, 1.0);
    std::array::from_fn(|c| {
        (f32::from(a[c]) + (f32::from(b[c]) - f32::from(a[c])) * t).round() as u8
    })
}

/// Draws the backdrop into `image`, the display mapping (by `mapper`) of `rect` of `film` (all
/// of it for `None`): pixels that saw only background become the backdrop; a pixel that saw some
/// of it (an edge) blends the backdrop with its surface, mapped at the surface's own mean.
pub fn draw(
    image: &mut ColorImage,
    film: &ProgressiveFilm,
    mapper: &DisplayMapper,
    rect: Option<Tile>,
) {
    let rect = rect.unwrap_or(Tile {
        x0: 0,
        y0: 0,
        x1: film.width(),
        y1: film.height(),
    });
    for ((x, y), out) in rect.pixels().zip(image.pixels.iter_mut()) {
        let i = film.accum.index(x, y);
        let background = film.background_fraction(i);
        if background <= 0.0 {
            continue;
        }
        let backdrop = colour_at(y, film.height());
        if background >= 1.0 {
            *out = backdrop;
            continue;
        }
        // The film's mean counts the background's samples as 0 cd/m²; the surface's own mean
        // is that over the share of samples that hit it.
        let hit = 1.0 - background;
        let [r, g, b, _] = mapper.map(film.shown_rgb(i) / hit, film.shown_illuminance(i) / hit);
        let [br, bg, bb, _] = backdrop.to_array();
        let [r, g, b] = lerp([r, g, b], [br, bg, bb], background);
        *out = Color32::from_rgb(r, g, b);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gradient_runs_from_top_to_bottom_and_is_never_black() {
        let rgb = |[r, g, b]: [u8; 3]| Color32::from_rgb(r, g, b);
        assert_eq!(colour_at(0, 100), rgb(TOP));
        assert_eq!(colour_at(99, 100), rgb(BOTTOM));
        assert_eq!(colour_at(0, 1), rgb(TOP));
        for y in 0..100 {
            let [r, g, b, _] = colour_at(y, 100).to_array();
            assert!(r.min(g).min(b) >= 28, "row {y} is too close to black");
        }
    }
}
