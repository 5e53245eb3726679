//! The sun in the glare image. Its disc is half a degree across: a pixel or a few of an 800²
//! fisheye, 10⁸–10⁹ cd/m² behind them. A handful of samples in those pixels decide Ev, UGR
//! and DGP, so at a few samples a pixel they were wrong by tens of per cent (or missed the sun
//! altogether). The pixels the disc may fall in therefore get [`SUN_SAMPLES`] times the
//! samples of the rest: their own, more of the same estimator, so every pixel's mean stays
//! unbiased and the film's per-pixel errors (and the batches') stay true.

use crate::lit_scene::LitScene;
use crate::scene::CameraBasis;

/// How many times the samples of the rest the sun's pixels get.
pub const SUN_SAMPLES: u32 = 256;

/// Per pixel of `basis`'s image (row-major): whether the sun's disc may fall in it (its
/// centre within the disc's radius plus a pixel's diagonal of the sun's direction). All false
/// without a sun.
pub fn sun_pixels(lit: &LitScene<'_>, basis: &CameraBasis) -> Vec<bool> {
    let (w, h) = (basis.width, basis.height);
    let mut mask = vec![false; w as usize * h as usize];
    let Some(sun) = lit.environment.as_ref().and_then(|e| e.sun()) else {
        return mask;
    };
    let towards = sun.direction().as_dvec3().normalize();
    // The widest a pixel gets: the fisheye's angle over its side, at most 180° over the width.
    let pixel = std::f64::consts::PI / f64::from(w.min(h).max(1));
    let reach = sun.angular_radius() + 1.5 * pixel;
    let sin_reach = reach.min(std::f64::consts::FRAC_PI_2).sin();
    for y in 0..h {
        for x in 0..w {
            let Some(ray) = basis.ray(x as f32 + 0.5, y as f32 + 0.5) else {
                continue;
            };
            let d = ray.dir.as_dvec3().normalize();
            // Within `reach`: in front, and the sine of the angle no larger (accurate at such
            // small angles, where the cosine would not be).
            let near = d.dot(towards) > 0.0 && d.cross(towards).length() <= sin_reach;
            mask[(y * w + x) as usize] = near;
        }
    }
    mask
}
