//! Where new calculation grids go: over a surface the user picked, or as a work plane fitted to
//! the scene. The viewer's Measure panel asks for these; the geometry lives here, beside the
//! grids it makes.

use super::Grid;
use crate::scene::{GridContext, GridSpec, Scene, en12464_spacing_m};
use glam::Vec3;

/// The first of `stem1`, `stem2`, … not among `taken`.
pub fn free_name(stem: &str, taken: &[Grid]) -> String {
    (1..)
        .map(|k| format!("{stem}{k}"))
        .find(|name| taken.iter().all(|g| &g.name != name))
        .unwrap_or_else(|| stem.to_owned())
}

/// A grid over the plane of material slot `slot`'s largest triangle, covering the slot's
/// triangles in that plane, 0.1 % of the scene's size in front of it (on the side of `eye`),
/// with points at EN 12464-1 spacing for its size. Named after the slot.
pub fn grid_on_surface(
    scene: &Scene,
    slot: u32,
    eye: Vec3,
    metres_per_unit: f32,
    taken: &[Grid],
) -> Result<Grid, String> {
    let brep = scene
        .slots
        .get(slot as usize)
        .ok_or("the selected surface is not in the scene")?
        .brep as usize;
    let tris: Vec<u32> = scene
        .brep_triangles(brep)
        .map(|t| t as u32)
        .filter(|&t| scene.slot(t) == slot)
        .collect();
    let area = |t: u32| {
        let [a, b, c] = scene.triangle(t);
        (b - a).cross(c - a).length()
    };
    let largest = tris
        .iter()
        .copied()
        .max_by(|&a, &b| area(a).total_cmp(&area(b)))
        .ok_or("the selected surface has no triangles")?;
    let [a, b, c] = scene.triangle(largest);
    let mut n = (b - a)
        .cross(c - a)
        .try_normalize()
        .ok_or("the selected surface has no area")?;
    if n.dot(eye - a) < 0.0 {
        n = -n;
    }
    // The slot's triangles in this plane (parallel, and on it within 0.1 % of the scene).
    let tol = 1e-3 * scene.bounds.radius().max(1e-6);
    let mut points = Vec::new();
    for &t in &tris {
        let [p, q, r] = scene.triangle(t);
        let m = (q - p).cross(r - p).normalize_or_zero();
        if m.cross(n).length() < 0.02 && [p, q, r].iter().all(|v| (v - a).dot(n).abs() < tol) {
            points.extend([p, q, r]);
        }
    }
    let reference = if n.cross(Vec3::X).length() > 0.5 {
        Vec3::X
    } else {
        Vec3::Z
    };
    let e1 = (reference - n * n.dot(reference)).normalize();
    let e2 = n.cross(e1);
    let (mut lo, mut hi) = (
        glam::Vec2::splat(f32::INFINITY),
        glam::Vec2::splat(f32::NEG_INFINITY),
    );
    for p in &points {
        let q = glam::Vec2::new((p - a).dot(e1), (p - a).dot(e2));
        lo = lo.min(q);
        hi = hi.max(q);
    }
    let size = hi - lo;
    let origin = a + e1 * lo.x + e2 * lo.y + n * tol;
    // Grid names are A-Z, a-z, 0-9, _ and -: anything else in a slot's name becomes _.
    let label: String = scene
        .slot_label(slot)
        .chars()
        .map(|c| match c {
            '/' => '-',
            c if c.is_ascii_alphanumeric() || c == '_' || c == '-' => c,
            _ => '_',
        })
        .collect();
    let name = free_name(&label, taken);
    let p = en12464_spacing_m(size.max_element() * metres_per_unit) / metres_per_unit;
    let count = |l: f32| ((l / p).ceil() as u32).clamp(1, 1000);
    Grid::new(
        &name,
        origin.to_array(),
        (e1 * size.x).to_array(),
        (e2 * size.y).to_array(),
        count(size.x),
        count(size.y),
        Some(n.to_array()),
    )
    .map_err(|e| e.to_string())
}

/// A work plane: 0.75 m over the floor and 0.5 m in from the walls (EN 12464-1 practice). A
/// scene too small for that (a model box) gets one at a quarter of its height and a tenth of its
/// shorter side in, below a camera at mid-height, so it is seen as a plane, not edge-on; the
/// note says where it went.
pub fn work_plane(
    scene: &Scene,
    metres_per_unit: f32,
    unit_symbol: &str,
    taken: &[Grid],
) -> Result<(Grid, Option<String>), String> {
    let b = scene.bounds;
    let per_m = 1.0 / metres_per_unit;
    let (height, margin) = (0.75 * per_m, 0.5 * per_m);
    let small = height > 0.5 * b.extent().y || margin > 0.1 * b.extent().x.min(b.extent().z);
    let (h, m) = if small {
        (0.25 * b.extent().y, 0.1 * b.extent().x.min(b.extent().z))
    } else {
        (height, margin)
    };
    let note = small.then(|| {
        format!(
            "the scene is small for a 0.75 m work plane 0.5 m from the walls: placed {} \
             {unit_symbol} over the floor (a quarter of the height), {} {unit_symbol} from the \
             walls",
            three_digits(h),
            three_digits(m)
        )
    });
    let spec = GridSpec {
        name: free_name("workplane", taken),
        work_plane: Some(true),
        height: Some(h),
        margin: Some(m),
        ..GridSpec::default()
    };
    let context = GridContext {
        bounds: b,
        metres_per_unit,
    };
    match spec.to_grid(Some(context))? {
        Some(grid) => Ok((grid, note)),
        None => Err("the scene has no floor for a work plane".to_owned()),
    }
}

/// `v` with 3 significant digits ("137", "0.412").
fn three_digits(v: f32) -> String {
    let digits = (2 - v.abs().max(1e-9).log10().floor() as i32).max(0) as usize;
    format!("{v:.digits$}")
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    /// The built-in box (556 mm) is too small for a 0.75 m plane: it goes a quarter of the way
    /// up (137 mm over the floor at y = 0), below the camera's 273 mm, and the note says so.
    #[test]
    fn a_work_plane_in_a_model_box_sits_a_quarter_up() {
        let loaded = crate::scene::builtin_cornell_box(None).unwrap();
        let scene = &loaded.scene;
        let (g, note) = work_plane(scene, 0.001, "mm", &[]).unwrap();
        let y = g.origin[1];
        let extent = scene.bounds.extent().y;
        assert!((y - scene.bounds.min.y - 0.25 * extent).abs() < 1.0, "{y}");
        assert!(y < loaded.setup.camera.position[1] - 50.0);
        let note = note.unwrap();
        assert!(note.contains("placed 137 mm over the floor"), "{note}");
        assert_eq!(g.name, "workplane1");
        let (g2, _) = work_plane(scene, 0.001, "mm", &[g]).unwrap();
        assert_eq!(g2.name, "workplane2");
    }

    /// The floor of the box picked as a surface: a grid covering the 556 x 559 mm floor, its
    /// normal up towards the eye.
    #[test]
    fn a_grid_on_the_floor_covers_it_and_faces_the_eye() {
        let loaded = crate::scene::builtin_cornell_box(None).unwrap();
        let scene = &loaded.scene;
        let c = scene.bounds.center();
        let down = crate::geometry::Ray::new(c, Vec3::NEG_Y);
        let floor = scene.pick_slot(&down, &[]).unwrap();
        let eye = Vec3::from(loaded.setup.camera.position);
        let g = grid_on_surface(scene, floor, eye, 0.001, &[]).unwrap();
        let area = Vec3::from(g.u).cross(Vec3::from(g.v)).length();
        assert!((area - 556.0 * 559.2).abs() < 0.02 * area, "{area}");
        assert!(g.normal[1] > 0.99, "{:?}", g.normal);
    }
}
