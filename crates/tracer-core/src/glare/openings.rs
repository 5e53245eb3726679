//! Luminaires' luminous openings as the eye sees them. Renders do not draw an opening (rays pass
//! through it; its light arrives by next-event estimation), but glare is about looking at it:
//! the glare image draws each opening in front of what the render shows behind it, with the
//! luminance the light model gives it, L(d) = I(d) / A_proj(d), uniform over the opening.

use super::image::GlareImage;
use crate::geometry::Ray;
use crate::light::{GoniometricLight, LuminousShape, PlacedLight};
use crate::lit_scene::LitScene;
use crate::scene::CameraBasis;
use glam::{DVec3, Vec3};

/// Sub-pixel positions per side where a pixel meets an opening's edge.
pub const SUBPIXELS: u32 = 4;

/// The luminance (cd/m²) `light`'s opening shows along unit `to_eye` (leaving the light), or
/// None when it shows none (a point, or seen edge-on).
pub fn opening_luminance(light: &GoniometricLight, to_eye: Vec3) -> Option<f64> {
    if light.shape == LuminousShape::Point {
        return None;
    }
    let local = light.frame.to_local(to_eye);
    let area_m2 =
        f64::from(light.shape.projected_area(local)) * f64::from(light.metres_per_unit_sq);
    if area_m2 <= 1e-12 {
        return None;
    }
    Some(f64::from(light.intensity_towards(to_eye)) / area_m2)
}

/// The distance along `ray` (unit direction) to `light`'s opening, if it crosses it.
pub fn hit_opening(light: &GoniometricLight, ray: &Ray) -> Option<f32> {
    let o = light.frame.to_local(ray.origin - light.position);
    let d = light.frame.to_local(ray.dir);
    hit_shape(&light.shape, o, d).filter(|&t| t > 1e-5)
}

/// The nearest t > 0 where o + t d meets `shape` (local coordinates, centred on the opening).
fn hit_shape(shape: &LuminousShape, o: Vec3, d: Vec3) -> Option<f32> {
    let flat = |inside: &dyn Fn(Vec3) -> bool| {
        if d.z.abs() < 1e-9 {
            return None;
        }
        let t = -o.z / d.z;
        (t > 0.0 && inside(o + d * t)).then_some(t)
    };
    match *shape {
        LuminousShape::Point => None,
        LuminousShape::Rectangle { length, width } => {
            flat(&|p| p.x.abs() <= 0.5 * length && p.y.abs() <= 0.5 * width)
        }
        LuminousShape::Disc { diameter } => {
            let r2 = 0.25 * diameter * diameter;
            flat(&|p| p.x * p.x + p.y * p.y <= r2)
        }
        LuminousShape::Box { .. } => {
            let h = shape.half_extent();
            let (mut t0, mut t1) = (0.0f32, f32::INFINITY);
            for a in 0..3 {
                if d[a].abs() < 1e-12 {
                    if o[a].abs() > h[a] {
                        return None;
                    }
                    continue;
                }
                let (ta, tb) = ((-h[a] - o[a]) / d[a], (h[a] - o[a]) / d[a]);
                t0 = t0.max(ta.min(tb));
                t1 = t1.min(ta.max(tb));
            }
            (t0 <= t1 && t0 > 0.0).then_some(t0)
        }
        LuminousShape::Cylinder { diameter, height } => {
            let (r, hz) = (0.5 * diameter, 0.5 * height);
            let mut best: Option<f32> = None;
            let mut keep = |t: f32| {
                if t > 0.0 && best.is_none_or(|b| t < b) {
                    best = Some(t);
                }
            };
            let a = d.x * d.x + d.y * d.y;
            if a > 1e-12 {
                let b = o.x * d.x + o.y * d.y;
                let c = o.x * o.x + o.y * o.y - r * r;
                let disc = b * b - a * c;
                if disc >= 0.0 {
                    for t in [(-b - disc.sqrt()) / a, (-b + disc.sqrt()) / a] {
                        if (o.z + t * d.z).abs() <= hz {
                            keep(t);
                        }
                    }
                }
            }
            if d.z.abs() > 1e-12 {
                for z in [-hz, hz] {
                    let t = (z - o.z) / d.z;
                    let p = o + d * t;
                    if p.x * p.x + p.y * p.y <= r * r {
                        keep(t);
                    }
                }
            }
            best
        }
    }
}

/// The luminaires of `lit` that have a luminous opening.
pub fn luminaires_with_openings<'a>(
    lit: &'a LitScene<'_>,
) -> impl Iterator<Item = (usize, &'a GoniometricLight)> {
    lit.lights.iter().enumerate().filter_map(|(i, l)| match l {
        PlacedLight::Goniometric(g) if g.shape != LuminousShape::Point => Some((i, g)),
        _ => None,
    })
}

/// Draws every luminous opening the eye sees into `image` (rendered through `basis` in
/// `lit`'s scene): in each pixel an opening covers, `SUBPIXELS`² rays find the share it covers
/// (in front of the first surface, times what panes let through), and the pixel becomes that
/// share of the opening's luminance plus the rest of the rendered one (whose standard error
/// shrinks with it). Returns the number of pixels changed.
pub fn draw_openings(image: &mut GlareImage, lit: &LitScene<'_>, basis: &CameraBasis) -> usize {
    let lights: Vec<(&GoniometricLight, DVec3, f64)> = luminaires_with_openings(lit)
        .filter_map(|(_, g)| {
            let to = (g.position - basis.origin).as_dvec3();
            let dist = to.length();
            let radius = f64::from(g.shape.half_extent().length());
            if dist <= radius {
                return None;
            }
            // The cone around the opening's centre that holds it, widened by two pixels.
            let half_angle =
                (radius / dist).asin() + 2.0 * std::f64::consts::PI / f64::from(basis.width);
            Some((g, to / dist, half_angle.cos()))
        })
        .collect();
    if lights.is_empty() {
        return 0;
    }
    let mut changed = 0;
    let n = SUBPIXELS;
    for y in 0..image.height {
        for x in 0..image.width {
            let i = (y * image.width + x) as usize;
            if image.solid_angle[i] <= 0.0 {
                continue;
            }
            let Some(centre) = basis.ray(x as f32 + 0.5, y as f32 + 0.5) else {
                continue;
            };
            let c = centre.dir.as_dvec3();
            let near: Vec<&GoniometricLight> = lights
                .iter()
                .filter(|(_, axis, cos)| c.dot(*axis) >= *cos)
                .map(|(g, _, _)| *g)
                .collect();
            if near.is_empty() {
                continue;
            }
            let (mut covered, mut glow) = (0.0f64, 0.0f64);
            for sy in 0..n {
                for sx in 0..n {
                    let fx = x as f32 + (sx as f32 + 0.5) / n as f32;
                    let fy = y as f32 + (sy as f32 + 0.5) / n as f32;
                    let Some(ray) = basis.ray(fx, fy) else {
                        continue;
                    };
                    let nearest = near
                        .iter()
                        .filter_map(|g| hit_opening(g, &ray).map(|t| (t, *g)))
                        .min_by(|a, b| a.0.total_cmp(&b.0));
                    let Some((t, g)) = nearest else { continue };
                    let through = lit.transmittance(ray.origin, ray.dir * t);
                    if through <= 0.0 {
                        continue;
                    }
                    covered += 1.0;
                    glow += f64::from(through) * opening_luminance(g, -ray.dir).unwrap_or(0.0);
                }
            }
            if covered > 0.0 {
                let k = f64::from(n * n);
                let rest = 1.0 - covered / k;
                image.luminance[i] = image.luminance[i] * rest + glow / k;
                image.opening[i] = glow / k;
                image.std_error[i] *= rest;
                changed += 1;
            }
        }
    }
    changed
}
