//! Daylight skies against their closed forms, through the sidecar and the renderer: an
//! unobstructed floor under the CIE overcast sky reads E_h = 7π/9 · Lz, under a uniform sky
//! π · L (LIGHTING.md), within 0.5 %, in path and bidirectional modes; a ceiling facing down
//! reads the ground's ρ_g E_h.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::gi_support::*;
use std::f64::consts::PI;
use std::path::Path;
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::{RenderSettings, render};
use tracer_core::scene::Sidecar;

/// A 200 x 200 m floor (front +Y) seen from 2 m up, under the sidecar's `[daylight]` keys
/// `sky`: the picture's mean illuminance and luminance.
fn floor_under(sky: &str, integrator: IntegratorKind, facing_down: bool) -> (f64, f64) {
    let mut quad = [
        [-100.0, 0.0, -100.0],
        [-100.0, 0.0, 100.0],
        [100.0, 0.0, 100.0],
        [100.0, 0.0, -100.0],
    ];
    if facing_down {
        quad.reverse();
    }
    let sc = scene(vec![brep("floor", &[quad])]);
    let (y, look) = if facing_down { (-2.0, 0.0) } else { (2.0, 0.0) };
    let text = format!(
        "unit = \"m\"\nhandedness = \"right\"\n\
         [camera]\nposition = [0.0, {y}, 0.01]\nlook_at = [0.0, {look}, 0.0]\nup = [0.0, 0.0, 1.0]\nfov_deg = 20.0\n\
         [materials.floor]\nkd = [0.5, 0.5, 0.5]\n\
         [daylight]\nlatitude = 52.0\nlongitude = 5.0\ndate = \"2026-03-20\"\ntime = \"12:00\"\n\
         timezone = 1.0\n{sky}\n"
    );
    let sidecar = Sidecar::parse(&text, Path::new("floor.raygine.toml")).unwrap();
    let mut warnings = Vec::new();
    let mut st = sidecar.apply(&sc, None, &mut warnings);
    st.lights.clear();
    assert!(
        st.environment.is_some(),
        "the sky is the environment: {warnings:?}"
    );
    let settings = RenderSettings {
        width: 8,
        height: 8,
        samples_per_pixel: 2048,
        integrator,
        ..RenderSettings::default()
    };
    let (film, _) = render(&sc, &st, &settings);
    let n = film.pixels.len() as f64;
    let e = film
        .pixels
        .iter()
        .map(|p| f64::from(p.mean_illuminance()))
        .sum::<f64>()
        / n;
    let l = film.pixels.iter().map(|p| p.mean_luminance()).sum::<f64>() / n;
    (e, l)
}

#[test]
fn skies_give_their_closed_form_horizontal_illuminance() {
    let lz = 3000.0;
    for (sky, exact) in [
        ("sky = \"cie-overcast\"", 7.0 * PI / 9.0 * lz),
        ("sky = \"uniform\"", PI * lz),
    ] {
        for integrator in [IntegratorKind::Path, IntegratorKind::Bidirectional] {
            let keys = format!("{sky}\nzenith_luminance_cd_m2 = {lz}");
            let (e, l) = floor_under(&keys, integrator, false);
            println!(
                "{sky}, {integrator}: E {e:.1} lx vs {exact:.1} ({:+.2} %), L {l:.2} vs ρE/π {:.2}",
                (e / exact - 1.0) * 100.0,
                0.5 * exact / PI
            );
            assert!(
                (e / exact - 1.0).abs() < 0.005,
                "{sky} {integrator}: {e} vs {exact}"
            );
            assert!((l / (0.5 * exact / PI) - 1.0).abs() < 0.01, "{sky}: L {l}");
        }
    }
    // diffuse_horizontal_lx sets the same sky by its illuminance.
    let (e, _) = floor_under(
        "sky = \"cie-overcast\"\ndiffuse_horizontal_lx = 10000.0",
        IntegratorKind::Path,
        false,
    );
    assert!((e / 10_000.0 - 1.0).abs() < 0.005, "{e}");
}

/// The ground below the horizon is Lambertian at ρ_g E_h / π: a surface facing down, far
/// above it, reads ρ_g E_h.
#[test]
fn the_ground_reflects_the_sky() {
    let lz = 1000.0;
    let eh = 7.0 * PI / 9.0 * lz;
    let (e, _) = floor_under(
        &format!("sky = \"cie-overcast\"\nzenith_luminance_cd_m2 = {lz}\nground_reflectance = 0.3"),
        IntegratorKind::Path,
        true,
    );
    println!("ground: E {e:.2} lx vs ρ_g E_h {:.2}", 0.3 * eh);
    assert!((e / (0.3 * eh) - 1.0).abs() < 0.005, "{e} vs {}", 0.3 * eh);
}
