//! The linear EXR against the analytic answer, and the unit hint.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use raygine_e2e::{floor_quad, read_exr, read_png, render_in, shp_of_quads, temp_dir};
use std::f64::consts::PI;

/// A Lambertian floor (Kd 0.5) under a 100 cd light 1 m above it, seen from 2 m straight above:
/// the EXR holds `L = Kd E / π` with `E = I h / (h² + d²)^(3/2)`, below the light and off-axis.
#[test]
fn exr_floor_luminance_matches_the_analytic_value() {
    let dir = temp_dir();
    let d = dir.path();
    let quads = [floor_quad(1500.0)];
    std::fs::write(d.join("floor.shp"), shp_of_quads(&[("floor", &quads)])).unwrap();
    std::fs::write(
        d.join("floor.raygine.toml"),
        "unit = \"mm\"\n\
         [camera]\nposition = [0.0, 2000.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\n\
         up = [0.0, 0.0, -1.0]\nfov_deg = 40.0\n\
         [[lights]]\nposition = [0.0, 1000.0, 0.0]\nintensity_cd = 100.0\n\
         [default_material]\nkd = [0.5, 0.5, 0.5]\n",
    )
    .unwrap();
    let run = render_in(
        d,
        [
            "-S",
            "floor.shp",
            "-W",
            "21",
            "-H",
            "21",
            "--exr",
            "floor.exr",
            "-R",
            "floor.png",
        ],
    );
    run.assert_ok();
    assert!(run.stdout.contains("floor.exr"), "{}", run.stdout);
    let exr = read_exr(&d.join("floor.exr"));
    assert_eq!((exr.width, exr.height), (21, 21));
    assert_eq!(read_png(&d.join("floor.png")).width, 21);
    let (kd, intensity, h) = (0.5, 100.0, 1.0);
    let expected = |dist_m: f64| kd / PI * intensity * h / (h * h + dist_m * dist_m).powf(1.5);
    let centre = exr.at(10, 10);
    for c in centre {
        let want = expected(0.0);
        assert!(
            (f64::from(c) / want - 1.0).abs() < 1e-3,
            "below the light {c} vs {want}"
        );
    }
    // The pixel at the right edge of the middle row: its centre is at film x = 20.5 of 21.
    let half = (20.0f64.to_radians()).tan();
    let offset_m = 2.0 * (2.0 * 20.5 / 21.0 - 1.0) * half;
    let edge = exr.at(20, 10)[1];
    let want = expected(offset_m);
    assert!(
        (f64::from(edge) / want - 1.0).abs() < 1e-3,
        "off-axis {edge} vs {want}"
    );
    assert!(f64::from(edge) < 0.8 * f64::from(centre[1]));
}

/// A scene 0.5 units across read as millimetres is 0.5 mm: the CLI suggests `--units`, and
/// says nothing once the unit is given.
#[test]
fn units_hint_for_a_scene_in_metres() {
    let dir = temp_dir();
    let d = dir.path();
    let quads = [floor_quad(0.2)];
    std::fs::write(d.join("small.shp"), shp_of_quads(&[("floor", &quads)])).unwrap();
    let run = render_in(d, ["-S", "small.shp", "-W", "16", "-H", "12"]);
    run.assert_ok();
    assert!(
        run.stderr.contains("--units m"),
        "expected a hint, stderr: {}",
        run.stderr
    );
    let run = render_in(
        d,
        ["-S", "small.shp", "-W", "16", "-H", "12", "--units", "m"],
    );
    run.assert_ok();
    assert!(
        !run.stderr.contains("--units"),
        "no hint with --units m: {}",
        run.stderr
    );
}
