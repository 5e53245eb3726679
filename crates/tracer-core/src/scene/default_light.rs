//! The light a scene without one gets, and the test behind it (and behind the framing camera):
//! whether the scene is a room seen into from an eye.

use super::geometry::Scene;
use super::light::Light;
use super::units::LengthUnit;

/// The light a scene without one gets, bright enough that a Kd 0.7 surface at distance `d` from
/// it, facing it, has a luminance of about 100 cd/m² (white at exposure 0): `L = Kd I / (π d²)`,
/// so `I = 100 π d² / 0.7`, rounded to two significant digits.
///
/// - In a room (a ceiling just above the top centre, open space below it): 2 % of the height
///   `h` under the ceiling, with `d = h` (the floor).
/// - Otherwise (an object): a key light halfway from the middle of the bounds to the camera at
///   `eye`, raised by `h / 2`, so it lights the faces the camera sees; `d` is the distance from
///   it to the first surface towards the middle (at least `h / 4`). A light above the top
///   centre lit only thin rims of the teapot and nefertiti, and burnt out the bunny's back.
///
/// The light must reach what the camera sees: when a surface stands between the chosen spot
/// and `eye` (the top centre is inside a closed mesh, which from inside looks like a room: ogre
/// and nefertiti rendered black), it becomes the key light, and when that is hidden too, it
/// goes to the eye itself.
pub fn default_light(scene: &Scene, unit: LengthUnit, eye: [f32; 3]) -> Light {
    let b = scene.bounds;
    let height = b.extent().y;
    let c = b.center();
    let under_top = glam::Vec3::new(c.x, b.max.y - 0.02 * height, c.z);
    let eye = glam::Vec3::from_array(eye);
    // A key light for an object: halfway from the middle of the bounds to the eye, raised by
    // half the height, so it lights the faces the camera sees.
    let key = c + 0.5 * (eye - c) + glam::Vec3::Y * (0.5 * height);
    let towards_middle = |p: glam::Vec3| {
        let d = first_hit(scene, p, c - p).unwrap_or((c - p).length());
        d.max(0.25 * height)
    };
    let (position, reach) = if is_room(scene, under_top, height) {
        (under_top, height)
    } else {
        (key, towards_middle(key))
    };
    let (position, reach) = if sees(scene, position, eye) {
        (position, reach)
    } else if sees(scene, key, eye) {
        (key, towards_middle(key))
    } else {
        (eye, towards_middle(eye))
    };
    let d_m = (reach * unit.metres_per_unit()).max(1e-6);
    let intensity = 100.0 * std::f32::consts::PI * d_m * d_m / 0.7;
    Light::point(position.to_array(), round_2_significant(intensity))
}

/// Whether the scene is a room seen into from `eye`: a ceiling just above its top centre, open
/// space below it, and nothing between there and `eye` (a closed mesh, whose inside looks like
/// a room, is not one: its inside is hidden from an eye outside).
pub(super) fn is_room_seen_from(scene: &Scene, eye: glam::Vec3) -> bool {
    let b = scene.bounds;
    let height = b.extent().y;
    let c = b.center();
    let under_top = glam::Vec3::new(c.x, b.max.y - 0.02 * height, c.z);
    is_room(scene, under_top, height) && sees(scene, under_top, eye)
}

/// Whether `p`, just under the top centre, is under a ceiling with open space below (a room or
/// a closed box), rather than open to the sky or inside a solid object's top.
fn is_room(scene: &Scene, p: glam::Vec3, height: f32) -> bool {
    let mut up = crate::geometry::Ray::new(p, glam::Vec3::Y);
    up.t_max = 0.021 * height;
    height > 0.0 && scene.occluded(&up) && open_below(scene, p)
}

/// Distance from `p` to the first surface in direction `dir`.
fn first_hit(scene: &Scene, p: glam::Vec3, dir: glam::Vec3) -> Option<f32> {
    let dir = dir.try_normalize()?;
    scene
        .intersect(&crate::geometry::Ray::new(p, dir))
        .map(|h| h.t)
}

/// Whether nothing lies between `p` and `eye`.
fn sees(scene: &Scene, p: glam::Vec3, eye: glam::Vec3) -> bool {
    let mut ray = crate::geometry::Ray::new(p, eye - p);
    ray.t_max = 1.0 - 1e-4;
    !scene.occluded(&ray)
}

/// A room's ceiling is also just above `p`; in a room the view down from `p` is open for a
/// while (the floor is far), in a solid object the next surface down is close.
fn open_below(scene: &Scene, p: glam::Vec3) -> bool {
    let down = crate::geometry::Ray::new(p, glam::Vec3::NEG_Y);
    let height = scene.bounds.extent().y;
    scene.intersect(&down).is_some_and(|h| h.t > 0.25 * height)
}

fn round_2_significant(x: f32) -> f32 {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    let scale = 10f32.powf(x.log10().floor() - 1.0);
    (x / scale).round() * scale
}
