//! A grid's plan drawn from its own data: cells in false colour, isolux lines at round levels,
//! the value at each point where there is room, points inside objects crossed out, a scale bar
//! and the colour scale.

use super::canvas::{BLACK, Canvas, GREY, LIGHT, Rgb};
use tracer_core::display::{FalseColour, FalseColourQuantity, FalseColourScale};
use tracer_core::measure::isolux::{isolux_levels, isolux_segments};
use tracer_core::measure::rounding::format_reading;
use tracer_core::measure::{Grid, GridResult};

/// Draws the plan of `grid` (readings `r`) into the box at (`x`, `y`), at most `w` x `h`
/// points, keeping the grid's proportions; returns the height used.
pub fn draw(
    c: &mut Canvas<'_, '_>,
    grid: &Grid,
    r: &GridResult,
    unit: &str,
    at: (f32, f32),
    w: f32,
    h: f32,
) -> f32 {
    let (x, y) = at;
    let lu = glam::Vec3::from(grid.u).length().max(1e-9);
    let lv = glam::Vec3::from(grid.v).length().max(1e-9);
    let scale = (w / lu).min(h / lv);
    let (pw, ph) = (lu * scale, lv * scale);
    let (nu, nv) = (grid.nu as usize, grid.nv as usize);
    let (cw, ch) = (pw / nu as f32, ph / nv as f32);
    let s = r.statistics();
    let colours = FalseColour {
        quantity: FalseColourQuantity::Illuminance,
        scale: FalseColourScale::Linear,
        min: 0.0,
        max: (s.e_max_lx as f32).max(1e-6),
    };
    // j grows along v, drawn upwards (a plan seen from the normal's side, v up the page).
    let cell = |i: usize, j: usize| (x + i as f32 * cw, y + ph - (j + 1) as f32 * ch);
    for p in &r.points {
        let (cx, cy) = cell(p.i as usize, p.j as usize);
        if p.buried {
            c.rect(cx, cy, cw, ch, LIGHT);
            c.line((cx, cy), (cx + cw, cy + ch), 0.5, GREY);
            c.line((cx + cw, cy), (cx, cy + ch), 0.5, GREY);
            continue;
        }
        let [r8, g8, b8, _] = colours.colour(p.illuminance_lx as f32);
        c.rect(cx, cy, cw, ch, [r8, g8, b8]);
    }
    c.polygon(
        &[(x, y), (x + pw, y), (x + pw, y + ph), (x, y + ph)],
        0.6,
        BLACK,
    );
    // Isolux lines over the cell centres (points inside objects read as their neighbours do
    // not exist: they are left at their value, which is shown crossed out).
    let values: Vec<f64> = r.points.iter().map(|p| p.illuminance_lx).collect();
    // Round levels over the upper part of the range (a hard shadow's 0 lx would crowd the low
    // ones into its edge).
    let levels = isolux_levels(s.e_min_lx.max(s.e_max_lx / 20.0), s.e_max_lx);
    let to_page = |(i, j): (f64, f64)| (x + (i as f32 + 0.5) * cw, y + ph - (j as f32 + 0.5) * ch);
    for &level in &levels {
        for [a, b] in isolux_segments(&values, nu, nv, level) {
            c.line(to_page(a), to_page(b), 0.9, BLACK);
        }
    }
    // Values where a number fits in its cell.
    let size = (cw / 4.5).min(ch * 0.45).min(8.0);
    if size >= 4.0 {
        for p in r.points.iter().filter(|p| !p.buried) {
            let (cx, cy) = cell(p.i as usize, p.j as usize);
            let text = format_reading(p.illuminance_lx, p.std_error_lx);
            c.text_centre(
                cx + 0.5 * cw,
                cy + 0.5 * ch + 0.35 * size,
                size,
                BLACK,
                &text,
            );
        }
    }
    // Scale bar: a round length near a quarter of the plan's width.
    let mut y_next = y + ph + 14.0;
    let target = lu / 4.0;
    let decade = 10f32.powf(target.log10().floor());
    let bar = [1.0, 2.0, 5.0]
        .iter()
        .map(|m| m * decade)
        .filter(|v| *v <= target)
        .fold(decade, f32::max);
    let bar_pt = bar * scale;
    c.rect(x, y_next - 4.0, bar_pt, 3.0, BLACK);
    c.text(
        x + bar_pt + 5.0,
        y_next,
        8.0,
        BLACK,
        &format!("{} {unit}", trim(bar)),
    );
    let levels_text: Vec<String> = levels.iter().map(|l| trim(*l as f32)).collect();
    if !levels_text.is_empty() {
        c.text(
            x + bar_pt + 60.0,
            y_next,
            8.0,
            BLACK,
            &format!("isolux lines: {} lx", levels_text.join(", ")),
        );
    }
    // Colour scale.
    y_next += 10.0;
    let steps = 10;
    let sw = (w.min(300.0)) / steps as f32;
    for k in 0..steps {
        let v = colours.max * (k as f32 + 0.5) / steps as f32;
        let [r8, g8, b8, _] = colours.colour(v);
        let colour: Rgb = [r8, g8, b8];
        c.rect(x + k as f32 * sw, y_next, sw, 8.0, colour);
    }
    c.text(x, y_next + 18.0, 7.0, GREY, "0 lx");
    c.text_right(
        x + sw * steps as f32,
        y_next + 18.0,
        7.0,
        GREY,
        &format!("{} lx", format_reading(f64::from(colours.max), 0.0)),
    );
    y_next + 22.0 - y
}

/// A number as short as it reads (no float noise, no trailing zeros).
fn trim(v: f32) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s.is_empty() {
        "0".into()
    } else {
        s.to_owned()
    }
}
