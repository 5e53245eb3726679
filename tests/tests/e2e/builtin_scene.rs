//! The built-in Cornell box through the real binary: image size, where colours land, default
//! output path, antialiasing and thread-count independence.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use raygine_e2e::{read_png, render_in, temp_dir};

/// Red on the left, green on the right (Lumicept's picture), a lit floor under the light.
#[test]
fn builtin_cornell_box_has_red_left_green_right_and_a_lit_floor() {
    let dir = temp_dir();
    let out = dir.path().join("box.png");
    let run = render_in(
        dir.path(),
        ["-W", "160", "-H", "120", "-R"]
            .map(Into::into)
            .into_iter()
            .chain([out.clone().into_os_string()]),
    );
    run.assert_ok();
    assert!(
        run.stdout.contains("cd/m²"),
        "the summary states its units: {}",
        run.stdout
    );
    let img = read_png(&out);
    assert_eq!((img.width, img.height), (160, 120));
    let left = img.mean_frac(0.16, 0.35, 0.24, 0.65);
    let right = img.mean_frac(0.76, 0.35, 0.84, 0.65);
    // The filmic curve desaturates bright colours, so "dominant" is a margin, not a ratio.
    let dominant = |c: [f64; 3], i: usize| (0..3).all(|j| j == i || c[i] > c[j] + 50.0);
    assert!(dominant(left, 0), "left wall should be red: {left:?}");
    assert!(dominant(right, 1), "right wall should be green: {right:?}");
    // Floor near the light's foot, (400, 0, -150) in file coordinates, between the blocks, and
    // floor near the two front corners of the box (bottom edge of the picture, inside the walls).
    let under_light = img.mean_frac(0.34, 0.89, 0.39, 0.92);
    let front_left = img.mean_frac(0.18, 0.95, 0.23, 0.99);
    let front_right = img.mean_frac(0.77, 0.95, 0.82, 0.99);
    let y = |c: [f64; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    assert!(
        y(under_light) > y(front_left) + 10.0 && y(under_light) > y(front_right) + 10.0,
        "floor under the light {under_light:?}, front corners {front_left:?} {front_right:?}"
    );
}

/// Without `-S` or `-R` the image is `cornell_box.png` in the current folder.
#[test]
fn builtin_scene_writes_cornell_box_png_in_the_current_folder() {
    let dir = temp_dir();
    render_in(dir.path(), ["-W", "40", "-H", "30"]).assert_ok();
    let img = read_png(&dir.path().join("cornell_box.png"));
    assert_eq!((img.width, img.height), (40, 30));
}

/// Without the subcommand `raygine` opens the viewer; with no display it says so on one line
/// and exits non-zero instead of panicking.
#[test]
fn viewer_without_a_display_fails_cleanly() {
    let dir = temp_dir();
    let out = std::process::Command::new(raygine_e2e::raygine_exe())
        .arg("--no-restore")
        .current_dir(dir.path())
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env("XDG_RUNTIME_DIR", dir.path())
        .output()
        .unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("cannot open the viewer window"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// `-A` is 16 samples: the same image as `--samples 16`, different from 1 sample, with softer
/// edges (more distinct grey levels across the silhouettes).
#[test]
fn antialiasing_is_16_samples_and_softens_edges() {
    let dir = temp_dir();
    let p = |name: &str| dir.path().join(name);
    let size = ["-W", "160", "-H", "120"];
    let run = |extra: &[&str], out: &str| {
        let mut args: Vec<String> = size.iter().map(|s| s.to_string()).collect();
        args.extend(extra.iter().map(|s| s.to_string()));
        args.push("-R".into());
        args.push(p(out).display().to_string());
        render_in(dir.path(), args).assert_ok();
        read_png(&p(out))
    };
    let one = run(&[], "one.png");
    let aa = run(&["-A"], "aa.png");
    let sixteen = run(&["--samples", "16"], "sixteen.png");
    assert_eq!(aa, sixteen, "-A must be --samples 16");
    assert_ne!(aa, one);
    // Colours per pixel over the whole image: 16 samples blend edges into in-between values.
    let distinct = |img: &raygine_e2e::Rgb8| {
        let mut v: Vec<[u8; 3]> = img.pixels.clone();
        v.sort_unstable();
        v.dedup();
        v.len()
    };
    assert!(
        distinct(&aa) as f64 > 1.2 * distinct(&one) as f64,
        "distinct colours: 16 spp {} vs 1 spp {}",
        distinct(&aa),
        distinct(&one)
    );
    // Along a row crossing the left wall's front edge the AA image has in-between values.
    let row = 60;
    let edge_levels = |img: &raygine_e2e::Rgb8| {
        let mut reds: Vec<u8> = (0..40).map(|x| img.at(x, row)[0]).collect();
        reds.sort_unstable();
        reds.dedup();
        reds.len()
    };
    assert!(
        edge_levels(&aa) >= edge_levels(&one),
        "{} vs {}",
        edge_levels(&aa),
        edge_levels(&one)
    );
}

/// One thread and two threads give byte-identical PNG files.
#[test]
fn thread_count_does_not_change_the_image() {
    let dir = temp_dir();
    let mut files = Vec::new();
    for threads in ["1", "2", "3"] {
        let out = dir.path().join(format!("t{threads}.png"));
        let out_s = out.display().to_string();
        render_in(
            dir.path(),
            [
                "-W",
                "96",
                "-H",
                "72",
                "--samples",
                "4",
                "--threads",
                threads,
                "-R",
                &out_s,
            ],
        )
        .assert_ok();
        files.push(std::fs::read(&out).unwrap());
    }
    assert!(
        files[0] == files[1] && files[1] == files[2],
        "PNG bytes differ between thread counts"
    );
}

/// A light outside the box leaves every pixel at 0 cd/m²: the command says so on stderr (and
/// names the light outside the bounds); a lit image gets no such warning.
#[test]
fn an_all_zero_image_is_warned_about() {
    let dir = temp_dir();
    let out = dir.path().join("dark.png");
    let run = render_in(
        dir.path(),
        ["-W", "64", "-H", "48", "-R"]
            .map(Into::into)
            .into_iter()
            .chain([out.clone().into_os_string()])
            .chain(["--", "-5000", "270", "-280"].map(Into::into)),
    );
    run.assert_ok();
    assert!(
        run.stderr
            .contains("warning: every pixel is 0 cd/m²: no light reaches what the camera sees"),
        "stderr: {}",
        run.stderr
    );
    assert!(run.stderr.contains("light 1"), "stderr: {}", run.stderr);

    let lit = dir.path().join("lit.png");
    let run = render_in(
        dir.path(),
        ["-W", "64", "-H", "48", "-R"]
            .map(Into::into)
            .into_iter()
            .chain([lit.into_os_string()]),
    );
    run.assert_ok();
    assert!(
        !run.stderr.contains("every pixel is 0"),
        "stderr: {}",
        run.stderr
    );
}
