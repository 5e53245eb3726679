//! The denoiser's guides and the denoised picture.
//!
//! Guides are checked against what the scene says (the material's reflectance, the wall's
//! normal), and for exactness (thread counts, shards, no change to the film's sums). The
//! denoiser is checked against a converged image: at few samples its picture must be much
//! closer to it than the raw one. Those tests need Open Image Denoise: they skip with the
//! reason without it, and fail instead under CI (RAYGINE_REQUIRE_OIDN=1, set by check.sh).

use crate::gi_support::render_on_threads;
use glam::Vec3;
use tracer_core::denoise::{Denoiser, Quality, denoise_film};
use tracer_core::integrator::IntegratorKind;
use tracer_core::light::LUMINANCE_WEIGHTS;
use tracer_core::render::{RenderSettings, render_samples};
use tracer_core::scene::builtin_cornell_box;

fn settings(width: u32, height: u32, spp: u32, guides: bool) -> RenderSettings {
    RenderSettings {
        width,
        height,
        samples_per_pixel: spp,
        integrator: IntegratorKind::Bidirectional,
        pixel_illuminance: false,
        guides,
        ..RenderSettings::default()
    }
}

fn denoiser() -> Option<Denoiser> {
    match Denoiser::load(2) {
        Ok(d) => Some(d),
        Err(e) if std::env::var_os("RAYGINE_REQUIRE_OIDN").is_some() => {
            panic!("RAYGINE_REQUIRE_OIDN is set and {e}")
        }
        Err(e) => {
            eprintln!("skipped: {e}");
            None
        }
    }
}

#[test]
fn guides_change_no_sum_and_are_exact_across_threads_and_shards() {
    let b = builtin_cornell_box(None).unwrap();
    let (scene, setup) = (&b.scene, &b.setup);
    let with = settings(40, 30, 4, true);
    let one = render_on_threads(scene, setup, &with, 1);
    let two = render_on_threads(scene, setup, &with, 2);
    assert!(one.guides.is_some());
    assert_eq!(one, two, "guides or sums depend on the thread count");
    let without = render_on_threads(scene, setup, &settings(40, 30, 4, false), 2);
    assert!(without.guides.is_none());
    assert_eq!(
        one.pixels().collect::<Vec<_>>(),
        without.pixels().collect::<Vec<_>>(),
        "tracing guides changed the film's sums"
    );
    let (mut merged, _) = render_samples(scene, setup, &with, 0..1);
    let (rest, _) = render_samples(scene, setup, &with, 1..4);
    merged.merge(&rest).unwrap();
    assert_eq!(merged, one, "shards' guides do not add up to the whole");
    // A shard without guides leaves none: guides of some samples only would be wrong.
    let (no_guides, _) = render_samples(scene, setup, &settings(40, 30, 4, false), 1..4);
    let (mut part, _) = render_samples(scene, setup, &with, 0..1);
    part.merge(&no_guides).unwrap();
    assert!(part.guides.is_none());
}

#[test]
fn guides_hold_the_material_reflectance_and_the_wall_normal() {
    let b = builtin_cornell_box(None).unwrap();
    let (scene, setup) = (&b.scene, &b.setup);
    let (w, h) = (40, 30);
    let film = render_on_threads(scene, setup, &settings(w, h, 8, true), 2);
    let guides = film.guides.as_ref().unwrap();
    let basis = setup.camera.basis(setup.handedness, w, h);
    // The pixel in the middle of the picture sees the back wall, head on.
    let (x, y) = (w / 2, h / 2);
    let centre = basis.ray(x as f32 + 0.5, y as f32 + 0.5).unwrap();
    let hidden = vec![false; setup.materials.len()];
    let slot = scene.pick_slot(&centre, &hidden).expect("the back wall") as usize;
    let kd = Vec3::from(setup.materials[slot].kd);
    let i = (y * w + x) as usize;
    let albedo = guides.pixels[i].mean_albedo();
    assert!(
        (albedo - kd).abs().max_element() < 1e-4,
        "albedo {albedo} where the material says Kd {kd}"
    );
    let normal = guides.pixels[i].mean_normal();
    let towards_camera = -centre.dir.normalize();
    assert!(
        normal.dot(towards_camera) > 0.97,
        "normal {normal} does not face the camera ({towards_camera})"
    );
}

/// Relative RMS error of luminance against `reference`, leaving out the 0.5 % brightest
/// reference pixels (the lamp's hot spot), as BENCHMARK.md measures pictures.
fn rel_rmse(image: &[Vec3], reference: &[Vec3]) -> f64 {
    let y = |v: &Vec3| f64::from(v.dot(LUMINANCE_WEIGHTS));
    let mut refs: Vec<f64> = reference.iter().map(y).collect();
    let keep = refs.len() - refs.len() / 200;
    let cut = *refs.select_nth_unstable_by(keep - 1, f64::total_cmp).1;
    let (mut se, mut sum, mut n) = (0.0, 0.0, 0.0);
    for (a, r) in image.iter().zip(reference) {
        if y(r) <= cut {
            se += (y(a) - y(r)).powi(2);
            sum += y(r);
            n += 1.0;
        }
    }
    (se / n).sqrt() / (sum / n)
}

#[test]
fn the_denoised_picture_is_much_closer_to_the_converged_one_than_the_raw() {
    let Some(d) = denoiser() else {
        return;
    };
    let b = builtin_cornell_box(None).unwrap();
    let (scene, setup) = (&b.scene, &b.setup);
    let (w, h) = (80, 60);
    let reference = render_on_threads(scene, setup, &settings(w, h, 256, false), 2);
    let noisy = render_on_threads(scene, setup, &settings(w, h, 4, true), 2);
    let denoised = denoise_film(&d, &noisy, Quality::High).unwrap();
    let truth = reference.mean_rgb_all();
    let raw_error = rel_rmse(&noisy.mean_rgb_all(), &truth);
    let denoised_error = rel_rmse(&denoised, &truth);
    let reference_noise = reference.relative_noise().unwrap();
    eprintln!(
        "4 spp: raw {:.1} %, denoised {:.1} % (reference: 256 spp, noise {:.1} %)",
        raw_error * 100.0,
        denoised_error * 100.0,
        reference_noise * 100.0
    );
    assert!(
        denoised_error < 0.5 * raw_error,
        "denoised {denoised_error} vs raw {raw_error}"
    );
    // Denoising only the picture: the film is untouched.
    assert_eq!(
        noisy.pixels().collect::<Vec<_>>(),
        render_on_threads(scene, setup, &settings(w, h, 4, false), 2)
            .pixels()
            .collect::<Vec<_>>()
    );
}

#[test]
fn the_balanced_quality_and_prefiltered_guides_give_a_picture_too() {
    let Some(d) = denoiser() else {
        return;
    };
    assert!(d.version() >= tracer_core::denoise::MIN_VERSION);
    let b = builtin_cornell_box(None).unwrap();
    let film = render_on_threads(&b.scene, &b.setup, &settings(32, 24, 2, true), 2);
    let out = denoise_film(&d, &film, Quality::Balanced).unwrap();
    assert_eq!(out.len(), 32 * 24);
    assert!(out.iter().all(|p| p.is_finite() && p.min_element() >= 0.0));
    let mean = out
        .iter()
        .map(|p| f64::from(p.dot(LUMINANCE_WEIGHTS)))
        .sum::<f64>()
        / 768.0;
    let raw = film.mean_rgb_all();
    let raw_mean = raw
        .iter()
        .map(|p| f64::from(p.dot(LUMINANCE_WEIGHTS)))
        .sum::<f64>()
        / 768.0;
    // The denoiser keeps the picture's brightness (a loose bound: 2 spp are noisy).
    assert!((mean / raw_mean - 1.0).abs() < 0.25, "{mean} vs {raw_mean}");
    // Mismatched sizes are an error, not a crash.
    let wrong = film.mean_rgb_all();
    let err = d
        .denoise(
            &tracer_core::denoise::Images {
                width: 31,
                height: 24,
                color: &wrong,
                albedo: &wrong,
                normal: &wrong,
            },
            Quality::High,
        )
        .unwrap_err();
    assert!(err.to_string().contains("do not match"), "{err}");
}
