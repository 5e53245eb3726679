//! OBJ and glTF scenes through the real binary, against analytic answers: a glTF point light
//! (KHR_lights_punctual, candela) above a floor gives E = I cos θ / R² on a grid (`.gltf` with a
//! `.bin` beside it, and the same scene as `.glb`); an OBJ floor with an MTL Kd under a sidecar
//! light shows L = Kd E / π; the shared OBJ models load and render; bad files give one line.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use raygine_e2e::{raygine_in, read_exr, read_png, render_in, shared, temp_dir};
use std::f64::consts::PI;
use std::path::Path;

/// A 4 x 4 m floor at y = 0 facing +Y: positions then u16 indices, little-endian.
fn floor_buffer() -> Vec<u8> {
    let mut b = Vec::new();
    for p in [
        [-2.0f32, 0.0, -2.0],
        [2.0, 0.0, -2.0],
        [2.0, 0.0, 2.0],
        [-2.0, 0.0, 2.0],
    ] {
        for c in p {
            b.extend_from_slice(&c.to_le_bytes());
        }
    }
    for i in [0u16, 2, 1, 0, 3, 2] {
        b.extend_from_slice(&i.to_le_bytes());
    }
    b
}

/// glTF JSON of the floor (mesh "floor", material "grey") under a 100 cd point light 2 m up;
/// `uri` is the buffer's URI (None: the GLB's binary chunk).
fn floor_json(uri: Option<&str>) -> String {
    let uri = uri.map_or(String::new(), |u| format!("\"uri\": \"{u}\", "));
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {{"KHR_lights_punctual": {{"lights": [
    {{"type": "point", "intensity": 100.0, "color": [1, 1, 1], "name": "lamp"}}]}}}},
  "scene": 0,
  "scenes": [{{"nodes": [0, 1]}}],
  "nodes": [
    {{"name": "floor", "mesh": 0}},
    {{"name": "lamp", "translation": [0, 2, 0],
      "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1, "material": 0}}]}}],
  "materials": [{{"name": "grey", "pbrMetallicRoughness": {{"baseColorFactor": [0.5, 0.5, 0.5, 1],
    "metallicFactor": 0, "roughnessFactor": 1}}}}],
  "buffers": [{{{uri}"byteLength": 60}}],
  "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
                  {{"buffer": 0, "byteOffset": 48, "byteLength": 12}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
      "min": [-2, 0, -2], "max": [2, 0, 2]}},
    {{"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}}]
}}"#
    )
}

/// A binary glTF: header, JSON chunk, BIN chunk (each padded to 4 bytes).
fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut j = json.as_bytes().to_vec();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let mut b = bin.to_vec();
    while !b.len().is_multiple_of(4) {
        b.push(0);
    }
    let total = 12 + 8 + j.len() + 8 + b.len();
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(b.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&b);
    out
}

const GRID: &str = "[[grids]]\nname = \"floor\"\norigin = [-2.0, 0.0, -2.0]\nu = [4.0, 0.0, 0.0]\n\
                    v = [0.0, 0.0, 4.0]\nnu = 4\nnv = 4\nnormal = [0.0, 1.0, 0.0]\n";

/// `raygine measure --gi direct` on `scene`; the grid's rows against I h / R³ (I = 100 cd, h = 2 m).
fn measure_matches_inverse_square(dir: &Path, scene: &str) {
    let csv = dir.join(format!("{scene}.csv"));
    let run = raygine_in(
        dir,
        [
            "measure".as_ref(),
            "--precision".as_ref(),
            "full".as_ref(),
            "-S".as_ref(),
            scene.as_ref(),
            "--gi".as_ref(),
            "direct".as_ref(),
            "--csv".as_ref(),
            csv.as_os_str(),
        ],
    );
    run.assert_ok();
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').skip(3).map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 16, "{text}");
    for r in &rows {
        let (x, z, e) = (r[0], r[2], r[3]);
        let d2 = x * x + z * z + 4.0;
        let exact = 100.0 * 2.0 / (d2 * d2.sqrt());
        assert!(
            (e / exact - 1.0).abs() < 1e-3,
            "{scene} {r:?}: exact {exact}"
        );
    }
    // Straight below the lamp the grid's centre cells are at 0.5 m: the formula's own
    // value there, and I / h² = 25 lx at the centre itself, are what a lighting engineer checks.
    assert!(rows.iter().all(|r| r[3] <= 25.0));
}

#[test]
fn gltf_point_light_above_a_floor_gives_i_over_r_squared() {
    let dir = temp_dir();
    let d = dir.path();
    std::fs::write(d.join("floor.bin"), floor_buffer()).unwrap();
    std::fs::write(d.join("floor.gltf"), floor_json(Some("floor.bin"))).unwrap();
    std::fs::write(d.join("floor.raygine.toml"), GRID).unwrap();
    measure_matches_inverse_square(d, "floor.gltf");
    std::fs::write(
        d.join("packed.glb"),
        glb(&floor_json(None), &floor_buffer()),
    )
    .unwrap();
    std::fs::write(d.join("packed.raygine.toml"), GRID).unwrap();
    measure_matches_inverse_square(d, "packed.glb");

    // `info` names the format's breps, parts and the light in candela.
    let run = raygine_in(d, ["info", "-S", "packed.glb"]);
    run.assert_ok();
    assert!(run.stdout.contains("floor"), "{}", run.stdout);
}

#[test]
fn obj_floor_with_an_mtl_kd_shows_kd_e_over_pi() {
    let dir = temp_dir();
    let d = dir.path();
    std::fs::write(
        d.join("floor.obj"),
        "# a 4 x 4 m floor\nmtllib floor.mtl\no floor\nv -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\n\
         vn 0 1 0\nusemtl paint\nf 1//1 4//1 3//1 2//1\n",
    )
    .unwrap();
    std::fs::write(d.join("floor.mtl"), "newmtl paint\nKd 0.5 0.25 0.1\n").unwrap();
    std::fs::write(
        d.join("floor.raygine.toml"),
        "unit = \"m\"\n[camera]\nposition = [0.0, 3.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\n\
         up = [0.0, 0.0, -1.0]\nfov_deg = 40.0\n\
         [[lights]]\nposition = [0.0, 2.0, 0.0]\nintensity_cd = 100.0\n",
    )
    .unwrap();
    let run = render_in(
        d,
        [
            "-S",
            "floor.obj",
            "-W",
            "21",
            "-H",
            "21",
            "--exr",
            "floor.exr",
        ],
    );
    run.assert_ok();
    let exr = read_exr(&d.join("floor.exr"));
    let e = 100.0 / 4.0;
    for (c, kd) in exr.at(10, 10).into_iter().zip([0.5, 0.25, 0.1]) {
        let want = kd * e / PI;
        assert!((f64::from(c) / want - 1.0).abs() < 1e-3, "{c} vs {want}");
    }
}

#[test]
fn the_shared_obj_models_load_and_render() {
    let Some(models) = shared("models") else {
        return;
    };
    let dir = temp_dir();
    for name in [
        "teapot",
        "stanford-bunny",
        "suzanne",
        "spot",
        "nefertiti",
        "ogre",
    ] {
        let obj = models.join(format!("{name}.obj"));
        let png = dir.path().join(format!("{name}.png"));
        let run = render_in(
            dir.path(),
            [
                "-S".as_ref(),
                obj.as_os_str(),
                "-W".as_ref(),
                "64".as_ref(),
                "-H".as_ref(),
                "48".as_ref(),
                "-R".as_ref(),
                png.as_os_str(),
            ],
        );
        run.assert_ok();
        let img = read_png(&png);
        let centre = img.mean_frac(0.3, 0.3, 0.7, 0.7);
        assert!(
            centre.iter().sum::<f64>() > 10.0,
            "{name}: the middle of the picture is black: {centre:?}"
        );
    }
}

#[test]
fn bad_obj_and_gltf_files_get_one_line_naming_file_and_place() {
    let dir = temp_dir();
    let d = dir.path();
    let outside = floor_json(Some("../floor.bin"));
    let bad_data = floor_json(Some("data:application/octet-stream;base64,@@@"));
    let cases: [(&str, &[u8], &str); 5] = [
        (
            "bad.obj",
            b"v 0 0 0\nv 1 0 0\nf 1 2 3\n",
            "bad.obj:3: f: corner `3`: vertex 3 does not exist (the file has 2)",
        ),
        (
            "nan.obj",
            b"v 0 0 0\nv 1 nan 0\n",
            "nan.obj:2: v: `nan` is not a finite number",
        ),
        (
            "outside.gltf",
            outside.as_bytes(),
            "buffer 0: `../floor.bin` is outside the file's folder",
        ),
        (
            "data.gltf",
            bad_data.as_bytes(),
            "buffer 0: data URI: does not decode as base64",
        ),
        ("junk.glb", b"glTF\x02\0\0\0junk", "not a valid glTF file"),
    ];
    for (name, bytes, want) in cases {
        std::fs::write(d.join(name), bytes).unwrap();
        let run = render_in(d, ["-S", name, "-W", "8", "-H", "8", "-R", "out.png"]);
        assert!(!run.success(), "{name} was accepted");
        let lines = run.stderr_lines();
        assert!(
            lines.iter().any(|l| l.contains(want) && l.contains(name)),
            "{name}: {lines:?}"
        );
        assert!(!d.join("out.png").exists(), "{name}: an image was written");
    }
}
