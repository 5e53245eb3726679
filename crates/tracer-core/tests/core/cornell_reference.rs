//! The built-in Cornell box in path mode against an independent renderer: Mitsuba 3.9.1's light
//! tracer (`ptracer`, max_depth −1, 8192 spp, llvm_ad_rgb, seed 3), rendered from the same
//! triangles, reflectances, light and camera by `scripts/mitsuba/cornell_scene.py` and mirrored
//! to raygine's left-handed view. The light is moved 49 mm under the ceiling (y = 500 mm):
//! at its usual 0.1 mm a camera-side path tracer converges far too slowly (part 2's issue).
//! Reference luminance means (cd/m², Rec. 709 Y) over pixel boxes at 160x120; the reference's
//! own noise on each is below 0.1 %.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use tracer_core::integrator::IntegratorKind;
use tracer_core::render::{RenderSettings, render};
use tracer_core::scene::builtin_cornell_box;

/// (name, x0, x1, y0, y1 half-open, Mitsuba's mean Y in cd/m²).
const REGIONS: [(&str, u32, u32, u32, u32, f64); 5] = [
    ("red wall", 26, 42, 32, 88, 68.863),
    ("green wall", 120, 134, 32, 88, 140.585),
    ("floor", 40, 74, 106, 116, 164.348),
    ("ceiling", 50, 110, 6, 20, 896.548),
    ("back wall", 50, 108, 32, 48, 390.452),
];
const IMAGE_MEAN: f64 = 135.099;

#[test]
fn cornell_box_regions_match_mitsubas_light_tracer() {
    let mut loaded = builtin_cornell_box(None).unwrap();
    loaded.setup.lights[0].position[1] = 500.0;
    let settings = RenderSettings {
        width: 160,
        height: 120,
        samples_per_pixel: 256,
        integrator: IntegratorKind::Path,
        ..RenderSettings::default()
    };
    let (film, stats) = render(&loaded.scene, &loaded.setup, &settings);
    println!(
        "{:.2} Mrays/s, {:.1} s",
        stats.mrays_per_sec(),
        stats.elapsed_secs
    );
    let mut all = 0.0;
    for p in film.pixels() {
        all += p.mean_luminance();
    }
    let all = all / film.len() as f64;
    println!("image mean {all:.3} vs Mitsuba {IMAGE_MEAN}");
    assert!((all / IMAGE_MEAN - 1.0).abs() < 0.01);
    for (name, x0, x1, y0, y1, reference) in REGIONS {
        let (mut sum, mut var, mut n) = (0.0, 0.0, 0.0);
        for y in y0..y1 {
            for x in x0..x1 {
                let p = &film.pixel(film.index(x, y));
                sum += p.mean_luminance();
                var += p.luminance_std_error().unwrap().powi(2);
                n += 1.0;
            }
        }
        let (mean, se) = (sum / n, var.sqrt() / n);
        println!(
            "{name}: {mean:.3} ± {se:.3} cd/m² vs Mitsuba {reference} ({:+.2} %)",
            (mean / reference - 1.0) * 100.0
        );
        // Four of our standard errors plus 0.3 % for the reference's own noise.
        assert!(
            (mean - reference).abs() < 4.0 * se + 0.003 * reference,
            "{name}: {mean} vs {reference}"
        );
    }
}
