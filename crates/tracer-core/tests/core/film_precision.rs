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
