//! Thin panes (`kind = "pane"`): a window as one polygon, whose transmission T(θ) is that of
//! one pane with its internal reflections, per polarisation (LIGHTING.md). Tested against the
//! formula written out here on its own, in f64:
//! - shadow rays from a point light pass the pane weighted by T(θ) at the angle they cross it;
//! - under a uniform sky (black ground) a point below a large horizontal pane receives
//!   E = 2π L ∫ T(θ) cos θ sin θ dθ, reached both by light sampling (shadow rays through the
//!   pane) and by paths sampled through it, with MIS between them;
//!
//! in every integrator.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::gi_support::*;
use std::f64::consts::PI;
use std::path::Path;
use tracer_core::integrator::IntegratorKind;
use tracer_core::measure::{MeasureSettings, measure_grids};
use tracer_core::scene::Sidecar;

/// T of a clear pane of index `n` at incidence θ (cos θ = `c`), the mean over s and p of
/// (1 − R)/(1 + R) with R Fresnel's reflectance of one face.
fn pane_t(c: f64, n: f64) -> f64 {
    let s2 = 1.0 - c * c;
    let ct = (1.0 - s2 / (n * n)).sqrt();
    let rs = ((c - n * ct) / (c + n * ct)).powi(2);
    let rp = ((n * c - ct) / (n * c + ct)).powi(2);
    0.5 * ((1.0 - rs) / (1.0 + rs) + (1.0 - rp) / (1.0 + rp))
}

/// A large horizontal pane at y = 1 (front up) over sensors at y = 0, with the sidecar `keys`.
fn under_a_pane(keys: &str, grid: &str) -> (tracer_core::scene::Scene, tracer_core::scene::Setup) {
    let sc = scene(vec![brep(
        "window",
        &[[
            [-100.0, 1.0, -100.0],
            [-100.0, 1.0, 100.0],
            [100.0, 1.0, 100.0],
            [100.0, 1.0, -100.0],
        ]],
    )]);
    let text = format!(
        "unit = \"m\"\nhandedness = \"right\"\n[materials.window]\nkind = \"pane\"\n{grid}\n{keys}\n"
    );
    let sidecar = Sidecar::parse(&text, Path::new("pane.raygine.toml")).unwrap();
    let mut warnings = Vec::new();
    let st = sidecar.apply(&sc, None, &mut warnings);
    assert!(warnings.is_empty(), "{warnings:?}");
    (sc, st)
}

fn settings(integrator: IntegratorKind, samples: u32) -> MeasureSettings {
    MeasureSettings {
        integrator,
        max_bounces: None,
        samples,
        time_limit: None,
        target_error: None,
    }
}

/// A 1000 cd point light 3 m above the pane (4 m above the sensors); sensors along X where the
/// light's rays cross the pane at 0°, 30°, 45° and 60°: E = I cos θ / d² · T(θ).
#[test]
fn shadow_rays_pass_a_pane_weighted_by_its_transmission() {
    let xs: Vec<f64> = [0.0f64, 30.0, 45.0, 60.0]
        .iter()
        .map(|deg| 4.0 * deg.to_radians().tan())
        .collect();
    let mut grid = String::new();
    for (k, x) in xs.iter().enumerate() {
        grid += &format!(
            "[[grids]]\nname = \"p{k}\"\norigin = [{x0}, 0.0, -0.001]\nu = [0.002, 0.0, 0.0]\n\
             v = [0.0, 0.0, 0.002]\nnu = 1\nnv = 1\nnormal = [0.0, 1.0, 0.0]\n",
            x0 = x - 0.001
        );
    }
    let (sc, mut st) = under_a_pane("", &grid);
    st.lights = vec![tracer_core::scene::Light::point([0.0, 4.0, 0.0], 1000.0)];
    for integrator in IntegratorKind::ALL {
        let results = measure_grids(&sc, &st, &settings(integrator, 64));
        for ((r, x), deg) in results.iter().zip(&xs).zip([0.0f64, 30.0, 45.0, 60.0]) {
            let d2 = x * x + 16.0;
            let cos = 4.0 / d2.sqrt();
            let exact = 1000.0 * cos / d2 * pane_t(cos, 1.52);
            let e = r.points[0].illuminance_lx;
            println!(
                "{integrator} {deg}°: E {e:.4} lx vs {exact:.4} (T {:.4})",
                pane_t(cos, 1.52)
            );
            assert!(
                (e / exact - 1.0).abs() < 2e-3,
                "{integrator} {deg}°: {e} vs {exact}"
            );
        }
    }
}

/// Under a uniform sky of 1000 cd/m² with a black ground, below a clear pane:
/// E = 2π L ∫₀^{π/2} T(θ) cos θ sin θ dθ (0.8464 π L), in every integrator, within 1 %. Above
/// it, facing down, a sensor sees the sky in the pane: E = π L − that (the pane absorbs
/// nothing, R = 1 − T).
#[test]
fn a_uniform_sky_through_a_pane() {
    let grid = "[[grids]]\nname = \"below\"\norigin = [-1.0, 0.0, -1.0]\nu = [2.0, 0.0, 0.0]\n\
                v = [0.0, 0.0, 2.0]\nnu = 2\nnv = 2\nnormal = [0.0, 1.0, 0.0]\n\
                [[grids]]\nname = \"above\"\norigin = [-1.0, 2.0, -1.0]\nu = [2.0, 0.0, 0.0]\n\
                v = [0.0, 0.0, 2.0]\nnu = 2\nnv = 2\nnormal = [0.0, -1.0, 0.0]\n";
    let keys = "[daylight]\nlatitude = 52.0\nlongitude = 5.0\ndate = \"2026-03-20\"\n\
                time = \"12:00\"\ntimezone = 1.0\nsky = \"uniform\"\n\
                zenith_luminance_cd_m2 = 1000.0\nground_reflectance = 0.0";
    let (sc, mut st) = under_a_pane(keys, grid);
    st.lights.clear();
    // The integral by the midpoint rule in θ (20,000 steps).
    let steps = 20_000;
    let exact: f64 = (0..steps)
        .map(|i| {
            let t = (i as f64 + 0.5) / steps as f64 * PI / 2.0;
            pane_t(t.cos(), 1.52) * t.cos() * t.sin() * (PI / 2.0 / steps as f64)
        })
        .sum::<f64>()
        * 2.0
        * PI
        * 1000.0;
    let reflected = PI * 1000.0 - exact;
    for integrator in IntegratorKind::ALL {
        let results = measure_grids(&sc, &st, &settings(integrator, 65_536));
        for (r, exact) in results.iter().zip([exact, reflected]) {
            let n = r.points.len() as f64;
            let e = r.points.iter().map(|p| p.illuminance_lx).sum::<f64>() / n;
            let se = (r.points.iter().map(|p| p.std_error_lx.powi(2)).sum::<f64>()).sqrt() / n;
            println!(
                "{integrator} {}: E {e:.1} ± {se:.1} lx vs {exact:.1} ({:+.2} %; πL = {:.1})",
                r.name,
                (e / exact - 1.0) * 100.0,
                PI * 1000.0
            );
            assert!(
                (e / exact - 1.0).abs() < 0.01,
                "{integrator} {}: {e} vs {exact}",
                r.name
            );
            assert!(
                (e - exact).abs() < 4.0 * se + 1e-9,
                "{integrator} {}: {e} ± {se} vs {exact}",
                r.name
            );
        }
    }
}

/// Looking through a pane at a glowing wall, straight on: the picture shows T(0) L of the wall,
/// in direct mode (which looks through panes) as in path and bidirectional modes.
#[test]
fn the_camera_looks_through_a_pane() {
    use tracer_core::render::{RenderSettings, render};
    let sc = scene(vec![
        brep(
            "window",
            &[[
                [-50.0, -50.0, -1.0],
                [50.0, -50.0, -1.0],
                [50.0, 50.0, -1.0],
                [-50.0, 50.0, -1.0],
            ]],
        ),
        brep(
            "wall",
            &[[
                [-50.0, -50.0, -5.0],
                [50.0, -50.0, -5.0],
                [50.0, 50.0, -5.0],
                [-50.0, 50.0, -5.0],
            ]],
        ),
    ]);
    let text = "unit = \"m\"\nhandedness = \"right\"\n\
                [camera]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.0, 0.0, -1.0]\nfov_deg = 2.0\n\
                [materials.window]\nkind = \"pane\"\n\
                [materials.wall]\nkd = [0.0, 0.0, 0.0]\nemission_cd_m2 = 100.0\n";
    let sidecar = Sidecar::parse(text, Path::new("look.raygine.toml")).unwrap();
    let mut warnings = Vec::new();
    let mut st = sidecar.apply(&sc, None, &mut warnings);
    st.lights.clear();
    let exact = 100.0 * pane_t(1.0, 1.52);
    for integrator in [
        IntegratorKind::Direct,
        IntegratorKind::Path,
        IntegratorKind::Bidirectional,
    ] {
        let settings = RenderSettings {
            width: 4,
            height: 4,
            samples_per_pixel: 1024,
            integrator,
            ..RenderSettings::default()
        };
        let (film, _) = render(&sc, &st, &settings);
        let (l, se) = film_mean_luminance(&film);
        println!("{integrator}: L {l:.3} ± {se:.3} cd/m² vs T(0) L = {exact:.3}");
        assert!(
            (l / exact - 1.0).abs() < 0.01,
            "{integrator}: {l} vs {exact}"
        );
    }
}
