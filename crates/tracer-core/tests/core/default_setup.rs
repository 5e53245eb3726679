//! Defaults for a scene without a sidecar: where the light goes, how bright it is, which side
//! the camera looks from.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use glam::Vec3;
use tracer_core::scene::{
    DEFAULT_FOV_DEG, LengthUnit, Scene, builtin_cornell_box, default_light, framing_camera,
    framing_side, outline_areas,
};
use tracer_core::shp::{BrepDef, ShpDescription};

/// A camera in front of and above the test scenes (metres).
const EYE: [f32; 3] = [0.5, 2.0, 6.0];

/// A lid: a slab 5 cm thick whose top is the top of a 1 m tall scene (a floor at y = 0).
fn lid_over_floor() -> Scene {
    let v = |x: f64, y: f64, z: f64| [x, y, z];
    let corners = [
        v(0.0, 0.95, 0.0),
        v(1.0, 0.95, 0.0),
        v(1.0, 1.0, 0.0),
        v(0.0, 1.0, 0.0),
        v(0.0, 0.95, 1.0),
        v(1.0, 0.95, 1.0),
        v(1.0, 1.0, 1.0),
        v(0.0, 1.0, 1.0),
        v(-2.0, 0.0, -2.0),
        v(3.0, 0.0, -2.0),
        v(3.0, 0.0, 3.0),
        v(-2.0, 0.0, 3.0),
    ];
    let faces = [
        [0, 1, 2, 3],
        [4, 5, 6, 7],
        [0, 1, 5, 4],
        [3, 2, 6, 7],
        [0, 3, 7, 4],
        [1, 2, 6, 5],
        [8, 9, 10, 11],
    ];
    let mut triangles = Vec::new();
    for f in faces {
        triangles.push([f[0], f[1], f[2]]);
        triangles.push([f[0], f[2], f[3]]);
    }
    mesh("lid", corners.to_vec(), triangles)
}

/// A one-brep scene of these vertices and triangles.
fn mesh(name: &str, vertices: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> Scene {
    let brep = BrepDef {
        name: name.into(),
        vertices,
        parts: vec![0; triangles.len()],
        triangles,
        part_count: 1,
        ..BrepDef::default()
    };
    let desc = ShpDescription {
        breps: vec![brep],
        ..ShpDescription::default()
    };
    Scene::build(&desc, name).unwrap()
}

#[test]
fn light_of_a_solid_object_is_a_key_light_above_it() {
    let light = default_light(&lid_over_floor(), LengthUnit::M, EYE);
    assert!(
        light.position[1] > 1.0,
        "{:?} is inside the lid",
        light.position
    );
    // The key light: halfway from the middle (0.5, 0.5, 0.5) to the eye, 0.5 m up.
    assert_eq!(light.position, [0.5, 1.75, 3.25]);
    // Towards the middle (0, -1.25, -2.75) it passes under the lid and meets the floor at
    // 1.4 times that: d = 4.23 m; 100 π d² / 0.7 = 8026 -> 8000.
    assert_eq!(light.intensity_cd(), Some(8000.0));
}

/// A scene of axis-aligned boxes (`(min, max)` corners), each as six quads.
fn boxes(list: &[([f64; 3], [f64; 3])]) -> Scene {
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for (lo, hi) in list {
        let base = vertices.len() as u32;
        for i in 0..8 {
            let pick = |axis: usize| {
                if i >> axis & 1 == 0 {
                    lo[axis]
                } else {
                    hi[axis]
                }
            };
            vertices.push([pick(0), pick(1), pick(2)]);
        }
        // Corner i has x from bit 0, y from bit 1, z from bit 2.
        for [a, b, c, d] in [
            [0, 1, 3, 2],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 3, 7, 6],
            [0, 2, 6, 4],
            [1, 3, 7, 5],
        ] {
            triangles.push([base + a, base + b, base + c]);
            triangles.push([base + a, base + c, base + d]);
        }
    }
    mesh("boxes", vertices, triangles)
}

/// Open above the top centre (the scene's height comes from a post in a corner): a key light
/// between the middle and the eye, its intensity set by the distance to the first surface
/// towards the middle (0, 0.495, 0).
#[test]
fn light_over_an_open_scene_is_a_key_light_scaled_to_the_surface_it_faces() {
    let floor = ([-2.0, -0.01, -2.0], [2.0, 0.0, 2.0]);
    let post = ([1.8, 0.0, 1.8], [1.9, 1.0, 1.9]);
    let block = ([-0.5, 0.0, -0.5], [0.5, 0.5, 0.5]);
    let over_block = default_light(&boxes(&[floor, post, block]), LengthUnit::M, EYE);
    // Halfway to EYE = (0.5, 2, 6), plus h / 2 = 0.505 up.
    let expected = [0.25, 1.7525, 3.0];
    for (got, want) in over_block.position.iter().zip(expected) {
        assert!((got - want).abs() < 1e-4, "{over_block:?}");
    }
    // Towards the middle, direction (-0.25, -1.2575, -3), the block's top (y = 0.5) is met at
    // 0.996 of it: d = 3.249 m; 100 π d² / 0.7 = 4738 -> 4700.
    assert_eq!(over_block.intensity_cd(), Some(4700.0));
    // Without the block the floor is met at 1.394 of it: d = 4.547 m; 9278 -> 9300.
    let over_floor = default_light(&boxes(&[floor, post]), LengthUnit::M, EYE);
    assert_eq!(over_floor.intensity_cd(), Some(9300.0));
}

#[test]
fn light_of_a_room_stays_under_the_ceiling() {
    let loaded = builtin_cornell_box(None).unwrap();
    let eye = loaded.setup.camera.position;
    let light = default_light(&loaded.scene, LengthUnit::Mm, eye);
    let top = loaded.scene.bounds.max.y;
    assert!(
        light.position[1] < top && light.position[1] > 0.95 * top,
        "{:?}",
        light.position
    );
}

/// A closed mesh looks like a room from inside (a surface just above, the floor far below), but
/// a light inside it lights nothing the camera outside can see (nefertiti and ogre rendered
/// black): it becomes a key light between the mesh and the camera instead.
#[test]
fn light_inside_a_closed_mesh_seen_from_outside_becomes_a_key_light() {
    let cube = boxes(&[([0.0, 0.0, 0.0], [1.0, 1.0, 1.0])]);
    let light = default_light(&cube, LengthUnit::M, EYE);
    assert_eq!(light.position, [0.5, 1.75, 3.25]);
    assert!(light.intensity_cd().is_some_and(|cd| cd > 0.0));
    // Seen from inside (a camera in the box, as in a room), the light stays under the top.
    let inside = default_light(&cube, LengthUnit::M, [0.5, 0.5, 0.9]);
    assert!(inside.position[1] < 1.0, "{inside:?}");
}

/// A slab fills its bounds, so its outlines are exactly the bounds' faces.
#[test]
fn outline_areas_of_a_slab_are_its_faces() {
    let slab = boxes(&[([0.0, 0.0, 0.0], [0.05, 1.0, 2.0])]);
    let [x, y, z] = outline_areas(&slab);
    for (got, want) in [(x, 1.0 * 2.0), (y, 2.0 * 0.05), (z, 0.05 * 1.0)] {
        assert!((got - want).abs() < 1e-4 * want, "{:?}", [x, y, z]);
    }
}

/// A slab standing in the YZ plane is seen face-on from +X (up +Y), a slab lying flat from
/// above (+Z, its front, at the bottom of the picture): the side with the largest outline.
#[test]
fn a_slab_is_framed_from_its_largest_side() {
    let standing = boxes(&[([0.0, 0.0, 0.0], [0.05, 1.0, 2.0])]);
    assert_eq!(framing_side(&standing), (Vec3::X, Vec3::Y));
    let camera = framing_camera(&standing, DEFAULT_FOV_DEG);
    let c = standing.bounds.center();
    let distance = standing.bounds.radius() / (DEFAULT_FOV_DEG.to_radians() * 0.5).sin();
    assert_eq!(camera.look_at, c.to_array());
    assert_eq!(camera.position, (c + Vec3::X * distance).to_array());
    assert_eq!(camera.up, [0.0, 1.0, 0.0]);

    let lying = boxes(&[([0.0, 0.0, 0.0], [2.0, 0.05, 1.0])]);
    assert_eq!(framing_side(&lying), (Vec3::Y, Vec3::NEG_Z));
}

/// Seen from above only when lying flat: a box lower than it is wide and deep (outline from
/// above 1.0, sides 0.7) is seen from the front, as a teapot is; a flat one (above 1.0, sides
/// 0.45) from above.
#[test]
fn only_a_flat_scene_is_seen_from_above() {
    let low = boxes(&[([0.0, 0.0, 0.0], [1.0, 0.7, 1.0])]);
    let [x, y, z] = outline_areas(&low);
    assert!(y > x / 0.9 && y < 2.0 * x.max(z), "{:?}", [x, y, z]);
    assert_eq!(framing_side(&low), (Vec3::Z, Vec3::Y));
    let flat = boxes(&[([0.0, 0.0, 0.0], [1.0, 0.45, 1.0])]);
    assert_eq!(framing_side(&flat), (Vec3::Y, Vec3::NEG_Z));
}

/// +Z stays while its outline is within 10 % of the largest: a box 8 % deeper than wide keeps
/// the front view, one 15 % deeper is seen from +X.
#[test]
fn the_front_view_stays_within_ten_percent() {
    let cube = boxes(&[([0.0, 0.0, 0.0], [1.0, 1.0, 1.0])]);
    assert_eq!(framing_side(&cube), (Vec3::Z, Vec3::Y));
    let a_little_deeper = boxes(&[([0.0, 0.0, 0.0], [1.0, 1.0, 1.08])]);
    assert_eq!(framing_side(&a_little_deeper), (Vec3::Z, Vec3::Y));
    let deeper = boxes(&[([0.0, 0.0, 0.0], [1.0, 1.0, 1.15])]);
    assert_eq!(framing_side(&deeper), (Vec3::X, Vec3::Y));
}

/// A room is seen from +Z even when its outline along X is five times larger (a corridor).
#[test]
fn a_room_keeps_the_front_view() {
    let (w, h, d, t) = (2.0, 2.5, 10.0, 0.02);
    let corridor = boxes(&[
        ([0.0, 0.0, 0.0], [w, t, d]),
        ([0.0, h - t, 0.0], [w, h, d]),
        ([0.0, 0.0, 0.0], [t, h, d]),
        ([w - t, 0.0, 0.0], [w, h, d]),
        ([0.0, 0.0, 0.0], [w, h, t]),
    ]);
    let [x, _, z] = outline_areas(&corridor);
    assert!(x > 4.0 * z, "{x} {z}");
    assert_eq!(framing_side(&corridor), (Vec3::Z, Vec3::Y));
    let cornell = builtin_cornell_box(None).unwrap();
    assert_eq!(framing_side(&cornell.scene), (Vec3::Z, Vec3::Y));
}

/// Nefertiti (stored Z-up) was seen from the top of her head; her outline from +X is the
/// largest, the one along Z (the top) 29 % smaller.
#[test]
fn nefertiti_is_seen_from_the_side() {
    let Some(path) = raygine_fixtures::shared("scenes/meshes/nefertiti.shp") else {
        return;
    };
    let loaded = tracer_core::scene::load(&path, &Default::default()).unwrap();
    let [x, y, z] = outline_areas(&loaded.scene);
    assert!(z < 0.9 * x && y < x, "{:?}", [x, y, z]);
    assert_eq!(framing_side(&loaded.scene), (Vec3::X, Vec3::Y));
    assert_eq!(
        loaded.setup.camera,
        framing_camera(&loaded.scene, DEFAULT_FOV_DEG)
    );
}
