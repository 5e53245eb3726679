//! UsdGeomCamera: the first perspective camera met (in namespace order) becomes the scene's,
//! looking along its −Z with +Y up; its vertical field of view is 2 atan(verticalAperture /
//! 2 focalLength) (USD's defaults 15.2908 and 50). Clipping ranges, focus and shutter are not
//! used; orthographic cameras are noted.

use super::Reader;
use super::values;
use crate::formats::CameraDescription;
use glam::{DMat4, DVec3};
use openusd::usd::Prim;

impl Reader<'_> {
    pub(super) fn camera(&mut self, prim: &Prim, world: DMat4) {
        if self.desc.camera.is_some() {
            self.extra_cameras += 1;
            return;
        }
        let time = self.time;
        let projection = values::attr_token(prim, "projection").ok().flatten();
        if projection.as_deref() == Some("orthographic") {
            self.desc.notes.push(format!(
                "{}: an orthographic camera; raygine's cameras are perspective (not used)",
                self.at(prim)
            ));
            return;
        }
        let focal = values::attr_scalar(prim, "focalLength", time, 50.0).unwrap_or(50.0);
        let vertical =
            values::attr_scalar(prim, "verticalAperture", time, 15.2908).unwrap_or(15.2908);
        let fov = 2.0 * (vertical / (2.0 * focal)).atan().to_degrees();
        let position = world.transform_point3(DVec3::ZERO);
        let forward = world.transform_vector3(-DVec3::Z).normalize_or_zero();
        let up = world.transform_vector3(DVec3::Y).normalize_or_zero();
        if forward == DVec3::ZERO || up == DVec3::ZERO || !fov.is_finite() || fov <= 0.0 {
            self.desc.notes.push(format!(
                "{}: the camera's transform or lens is degenerate (not used)",
                self.at(prim)
            ));
            return;
        }
        self.desc.camera = Some(CameraDescription {
            line: 0,
            position: position.as_vec3().to_array(),
            look_at: (position + forward).as_vec3().to_array(),
            up: up.as_vec3().to_array(),
            fov_deg: (fov as f32).clamp(1.0, 170.0),
            resolution: None,
        });
    }
}
