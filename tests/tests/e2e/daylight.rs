//! Daylight through the real binary: the morning sun lights the east face of a block, in a
//! right-handed glTF scene (east = +X with north −Z) and in a left-handed `.shp` scene (east =
//! −X: the file is a mirror image, and its sun is mirrored with it), and leaves the west face
//! dark. The sun alone (no sky, no ground), so the west face reads exactly 0.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use raygine_e2e::{raygine_in, shp_of_quads, temp_dir};
use std::path::Path;

/// The six faces of the block [-1, 1]³ (2 m), as quads.
fn block() -> Vec<[[f64; 3]; 4]> {
    let c = |x: f64, y: f64, z: f64| [x, y, z];
    vec![
        [
            c(-1., -1., -1.),
            c(1., -1., -1.),
            c(1., -1., 1.),
            c(-1., -1., 1.),
        ],
        [
            c(-1., 1., -1.),
            c(-1., 1., 1.),
            c(1., 1., 1.),
            c(1., 1., -1.),
        ],
        [
            c(-1., -1., -1.),
            c(-1., -1., 1.),
            c(-1., 1., 1.),
            c(-1., 1., -1.),
        ],
        [
            c(1., -1., -1.),
            c(1., 1., -1.),
            c(1., 1., 1.),
            c(1., -1., 1.),
        ],
        [
            c(-1., -1., -1.),
            c(-1., 1., -1.),
            c(1., 1., -1.),
            c(1., -1., -1.),
        ],
        [
            c(-1., -1., 1.),
            c(1., -1., 1.),
            c(1., 1., 1.),
            c(-1., 1., 1.),
        ],
    ]
}

/// The block as a `.gltf` with its `.bin` (positions, then u16 indices).
fn write_gltf(dir: &Path) {
    let mut bin = Vec::new();
    for q in block() {
        for v in q {
            for c in v {
                bin.extend_from_slice(&(c as f32).to_le_bytes());
            }
        }
    }
    let positions = bin.len();
    for f in 0..6u16 {
        let b = f * 4;
        for i in [b, b + 1, b + 2, b, b + 2, b + 3] {
            bin.extend_from_slice(&i.to_le_bytes());
        }
    }
    let indices = bin.len() - positions;
    std::fs::write(dir.join("block.bin"), &bin).unwrap();
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"name": "block", "mesh": 0}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
  "buffers": [{{"uri": "block.bin", "byteLength": {total}}}],
  "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": {positions}}},
                  {{"buffer": 0, "byteOffset": {positions}, "byteLength": {indices}}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 24, "type": "VEC3",
      "min": [-1, -1, -1], "max": [1, 1, 1]}},
    {{"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}}]}}"#,
        total = bin.len()
    );
    std::fs::write(dir.join("block.gltf"), json).unwrap();
}

/// The sidecar: 07:30 at the March equinox on the equator (the sun 22° up, a little north of
/// east), and one sensor on each X face, facing out.
const SIDECAR: &str = "unit = \"m\"\n\
    [[grids]]\nname = \"plus_x\"\norigin = [1.01, -0.01, -0.01]\nu = [0.0, 0.02, 0.0]\n\
    v = [0.0, 0.0, 0.02]\nnu = 1\nnv = 1\nnormal = [1.0, 0.0, 0.0]\n\
    [[grids]]\nname = \"minus_x\"\norigin = [-1.01, -0.01, -0.01]\nu = [0.0, 0.02, 0.0]\n\
    v = [0.0, 0.0, 0.02]\nnu = 1\nnv = 1\nnormal = [-1.0, 0.0, 0.0]\n\
    [daylight]\nlatitude = 0.0\nlongitude = 0.0\ndate = \"2026-03-20\"\ntime = \"07:30\"\n\
    timezone = 0.0\nsun = true\nsun_normal_illuminance_lx = 80000.0\n";

/// `raygine measure` on `scene`: (E on the +X face, E on the −X face), lx.
fn faces(dir: &Path, scene: &str) -> (f64, f64) {
    let json = dir.join(format!("{scene}.json"));
    let run = raygine_in(
        dir,
        [
            "measure".as_ref(),
            "--precision".as_ref(),
            "full".as_ref(),
            "-S".as_ref(),
            scene.as_ref(),
            "--gi".as_ref(),
            "path".as_ref(),
            "--samples".as_ref(),
            "64".as_ref(),
            "--json".as_ref(),
            json.as_os_str(),
        ],
    );
    run.assert_ok();
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let e = |name: &str| {
        v["grids"]
            .as_array()
            .unwrap()
            .iter()
            .find(|g| g["name"] == name)
            .unwrap()["e_avg_lx"]
            .as_f64()
            .unwrap()
    };
    (e("plus_x"), e("minus_x"))
}

#[test]
fn the_morning_sun_lights_the_east_face_in_either_handedness() {
    let dir = temp_dir();
    write_gltf(dir.path());
    std::fs::write(dir.path().join("block.raygine.toml"), SIDECAR).unwrap();
    let quads = block();
    std::fs::write(
        dir.path().join("mirror.shp"),
        shp_of_quads(&[("block", quads.as_slice())]),
    )
    .unwrap();
    std::fs::write(dir.path().join("mirror.raygine.toml"), SIDECAR).unwrap();
    let (east_gltf, west_gltf) = faces(dir.path(), "block.gltf");
    let (west_shp, east_shp) = faces(dir.path(), "mirror.shp");
    println!(
        "glTF (right-handed): +X {east_gltf:.0} lx, -X {west_gltf:.0} lx; \
         .shp (left-handed): -X {east_shp:.0} lx, +X {west_shp:.0} lx"
    );
    // E_n cos(altitude) cos(azimuth − 90°): over 70,000 lx on the east face.
    for (east, west) in [(east_gltf, west_gltf), (east_shp, west_shp)] {
        assert!(east > 70_000.0 && east < 80_000.0, "{east}");
        assert_eq!(west, 0.0);
    }
    assert!((east_gltf / east_shp - 1.0).abs() < 1e-3);
}
