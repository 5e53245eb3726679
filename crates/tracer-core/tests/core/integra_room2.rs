//! The Integra room of `../shared/scenes/ipur-room2` opened as designed (skipped when absent):
//! known answers from the files themselves, worked out by hand.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use glam::Vec3;
use std::path::{Path, PathBuf};
use tracer_core::light::luminance;
use tracer_core::scene::{self, Handedness, LengthUnit, LoadOptions, LoadedScene, Sidecar};

fn room2() -> Option<PathBuf> {
    raygine_fixtures::shared("scenes/ipur-room2/room2.shp")
}

fn load(path: &Path) -> LoadedScene {
    scene::load(path, &LoadOptions::default()).unwrap()
}

/// room2.cam as written: the eye and the top-left, top-right, bottom-left screen corners.
const EYE: [f32; 3] = [-7.9109, 1.4619, -16.2877];
const C1: [f32; 3] = [-8.6393, 1.7712, -15.3705];
const C2: [f32; 3] = [-7.4822, 1.7712, -15.1977];
const C3: [f32; 3] = [-8.6347, 1.0637, -15.4016];

#[test]
fn room2_has_twenty_named_materials_in_metres() {
    let Some(path) = room2() else { return };
    let loaded = load(&path);
    let (scene, setup) = (&loaded.scene, &loaded.setup);
    assert_eq!(scene.slots.len(), 20);
    assert_eq!(setup.unit, LengthUnit::M);
    assert_eq!(scene.slot_label(0), "room2/proom2_0001");
    assert_eq!(scene.slot_label(19), "room2/proom2_0020");
    // a000001: kd 0.5, colour 255 248 228: a warm white whose luminance is kd.
    let wall = Vec3::from(setup.materials[0].kd);
    assert!((luminance(wall) - 0.5).abs() < 1e-4, "{wall}");
    assert!(wall.x > wall.y && wall.y > wall.z);
    // a000008: kd 0.45 grey, ks 0.55 with glossiness 29 (mirror off).
    let m8 = setup.materials[7];
    assert!((m8.kd[0] - 0.45).abs() < 1e-4 && (m8.ks[1] - 0.55).abs() < 1e-6);
    assert_eq!(m8.glossiness, 29.0);
    // a000002: kd 0.5, ks 0, mirror on: not a mirror.
    assert_eq!(setup.materials[1].ks, [0.0; 3]);
    // a000020 (154 67 0 at kd 0.3413) asks for red 1.01: clamped with a note.
    assert_eq!(setup.materials[19].kd[0], 1.0);
    let said = |needle: &str| {
        loaded
            .warnings
            .iter()
            .filter(|w| w.contains(needle))
            .count()
    };
    assert_eq!(
        said("attribute a000020: colour"),
        1,
        "{:#?}",
        loaded.warnings
    );
    // Transmission: a000003 (kts 0.2019) and a000011 (kts 0.2981), both eta 1 (thin sheets),
    // become glass; nothing is said about them, and no attribute has diffuse transmission.
    assert_eq!(said("transmission"), 0, "{:#?}", loaded.warnings);
    for kts in [0.2019f32, 0.2981] {
        let glass = loaded
            .setup
            .materials
            .iter()
            .find(|m| (m.kt[0] - kts).abs() < 1e-4)
            .unwrap_or_else(|| panic!("no material with kt {kts}"));
        assert_eq!(glass.kt, [glass.kt[0]; 3]);
        assert_eq!(glass.ior, 1.0);
    }
    // Texture maps on parts 3, 8, 13 and 16 (0-based, as the mapping names say), said once.
    assert_eq!(said("texture maps"), 1);
    assert_eq!(
        said("parts proom2_0004, proom2_0009, proom2_0014, proom2_0017 have texture maps"),
        1,
        "{:#?}",
        loaded.warnings
    );
    // Geography TokyoMidday is read (no longer skipped): the setup's daylight.
    assert_eq!(said("Geography"), 0);
    let d = loaded
        .setup
        .daylight
        .as_ref()
        .expect("daylight from Geography");
    assert_eq!(
        (d.place_time.latitude_deg, d.place_time.longitude_deg),
        (36.0, 140.0)
    );
    let sun = d.sun();
    assert!((sun.altitude_deg - 76.84).abs() < 0.01, "{sun:?}");
    assert!((sun.azimuth_deg - 198.65).abs() < 0.01, "{sun:?}");
}

#[test]
fn room2_has_nine_fixtures_of_5920_lumens() {
    let Some(path) = room2() else { return };
    let setup = load(&path).setup;
    assert_eq!(setup.lights.len(), 9);
    let total: f32 = setup.lights.iter().map(|l| l.flux_lm()).sum();
    // Seven fixtures of light L000001 (760 lm) and two of 300 lm.
    assert!((total - 5920.0).abs() < 0.05, "{total}");
    let first = &setup.lights[0];
    assert_eq!(first.position, [-6.5881, 1.5217, -6.6872]);
    assert!(
        (first.intensity_cd().unwrap_or(0.0) - 760.0 / (4.0 * std::f32::consts::PI)).abs() < 1e-3
    );
    // L000009 is tinted blue; the tint keeps the flux.
    let blue = &setup.lights[7];
    assert_eq!(blue.color, [0.7812, 0.8594, 1.0]);
    assert!((blue.flux_lm() - 300.0).abs() < 1e-3);
}

#[test]
fn room2_camera_comes_from_the_screen_corners_in_a_left_handed_frame() {
    let Some(path) = room2() else { return };
    let loaded = load(&path);
    let cam = loaded.setup.camera;
    assert_eq!(cam.position, EYE);
    assert_eq!(loaded.scene.design.resolution, Some([1011, 612]));
    // The screen is 0.7082 high at 1.000 from the eye: 2 atan(0.3541) = 39.0°.
    assert!((cam.fov_deg - 39.0).abs() < 0.1, "{}", cam.fov_deg);
    let (c1, c2, c3, eye) = (
        Vec3::from(C1),
        Vec3::from(C2),
        Vec3::from(C3),
        Vec3::from(EYE),
    );
    let aspect = (c2 - c1).length() / (c1 - c3).length();
    assert!((aspect - 1011.0 / 612.0).abs() < 0.005, "{aspect}");
    // right = c2 − c1 = up × forward: left-handed.
    let forward = ((c2 + c3) * 0.5 - eye).normalize();
    let up = (c1 - c3).normalize();
    assert!(up.cross(forward).dot((c2 - c1).normalize()) > 0.999);
    assert!(forward.cross(up).dot((c2 - c1).normalize()) < -0.999);
    // Drawn left-handed, the corners land on the corners of the 1011 x 612 picture.
    assert_eq!(loaded.setup.handedness, Handedness::Left);
    let basis = cam.basis(Handedness::Left, 1011, 612);
    for (corner, pixel) in [(c1, (0.0, 0.0)), (c2, (1011.0, 0.0)), (c3, (0.0, 612.0))] {
        let (x, y) = basis.project(corner).unwrap();
        assert!(
            (x - pixel.0).abs() < 2.0 && (y - pixel.1).abs() < 2.0,
            "{corner}: {x} {y}"
        );
    }
}

#[test]
fn a_sidecar_overrides_the_bundle_by_part_name_or_number() {
    let Some(path) = room2() else { return };
    let dir = std::env::temp_dir().join(format!("raygine-room2-sidecar-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let sidecar = dir.join("room2.raygine.toml");
    let text = "[materials.\"room2/proom2_0003\"]\nkd = [0.1, 0.2, 0.3]\n\
                [materials.\"room2/4\"]\nkd = [0.4, 0.4, 0.4]\n\
                [materials.proom2_0006]\nkd = [0.6, 0.6, 0.6]\n";
    std::fs::write(&sidecar, text).unwrap();
    let options = LoadOptions {
        sidecar: Some(&sidecar),
        ..LoadOptions::default()
    };
    let loaded = scene::load(&path, &options).unwrap();
    let bundle = load(&path);
    let m = &loaded.setup.materials;
    assert_eq!(m[2].kd, [0.1, 0.2, 0.3]);
    assert_eq!(m[4].kd, [0.4; 3]);
    assert_eq!(m[5].kd, [0.6; 3]);
    assert_eq!(
        m[0], bundle.setup.materials[0],
        "the rest stays as designed"
    );
    assert_eq!(loaded.setup.lights.len(), 9);
    // What Ctrl+S writes: part names, and it reads back to the same setup.
    let written = Sidecar::from_setup(&loaded.scene, &loaded.setup).to_toml();
    assert!(
        written.contains("[materials.\"room2/proom2_0003\"]"),
        "{written}"
    );
    std::fs::write(&sidecar, &written).unwrap();
    let again = scene::load(&path, &options).unwrap();
    // The file holds 6 significant digits: the same setup to within 5e-6 of each value.
    let close = |a: f32, b: f32| (a - b).abs() <= 5e-6 * a.abs().max(b.abs()).max(1e-3);
    let same = |a: &[f32], b: &[f32]| a.iter().zip(b).all(|(x, y)| close(*x, *y));
    for (a, b) in again.setup.materials.iter().zip(&loaded.setup.materials) {
        assert!(
            same(&a.kd, &b.kd) && same(&a.ks, &b.ks) && same(&a.kt, &b.kt),
            "{a:?} vs {b:?}"
        );
        assert!(close(a.glossiness, b.glossiness) && close(a.ior, b.ior));
        assert!(close(a.emission_cd_m2, b.emission_cd_m2));
    }
    let (c, d) = (again.setup.camera, loaded.setup.camera);
    assert!(
        same(&c.position, &d.position) && same(&c.look_at, &d.look_at),
        "{c:?} vs {d:?}"
    );
    assert!(close(c.fov_deg, d.fov_deg));
    std::fs::remove_dir_all(&dir).ok();
}

/// A dense work plane at 0.75 m through room2: the points inside its furniture are few, and
/// every one of them is boxed in (its view up ends close above it, under a desk top or inside a
/// cabinet), not out in the open room.
#[test]
fn room2_work_plane_finds_few_points_inside_furniture() {
    let Some(path) = room2() else {
        return;
    };
    let loaded = load(&path);
    let scene = &loaded.scene;
    let (mut grid, _) = tracer_core::measure::placement::work_plane(scene, 1.0, "m", &[]).unwrap();
    (grid.nu, grid.nv) = (40, 40);
    let points: Vec<_> = grid.points().collect();
    let buried = tracer_core::measure::buried_points(scene, &loaded.setup, &points);
    let count = buried.iter().filter(|&&b| b).count();
    eprintln!(
        "room2: {count} of {} work-plane points inside objects",
        points.len()
    );
    assert!(count * 4 < points.len(), "{count} of {}", points.len());
    for (p, b) in points.iter().zip(&buried) {
        if *b {
            let up = scene
                .closest_drawn(&tracer_core::geometry::Ray::new(p.position, Vec3::Y), &[])
                .unwrap();
            assert!(
                up.t < 0.9 * (scene.bounds.max.y - p.position.y),
                "{p:?} is in the open"
            );
        }
    }
}
