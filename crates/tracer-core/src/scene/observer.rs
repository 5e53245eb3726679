//! Observers: named eye positions with a view direction, `[[observers]]` in the sidecar. Glare
//! is judged at them; "view from observer" looks through a 180° equidistant fisheye there
//! (Radiance's `-vta`, evalglare's input).

use super::camera::{Camera, MAX_FISHEYE_FOV_DEG, Projection};
use glam::Vec3;
use serde::{Deserialize, Serialize};

/// An eye in the scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Observer {
    /// `[A-Za-z0-9_-]+`, unique in the scene.
    pub name: String,
    /// The eye, scene coordinates.
    pub position: [f32; 3],
    /// The line of sight (any length but zero).
    pub direction: [f32; 3],
    /// Up (need not be unit or orthogonal to the line of sight; not along it).
    #[serde(default = "y_up")]
    pub up: [f32; 3],
}

fn y_up() -> [f32; 3] {
    [0.0, 1.0, 0.0]
}

impl Observer {
    /// An observer at `camera`'s eye, looking where it looks.
    pub fn at_camera(name: &str, camera: &Camera) -> Observer {
        let eye = Vec3::from(camera.position);
        let direction = (Vec3::from(camera.look_at) - eye)
            .try_normalize()
            .unwrap_or(Vec3::NEG_Z);
        Observer {
            name: name.to_owned(),
            position: camera.position,
            direction: direction.to_array(),
            up: camera.up,
        }
    }

    /// The view from this observer: a 180° equidistant fisheye at the eye.
    pub fn fisheye_camera(&self) -> Camera {
        let eye = Vec3::from(self.position);
        let dir = Vec3::from(self.direction)
            .try_normalize()
            .unwrap_or(Vec3::NEG_Z);
        Camera {
            position: self.position,
            look_at: (eye + dir).to_array(),
            up: self.up,
            fov_deg: MAX_FISHEYE_FOV_DEG,
            projection: Projection::FisheyeEquidistant,
            width: None,
        }
    }

    /// Whether this observer can be used, as a message naming the key.
    pub fn check(&self) -> Result<(), String> {
        let name = &self.name;
        if name.is_empty()
            || !name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        {
            return Err(format!(
                "observer \"{name}\": name must be letters, digits, _ or - (at least one)"
            ));
        }
        for (key, v) in [
            ("position", self.position),
            ("direction", self.direction),
            ("up", self.up),
        ] {
            if !v.iter().all(|x| x.is_finite()) {
                return Err(format!("observer {name}: {key} must be finite numbers"));
            }
        }
        // In f64: the squares of large f32 components overflow.
        let dir = Vec3::from(self.direction).as_dvec3();
        if dir.length_squared() < 1e-12 {
            return Err(format!("observer {name}: direction must not be zero"));
        }
        let up = Vec3::from(self.up).as_dvec3();
        if up.length_squared() < 1e-12 || dir.normalize().cross(up.normalize()).length() < 1e-4 {
            return Err(format!(
                "observer {name}: up [{}, {}, {}] must not be zero or along the direction \
                 (looking straight up or down, give an up across the line of sight)",
                self.up[0], self.up[1], self.up[2]
            ));
        }
        Ok(())
    }
}

/// Every observer checked, and names unique: the first problem.
pub fn check_observers(observers: &[Observer]) -> Result<(), String> {
    for (i, o) in observers.iter().enumerate() {
        o.check()?;
        if observers[..i].iter().any(|p| p.name == o.name) {
            return Err(format!(
                "observer {}: a second observer has that name",
                o.name
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)]
    use super::*;

    fn desk() -> Observer {
        Observer {
            name: "desk".into(),
            position: [1.0, 1.2, 2.0],
            direction: [0.0, 0.0, -2.0],
            up: [0.0, 1.0, 0.0],
        }
    }

    #[test]
    fn the_view_from_an_observer_is_a_180_degree_equidistant_fisheye_at_the_eye() {
        let c = desk().fisheye_camera();
        assert_eq!(c.projection, Projection::FisheyeEquidistant);
        assert_eq!(c.fov_deg, 180.0);
        assert_eq!(c.position, [1.0, 1.2, 2.0]);
        assert_eq!(c.look_at, [1.0, 1.2, 1.0]);
        let back = Observer::at_camera("desk", &c);
        assert_eq!(back.position, desk().position);
        assert_eq!(back.direction, [0.0, 0.0, -1.0]);
    }

    #[test]
    fn bad_observers_are_errors_naming_the_key() {
        let err = |o: Observer| o.check().unwrap_err();
        assert!(
            err(Observer {
                direction: [0.0; 3],
                ..desk()
            })
            .contains("direction must not be zero")
        );
        assert!(
            err(Observer {
                position: [f32::NAN, 0.0, 0.0],
                ..desk()
            })
            .contains("position")
        );
        assert!(
            err(Observer {
                up: [0.0, 0.0, 1.0],
                ..desk()
            })
            .contains("must not be zero or along the direction")
        );
        // Huge but finite numbers: no overflow blamed on up.
        let far = Observer {
            direction: [0.0, 0.0, -2e19],
            ..desk()
        };
        assert!(far.check().is_ok(), "{:?}", far.check());
        assert!(
            err(Observer {
                name: "a b".into(),
                ..desk()
            })
            .contains("name")
        );
        let twice = check_observers(&[desk(), desk()]).unwrap_err();
        assert!(twice.contains("second observer"), "{twice}");
        assert!(check_observers(&[desk()]).is_ok());
    }
}
