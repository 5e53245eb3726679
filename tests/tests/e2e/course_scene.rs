//! The course's Cornell box (`../shared/scenes/cornell/cornel_box0.shp`) through the original
//! positional interface `lx ly lz cx cy cz cf`, prefixes of it, negative numbers without `--`,
//! both spellings of the options and the default output path. Skipped, with the reason printed,
//! when `../shared` is absent.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use raygine_e2e::{Rgb8, course_cornell_box, read_png, render_in, temp_dir};
use std::path::Path;

const SIZE: [&str; 4] = ["-W", "80", "-H", "60"];

/// Renders the scene with `extra` arguments into `dir/out` and decodes the result.
fn render(dir: &Path, scene: &Path, extra: &[&str], out: &str) -> Rgb8 {
    let out_path = dir.join(out);
    let mut args: Vec<String> = SIZE.iter().map(|s| s.to_string()).collect();
    args.extend(["-S".into(), scene.display().to_string()]);
    args.extend(["-R".into(), out_path.display().to_string()]);
    args.extend(extra.iter().map(|s| s.to_string()));
    render_in(dir, args).assert_ok();
    read_png(&out_path)
}

/// Mean absolute difference per channel value, 0..=255.
fn mean_abs_diff(a: &Rgb8, b: &Rgb8) -> f64 {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let sum: u64 = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .flat_map(|(p, q)| (0..3).map(move |c| u64::from(p[c].abs_diff(q[c]))))
        .sum();
    sum as f64 / (a.pixels.len() * 3) as f64
}

#[test]
fn original_positional_interface_moves_light_and_camera() {
    let Some(scene) = course_cornell_box() else {
        return;
    };
    let dir = temp_dir();
    let d = dir.path();
    let course = ["278", "548.7", "-279.5", "278", "273", "800", "40"];
    let base = render(d, &scene, &course, "base.png");
    assert_eq!((base.width, base.height), (80, 60));
    // The light under the ceiling lights the floor (bottom centre) more than the ceiling's
    // front edge, and the picture is not black.
    let floor = base.mean_frac(0.4, 0.8, 0.6, 0.9);
    assert!(floor[1] > 40.0, "floor {floor:?}");
    // Moving the light to the left wall's side changes the picture; so does the camera.
    let mut moved_light = course;
    moved_light[0] = "500";
    let lit_left = render(d, &scene, &moved_light, "light.png");
    assert!(mean_abs_diff(&base, &lit_left) > 2.0);
    // +X is on the left of the picture: with the light near x = 500 the front of the floor is
    // brighter on the left than on the right.
    let left = lit_left.mean_frac(0.2, 0.9, 0.35, 0.97);
    let right = lit_left.mean_frac(0.65, 0.9, 0.8, 0.97);
    assert!(left[1] > right[1] + 5.0, "left {left:?} right {right:?}");
    let mut moved_camera = course;
    moved_camera[5] = "1200";
    let far = render(d, &scene, &moved_camera, "far.png");
    assert!(mean_abs_diff(&base, &far) > 2.0);
    let mut narrow = course;
    narrow[6] = "20";
    let zoomed = render(d, &scene, &narrow, "narrow.png");
    assert!(mean_abs_diff(&base, &zoomed) > 2.0);
}

/// Negative positionals need no `--`, also as the first value and as the camera's.
#[test]
fn negative_positionals_work_without_double_dash() {
    let Some(scene) = course_cornell_box() else {
        return;
    };
    let dir = temp_dir();
    let d = dir.path();
    let a = render(d, &scene, &["-100", "300", "-279.5"], "a.png");
    let b = render(d, &scene, &["--", "-100", "300", "-279.5"], "b.png");
    assert_eq!(a, b, "`-100 ...` and `-- -100 ...` must mean the same");
    let c = render(d, &scene, &["100", "300", "-279.5"], "c.png");
    assert_ne!(a, c, "the sign of lx must matter");
    render(
        d,
        &scene,
        &["278", "548.7", "-279.5", "-200", "273", "-100", "60"],
        "cam.png",
    );
}

/// What the positionals leave out comes from the scene, not from zeros: with a sidecar light at
/// (200, 500, -250), `lx` alone equals `lx 500 -250` exactly; without a sidecar it matches the
/// default light (just under the top centre of the bounds).
#[test]
fn a_prefix_takes_the_rest_from_the_scene() {
    let Some(scene) = course_cornell_box() else {
        return;
    };
    let dir = temp_dir();
    let d = dir.path();
    let sidecar = d.join("light.toml");
    std::fs::write(
        &sidecar,
        "[[lights]]\nposition = [200.0, 500.0, -250.0]\nintensity_cd = 100.0\n",
    )
    .unwrap();
    let side = sidecar.display().to_string();
    let only_x = render(d, &scene, &["--sidecar", &side, "330"], "x.png");
    let full = render(
        d,
        &scene,
        &["--sidecar", &side, "330", "500", "-250"],
        "xyz.png",
    );
    assert_eq!(only_x, full);
    let zeros = render(d, &scene, &["--sidecar", &side, "330", "0", "0"], "x00.png");
    assert!(mean_abs_diff(&only_x, &zeros) > 2.0);

    // No sidecar: the default light sits at (278, 548.8 - 2 % of 548.8, -279.6).
    let default_only_x = render(d, &scene, &["330"], "dx.png");
    let default_full = render(d, &scene, &["330", "537.824", "-279.6"], "dxyz.png");
    let diff = mean_abs_diff(&default_only_x, &default_full);
    assert!(
        diff < 0.05,
        "lx alone should use the default ly lz, diff {diff}"
    );
    let default_zeros = render(d, &scene, &["330", "0", "0"], "d00.png");
    assert!(mean_abs_diff(&default_only_x, &default_zeros) > 2.0);
}

/// `-S`, `--scene_path` and `--scene-path` are the same option; `-R`, `--render_path` too.
#[test]
fn option_spellings_agree() {
    let Some(scene) = course_cornell_box() else {
        return;
    };
    let dir = temp_dir();
    let d = dir.path();
    let s = scene.display().to_string();
    let mut images = Vec::new();
    for (i, (scene_opt, render_opt)) in [
        ("-S", "-R"),
        ("--scene_path", "--render_path"),
        ("--scene-path", "--render-path"),
    ]
    .into_iter()
    .enumerate()
    {
        let out = d.join(format!("{i}.png"));
        let o = out.display().to_string();
        render_in(d, ["-W", "48", "-H", "36", scene_opt, &s, render_opt, &o]).assert_ok();
        images.push(std::fs::read(&out).unwrap());
    }
    assert!(images.iter().all(|b| *b == images[0]));
}

/// Without `-R` the PNG goes beside the scene, named like it.
#[test]
fn default_render_path_is_the_scene_path_with_png() {
    let Some(scene) = course_cornell_box() else {
        return;
    };
    let dir = temp_dir();
    let copy = dir.path().join("my_box.shp");
    std::fs::copy(&scene, &copy).unwrap();
    let elsewhere = temp_dir();
    render_in(
        elsewhere.path(),
        ["-W", "32", "-H", "24", "-S", &copy.display().to_string()],
    )
    .assert_ok();
    let img = read_png(&dir.path().join("my_box.png"));
    assert_eq!((img.width, img.height), (32, 24));
    assert!(
        std::fs::read_dir(elsewhere.path())
            .unwrap()
            .next()
            .is_none()
    );
}
