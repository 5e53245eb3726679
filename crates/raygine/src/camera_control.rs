//! Mouse camera control: orbit (about the look-at point, or a pivot such as the surface point
//! under the cursor), pan, dolly. Pure functions on `Camera`, so the viewport and tests share
//! them.

use glam::{Quat, Vec3};
use tracer_core::scene::{Camera, Handedness, Projection};

/// Radians of orbit per pixel of mouse drag.
const ORBIT_PER_PIXEL: f32 = 0.008;

/// Orbits the eye about the look-at point: `dx` pixels to the right turns the view so the scene
/// follows the mouse; `dy` tilts it. The elevation stays short of the poles.
pub fn orbit(camera: &Camera, handedness: Handedness, dx: f32, dy: f32) -> Camera {
    orbit_about(camera, handedness, Vec3::from(camera.look_at), dx, dy)
}

/// Orbits eye and look-at point together about `pivot` by the turn [`orbit`] makes: the scene
/// turns about the point the user grabbed, which keeps its distance from the eye.
pub fn orbit_about(
    camera: &Camera,
    handedness: Handedness,
    pivot: Vec3,
    dx: f32,
    dy: f32,
) -> Camera {
    let up = Vec3::from(camera.up).try_normalize().unwrap_or(Vec3::Y);
    let back = Vec3::from(camera.position) - Vec3::from(camera.look_at);
    // In a left-handed picture the screen's x axis is mirrored, so the turn is too.
    let sign = match handedness {
        Handedness::Right => -1.0,
        Handedness::Left => 1.0,
    };
    let yaw = Quat::from_axis_angle(up, sign * dx * ORBIT_PER_PIXEL);
    let mut turn = yaw;
    let yawed = yaw * back;
    if let Some(right) = yawed.cross(up).try_normalize() {
        let pitch = Quat::from_axis_angle(right, -dy * ORBIT_PER_PIXEL);
        // Keep away from looking straight along the up axis.
        let cos = (pitch * yawed).normalize_or_zero().dot(up).abs();
        if cos < 0.995 {
            turn = pitch * yaw;
        }
    }
    let about = |p: [f32; 3]| (pivot + turn * (Vec3::from(p) - pivot)).to_array();
    Camera {
        position: about(camera.position),
        look_at: about(camera.look_at),
        ..*camera
    }
}

/// Moves eye and look-at together in the view plane; `dx`, `dy` in pixels of an image
/// `size_px` (width, height), so the point under the mouse at the look-at distance follows
/// it (an orthographic view's points all do).
pub fn pan(camera: &Camera, handedness: Handedness, dx: f32, dy: f32, size_px: [f32; 2]) -> Camera {
    let basis = camera.basis(handedness, 1, 1);
    let [width_px, height_px] = size_px.map(|v| v.max(1.0));
    let units_per_px = if camera.projection == Projection::Orthographic {
        camera.orthographic_width(width_px / height_px) / width_px
    } else {
        let distance = (Vec3::from(camera.look_at) - Vec3::from(camera.position)).length();
        2.0 * distance * basis.half_height / height_px
    };
    let shift = (-basis.right * dx + basis.up * dy) * units_per_px;
    Camera {
        position: (Vec3::from(camera.position) + shift).to_array(),
        look_at: (Vec3::from(camera.look_at) + shift).to_array(),
        ..*camera
    }
}

/// Moves the eye towards (positive `amount`) or away from the look-at point; the distance is
/// scaled by `exp(-amount)` and never reaches zero. An orthographic view, where distance
/// changes nothing, narrows its width by the same factor instead (`aspect`, the image's width
/// over height, gives the default width a value first).
pub fn dolly(camera: &Camera, amount: f32, aspect: f32) -> Camera {
    if camera.projection == Projection::Orthographic {
        let width = camera.orthographic_width(aspect) * (-amount).exp();
        return Camera {
            width: Some(width.clamp(1e-4, 1e9)),
            ..*camera
        };
    }
    let target = Vec3::from(camera.look_at);
    let offset = Vec3::from(camera.position) - target;
    let scaled = offset * (-amount).exp();
    let scaled = if scaled.length() < 1e-4 {
        offset
    } else {
        scaled
    };
    Camera {
        position: (target + scaled).to_array(),
        ..*camera
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam() -> Camera {
        Camera {
            position: [0.0, 0.0, 10.0],
            look_at: [0.0; 3],
            up: [0.0, 1.0, 0.0],
            fov_deg: 45.0,
            ..Camera::default()
        }
    }

    #[test]
    fn orbit_keeps_distance_and_target() {
        let c = orbit(&cam(), Handedness::Left, 100.0, 40.0);
        assert_eq!(c.look_at, [0.0; 3]);
        assert!((Vec3::from(c.position).length() - 10.0).abs() < 1e-3);
        assert_ne!(c.position, cam().position);
    }

    /// About a pivot off the view axis both eye and look-at move, the eye keeps its distance
    /// from the pivot, and the turn is the one `orbit` makes.
    #[test]
    fn orbit_about_a_pivot_keeps_the_pivots_distance() {
        let pivot = Vec3::new(3.0, -1.0, 2.0);
        let c = orbit_about(&cam(), Handedness::Right, pivot, 50.0, -20.0);
        let before = Vec3::from(cam().position).distance(pivot);
        assert!((Vec3::from(c.position).distance(pivot) - before).abs() < 1e-4);
        assert_ne!(c.look_at, cam().look_at);
        let plain = orbit(&cam(), Handedness::Right, 50.0, -20.0);
        let dir = |c: &Camera| (Vec3::from(c.look_at) - Vec3::from(c.position)).normalize();
        assert!(dir(&c).distance(dir(&plain)) < 1e-5, "the same turn");
    }

    #[test]
    fn pan_moves_both_and_dolly_scales_distance() {
        let c = pan(&cam(), Handedness::Right, 10.0, 0.0, [100.0, 100.0]);
        let shift = Vec3::from(c.position) - Vec3::from(cam().position);
        assert!((Vec3::from(c.look_at) - shift).length() < 1e-5);
        assert!(
            shift.x < 0.0,
            "dragging right moves the view left in a right-handed frame"
        );
        let d = dolly(&cam(), 0.5, 1.0);
        assert!((Vec3::from(d.position).length() - 10.0 * (-0.5f32).exp()).abs() < 1e-4);
    }

    /// Orthographic: the dolly narrows the width (the eye stays), and a pan moves the scene
    /// with the mouse at the film's scale, whatever the depth.
    #[test]
    fn orthographic_dolly_changes_width_and_pan_follows_the_mouse() {
        let ortho = Camera {
            projection: Projection::Orthographic,
            width: Some(8.0),
            ..cam()
        };
        let d = dolly(&ortho, 0.5, 2.0);
        assert_eq!(d.position, ortho.position);
        assert!((d.width.unwrap_or_default() - 8.0 * (-0.5f32).exp()).abs() < 1e-5);
        // Without a width the default (the perspective view's at the look-at point) is taken
        // first: 2 · 10 · tan(22.5°) · 2 across.
        let default = Camera {
            width: None,
            ..ortho
        };
        let want = 2.0 * 10.0 * 22.5f32.to_radians().tan() * 2.0;
        assert!((dolly(&default, 0.0, 2.0).width.unwrap_or_default() - want).abs() < 1e-3);
        // 8 units over 200 px: a 50 px drag moves the view by 2 units.
        let c = pan(&ortho, Handedness::Right, 50.0, 0.0, [200.0, 100.0]);
        let shift = Vec3::from(c.position) - Vec3::from(ortho.position);
        assert!((shift.length() - 2.0).abs() < 1e-4, "{shift}");
    }
}
