//! The film's standard errors in dim scenes and its exactness at a lamp's hot spot.
//!
//! Scale invariance is the answer a dim furnace is checked against: a furnace whose surfaces
//! emit 10⁻³ or 10⁻⁴ cd/m² draws the same random paths as one emitting 100 cd/m², every sample
//! scaled by the same factor, so every pixel's relative standard error must be the same. The
//! former squared-luminance unit (2⁻¹⁶ (cd/m²)²) rounded each square of such a furnace to 0 and
//! reported no error at all. The reported error must also match the spread of the pixel means
//! (all pixels of a furnace see the same thing).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::gi_support::*;
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::{Film, RenderSettings, render};

/// Every pixel's mean luminance and standard error (cd/m²) of a path-traced diffuse furnace
/// (ρ 0.5) whose surfaces emit `le` cd/m².
fn furnace(le: f32) -> Vec<(f64, f64)> {
    let sc = box_scene(2.0, 2.0, 2.0, vec![]);
    let mats = vec![emitting(diffuse(0.5), le); 6];
    let cam = camera([1.0, 1.0, 1.5], [1.0, 1.0, 0.0], 70.0);
    let st = setup(&sc, cam, vec![], mats);
    let settings = RenderSettings {
        width: 16,
        height: 16,
        samples_per_pixel: 64,
        integrator: IntegratorKind::Path,
        ..RenderSettings::default()
    };
    let (film, _) = render(&sc, &st, &settings);
    pixels(&film)
}

fn pixels(film: &Film) -> Vec<(f64, f64)> {
    (0..film.len())
        .map(|i| {
            let p = film.pixel(i);
            (p.mean_luminance(), p.luminance_std_error().unwrap())
        })
        .collect()
}

#[test]
fn a_dim_furnace_reports_the_same_relative_error_as_a_bright_one() {
    let bright = furnace(100.0);
    for le in [1.0e-3f32, 1.0e-4] {
        let dim = furnace(le);
        let mut worst = 0.0f64;
        for ((m1, se1), (m2, se2)) in bright.iter().zip(&dim) {
            assert!(*se1 > 0.0 && *m2 > 0.0, "{le}: {m1} {se1} {m2} {se2}");
            let (r1, r2) = (se1 / m1, se2 / m2);
            worst = worst.max((r2 / r1 - 1.0).abs());
        }
        println!(
            "furnace at {le} cd/m² against 100 cd/m²: relative standard errors differ by at \
             most {:.2e} (relative)",
            worst
        );
        assert!(worst < 1e-3, "{le}: {worst}");
        // The reported error is the error: the spread of the 256 pixel means (the same in
        // every pixel of a furnace) against the RMS reported error.
        let n = dim.len() as f64;
        let mean = dim.iter().map(|p| p.0).sum::<f64>() / n;
        let spread = (dim.iter().map(|p| (p.0 - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let reported = (dim.iter().map(|p| p.1 * p.1).sum::<f64>() / n).sqrt();
        println!("  spread of pixel means {spread:.3e}, reported {reported:.3e} cd/m²");
        assert!(
            (spread / reported - 1.0).abs() < 0.15,
            "{le}: spread {spread} reported {reported}"
        );
    }
}

/// The film's compact cells hold the same sums as full-width pixel sums for every sample of
/// the built-in box, whose point light a few millimetres below the ceiling makes a hot spot of
/// about 10⁹-10¹⁰ cd/m² (past a 64-bit sum of 2⁻³² units after one sample): each pixel of a
/// render equals the sum of its samples traced one by one, the hot spot's pixels moved to the
/// wide table, and nothing was rejected. In every integrator (splats included).
#[test]
fn the_built_in_box_hot_spot_stays_exact_in_compact_cells() {
    use tracer_core::render::{FrameSampler, PixelSum, render_samples};
    use tracer_core::scene::builtin_cornell_box;
    let mut loaded = builtin_cornell_box(None).unwrap();
    // The camera looks at the ceiling straight above the light, through a narrow field.
    let light = loaded.setup.lights[0].position;
    let cam = &mut loaded.setup.camera;
    cam.look_at = [light[0], light[1] + 1.0, light[2]];
    cam.fov_deg = 0.05;
    for kind in [
        IntegratorKind::Direct,
        IntegratorKind::Path,
        IntegratorKind::Bidirectional,
        IntegratorKind::Light,
    ] {
        let settings = RenderSettings {
            width: 64,
            height: 48,
            samples_per_pixel: 2,
            integrator: kind,
            ..RenderSettings::default()
        };
        let (film, _) = render_samples(&loaded.scene, &loaded.setup, &settings, 0..2);
        let frame = FrameSampler::new(&loaded.scene, &loaded.setup, &settings);
        let mut splats = Vec::new();
        let mut expected = vec![PixelSum::default(); film.len()];
        let mut brightest = 0.0f64;
        for y in 0..settings.height {
            for x in 0..settings.width {
                let i = film.index(x, y);
                for s in 0..2 {
                    let sample = frame.sample(x, y, s, &mut splats);
                    brightest = brightest.max(f64::from(sample.rgb.max_element()));
                    assert!(expected[i].add(&sample));
                }
            }
        }
        for s in &splats {
            assert!(expected[film.index(s.x, s.y)].add_splat(s.rgb));
        }
        for (i, e) in expected.iter().enumerate() {
            assert_eq!(film.pixel(i), *e, "{kind}: pixel {i}");
        }
        let (bytes, (moved, moved_splats)) = film.memory();
        println!(
            "{kind}: brightest sample {brightest:.3e} cd/m²; {moved} pixels (own samples) and \
             {moved_splats} (splats) of {} in the wide table; {:.1} bytes a pixel",
            film.len(),
            bytes as f64 / film.len() as f64
        );
        assert_eq!(film.rejected_samples(), 0);
        if kind == IntegratorKind::Direct {
            assert!(brightest > 2.0f64.powi(31), "no hot spot: {brightest}");
            assert!(moved > 0);
        }
    }
}
