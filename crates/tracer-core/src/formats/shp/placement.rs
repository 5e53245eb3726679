//! The placement convention of `set breps` blocks, in one place.
//!
//! Lumicept writes `rotation rx ry rz`, `translation tx ty tz` and `scale sx sy sz` without
//! documenting their meaning; every real file holds the identity. raygine applies
//!
//! ```text
//! p' = T · Rz · Ry · Rx · S · p
//! ```
//!
//! scale first, then rotations about the X, Y and Z axes in that order, then translation. Angles
//! are degrees, and each rotation follows the right-hand rule applied to the file's numbers (a
//! positive `rz` turns +X towards +Y), whatever the handedness used to display the scene.

use super::description::Placement;
use glam::{DMat4, DVec3};

/// The matrix that takes a brep's local coordinates to scene coordinates.
pub fn world_from_local(placement: &Placement) -> DMat4 {
    let [rx, ry, rz] = placement.rotation_deg.map(f64::to_radians);
    DMat4::from_translation(DVec3::from(placement.translation))
        * DMat4::from_rotation_z(rz)
        * DMat4::from_rotation_y(ry)
        * DMat4::from_rotation_x(rx)
        * DMat4::from_scale(DVec3::from(placement.scale))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn placed(rotation_deg: [f64; 3], translation: [f64; 3], scale: [f64; 3]) -> Placement {
        Placement {
            rotation_deg,
            translation,
            scale,
            ..Placement::default()
        }
    }

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-9
    }

    #[test]
    fn identity_keeps_points() {
        let m = world_from_local(&Placement::default());
        assert!(close(
            m.transform_point3(DVec3::new(1.0, 2.0, 3.0)),
            DVec3::new(1.0, 2.0, 3.0)
        ));
    }

    #[test]
    fn rotation_follows_right_hand_rule_in_degrees() {
        let rz = world_from_local(&placed([0.0, 0.0, 90.0], [0.0; 3], [1.0; 3]));
        assert!(close(rz.transform_point3(DVec3::X), DVec3::Y));
        let rx = world_from_local(&placed([90.0, 0.0, 0.0], [0.0; 3], [1.0; 3]));
        assert!(close(rx.transform_point3(DVec3::Y), DVec3::Z));
        let ry = world_from_local(&placed([0.0, 90.0, 0.0], [0.0; 3], [1.0; 3]));
        assert!(close(ry.transform_point3(DVec3::Z), DVec3::X));
    }

    #[test]
    fn order_is_scale_then_x_y_z_then_translation() {
        // S = (2,1,1): X -> (2,0,0); Rx(90) leaves it; Ry(90): X -> -Z, so (0,0,-2);
        // Rz(90) leaves Z; then T adds (10,0,0).
        let m = world_from_local(&placed(
            [90.0, 90.0, 90.0],
            [10.0, 0.0, 0.0],
            [2.0, 1.0, 1.0],
        ));
        assert!(close(
            m.transform_point3(DVec3::X),
            DVec3::new(10.0, 0.0, -2.0)
        ));
        // Y: S keeps Y; Rx(90): Y -> Z; Ry(90): Z -> X; Rz(90): X -> Y; T: (10,1,0).
        assert!(close(
            m.transform_point3(DVec3::Y),
            DVec3::new(10.0, 1.0, 0.0)
        ));
    }
}
