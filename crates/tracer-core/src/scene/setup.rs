//! The editable part of a scene: camera, lights, materials, unit and handedness. Cheap to clone;
//! every render snapshot carries one.

use super::camera::Camera;
use super::geometry::Scene;
use super::light::PointLight;
use super::material::Material;
use super::units::{Handedness, LengthUnit};

/// Default vertical field of view, degrees.
pub const DEFAULT_FOV_DEG: f32 = 45.0;

#[derive(Clone, Debug, PartialEq)]
pub struct Setup {
    pub unit: LengthUnit,
    pub handedness: Handedness,
    pub camera: Camera,
    pub lights: Vec<PointLight>,
    /// One material per slot of the scene (`Scene::slots`).
    pub materials: Vec<Material>,
    /// Slots not drawn (hidden breps). Indexed like `materials`.
    pub hidden: Vec<bool>,
}

impl Setup {
    /// What a scene without a sidecar gets: neutral grey diffuse everywhere, one light just below
    /// the top centre of the bounds, a camera framing the bounds looking towards -Z.
    pub fn defaults(scene: &Scene, unit: LengthUnit) -> Setup {
        let slots = scene.slots.len();
        Setup {
            unit,
            handedness: Handedness::Left,
            camera: framing_camera(scene, DEFAULT_FOV_DEG),
            lights: vec![default_light(scene, unit)],
            materials: vec![Material::default(); slots],
            hidden: vec![false; slots],
        }
    }

    pub fn is_hidden(&self, slot: u32) -> bool {
        self.hidden.get(slot as usize).copied().unwrap_or(false)
    }
}

/// A camera on the +Z side of the bounds looking towards -Z at their centre, far enough that the
/// bounding sphere fits the vertical field of view.
pub fn framing_camera(scene: &Scene, fov_deg: f32) -> Camera {
    let c = scene.bounds.center();
    let r = scene.bounds.radius().max(1e-6);
    let half = (fov_deg.clamp(1.0, 170.0).to_radians() * 0.5).sin();
    Camera {
        position: [c.x, c.y, c.z + r / half],
        look_at: c.to_array(),
        up: [0.0, 1.0, 0.0],
        fov_deg,
    }
}

/// One light just below the top centre of the bounds (2 % of the height down: under the
/// ceiling of a room), bright enough that a Kd 0.7 floor straight below has a luminance of about
/// 100 cd/m²: `L = Kd I / (π h²)` so `I = 100 π h² / 0.7`, rounded to two significant digits.
///
/// When that point is inside solid geometry (an object whose top is at the top centre, such as a
/// teapot's lid: a surface just above and another just below), the light goes half the height
/// above the bounds instead, where it can shine. A closed box is taken for a room.
pub fn default_light(scene: &Scene, unit: LengthUnit) -> PointLight {
    let b = scene.bounds;
    let height = b.extent().y;
    let c = b.center();
    let h_m = (height * unit.metres_per_unit()).max(1e-6);
    let intensity = 100.0 * std::f32::consts::PI * h_m * h_m / 0.7;
    let under_top = glam::Vec3::new(c.x, b.max.y - 0.02 * height, c.z);
    let position = if solid_at_top(scene, under_top, height) {
        [c.x, b.max.y + 0.5 * height, c.z]
    } else {
        under_top.to_array()
    };
    PointLight {
        position,
        intensity_cd: round_2_significant(intensity),
        color: [1.0; 3],
    }
}

/// Whether a surface lies above `p` within the top 2 % of the scene (so `p` is under a lid,
/// not under an open ceiling far away) — looking straight up from `p`.
fn solid_at_top(scene: &Scene, p: glam::Vec3, height: f32) -> bool {
    let mut ray = crate::geometry::Ray::new(p, glam::Vec3::Y);
    ray.t_max = 0.021 * height;
    height > 0.0 && scene.bvh.occluded(&ray) && !open_below(scene, p)
}

/// A room's ceiling is also just above `p`; in a room the view down from `p` is open for a
/// while (the floor is far), in a solid object the next surface down is close.
fn open_below(scene: &Scene, p: glam::Vec3) -> bool {
    let down = crate::geometry::Ray::new(p, glam::Vec3::NEG_Y);
    let height = scene.bounds.extent().y;
    scene
        .bvh
        .intersect(&down)
        .is_some_and(|h| h.t > 0.25 * height)
}

fn round_2_significant(x: f32) -> f32 {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    let scale = 10f32.powf(x.log10().floor() - 1.0);
    (x / scale).round() * scale
}
