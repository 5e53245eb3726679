//! The environment light against exact answers: a convex Lambertian object under a uniform
//! sky reads ρ·L on every pixel (a furnace: nothing it reflects comes back to it), the
//! background reads L, and a map with one bright patch gives the illuminance of that patch's
//! solid angle, in closed form.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::gi_support::*;
use glam::Vec3;
use std::f64::consts::PI;
use std::path::Path;
use std::sync::Arc;
use tracer_core::integrator::IntegratorKind;
use tracer_core::light::{Environment, EnvironmentMap, EnvironmentSource};
use tracer_core::render::{RenderSettings, render};

fn settings(integrator: IntegratorKind, spp: u32) -> RenderSettings {
    RenderSettings {
        width: 12,
        height: 12,
        samples_per_pixel: spp,
        integrator,
        ..RenderSettings::default()
    }
}

/// The picture's mean illuminance (lx).
fn mean_lx(film: &tracer_core::render::Film) -> f64 {
    film.pixels()
        .map(|p| f64::from(p.mean_illuminance()))
        .sum::<f64>()
        / film.len() as f64
}

fn uniform(luminance_cd_m2: f32) -> Environment {
    Environment {
        source: EnvironmentSource::Uniform {
            luminance_cd_m2,
            color: [1.0; 3],
        },
        scale: 1.0,
        rotation_deg: 0.0,
        background: true,
    }
}

/// A cube [0, 1]³ seen face-on, filling the picture.
fn cube_setup(
    rho: f32,
    env: Environment,
) -> (tracer_core::scene::Scene, tracer_core::scene::Setup) {
    let sc = box_scene(1.0, 1.0, 1.0, vec![]);
    let cam = camera([0.5, 0.5, 3.0], [0.5, 0.5, 0.5], 12.0);
    let mut st = setup(&sc, cam, vec![], vec![diffuse(rho); 6]);
    st.environment = Some(env);
    (sc, st)
}

#[test]
fn a_convex_object_under_a_uniform_sky_reads_rho_times_l() {
    let (l, rho) = (100.0f32, 0.6f32);
    let exact = f64::from(l * rho);
    for (integrator, spp) in [
        (IntegratorKind::Path, 1024),
        (IntegratorKind::Direct, 8192),
        (IntegratorKind::Bidirectional, 2048),
        (IntegratorKind::Light, 98_304),
    ] {
        let (sc, st) = cube_setup(rho, uniform(l));
        let (film, _) = render(&sc, &st, &settings(integrator, spp));
        let (mean, se) = film_mean_luminance(&film);
        check(
            &format!("{integrator:?} furnace"),
            mean,
            se,
            exact,
            0.005,
            0.002,
        );
        for (i, p) in film.pixels().enumerate() {
            let d = (p.mean_luminance() - exact).abs();
            assert!(
                d < 4.5 * p.luminance_std_error().unwrap() + 1e-6 * exact,
                "{integrator:?}: pixel {i} reads {} for {exact}",
                p.mean_luminance()
            );
        }
        // Its illuminance is that of the open sky over a plane: E = π L.
        let e = mean_lx(&film);
        assert!(
            (e / (PI * f64::from(l)) - 1.0).abs() < 0.01,
            "{integrator:?}: E {e}"
        );
    }
}

#[test]
fn the_background_is_the_sky_unless_the_backdrop_is_kept() {
    for integrator in [
        IntegratorKind::Path,
        IntegratorKind::Direct,
        IntegratorKind::Bidirectional,
        IntegratorKind::Light,
    ] {
        let (sc, mut st) = cube_setup(0.5, uniform(250.0));
        // Looking away from the cube.
        st.camera = camera([0.5, 0.5, 3.0], [0.5, 0.5, 6.0], 30.0);
        let (film, _) = render(&sc, &st, &settings(integrator, 4));
        for p in film.pixels() {
            assert!((p.mean_luminance() - 250.0).abs() < 1e-3, "{integrator:?}");
        }
        st.environment.as_mut().unwrap().background = false;
        let (film, _) = render(&sc, &st, &settings(integrator, 4));
        assert!(film.pixels().all(|p| p.mean_luminance() == 0.0));
    }
}

/// A 64 x 32 map, black but for one texel of luminance `l` at row `row`, column `col`.
fn patch_map(row: usize, col: usize, l: f32) -> Environment {
    let (w, h) = (64, 32);
    let mut texels = vec![Vec3::ZERO; w * h];
    texels[row * w + col] = Vec3::splat(l);
    let (map, bad) = EnvironmentMap::from_texels(Path::new("patch.hdr"), w, h, texels).unwrap();
    assert_eq!(bad, 0);
    Environment {
        source: EnvironmentSource::Map(Arc::new(map)),
        scale: 1.0,
        rotation_deg: 0.0,
        background: true,
    }
}

#[test]
fn one_bright_patch_gives_its_solid_angle_times_its_cosine() {
    // The patch spans θ in [θ0, θ1] from the zenith, Δφ = 2π / 64: on a floor facing up,
    // E = L Δφ (sin² θ1 − sin² θ0) / 2, exactly.
    let (l, row, col) = (5000.0f32, 6usize, 20usize);
    let (t0, t1) = (row as f64 * PI / 32.0, (row + 1) as f64 * PI / 32.0);
    let exact = f64::from(l) * (2.0 * PI / 64.0) * (t1.sin().powi(2) - t0.sin().powi(2)) / 2.0;
    let floor = brep(
        "floor",
        &[[
            [-5.0, 0.0, -5.0],
            [-5.0, 0.0, 5.0],
            [5.0, 0.0, 5.0],
            [5.0, 0.0, -5.0],
        ]],
    );
    let sc = scene(vec![floor]);
    let cam = camera([0.0, 2.0, 0.01], [0.0, 0.0, 0.0], 20.0);
    let mut st = setup(&sc, cam, vec![], vec![diffuse(0.5)]);
    st.environment = Some(patch_map(row, col, l));
    let (film, _) = render(&sc, &st, &settings(IntegratorKind::Path, 256));
    let n = film.len() as f64;
    let (bd, _) = render(&sc, &st, &settings(IntegratorKind::Bidirectional, 256));
    let e_bd = bd
        .pixels()
        .map(|p| f64::from(p.mean_illuminance()))
        .sum::<f64>()
        / n;
    println!("patch, bdpt: E {e_bd:.4} lx");
    assert!(
        (e_bd / exact - 1.0).abs() < 0.01,
        "bdpt: E {e_bd} vs {exact}"
    );
    let e = mean_lx(&film);
    println!("patch: E {e:.4} lx, exact {exact:.4} lx");
    assert!((e / exact - 1.0).abs() < 0.01, "E {e} vs {exact}");
    // Turned half a turn, the same patch lights the floor alike (it is a cosine about the
    // zenith), and the luminance seen is ρ E / π.
    let lum = film.pixels().map(|p| p.mean_luminance()).sum::<f64>() / n;
    assert!((lum / (0.5 * exact / PI) - 1.0).abs() < 0.01, "L {lum}");
    st.environment.as_mut().unwrap().rotation_deg = 180.0;
    let (film, _) = render(&sc, &st, &settings(IntegratorKind::Path, 256));
    let e2 = mean_lx(&film);
    assert!((e2 / exact - 1.0).abs() < 0.01, "turned: E {e2} vs {exact}");
}
