//! Mouse camera control: orbit about the look-at point, pan, dolly. Pure functions on
//! `Camera`, so the viewport and tests share them.

use glam::{Quat, Vec3};
use tracer_core::scene::{Camera, Handedness};

/// Radians of orbit per pixel of mouse drag.
const ORBIT_PER_PIXEL: f32 = 0.008;

/// Orbits the eye about the look-at point: `dx` pixels to the right turns the view so the scene
/// follows the mouse; `dy` tilts it. The elevation stays short of the poles.
pub fn orbit(camera: &Camera, handedness: Handedness, dx: f32, dy: f32) -> Camera {
    let target = Vec3::from(camera.look_at);
    let up = Vec3::from(camera.up).try_normalize().unwrap_or(Vec3::Y);
    let offset = Vec3::from(camera.position) - target;
    // In a left-handed picture the screen's x axis is mirrored, so the turn is too.
    let sign = match handedness {
        Handedness::Right => -1.0,
        Handedness::Left => 1.0,
    };
    let yaw = Quat::from_axis_angle(up, sign * dx * ORBIT_PER_PIXEL);
    let mut offset = yaw * offset;
    let right = offset.cross(up).try_normalize();
    if let Some(right) = right {
        let pitched = Quat::from_axis_angle(right, -dy * ORBIT_PER_PIXEL) * offset;
        // Keep away from looking straight along the up axis.
        let cos = pitched.normalize_or_zero().dot(up).abs();
        if cos < 0.995 {
            offset = pitched;
        }
    }
    Camera {
        position: (target + offset).to_array(),
        ..*camera
    }
}

/// Moves eye and look-at together in the view plane; `dx`, `dy` in pixels of an image
/// `height_px` tall, so the point under the mouse at the look-at distance follows it.
pub fn pan(camera: &Camera, handedness: Handedness, dx: f32, dy: f32, height_px: f32) -> Camera {
    let basis = camera.basis(handedness, 1, 1);
    let distance = (Vec3::from(camera.look_at) - Vec3::from(camera.position)).length();
    let units_per_px = 2.0 * distance * basis.half_height / height_px.max(1.0);
    let shift = (-basis.right * dx + basis.up * dy) * units_per_px;
    Camera {
        position: (Vec3::from(camera.position) + shift).to_array(),
        look_at: (Vec3::from(camera.look_at) + shift).to_array(),
        ..*camera
    }
}

/// Moves the eye towards (positive `amount`) or away from the look-at point; the distance is
/// scaled by `exp(-amount)` and never reaches zero.
pub fn dolly(camera: &Camera, amount: f32) -> Camera {
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
        }
    }

    #[test]
    fn orbit_keeps_distance_and_target() {
        let c = orbit(&cam(), Handedness::Left, 100.0, 40.0);
        assert_eq!(c.look_at, [0.0; 3]);
        assert!((Vec3::from(c.position).length() - 10.0).abs() < 1e-3);
        assert_ne!(c.position, cam().position);
    }

    #[test]
    fn pan_moves_both_and_dolly_scales_distance() {
        let c = pan(&cam(), Handedness::Right, 10.0, 0.0, 100.0);
        let shift = Vec3::from(c.position) - Vec3::from(cam().position);
        assert!((Vec3::from(c.look_at) - shift).length() < 1e-5);
        assert!(
            shift.x < 0.0,
            "dragging right moves the view left in a right-handed frame"
        );
        let d = dolly(&cam(), 0.5);
        assert!((Vec3::from(d.position).length() - 10.0 * (-0.5f32).exp()).abs() < 1e-4);
    }
}
