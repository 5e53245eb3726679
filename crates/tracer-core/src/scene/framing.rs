//! The camera a scene without one gets: which side of the scene it looks from, and how far.
//!
//! Rooms, and scenes whose front/back outline (seen along Z) is within 10 % of the largest
//! outline, are seen from +Z, the usual front. Any other scene is seen from the side with the
//! largest outline (a bust stored Z-up from its side, not the top of its head); from above only
//! when the scene lies flat (its outline from above at least twice any side's), so a teapot is
//! not looked down on. Outline areas are measured by casting a grid of parallel rays along
//! each axis.

use super::camera::Camera;
use super::geometry::Scene;
use crate::geometry::Ray;
use glam::Vec3;

/// Rays per side of the grid that measures an outline area.
const OUTLINE_GRID: u32 = 96;
/// +Z stays the view while its outline is at least this share of the largest one.
const KEEP_FRONT: f32 = 0.9;
/// The view from above is taken only when its outline is at least this many times the largest
/// side's (a scene lying flat).
const FLAT_FROM_ABOVE: f32 = 2.0;

/// A camera looking at the centre of the bounds from the side [`framing_side`] picks, far
/// enough that the bounding sphere fits the vertical field of view.
pub fn framing_camera(scene: &Scene, fov_deg: f32) -> Camera {
    let c = scene.bounds.center();
    let r = scene.bounds.radius().max(1e-6);
    let half = (fov_deg.clamp(1.0, 170.0).to_radians() * 0.5).sin();
    let (towards_eye, up) = framing_side(scene);
    Camera {
        position: (c + towards_eye * (r / half)).to_array(),
        look_at: c.to_array(),
        up: up.to_array(),
        fov_deg,
        ..Camera::default()
    }
}

/// The unit direction from the scene's centre to the default camera, and the camera's up.
///
/// - +Z (up +Y) for a room the front camera sees into (a ceiling over open space, as the
///   default light finds it), and whenever the outline seen along Z is at least 90 % of the
///   largest outline.
/// - +Y (from above) with -Z up, so the scene's front (+Z) is at the bottom of the picture,
///   when the scene lies flat: its outline from above is at least twice the largest side's.
/// - Otherwise the side (+Z or +X, up +Y) with the larger outline, +Z while within 10 %.
pub fn framing_side(scene: &Scene) -> (Vec3, Vec3) {
    let front = (Vec3::Z, Vec3::Y);
    if scene.bounds.is_empty() {
        return front;
    }
    let half = (super::camera::DEFAULT_FOV_DEG.to_radians() * 0.5).sin();
    let front_eye = scene.bounds.center() + Vec3::Z * (scene.bounds.radius() / half);
    if super::default_light::is_room_seen_from(scene, front_eye) {
        return front;
    }
    let [x, y, z] = outline_areas(scene);
    let largest = x.max(y).max(z);
    let side = x.max(z);
    if z >= KEEP_FRONT * largest {
        front
    } else if y >= FLAT_FROM_ABOVE * side {
        (Vec3::Y, Vec3::NEG_Z)
    } else if z >= KEEP_FRONT * side {
        front
    } else {
        (Vec3::X, Vec3::Y)
    }
}

/// The area (scene units²) of the scene's outline seen along X, Y and Z: the share of a grid
/// of parallel rays across the bounds that hit something, times the bounds' face area.
pub fn outline_areas(scene: &Scene) -> [f32; 3] {
    let b = scene.bounds;
    let extent = b.extent();
    std::array::from_fn(|axis| {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut dir = Vec3::ZERO;
        dir[axis] = 1.0;
        let mut hits = 0u32;
        for i in 0..OUTLINE_GRID {
            for j in 0..OUTLINE_GRID {
                let mut origin = Vec3::ZERO;
                origin[axis] = b.min[axis] - 0.01 * extent[axis] - 1e-6;
                origin[u] = b.min[u] + extent[u] * (i as f32 + 0.5) / OUTLINE_GRID as f32;
                origin[v] = b.min[v] + extent[v] * (j as f32 + 0.5) / OUTLINE_GRID as f32;
                if scene.intersect(&Ray::new(origin, dir)).is_some() {
                    hits += 1;
                }
            }
        }
        hits as f32 / (OUTLINE_GRID * OUTLINE_GRID) as f32 * extent[u] * extent[v]
    })
}
