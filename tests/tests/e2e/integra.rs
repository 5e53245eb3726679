//! The Integra room of `../shared/scenes/ipur-room2` through the binary (skipped when absent),
//! and a broken bundle.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use raygine_e2e::{raygine_in, read_png, shared, temp_dir};
use std::path::PathBuf;

fn room2() -> Option<PathBuf> {
    shared("scenes/ipur-room2/room2.shp")
}

/// `raygine info --json`: 20 named materials, nine fixtures of 5,920 lm, room2.cam's camera.
#[test]
fn info_shows_the_room_as_designed() {
    let Some(shp) = room2() else { return };
    let dir = temp_dir();
    let run = raygine_in(
        dir.path(),
        [
            "info".as_ref(),
            "-S".as_ref(),
            shp.as_os_str(),
            "--json".as_ref(),
        ],
    );
    run.assert_ok();
    let v: serde_json::Value = serde_json::from_str(&run.stdout).unwrap();
    assert_eq!(v["unit"], "m");
    let materials = v["materials"].as_array().unwrap();
    assert_eq!(materials.len(), 20);
    assert_eq!(materials[0]["name"], "room2/proom2_0001");
    assert_eq!(materials[19]["name"], "room2/proom2_0020");
    let lights = v["lights"].as_array().unwrap();
    assert_eq!(lights.len(), 9);
    assert!(lights.iter().all(|l| l["kind"] == "point"));
    let total: f64 = lights.iter().map(|l| l["flux_lm"].as_f64().unwrap()).sum();
    assert!((total - 5920.0).abs() < 0.1, "{total}");
    assert!((v["total_flux_lm"].as_f64().unwrap() - 5920.0).abs() < 0.1);
    let cam = &v["camera"];
    let position: Vec<f64> = cam["position"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    for (got, want) in position.iter().zip([-7.9109, 1.4619, -16.2877]) {
        assert!((got - want).abs() < 1e-4, "{position:?}");
    }
    assert!((cam["fov_deg"].as_f64().unwrap() - 39.0).abs() < 0.1);
    assert_eq!(cam["resolution"], serde_json::json!([1011, 612]));
    // The two windows' clear transmission is glass now: nothing to warn about.
    assert!(!run.stderr.contains("transmission"), "{}", run.stderr);
}

/// A direct render from room2's camera is lit, and the rug in front of the fireplace is red.
#[test]
fn render_from_the_designed_camera_is_lit() {
    let Some(shp) = room2() else { return };
    let dir = temp_dir();
    let out = dir.path().join("room2.png");
    let run = raygine_in(
        dir.path(),
        [
            "render".as_ref(),
            "-S".as_ref(),
            shp.as_os_str(),
            "-W".as_ref(),
            "202".as_ref(),
            "-H".as_ref(),
            "122".as_ref(),
            "-R".as_ref(),
            out.as_os_str(),
        ],
    );
    run.assert_ok();
    let img = read_png(&out);
    let all = img.mean_frac(0.0, 0.0, 1.0, 1.0);
    assert!(all.iter().sum::<f64>() / 3.0 > 20.0, "too dark: {all:?}");
    let rug = img.mean_frac(0.35, 0.70, 0.6, 0.76);
    assert!(
        rug[0] > 1.5 * rug[1] && rug[0] > 1.5 * rug[2],
        "rug {rug:?}"
    );
}

/// A bad line in a bundle file stops the load with one line naming the file and the line.
#[test]
fn a_bad_bundle_file_names_its_line() {
    let dir = temp_dir();
    let shp = dir.path().join("room.shp");
    std::fs::write(
        &shp,
        "define breps room\nvertices 3\n0 0 0\n1 0 0\n0 0 -1\ntriangles 1\n0 1 2\nenddef\n",
    )
    .unwrap();
    std::fs::create_dir_all(dir.path().join("room")).unwrap();
    let lgt =
        "Light L1\n  TotalFlux 100\nenddef\nFixture F1\n  Light L2\n  Position 0 1 0\nenddef\n";
    std::fs::write(dir.path().join("room/room.lgt"), lgt).unwrap();
    let run = raygine_in(
        dir.path(),
        ["info".as_ref(), "-S".as_ref(), shp.as_os_str()],
    );
    assert!(!run.success());
    let errors: Vec<&str> = run
        .stderr
        .lines()
        .filter(|l| l.contains("room.lgt"))
        .collect();
    assert_eq!(errors.len(), 1, "{}", run.stderr);
    assert!(
        errors[0].contains("room.lgt:5: fixture F1 uses light L2, which the file does not define"),
        "{}",
        run.stderr
    );
}
