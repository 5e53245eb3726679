//! Defaults for a scene without a sidecar: where the light goes, how bright it is.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use tracer_core::scene::{LengthUnit, Scene, builtin_cornell_box, default_light};
use tracer_core::shp::{BrepDef, ShpDescription};

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
    let brep = BrepDef {
        name: "lid".into(),
        vertices: corners.to_vec(),
        parts: vec![0; triangles.len()],
        triangles,
        part_count: 1,
        ..BrepDef::default()
    };
    let desc = ShpDescription {
        breps: vec![brep],
        ..ShpDescription::default()
    };
    Scene::build(&desc, "lid").unwrap()
}

#[test]
fn light_of_a_solid_object_goes_above_it() {
    let light = default_light(&lid_over_floor(), LengthUnit::M);
    assert!(
        light.position[1] > 1.0,
        "{:?} is inside the lid",
        light.position
    );
    assert_eq!(
        light.intensity_cd, 450.0,
        "100 π h² / 0.7 for h = 1 m, two digits"
    );
}

#[test]
fn light_of_a_room_stays_under_the_ceiling() {
    let loaded = builtin_cornell_box(None).unwrap();
    let light = default_light(&loaded.scene, LengthUnit::Mm);
    let top = loaded.scene.bounds.max.y;
    assert!(
        light.position[1] < top && light.position[1] > 0.95 * top,
        "{:?}",
        light.position
    );
}
