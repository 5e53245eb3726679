//! `--denoise` through the real binary: without the library it says why and writes nothing;
//! with it the PNG is denoised while the EXR's R, G, B, the printed figures and merged shards
//! stay the raw film's, bit for bit. Tests that need Open Image Denoise skip with the reason
//! without it, and fail under CI (RAYGINE_REQUIRE_OIDN=1, set by check.sh).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use raygine_e2e::{Run, raygine_exe, raygine_in, render_in, temp_dir};
use std::path::Path;

const OPTS: [&str; 10] = [
    "--gi",
    "bdpt",
    "--samples",
    "4",
    "-W",
    "48",
    "-H",
    "36",
    "--exposure",
    "-1",
];

fn with_env(dir: &Path, var: &str, value: &str, args: &[&str]) -> Run {
    std::process::Command::new(raygine_exe())
        .current_dir(dir)
        .env(var, value)
        .args(args)
        .output()
        .expect("cannot start raygine")
        .into()
}

/// Whether the denoiser is there; panics when it must be.
fn have_oidn(dir: &Path) -> bool {
    let run = render_in(dir, ["--denoise", "-W", "8", "-H", "6", "-R", "probe.png"]);
    if run.success() {
        return true;
    }
    assert!(
        std::env::var_os("RAYGINE_REQUIRE_OIDN").is_none(),
        "RAYGINE_REQUIRE_OIDN is set and --denoise failed: {}",
        run.stderr
    );
    eprintln!("skipped: {}", run.stderr.trim());
    false
}

/// Channel name to samples of an EXR's first layer.
fn exr_channels(path: &Path) -> Vec<(String, Vec<f32>)> {
    let image = exr::prelude::read_all_flat_layers_from_file(path).unwrap();
    image.layer_data[0]
        .channel_data
        .list
        .iter()
        .map(|c| {
            let v = match &c.sample_data {
                exr::prelude::FlatSamples::F32(v) => v.clone(),
                other => panic!("{}: not f32: {other:?}", c.name),
            };
            (c.name.to_string(), v)
        })
        .collect()
}

fn channel<'a>(channels: &'a [(String, Vec<f32>)], name: &str) -> &'a [f32] {
    &channels
        .iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no channel {name}"))
        .1
}

/// Lines of the summary that carry figures (not timings).
fn figures(stdout: &str) -> Vec<String> {
    stdout
        .lines()
        .filter(|l| l.starts_with("remaining noise") || l.contains("luminance mean"))
        .map(|l| l.split("; luminance").nth(1).unwrap_or(l).to_owned())
        .collect()
}

#[test]
fn off_says_why_and_writes_nothing() {
    let dir = temp_dir();
    let d = dir.path();
    let run = with_env(
        d,
        "RAYGINE_OIDN",
        "off",
        &["render", "--denoise", "-W", "8", "-H", "6", "-R", "x.png"],
    );
    assert!(!run.success());
    assert!(
        run.stderr
            .contains("--denoise: the denoiser is off (RAYGINE_OIDN=off)"),
        "{}",
        run.stderr
    );
    assert!(!d.join("x.png").exists());
    // A library that is not there: the path and the way to install one.
    let run = with_env(
        d,
        "RAYGINE_OIDN",
        "/nonexistent/libOpenImageDenoise.so.2",
        &["render", "--denoise", "-W", "8", "-H", "6", "-R", "x.png"],
    );
    assert!(!run.success());
    assert!(
        run.stderr.contains("/nonexistent/libOpenImageDenoise.so.2")
            && run.stderr.contains("pip install pyoidn"),
        "{}",
        run.stderr
    );
    assert!(!d.join("x.png").exists());
    // Without --denoise nothing changes.
    with_env(
        d,
        "RAYGINE_OIDN",
        "off",
        &["render", "-W", "8", "-H", "6", "-R", "x.png"],
    )
    .assert_ok();
}

#[test]
fn the_png_is_denoised_and_the_raw_layers_and_figures_stay_bit_identical() {
    let dir = temp_dir();
    let d = dir.path();
    if !have_oidn(d) {
        return;
    }
    let mut raw_args = OPTS.to_vec();
    raw_args.extend(["-R", "raw.png", "--exr", "raw.exr"]);
    let raw = render_in(d, &raw_args);
    raw.assert_ok();
    let mut den_args = OPTS.to_vec();
    den_args.extend(["-R", "den.png", "--exr", "den.exr", "--denoise"]);
    let den = render_in(d, &den_args);
    den.assert_ok();
    assert!(den.stdout.contains("denoised in"), "{}", den.stdout);
    assert_eq!(figures(&raw.stdout), figures(&den.stdout));
    assert!(!figures(&raw.stdout).is_empty(), "{}", raw.stdout);
    let (a, b) = (
        exr_channels(&d.join("raw.exr")),
        exr_channels(&d.join("den.exr")),
    );
    for c in ["R", "G", "B"] {
        let (x, y) = (channel(&a, c), channel(&b, c));
        assert!(
            x.iter().zip(y).all(|(p, q)| p.to_bits() == q.to_bits()),
            "raw channel {c} differs with --denoise"
        );
    }
    assert_eq!(a.len(), 3, "the raw EXR has only R, G, B");
    let denoised_g = channel(&b, "denoised.G");
    assert_eq!(denoised_g.len(), 48 * 36);
    assert!(denoised_g != channel(&b, "G"), "denoised.G is the raw G");
    // The PNG shows the denoised picture: smoother than the raw one (fewer pixel-to-pixel
    // jumps on the walls).
    let roughness = |p: &str| {
        let img = image::open(d.join(p)).unwrap().to_luma8();
        let (w, h) = img.dimensions();
        let mut sum = 0u64;
        for y in 0..h {
            for x in 1..w {
                sum += u64::from(img.get_pixel(x, y)[0].abs_diff(img.get_pixel(x - 1, y)[0]));
            }
        }
        sum
    };
    let (r_raw, r_den) = (roughness("raw.png"), roughness("den.png"));
    assert!(r_den * 2 < r_raw, "denoised {r_den} vs raw {r_raw}");
}

#[test]
fn merge_denoises_parts_rendered_with_guides_and_refuses_parts_without() {
    let dir = temp_dir();
    let d = dir.path();
    if !have_oidn(d) {
        return;
    }
    let part = |k: &str, extra: &[&str]| {
        // (Parts take no display options: merge does.)
        let mut args = OPTS[..8].to_vec();
        args.extend(["--shard-index", k, "--shard-count", "2"]);
        let name = format!("p{k}{}.part", extra.len());
        args.extend(["--partial", &name]);
        args.extend(extra);
        render_in(d, &args).assert_ok();
        name
    };
    let guided = [part("0", &["--denoise"]), part("1", &["--denoise"])];
    let run = raygine_in(
        d,
        [
            "merge",
            &guided[0],
            &guided[1],
            "-R",
            "m.png",
            "--exr",
            "m.exr",
            "--denoise",
            "--exposure",
            "-1",
        ],
    );
    run.assert_ok();
    assert!(run.stdout.contains("denoised in"), "{}", run.stdout);
    // The same as one denoised render of all samples, byte for byte: guides add exactly.
    let mut one = OPTS.to_vec();
    one.extend(["-R", "one.png", "--exr", "one.exr", "--denoise"]);
    render_in(d, &one).assert_ok();
    assert_eq!(
        std::fs::read(d.join("m.png")).unwrap(),
        std::fs::read(d.join("one.png")).unwrap()
    );
    let plain = [part("0", &[]), part("1", &[])];
    let run = raygine_in(
        d,
        ["merge", &plain[0], &plain[1], "-R", "n.png", "--denoise"],
    );
    assert!(!run.success());
    assert!(run.stderr.contains("no denoiser guides"), "{}", run.stderr);
    assert!(!d.join("n.png").exists());
}
