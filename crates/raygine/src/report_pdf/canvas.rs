//! A thin drawing layer over krilla for the report: points (1/72 in) from the page's top-left
//! corner, one embedded font (DejaVu Sans, `assets/fonts`, Bitstream Vera licence), text, lines,
//! filled rectangles and raster images.

use krilla::color::rgb;
use krilla::geom::{PathBuilder, Point, Rect, Size, Transform};
use krilla::image::Image;
use krilla::num::NormalizedF32;
use krilla::paint::{Fill, Stroke};
use krilla::surface::Surface;
use krilla::text::{Font, TextDirection};

/// The report's typeface, embedded (subset) in every PDF.
pub const FONT_TTF: &[u8] = include_bytes!("../../../../assets/fonts/DejaVuSans.ttf");

/// Average advance of DejaVu Sans' digits and lower-case letters, in em: enough to right-align
/// numbers and to keep columns apart.
const ADVANCE_EM: f32 = 0.58;

/// The font, loaded once per document.
pub fn font() -> Result<Font, String> {
    Font::new(FONT_TTF.into(), 0).ok_or_else(|| "the embedded font cannot be read".to_owned())
}

/// An RGB colour.
pub type Rgb = [u8; 3];

pub const BLACK: Rgb = [0, 0, 0];
pub const GREY: Rgb = [110, 110, 110];
pub const LIGHT: Rgb = [200, 200, 200];
pub const RED: Rgb = [180, 20, 20];
pub const GREEN: Rgb = [20, 120, 40];

/// One page's drawing surface with the font.
pub struct Canvas<'s, 'p> {
    pub surface: &'s mut Surface<'p>,
    pub font: Font,
}

impl std::fmt::Debug for Canvas<'_, '_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Canvas")
    }
}

impl Canvas<'_, '_> {
    /// The width of `text` at `size` (an estimate: see [`ADVANCE_EM`]).
    pub fn width(text: &str, size: f32) -> f32 {
        text.chars().count() as f32 * size * ADVANCE_EM
    }

    /// `text` with its baseline's left end at (`x`, `y`).
    pub fn text(&mut self, x: f32, y: f32, size: f32, colour: Rgb, text: &str) {
        if text.is_empty() {
            return;
        }
        self.surface.set_stroke(None);
        self.surface.set_fill(Some(fill(colour)));
        self.surface.draw_text(
            Point::from_xy(x, y),
            self.font.clone(),
            size,
            text,
            false,
            TextDirection::Auto,
        );
    }

    /// `text` ending at `x` (right-aligned).
    pub fn text_right(&mut self, x: f32, y: f32, size: f32, colour: Rgb, text: &str) {
        self.text(x - Self::width(text, size), y, size, colour, text);
    }

    /// `text` centred on `x`.
    pub fn text_centre(&mut self, x: f32, y: f32, size: f32, colour: Rgb, text: &str) {
        self.text(x - 0.5 * Self::width(text, size), y, size, colour, text);
    }

    /// A straight line.
    pub fn line(&mut self, a: (f32, f32), b: (f32, f32), width: f32, colour: Rgb) {
        let mut p = PathBuilder::new();
        p.move_to(a.0, a.1);
        p.line_to(b.0, b.1);
        self.stroke_path(p, width, colour);
    }

    /// A closed polygon's outline.
    pub fn polygon(&mut self, points: &[(f32, f32)], width: f32, colour: Rgb) {
        if let Some(p) = polygon_path(points) {
            self.stroke_path(p, width, colour);
        }
    }

    /// A filled polygon.
    pub fn fill_polygon(&mut self, points: &[(f32, f32)], colour: Rgb) {
        if let Some(path) = polygon_path(points).and_then(PathBuilder::finish) {
            self.surface.set_stroke(None);
            self.surface.set_fill(Some(fill(colour)));
            self.surface.draw_path(&path);
        }
    }

    /// A filled rectangle.
    pub fn rect(&mut self, x: f32, y: f32, w: f32, h: f32, colour: Rgb) {
        let Some(r) = Rect::from_xywh(x, y, w.max(0.01), h.max(0.01)) else {
            return;
        };
        let mut p = PathBuilder::new();
        p.push_rect(r);
        if let Some(path) = p.finish() {
            self.surface.set_stroke(None);
            self.surface.set_fill(Some(fill(colour)));
            self.surface.draw_path(&path);
        }
    }

    /// An RGBA8 image of `pixels` (width x height) drawn into the box at (`x`, `y`), `w` x `h`.
    pub fn image(&mut self, rgba: Vec<u8>, pixels: (u32, u32), x: f32, y: f32, w: f32, h: f32) {
        let Some(size) = Size::from_wh(w, h) else {
            return;
        };
        let image = Image::from_rgba8(rgba, pixels.0, pixels.1);
        self.surface
            .push_transform(&Transform::from_translate(x, y));
        self.surface.draw_image(image, size);
        self.surface.pop();
    }

    fn stroke_path(&mut self, p: PathBuilder, width: f32, colour: Rgb) {
        if let Some(path) = p.finish() {
            self.surface.set_fill(None);
            self.surface.set_stroke(Some(Stroke {
                paint: rgb::Color::new(colour[0], colour[1], colour[2]).into(),
                width,
                ..Stroke::default()
            }));
            self.surface.draw_path(&path);
            self.surface.set_stroke(None);
        }
    }
}

/// The closed path through `points` (None for none).
fn polygon_path(points: &[(f32, f32)]) -> Option<PathBuilder> {
    let first = points.first()?;
    let mut p = PathBuilder::new();
    p.move_to(first.0, first.1);
    for q in &points[1..] {
        p.line_to(q.0, q.1);
    }
    p.close();
    Some(p)
}

fn fill(colour: Rgb) -> Fill {
    Fill {
        paint: rgb::Color::new(colour[0], colour[1], colour[2]).into(),
        opacity: NormalizedF32::ONE,
        rule: Default::default(),
    }
}
