//! Adaptive sampling: splats normalised by the film's light subpaths (a furnace's exact answer
//! in pixels of very different counts), every pixel's sums equal to its samples 0..n traced one
//! by one, threads changing nothing, samples going where the error is, a target error reached,
//! and the bias of choosing counts measured against the same samples taken uniformly.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::gi_support::*;
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::adaptive::{Stop, render_adaptive, worst_relative_error};
use tracer_core::render::{Film, FrameSampler, PixelSum, RenderSettings, render_pixels};
use tracer_core::scene::builtin_cornell_box;

fn settings(kind: IntegratorKind, w: u32, h: u32, cap: u32) -> RenderSettings {
    RenderSettings {
        width: w,
        height: h,
        samples_per_pixel: cap,
        integrator: kind,
        pixel_illuminance: false,
        ..RenderSettings::default()
    }
}

/// The built-in box, with its light at y = 500 mm (BENCHMARK.md E3, where path tracing
/// converges) when `lowered`.
fn cornell(lowered: bool) -> tracer_core::scene::LoadedScene {
    let mut loaded = builtin_cornell_box(None).unwrap();
    if lowered {
        loaded.setup.lights[0].position[1] = 500.0;
    }
    loaded
}

fn adaptive_on_threads(
    kind: IntegratorKind,
    w: u32,
    h: u32,
    target: f64,
    threads: usize,
) -> (Film, f64) {
    adaptive_capped(kind, w, h, target, threads, 256)
}

fn adaptive_capped(
    kind: IntegratorKind,
    w: u32,
    h: u32,
    target: f64,
    threads: usize,
    cap: u32,
) -> (Film, f64) {
    // Path tracing meets the light hanging 0.1 mm under the ceiling too rarely (BENCHMARK.md).
    let loaded = cornell(kind == IntegratorKind::Path);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let stop = Stop {
        target_error: Some(target),
        ..Stop::default()
    };
    let (film, stats) = pool.install(|| {
        render_adaptive(
            &loaded.scene,
            &loaded.setup,
            &settings(kind, w, h, cap),
            stop,
            &mut |_| {},
        )
    });
    (film, stats.mean_samples_per_pixel)
}

/// Pixels of 32, 64, 96 and 128 samples side by side in a furnace (every surface emits Le and
/// reflects ρ: L = Le / (1 − ρ) everywhere). The splats come from every pixel's light subpaths:
/// divided by each receiving pixel's own count, the 32-sample pixels would read 2.5 times their
/// splat share, the 128-sample ones 0.625 times.
#[test]
fn splats_are_normalised_by_the_films_light_subpaths_not_the_pixels_count() {
    let sc = box_scene(2.0, 2.0, 2.0, vec![]);
    let (le, rho) = (100.0f32, 0.5f32);
    let exact = f64::from(le) / (1.0 - f64::from(rho));
    let cam = camera([1.0, 1.0, 1.5], [1.0, 1.0, 0.0], 70.0);
    let st = setup(&sc, cam, vec![], vec![emitting(diffuse(rho), le); 6]);
    for kind in [IntegratorKind::Bidirectional, IntegratorKind::Light] {
        let s = settings(kind, 16, 16, 64);
        let class = |i: usize| (i % 4) as u32;
        let batches = 8u32;
        let mut means = vec![[0.0f64; 4]; batches as usize];
        for b in 0..batches {
            let start = b * 1000;
            let ranges = move |i: usize| start..start + 32 * (class(i) + 1);
            let (film, _) = render_pixels(&sc, &st, &s, &ranges);
            assert_eq!(film.splat_paths, Some(80.0), "{kind}");
            let mut n = [0.0f64; 4];
            for i in 0..film.len() {
                means[b as usize][class(i) as usize] += film.mean_luminance(i);
                n[class(i) as usize] += 1.0;
            }
            for c in 0..4 {
                means[b as usize][c] /= n[c];
            }
        }
        for c in 0..4 {
            let values: Vec<f64> = means.iter().map(|m| m[c]).collect();
            let mean = values.iter().sum::<f64>() / f64::from(batches);
            let var =
                values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / f64::from(batches - 1);
            let se = (var / f64::from(batches)).sqrt();
            let what = format!("{kind} furnace, pixels of {} samples", 32 * (c + 1));
            // Wrong normalisation is off by tens of per cent; light tracing is the noisier.
            let (tol, max_se) = match kind {
                IntegratorKind::Light => (0.03, 0.015),
                _ => (0.02, 0.008),
            };
            check(&what, mean, se, exact, tol, max_se);
        }
    }
}

/// Under a target error the render is deterministic: every pixel's sums are exactly those of
/// its samples 0..n traced one by one, and one thread gives the film two give.
#[test]
fn adaptive_films_are_their_pixels_samples_and_do_not_depend_on_threads() {
    let loaded = cornell(true);
    let (film, mean_spp) = adaptive_on_threads(IntegratorKind::Path, 40, 30, 0.1, 2);
    let counts: Vec<u32> = film.counts().collect();
    let (lo, hi) = (*counts.iter().min().unwrap(), *counts.iter().max().unwrap());
    println!("path, target 10 %: {mean_spp:.1} spp on average, {lo} to {hi}");
    assert!(lo >= 16 && hi > 2 * lo, "counts {lo}..{hi}");
    let frame = FrameSampler::new(
        &loaded.scene,
        &loaded.setup,
        &settings(IntegratorKind::Path, 40, 30, 256),
    );
    let mut splats = Vec::new();
    for y in 0..30 {
        for x in 0..40 {
            let i = film.index(x, y);
            let mut sum = PixelSum::default();
            frame.add_samples(x, y, 0..counts[i], &mut sum, &mut splats);
            assert_eq!(sum, film.pixel(i), "pixel ({x}, {y})");
        }
    }
    for kind in [IntegratorKind::Path, IntegratorKind::Bidirectional] {
        let (one, _) = adaptive_on_threads(kind, 24, 18, 0.2, 1);
        let (two, _) = adaptive_on_threads(kind, 24, 18, 0.2, 2);
        assert_eq!(
            one.pixels().collect::<Vec<_>>(),
            two.pixels().collect::<Vec<_>>(),
            "{kind}"
        );
        assert_eq!(one.splat_paths, two.splat_paths, "{kind}");
    }
}

/// A target error is met by every pixel but the 0.5 % brightest, with fewer samples than the
/// same target needs when every pixel gets the worst pixel's count.
#[test]
fn a_target_error_is_reached_where_it_is_needed() {
    let (film, mean_spp) = adaptive_capped(IntegratorKind::Bidirectional, 32, 24, 0.2, 2, 2048);
    let worst = worst_relative_error(&film);
    let hi = film.counts().max().unwrap();
    println!(
        "bdpt, target 20 %: worst {:.2} %, {mean_spp:.1} spp on average, at most {hi}",
        worst * 100.0
    );
    assert!(worst <= 0.2, "worst pixel {:.2} %", worst * 100.0);
    assert!(
        mean_spp < 0.75 * f64::from(hi),
        "{mean_spp} spp on average, {hi} at most: no adaptivity"
    );
}

/// The bias of choosing counts: each pixel's adaptive mean (its samples 0..n) against its mean
/// over samples 0..256, the same streams, so that the noise mostly cancels. Without bias the
/// difference averages to 0 within its standard error.
#[test]
fn choosing_counts_from_the_neighbours_does_not_bias_the_mean() {
    let (bias, se) = bias_against_uniform(IntegratorKind::Path, true, 48, 36, 600.0, 256);
    assert!(bias.abs() < 4.0 * se + 1e-4, "bias {bias} ± {se}");
}

/// The same at BENCHMARK.md's sizes, G1 (bdpt) and E3 (path), 160x120: slow in a debug build,
/// run with `cargo test --release -- --ignored bias_at_g1_and_e3 --nocapture`.
#[test]
#[ignore = "a measurement (about a minute in release); its figures are in the README"]
fn bias_at_g1_and_e3() {
    for (kind, lowered) in [
        (IntegratorKind::Bidirectional, false),
        (IntegratorKind::Path, true),
    ] {
        let (bias, se) = bias_against_uniform(kind, lowered, 160, 120, 512.0, 256);
        assert!(bias.abs() < 4.0 * se + 1e-4, "bias {bias} ± {se}");
    }
}

/// Renders adaptively to `mean` samples per pixel and returns (adaptive − uniform) / uniform of
/// the picture's mean luminance, and its standard error, the uniform film being every pixel's
/// samples 0..m.
fn bias_against_uniform(
    kind: IntegratorKind,
    lowered: bool,
    w: u32,
    h: u32,
    mean: f64,
    m: u32,
) -> (f64, f64) {
    let loaded = cornell(lowered);
    let stop = Stop {
        mean_samples: Some(mean),
        ..Stop::default()
    };
    let s = settings(kind, w, h, 4096);
    let (film, _) = render_adaptive(&loaded.scene, &loaded.setup, &s, stop, &mut |_| {});
    // Every pixel's samples 0..m: nested with its adaptive samples 0..n either way.
    let n_max = film.counts().max().unwrap();
    let uniform = render_pixels(&loaded.scene, &loaded.setup, &s, &|_| 0..m).0;
    let (mut diff, mut var, mut level) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..film.len() {
        let (a, u) = (film.mean_luminance(i), uniform.mean_luminance(i));
        diff += a - u;
        level += u;
        // Var(mean of n − mean of m) = σ² |1/n − 1/m| for nested samples (own samples); the
        // splat parts of the two films are counted as independent, which errs on the large
        // side (they share the light subpaths of the samples both have).
        let sigma2 = uniform.pixel(i).own_luminance_variance().unwrap();
        let n = f64::from(film.count(i));
        var += sigma2 * (1.0 / n - 1.0 / f64::from(m)).abs();
        var += uniform.luminance_std_error(i).unwrap().powi(2)
            - uniform.pixel(i).own_luminance_variance().unwrap() / f64::from(m);
        var += film.luminance_std_error(i).unwrap().powi(2)
            - film.pixel(i).own_luminance_variance().unwrap() / n;
    }
    let bias = diff / level;
    let se = var.max(0.0).sqrt() / level;
    let spread = film.counts().min().unwrap();
    println!(
        "{kind} {w}x{h}: adaptive − uniform {:+.4} % ± {:.4} % of the mean ({mean} spp on \
         average, {spread} to {n_max}; uniform {m})",
        bias * 100.0,
        se * 100.0,
    );
    assert!(
        spread < m / 4 && n_max > 2 * m,
        "counts {spread}..{n_max}: nothing adaptive to test"
    );
    (bias, se)
}
