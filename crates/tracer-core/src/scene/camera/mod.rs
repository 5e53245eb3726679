//! The camera as users edit it and its basis for one image, which depends on the scene's
//! handedness; the projections live in [`projection`].

mod projection;

use super::units::Handedness;
use crate::geometry::Ray;
use glam::Vec3;
pub use projection::{Lens, MAX_FISHEYE_FOV_DEG, Projection, Radial};
use serde::{Deserialize, Serialize};

/// Default vertical field of view, degrees.
pub const DEFAULT_FOV_DEG: f32 = 45.0;

/// A camera as users edit it: degrees only here, at the edge.
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
    /// Field of view in degrees: perspective from the top edge to the bottom edge of the
    /// image; fisheyes across their image circle (at most 180°). Unused by the equirectangular
    /// and orthographic projections.
    #[serde(default = "default_fov")]
    pub fov_deg: f32,
    #[serde(default, skip_serializing_if = "is_perspective")]
    pub projection: Projection,
    /// Orthographic: the image's width in scene units (default: the perspective view's width
    /// at the look-at point).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<f32>,
}

fn default_fov() -> f32 {
    DEFAULT_FOV_DEG
}

fn is_perspective(p: &Projection) -> bool {
    *p == Projection::Perspective
}

impl Default for Camera {
    /// At the origin looking along -Z, +Y up, perspective at [`DEFAULT_FOV_DEG`].
    fn default() -> Self {
        Camera {
            position: [0.0; 3],
            look_at: [0.0, 0.0, -1.0],
            up: y_up(),
            fov_deg: DEFAULT_FOV_DEG,
            projection: Projection::Perspective,
            width: None,
        }
    }
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
    /// tan(fov_y / 2) and that times the aspect ratio (the perspective view, whatever the
    /// projection: panning uses it).
    pub half_height: f32,
    pub half_width: f32,
    pub width: u32,
    pub height: u32,
    /// The projection, resolved for this image.
    pub lens: Lens,
}

impl Camera {
    /// The projection's limits, as a message naming the key: `fov_deg` above 0 and at most
    /// 180 for a fisheye, below 180 for a perspective camera; `width` above 0.
    pub fn check(&self) -> Result<(), String> {
        let fov = self.fov_deg;
        let p = self.projection;
        if p.is_fisheye() && !(fov > 0.0 && fov <= MAX_FISHEYE_FOV_DEG) {
            return Err(format!(
                "camera: fov_deg of a {p} camera must be above 0 and at most \
                 {MAX_FISHEYE_FOV_DEG}°, got {fov}"
            ));
        }
        if p == Projection::Perspective && !(fov > 0.0 && fov < 180.0) {
            return Err(format!(
                "camera: fov_deg of a perspective camera must be above 0 and below 180° \
                 (a wider view needs projection = \"fisheye-equidistant\" or another fisheye), \
                 got {fov}"
            ));
        }
        if let Some(w) = self.width
            && !(w.is_finite() && w > 0.0)
        {
            return Err(format!(
                "camera: width (the orthographic image's width in scene units) must be above \
                 0, got {w}"
            ));
        }
        Ok(())
    }

    /// The orthographic image's width in scene units for an image of aspect ratio `aspect`
    /// (width over height): `width`, or by default what the perspective view at `fov_deg`
    /// shows across at the look-at point.
    pub fn orthographic_width(&self, aspect: f32) -> f32 {
        match self.width {
            Some(w) if w.is_finite() && w > 0.0 => w,
            _ => {
                let distance = (Vec3::from(self.look_at) - Vec3::from(self.position)).length();
                let half_height = (self.fov_deg.clamp(0.1, 179.0).to_radians() * 0.5).tan();
                (2.0 * distance * half_height * aspect).max(1e-6)
            }
        }
    }

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
        let (width, height) = (width.max(1), height.max(1));
        let aspect = width as f32 / height as f32;
        let lens = match self.projection {
            Projection::Perspective => Lens::Pinhole,
            Projection::Equirectangular => Lens::Equirectangular,
            Projection::Orthographic => {
                let half_width = 0.5 * self.orthographic_width(aspect);
                Lens::Orthographic {
                    half_width,
                    half_height: half_width / aspect,
                }
            }
            p => {
                let radial = p.radial().unwrap_or(Radial::Equidistant);
                let fov = self.fov_deg.clamp(0.1, MAX_FISHEYE_FOV_DEG).to_radians();
                Lens::fisheye(radial, fov, width, height)
            }
        };
        CameraBasis {
            origin,
            forward,
            right,
            up,
            half_height,
            half_width: half_height * aspect,
            width,
            height,
            lens,
        }
    }
}

impl CameraBasis {
    /// The primary ray through film position (`x`, `y`) in pixels, (0, 0) the top-left corner of
    /// the image and (width, height) the bottom-right; None outside a fisheye's image circle.
    /// Direction is unit length.
    #[inline]
    pub fn ray(&self, x: f32, y: f32) -> Option<Ray> {
        let sx = 2.0 * x / self.width as f32 - 1.0;
        let sy = 1.0 - 2.0 * y / self.height as f32;
        match self.lens {
            Lens::Pinhole => {
                let (sx, sy) = (sx * self.half_width, sy * self.half_height);
                let dir = (self.forward + self.right * sx + self.up * sy).normalize();
                Some(Ray::new(self.origin, dir))
            }
            Lens::Orthographic {
                half_width,
                half_height,
            } => {
                let origin =
                    self.origin + self.right * (sx * half_width) + self.up * (sy * half_height);
                Some(Ray::new(origin, self.forward))
            }
            lens => {
                let d = lens.direction(x, y, self.width, self.height)?;
                Some(Ray::new(self.origin, self.world_from_camera(d).normalize()))
            }
        }
    }

    /// The scene direction of camera-frame direction `d` (right, up, forward).
    fn world_from_camera(&self, [a, b, c]: [f32; 3]) -> Vec3 {
        self.right * a + self.up * b + self.forward * c
    }

    /// The camera-frame coordinates (right, up, forward) of scene vector `v`.
    fn camera_from_world(&self, v: Vec3) -> [f32; 3] {
        [v.dot(self.right), v.dot(self.up), v.dot(self.forward)]
    }

    /// Where a scene point lands on the film, in pixels (None when the camera does not see
    /// it: behind a perspective or orthographic camera, outside a fisheye's field). A
    /// perspective or orthographic camera may place it outside the image.
    pub fn project(&self, p: Vec3) -> Option<(f32, f32)> {
        let d = p - self.origin;
        let z = d.dot(self.forward);
        let to_pixels = |sx: f32, sy: f32| {
            (
                (sx + 1.0) * 0.5 * self.width as f32,
                (1.0 - sy) * 0.5 * self.height as f32,
            )
        };
        match self.lens {
            Lens::Pinhole => {
                if z <= 1e-6 {
                    return None;
                }
                let sx = d.dot(self.right) / z / self.half_width;
                let sy = d.dot(self.up) / z / self.half_height;
                Some(to_pixels(sx, sy))
            }
            Lens::Orthographic {
                half_width,
                half_height,
            } => {
                if z <= 0.0 {
                    return None;
                }
                Some(to_pixels(
                    d.dot(self.right) / half_width,
                    d.dot(self.up) / half_height,
                ))
            }
            _ => self.film_position(d.try_normalize()?),
        }
    }

    /// The film position the eye sees along unit direction `w` (only cameras with an eye
    /// point; None for the orthographic one, whose directions are all `forward`), inside the
    /// image or None.
    pub fn film_position(&self, w: Vec3) -> Option<(f32, f32)> {
        match self.lens {
            Lens::Pinhole => {
                let cos = self.forward.dot(w);
                if cos <= 0.0 {
                    return None;
                }
                let sx = self.right.dot(w) / cos / self.half_width;
                let sy = self.up.dot(w) / cos / self.half_height;
                if !(-1.0..=1.0).contains(&sx) || !(-1.0..=1.0).contains(&sy) {
                    return None;
                }
                Some((
                    (sx + 1.0) * 0.5 * self.width as f32,
                    (1.0 - sy) * 0.5 * self.height as f32,
                ))
            }
            Lens::Orthographic { .. } => None,
            lens => lens.film_position(self.camera_from_world(w), self.width, self.height),
        }
    }

    /// Density per sr of the unit direction `w` (seen by the film) when camera samples are
    /// drawn uniformly over the image: 1 / (A cos³ θ) for the pinhole (A its film's area at
    /// unit distance), the film area per solid angle over the image's area for the others;
    /// 0 for the orthographic camera (a delta in direction).
    pub fn direction_density(&self, w: Vec3) -> f32 {
        match self.lens {
            Lens::Pinhole => {
                let cos = self.forward.dot(w);
                if cos <= 0.0 {
                    return 0.0;
                }
                1.0 / (4.0 * self.half_width * self.half_height * cos.powi(3))
            }
            Lens::Orthographic { .. } => 0.0,
            lens => lens.direction_density(self.camera_from_world(w), self.width, self.height),
        }
    }

    /// Whether pixel (`x`, `y`) lies wholly outside the image circle of a fisheye: black, it
    /// takes no camera rays.
    #[inline]
    pub fn pixel_outside(&self, x: u32, y: u32) -> bool {
        self.lens.pixel_outside(x, y)
    }

    /// Where the camera's ray towards scene point `p` starts: the eye, or for the
    /// orthographic camera the foot of `p` on the film's plane.
    pub fn eye_for(&self, p: Vec3) -> Vec3 {
        match self.lens {
            Lens::Orthographic { .. } => p - self.forward * (p - self.origin).dot(self.forward),
            _ => self.origin,
        }
    }

    /// Whether the camera has a single eye point (every projection but the orthographic).
    pub fn has_eye_point(&self) -> bool {
        !matches!(self.lens, Lens::Orthographic { .. })
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    fn cam() -> Camera {
        Camera {
            position: [0.0, 0.0, 10.0],
            look_at: [0.0, 0.0, 0.0],
            up: [0.0, 1.0, 0.0],
            fov_deg: 60.0,
            ..Camera::default()
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
        let r = b.ray(75.0, 20.0).unwrap();
        let (x, y) = b.project(r.at(5.0)).unwrap_or_default();
        assert!((x - 75.0).abs() < 1e-3 && (y - 20.0).abs() < 1e-3);
        // The top edge ray makes fov/2 = 30 degrees with the view direction.
        let top = b.ray(150.0, 0.0).unwrap();
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
