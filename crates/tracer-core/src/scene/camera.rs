//! The pinhole camera and its basis, which depends on the scene's handedness.

use super::units::Handedness;
use crate::geometry::Ray;
use glam::Vec3;
use serde::{Deserialize, Serialize};

/// Default vertical field of view, degrees.
pub const DEFAULT_FOV_DEG: f32 = 45.0;

/// A pinhole camera as users edit it: degrees only here, at the edge.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    /// Eye position in scene coordinates.
    pub position: [f32; 3],
    /// The point the camera looks at.
    pub look_at: [f32; 3],
    /// Up direction (need not be unit or orthogonal to the view direction).
    #[serde(default = "y_up")]
    pub up: [f32; 3],
    /// Vertical field of view in degrees, from the top edge to the bottom edge of the image.
    pub fov_deg: f32,
}

fn y_up() -> [f32; 3] {
    [0.0, 1.0, 0.0]
}

/// The camera resolved for one image: an orthonormal basis and the image-plane half extents.
#[derive(Clone, Copy, Debug)]
pub struct CameraBasis {
    pub origin: Vec3,
    pub forward: Vec3,
    /// Scene direction of increasing pixel x (towards the right of the picture).
    pub right: Vec3,
    /// Scene direction of decreasing pixel y (towards the top of the picture).
    pub up: Vec3,
    /// tan(fov_y / 2) and that times the aspect ratio.
    pub half_height: f32,
    pub half_width: f32,
    pub width: u32,
    pub height: u32,
}

impl Camera {
    /// The basis for an image of `width` x `height` pixels. In a right-handed frame
    /// `right = forward × up`; in a left-handed one (Lumicept files) `right = up × forward`, so a
    /// camera at +Z looking towards -Z sees +X on the left. Degenerate input (eye on the look-at
    /// point, up parallel to the view) falls back to looking along -Z with +Y (or +Z) up.
    pub fn basis(&self, handedness: Handedness, width: u32, height: u32) -> CameraBasis {
        let origin = Vec3::from(self.position);
        let forward = (Vec3::from(self.look_at) - origin)
            .try_normalize()
            .unwrap_or(Vec3::NEG_Z);
        let mut up_hint = Vec3::from(self.up).try_normalize().unwrap_or(Vec3::Y);
        if forward.cross(up_hint).length_squared() < 1e-10 {
            up_hint = if forward.cross(Vec3::Y).length_squared() < 1e-10 {
                Vec3::Z
            } else {
                Vec3::Y
            };
        }
        let rh_right = forward.cross(up_hint).normalize();
        let up = rh_right.cross(forward);
        let right = match handedness {
            Handedness::Right => rh_right,
            Handedness::Left => -rh_right,
        };
        let fov = self.fov_deg.clamp(0.1, 179.0).to_radians();
        let half_height = (fov * 0.5).tan();
        let aspect = width.max(1) as f32 / height.max(1) as f32;
        CameraBasis {
            origin,
            forward,
            right,
            up,
            half_height,
            half_width: half_height * aspect,
            width: width.max(1),
            height: height.max(1),
        }
    }
}

impl CameraBasis {
    /// The primary ray through film position (`x`, `y`) in pixels, (0, 0) the top-left corner of
    /// the image and (width, height) the bottom-right. Direction is unit length.
    pub fn ray(&self, x: f32, y: f32) -> Ray {
        let sx = (2.0 * x / self.width as f32 - 1.0) * self.half_width;
        let sy = (1.0 - 2.0 * y / self.height as f32) * self.half_height;
        let dir = (self.forward + self.right * sx + self.up * sy).normalize();
        Ray::new(self.origin, dir)
    }

    /// Where a scene point lands on the film, in pixels (None when behind the camera).
    pub fn project(&self, p: Vec3) -> Option<(f32, f32)> {
        let d = p - self.origin;
        let z = d.dot(self.forward);
        if z <= 1e-6 {
            return None;
        }
        let sx = d.dot(self.right) / z / self.half_width;
        let sy = d.dot(self.up) / z / self.half_height;
        Some((
            (sx + 1.0) * 0.5 * self.width as f32,
            (1.0 - sy) * 0.5 * self.height as f32,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam() -> Camera {
        Camera {
            position: [0.0, 0.0, 10.0],
            look_at: [0.0, 0.0, 0.0],
            up: [0.0, 1.0, 0.0],
            fov_deg: 60.0,
        }
    }

    #[test]
    fn left_handed_shows_plus_x_on_the_left() {
        let b = cam().basis(Handedness::Left, 200, 100);
        let (x, _) = b.project(Vec3::new(1.0, 0.0, 0.0)).unwrap_or_default();
        assert!(x < 100.0, "+X should be left of centre, got x = {x}");
        let b = cam().basis(Handedness::Right, 200, 100);
        let (x, _) = b.project(Vec3::new(1.0, 0.0, 0.0)).unwrap_or_default();
        assert!(x > 100.0);
    }

    #[test]
    fn ray_and_project_agree_and_fov_is_vertical() {
        let b = cam().basis(Handedness::Left, 300, 200);
        let r = b.ray(75.0, 20.0);
        let (x, y) = b.project(r.at(5.0)).unwrap_or_default();
        assert!((x - 75.0).abs() < 1e-3 && (y - 20.0).abs() < 1e-3);
        // The top edge ray makes fov/2 = 30 degrees with the view direction.
        let top = b.ray(150.0, 0.0);
        let angle = top.dir.angle_between(b.forward).to_degrees();
        assert!((angle - 30.0).abs() < 1e-3, "{angle}");
    }

    #[test]
    fn degenerate_cameras_still_give_a_basis() {
        let c = Camera {
            look_at: [0.0, 0.0, 10.0],
            ..cam()
        };
        let b = c.basis(Handedness::Left, 10, 10);
        assert!(b.forward.is_finite() && b.right.is_finite() && b.up.is_finite());
        let c = Camera {
            look_at: [0.0, -5.0, 10.0],
            ..cam()
        };
        let b = c.basis(Handedness::Right, 10, 10);
        assert!((b.right.length() - 1.0).abs() < 1e-5);
    }
}
