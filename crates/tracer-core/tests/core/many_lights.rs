//! Many lights through the light tree, against answers: CIE 171:2006 case 5.2 with 100
//! luminaires whose contributions add up to the analytic sum, a furnace of 1,200 small glowing
//! triangles, and every integrator agreeing on a room lit by every kind of light.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::gi_support::*;
use glam::Vec3;
use tracer_core::integrator::IntegratorKind;
use tracer_core::measure::{GridResult, MeasureSettings, measure_grids};
use tracer_core::render::{RenderSettings, render};
use tracer_core::scene::{Scene, Setup, Sidecar};

/// A folder of its own for one test, removed with the value.
struct Scratch(std::path::PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn scratch(name: &str) -> Scratch {
    let d = std::env::temp_dir().join(format!("raygine-many-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    Scratch(d)
}

/// The setup a sidecar `text` (written into `dir`) gives `sc`.
fn apply(sc: &Scene, dir: &Scratch, text: &str) -> Setup {
    let path = dir.0.join("room.raygine.toml");
    let sidecar = Sidecar::parse(text, &path).unwrap_or_else(|e| panic!("{e}"));
    let mut warnings = Vec::new();
    sidecar.apply(sc, None, &mut warnings)
}

fn measure(
    sc: &Scene,
    st: &Setup,
    kind: IntegratorKind,
    samples: u32,
    bounces: Option<u32>,
) -> GridResult {
    let settings = MeasureSettings {
        integrator: kind,
        max_bounces: bounces,
        samples,
        time_limit: None,
        target_error: None,
    };
    measure_grids(sc, st, &settings).remove(0)
}

/// I(γ) = 1000 cos γ cd per 1000 lm, for every luminaire of these tests.
fn cosine_ies(dir: &Scratch) {
    let down: Vec<f64> = (0..=36).map(|i| f64::from(i) * 2.5).collect();
    let text = ies(&down, &[0.0], |_, g: f64| 1000.0 * g.to_radians().cos());
    std::fs::write(dir.0.join("cos.ies"), text).unwrap();
}

/// CIE 171:2006 case 5.2 a hundred times over: 100 luminaires of I(γ) = I0 cos γ (I0 = 10 cd)
/// aimed down from a 10 x 10 grid 3 m above a black 4 x 4 m floor. Each gives I0 h² / d⁴ at a
/// floor point, so the floor's illuminance is the sum; every integrator that samples one light
/// per point must still reach it.
#[test]
fn cie_5_2_with_100_luminaires_adds_up() {
    let dir = scratch("cie52");
    cosine_ies(&dir);
    let sc = box_scene(4.0, 3.0, 4.0, vec![]);
    let mut text = String::from(
        "unit = \"m\"\nhandedness = \"right\"\n[default_material]\nkd = [0.0, 0.0, 0.0]\n\
         [[grids]]\nname = \"floor\"\norigin = [0.0, 0.0, 0.0]\nu = [4.0, 0.0, 0.0]\n\
         v = [0.0, 0.0, 4.0]\nnu = 4\nnv = 4\nnormal = [0.0, 1.0, 0.0]\n",
    );
    let mut sources = Vec::new();
    for i in 0..10 {
        for j in 0..10 {
            let p = Vec3::new(0.2 + 0.4 * i as f32, 3.0, 0.2 + 0.4 * j as f32);
            sources.push(p);
            text += &format!(
                "[[lights]]\nkind = \"luminaire\"\nshape = \"point\"\nfile = \"cos.ies\"\nmultiplier = 0.01\n\
                 position = [{}, {}, {}]\naim = [0.0, -1.0, 0.0]\n",
                p.x, p.y, p.z
            );
        }
    }
    let st = apply(&sc, &dir, &text);
    assert_eq!(st.lights.len(), 100);
    for (kind, samples) in [
        (IntegratorKind::Direct, 2),
        (IntegratorKind::Path, 4096),
        (IntegratorKind::Bidirectional, 8192),
    ] {
        let r = measure(&sc, &st, kind, samples, None);
        let mut worst = 0.0f64;
        for p in &r.points {
            let exact: f64 = sources
                .iter()
                .map(|s| {
                    let d2 = f64::from((p.position - *s).length_squared());
                    10.0 * 9.0 / (d2 * d2)
                })
                .sum();
            let rel = p.illuminance_lx / exact - 1.0;
            worst = worst.max(rel.abs());
            let se = p.std_error_lx;
            assert!(
                se <= 0.01 * exact && (p.illuminance_lx - exact).abs() <= 4.5 * se + 2e-3 * exact,
                "{kind} ({}, {}): {} ± {se} lx vs {exact}",
                p.i,
                p.j,
                p.illuminance_lx
            );
        }
        println!(
            "{kind}: worst point {:.3} % from Σ I0 h² / d⁴",
            worst * 100.0
        );
    }
}

/// The quad `q` cut into `n` x `n` quads (same orientation).
fn subdivide(q: Quad, n: usize) -> Vec<Quad> {
    let at = |s: f64, t: f64| -> [f64; 3] {
        let mut p = [0.0; 3];
        for (k, v) in p.iter_mut().enumerate() {
            let a = q[0][k] + (q[1][k] - q[0][k]) * s;
            let b = q[3][k] + (q[2][k] - q[3][k]) * s;
            *v = a + (b - a) * t;
        }
        p
    };
    let step = 1.0 / n as f64;
    let mut out = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (s0, t0) = (i as f64 * step, j as f64 * step);
            let (s1, t1) = (s0 + step, t0 + step);
            out.push([at(s0, t0), at(s1, t0), at(s1, t1), at(s0, t1)]);
        }
    }
    out
}

/// Furnace of 1,200 glowing triangles: a closed 2 m box whose faces are cut into 10 x 10
/// quads, all emitting Le and reflecting ρ = 0.5, shows L = Le / (1 − ρ) in every pixel, in path
/// and bidirectional mode (the light tree picks among 1,200 emitters at every vertex).
#[test]
fn furnace_of_1200_small_emitters() {
    let breps = box_faces(2.0, 2.0, 2.0)
        .into_iter()
        .map(|(name, q)| brep(name, &subdivide(q, 10)))
        .collect();
    let sc = scene(breps);
    assert_eq!(sc.triangle_count(), 1200);
    let le = 100.0;
    let rho = 0.5f32;
    let mats = vec![emitting(diffuse(rho), le); sc.slots.len()];
    let st = setup(
        &sc,
        camera([1.0, 1.0, 1.7], [1.0, 1.0, 0.0], 70.0),
        vec![],
        mats,
    );
    let exact = f64::from(le) / (1.0 - f64::from(rho));
    for kind in [IntegratorKind::Path, IntegratorKind::Bidirectional] {
        let settings = RenderSettings {
            width: 16,
            height: 16,
            samples_per_pixel: 256,
            integrator: kind,
            ..RenderSettings::default()
        };
        let (film, _) = render(&sc, &st, &settings);
        let n = film.len() as f64;
        let means: Vec<f64> = film.pixels().map(|p| p.mean_luminance()).collect();
        let mean = means.iter().sum::<f64>() / n;
        let var = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (n - 1.0);
        check(
            &format!("{kind} furnace"),
            mean,
            (var / n).sqrt(),
            exact,
            0.01,
            0.005,
        );
        for (i, p) in film.pixels().enumerate() {
            let se = p.luminance_std_error().unwrap();
            assert!(
                (p.mean_luminance() - exact).abs() <= 5.0 * se + 1e-3 * exact,
                "{kind} pixel {i}: {} ± {se} vs {exact}",
                p.mean_luminance()
            );
        }
    }
}

/// A grey room lit by a point, a spot, a luminaire and a glowing ceiling panel: path, bdpt and
/// the light tracer measure the same floor illuminance (within their standard errors), and
/// path mode with one bounce measures what direct mode does.
#[test]
fn integrators_agree_on_every_light_kind() {
    let dir = scratch("kinds");
    cosine_ies(&dir);
    let panel = brep(
        "panel",
        &[[
            [1.5, 2.95, 1.5],
            [2.5, 2.95, 1.5],
            [2.5, 2.95, 2.5],
            [1.5, 2.95, 2.5],
        ]],
    );
    let sc = box_scene(4.0, 3.0, 4.0, vec![panel]);
    let text = "unit = \"m\"\nhandedness = \"right\"\n[default_material]\nkd = [0.5, 0.5, 0.5]\n\
        [[lights]]\nposition = [1.0, 2.5, 1.0]\nintensity_cd = 50.0\n\
        [[lights]]\nkind = \"spot\"\nposition = [3.0, 2.5, 1.0]\nintensity_cd = 200.0\n\
        aim = [0.0, -1.0, 0.0]\ncone_deg = 20.0\nfalloff_deg = 35.0\n\
        [[lights]]\nkind = \"luminaire\"\nshape = \"point\"\nfile = \"cos.ies\"\nmultiplier = 0.1\n\
        position = [1.0, 2.9, 3.0]\naim = [0.0, -1.0, 0.0]\n\
        [[grids]]\nname = \"floor\"\norigin = [0.0, 0.0, 0.0]\nu = [4.0, 0.0, 0.0]\n\
        v = [0.0, 0.0, 4.0]\nnu = 3\nnv = 3\nnormal = [0.0, 1.0, 0.0]\n";
    let mut st = apply(&sc, &dir, text);
    // The panel (the last slot) glows 500 cd/m² downwards, on its front side (+y here, so the
    // back): both sides, to keep the test about light kinds, not sides.
    let last = st.materials.len() - 1;
    st.materials[last] = emitting(diffuse(0.0), 500.0);
    let runs = [
        (IntegratorKind::Path, 4096, None),
        (IntegratorKind::Bidirectional, 2048, None),
        (IntegratorKind::Light, 4096, None),
    ];
    let results: Vec<GridResult> = runs
        .iter()
        .map(|&(k, n, b)| measure(&sc, &st, k, n, b))
        .collect();
    for (ia, (a, ra)) in runs.iter().zip(&results).enumerate() {
        for (b, rb) in runs.iter().zip(&results).skip(ia + 1) {
            for (pa, pb) in ra.points.iter().zip(&rb.points) {
                let se = (pa.std_error_lx.powi(2) + pb.std_error_lx.powi(2)).sqrt();
                let diff = (pa.illuminance_lx - pb.illuminance_lx).abs();
                assert!(
                    diff <= 4.5 * se + 1e-3 * pa.illuminance_lx,
                    "{} vs {} at ({}, {}): {} ± {} vs {} ± {}",
                    a.0,
                    b.0,
                    pa.i,
                    pa.j,
                    pa.illuminance_lx,
                    pa.std_error_lx,
                    pb.illuminance_lx,
                    pb.std_error_lx
                );
            }
        }
    }
    let direct = measure(&sc, &st, IntegratorKind::Direct, 4096, None);
    let one = measure(&sc, &st, IntegratorKind::Path, 4096, Some(1));
    for (pd, p1) in direct.points.iter().zip(&one.points) {
        let se = (pd.std_error_lx.powi(2) + p1.std_error_lx.powi(2)).sqrt();
        assert!(
            (pd.illuminance_lx - p1.illuminance_lx).abs() <= 4.5 * se + 1e-3 * pd.illuminance_lx,
            "direct vs path one bounce at ({}, {}): {} ± {} vs {} ± {}",
            pd.i,
            pd.j,
            pd.illuminance_lx,
            pd.std_error_lx,
            p1.illuminance_lx,
            p1.std_error_lx
        );
    }
    let mean = |r: &GridResult| r.points.iter().map(|p| p.illuminance_lx).sum::<f64>() / 9.0;
    println!(
        "floor mean: path {:.2}, bdpt {:.2}, light {:.2}, direct {:.2}, path one bounce {:.2} lx",
        mean(&results[0]),
        mean(&results[1]),
        mean(&results[2]),
        mean(&direct),
        mean(&one)
    );
}
