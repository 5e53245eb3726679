//! The standard errors the film reports are the errors it has. A render is split into K
//! disjoint sample ranges (as shards split it); the spread of each pixel's K range means is a
//! direct measurement of a range's error, independent of the film's own estimate. For every
//! integrator, the reported standard error of a range's pixels (splats included) must match
//! that spread within 15 % (root mean square over the pixels).
//!
//! Direct light is the exception, and the test says by how much: with point lights its only
//! randomness is where in the pixel a sample lies, and those positions follow a low-discrepancy
//! sequence, which errs less than independent samples would. The film's estimate assumes
//! independent samples, so in direct mode it is an upper bound (here about 1.9 times the
//! measured error); it must never be below the measured error.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use tracer_core::integrator::IntegratorKind;
use tracer_core::render::{RenderSettings, render_samples};
use tracer_core::scene::{Scene, Setup, builtin_cornell_box};

/// Ranges a render is split into.
const RANGES: u32 = 12;

/// The measured and the reported RMS standard error of one range's pixel means (cd/m²), over
/// the pixels left after removing the 0.5 % brightest (a hot spot's few pixels would stand for
/// the whole picture) and those no range saw anything in.
fn measured_and_reported(
    scene: &Scene,
    setup: &Setup,
    settings: &RenderSettings,
    per_range: u32,
) -> (f64, f64) {
    // Sample 0 sits at the pixel centre (and takes a cheaper roulette in path mode): the
    // ranges start after it, so that all are alike.
    let films: Vec<_> = (0..RANGES)
        .map(|k| {
            let start = 1 + k * per_range;
            render_samples(scene, setup, settings, start..start + per_range).0
        })
        .collect();
    let pixels = films[0].len();
    let k = f64::from(RANGES);
    let mut rows: Vec<(f64, f64, f64)> = (0..pixels)
        .map(|i| {
            let means: Vec<f64> = films.iter().map(|f| f.pixel(i).mean_luminance()).collect();
            let mean = means.iter().sum::<f64>() / k;
            let spread = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (k - 1.0);
            let reported = films
                .iter()
                .map(|f| f.pixel(i).luminance_std_error().unwrap().powi(2))
                .sum::<f64>()
                / k;
            (mean, spread, reported)
        })
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    rows.truncate(pixels - pixels / 200);
    rows.retain(|r| r.0 > 0.0);
    let n = rows.len() as f64;
    let measured = (rows.iter().map(|r| r.1).sum::<f64>() / n).sqrt();
    let reported = (rows.iter().map(|r| r.2).sum::<f64>() / n).sqrt();
    (measured, reported)
}

fn check(what: &str, scene: &Scene, setup: &Setup, kind: IntegratorKind, per_range: u32) {
    check_within(what, scene, setup, kind, per_range, 0.85..1.15);
}

fn check_within(
    what: &str,
    scene: &Scene,
    setup: &Setup,
    kind: IntegratorKind,
    per_range: u32,
    ratios: std::ops::Range<f64>,
) {
    let settings = RenderSettings {
        width: 32,
        height: 24,
        integrator: kind,
        pixel_illuminance: false,
        ..RenderSettings::default()
    };
    let (measured, reported) = measured_and_reported(scene, setup, &settings, per_range);
    let ratio = reported / measured;
    println!(
        "{what}, {kind}: {RANGES} ranges of {per_range} samples: measured RMS error {measured:.4} cd/m², reported {reported:.4} (ratio {ratio:.3})"
    );
    assert!(
        ratios.contains(&ratio),
        "{what}, {kind}: reported standard error {reported} against a measured {measured}"
    );
}

/// The built-in box with its light 49 mm under the ceiling, where every integrator converges.
#[test]
fn reported_errors_match_the_spread_of_ranges_light_lowered() {
    let mut loaded = builtin_cornell_box(None).unwrap();
    loaded.setup.lights[0].position[1] = 500.0;
    for (kind, per) in [
        (IntegratorKind::Path, 32),
        (IntegratorKind::Bidirectional, 16),
        (IntegratorKind::Light, 32),
    ] {
        check("light at 500 mm", &loaded.scene, &loaded.setup, kind, per);
    }
    let (scene, setup) = (&loaded.scene, &loaded.setup);
    check_within(
        "light at 500 mm",
        scene,
        setup,
        IntegratorKind::Direct,
        16,
        0.85..2.5,
    );
}

/// The built-in box as it is (the light 0.1 mm under the ceiling), where light subpaths carry
/// most of the light: the splats' share of the error is most of it.
#[test]
fn reported_errors_match_the_spread_of_ranges_with_splats() {
    let loaded = builtin_cornell_box(None).unwrap();
    for (kind, per) in [
        (IntegratorKind::Bidirectional, 16),
        (IntegratorKind::Light, 32),
    ] {
        check("built-in box", &loaded.scene, &loaded.setup, kind, per);
    }
}
