//! Scenes and exact answers shared by the global-illumination tests: boxes and rooms built in
//! code (scene unit m, right-handed), and Lambert's contour form factor.
#![allow(dead_code, clippy::unwrap_used, clippy::expect_used)]

use glam::{DVec3, Vec3};
use std::fmt::Write as _;
use tracer_core::measure::Grid;
use tracer_core::render::{Film, RenderSettings};
use tracer_core::scene::{Camera, Handedness, LengthUnit, Light, Material, Scene, Setup};
use tracer_core::shp::{BrepDef, ShpDescription};

/// A quad as four corners; the front normal (right-handed) is (c1 − c0) × (c2 − c0).
pub type Quad = [[f64; 3]; 4];

pub fn brep(name: &str, quads: &[Quad]) -> BrepDef {
    let mut b = BrepDef {
        name: name.into(),
        part_count: 1,
        ..BrepDef::default()
    };
    for q in quads {
        let base = b.vertices.len() as u32;
        b.vertices.extend_from_slice(q);
        b.triangles.push([base, base + 1, base + 2]);
        b.triangles.push([base, base + 2, base + 3]);
    }
    b.parts = vec![0; b.triangles.len()];
    b
}

pub fn scene(breps: Vec<BrepDef>) -> Scene {
    let desc = ShpDescription {
        breps,
        ..ShpDescription::default()
    };
    Scene::build(&desc, "test").unwrap()
}

/// The six inner faces of the box [0, sx] x [0, sy] x [0, sz], front normals pointing inwards:
/// floor, ceiling, x = 0, x = sx, z = 0, z = sz.
pub fn box_faces(sx: f64, sy: f64, sz: f64) -> Vec<(&'static str, Quad)> {
    vec![
        (
            "floor",
            [
                [0.0, 0.0, 0.0],
                [0.0, 0.0, sz],
                [sx, 0.0, sz],
                [sx, 0.0, 0.0],
            ],
        ),
        (
            "ceiling",
            [[0.0, sy, 0.0], [sx, sy, 0.0], [sx, sy, sz], [0.0, sy, sz]],
        ),
        (
            "wall_x0",
            [
                [0.0, 0.0, 0.0],
                [0.0, sy, 0.0],
                [0.0, sy, sz],
                [0.0, 0.0, sz],
            ],
        ),
        (
            "wall_x1",
            [[sx, 0.0, 0.0], [sx, 0.0, sz], [sx, sy, sz], [sx, sy, 0.0]],
        ),
        (
            "wall_z0",
            [
                [0.0, 0.0, 0.0],
                [sx, 0.0, 0.0],
                [sx, sy, 0.0],
                [0.0, sy, 0.0],
            ],
        ),
        (
            "wall_z1",
            [[0.0, 0.0, sz], [0.0, sy, sz], [sx, sy, sz], [sx, 0.0, sz]],
        ),
    ]
}

/// A box scene whose faces are one brep each (slot i = face i of [`box_faces`]).
pub fn box_scene(sx: f64, sy: f64, sz: f64, extra: Vec<BrepDef>) -> Scene {
    let mut breps: Vec<BrepDef> = box_faces(sx, sy, sz)
        .into_iter()
        .map(|(n, q)| brep(n, &[q]))
        .collect();
    breps.extend(extra);
    scene(breps)
}

pub fn diffuse(rho: f32) -> Material {
    Material {
        kd: [rho; 3],
        ks: [0.0; 3],
        glossiness: 0.0,
        ..Material::default()
    }
}

pub fn emitting(mut m: Material, l: f32) -> Material {
    m.emission_cd_m2 = l;
    m
}

/// Setup in metres, right-handed, with the given camera, lights and one material per slot.
pub fn setup(scene: &Scene, camera: Camera, lights: Vec<Light>, materials: Vec<Material>) -> Setup {
    assert_eq!(materials.len(), scene.slots.len());
    Setup {
        unit: LengthUnit::M,
        handedness: Handedness::Right,
        camera,
        lights,
        hidden: vec![false; scene.slots.len()],
        materials,
        grids: Vec::new(),
        maintenance_factor: 1.0,
        environment: None,
        daylight: None,
        sun: None,
        observers: Vec::new(),
    }
}

pub fn camera(position: [f32; 3], look_at: [f32; 3], fov_deg: f32) -> Camera {
    Camera {
        position,
        look_at,
        up: [0.0, 1.0, 0.0],
        fov_deg,
        ..Default::default()
    }
}

/// An `n` x `n` grid just inside each face of the box (offset 1e-4 m), facing inwards.
pub fn face_grids(sx: f32, sy: f32, sz: f32, n: u32) -> Vec<Grid> {
    let e = 1e-4;
    let g = |name: &str, o: [f32; 3], u: [f32; 3], v: [f32; 3], normal: [f32; 3]| {
        Grid::new(name, o, u, v, n, n, Some(normal)).unwrap()
    };
    vec![
        g(
            "floor",
            [0.0, e, 0.0],
            [sx, 0.0, 0.0],
            [0.0, 0.0, sz],
            [0.0, 1.0, 0.0],
        ),
        g(
            "ceiling",
            [0.0, sy - e, 0.0],
            [sx, 0.0, 0.0],
            [0.0, 0.0, sz],
            [0.0, -1.0, 0.0],
        ),
        g(
            "x0",
            [e, 0.0, 0.0],
            [0.0, sy, 0.0],
            [0.0, 0.0, sz],
            [1.0, 0.0, 0.0],
        ),
        g(
            "x1",
            [sx - e, 0.0, 0.0],
            [0.0, sy, 0.0],
            [0.0, 0.0, sz],
            [-1.0, 0.0, 0.0],
        ),
        g(
            "z0",
            [0.0, 0.0, e],
            [sx, 0.0, 0.0],
            [0.0, sy, 0.0],
            [0.0, 0.0, 1.0],
        ),
        g(
            "z1",
            [0.0, 0.0, sz - e],
            [sx, 0.0, 0.0],
            [0.0, sy, 0.0],
            [0.0, 0.0, -1.0],
        ),
    ]
}

/// The point-to-polygon form factor by Lambert's contour formula:
/// F = (1/2π) |Σ_edges β_i (n · γ_i)|, β_i the angle edge i subtends at `p` and γ_i the unit
/// normal of the plane through `p` and the edge.
pub fn form_factor(p: DVec3, n: DVec3, polygon: &[DVec3]) -> f64 {
    let mut sum = 0.0;
    for i in 0..polygon.len() {
        let a = (polygon[i] - p).normalize();
        let b = (polygon[(i + 1) % polygon.len()] - p).normalize();
        let beta = a.dot(b).clamp(-1.0, 1.0).acos();
        let gamma = a.cross(b).normalize_or_zero();
        sum += beta * n.dot(gamma);
    }
    (sum / (2.0 * std::f64::consts::PI)).abs()
}

pub fn v3(p: Vec3) -> DVec3 {
    p.as_dvec3()
}

/// Checks an estimate against the exact value by the criteria: within `rel_tol`
/// (0.5 %) of it and within 4 reported standard errors, with the standard error below
/// `max_rel_se` (0.2 %) of the exact value.
pub fn check(what: &str, estimate: f64, std_error: f64, exact: f64, rel_tol: f64, max_rel_se: f64) {
    let rel = (estimate - exact) / exact;
    println!(
        "{what}: estimate {estimate:.5}, exact {exact:.5}, error {:+.3} %, std error {:.3} %",
        rel * 100.0,
        std_error / exact * 100.0
    );
    assert!(
        std_error.is_finite() && std_error > 0.0,
        "{what}: no standard error"
    );
    assert!(
        std_error / exact.abs() < max_rel_se,
        "{what}: standard error {:.3} % above {:.3} %",
        std_error / exact * 100.0,
        max_rel_se * 100.0
    );
    assert!(
        rel.abs() < rel_tol,
        "{what}: {estimate} is {:+.3} % from the exact {exact}",
        rel * 100.0
    );
    assert!(
        (estimate - exact).abs() < 4.0 * std_error,
        "{what}: {estimate} is more than 4 standard errors ({std_error}) from {exact}"
    );
}

/// A film's mean pixel luminance (cd/m²) and the standard error of that mean.
pub fn film_mean_luminance(film: &Film) -> (f64, f64) {
    let n = film.len() as f64;
    let mean = film.pixels().map(|p| p.mean_luminance()).sum::<f64>() / n;
    let se = film
        .pixels()
        .map(|p| p.luminance_std_error().unwrap_or(f64::INFINITY).powi(2))
        .sum::<f64>()
        .sqrt()
        / n;
    (mean, se)
}

/// Renders on a pool of `threads` worker threads.
pub fn render_on_threads(
    scene: &Scene,
    setup: &Setup,
    settings: &RenderSettings,
    threads: usize,
) -> Film {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| tracer_core::render::render(scene, setup, settings).0)
}

/// An LM-63-2002 file of `f(C, γ)` at the given angles (absolute photometry), with a
/// 0.1 x 0.2 m luminous rectangle.
pub fn ies(vert: &[f64], horiz: &[f64], f: impl Fn(f64, f64) -> f64) -> String {
    ies_sized(vert, horiz, f, [0.1, 0.2, 0.0])
}

/// [`ies`] with the luminous opening's width, length and height in metres (LM-63's fields).
pub fn ies_sized(
    vert: &[f64],
    horiz: &[f64],
    f: impl Fn(f64, f64) -> f64,
    [width, length, height]: [f64; 3],
) -> String {
    let mut s = String::from("IESNA:LM-63-2002\n[TEST] raygine\n[MANUFAC] tests\nTILT=NONE\n");
    let _ = writeln!(
        s,
        "1 -1 1 {} {} 1 2 {width} {length} {height}",
        vert.len(),
        horiz.len()
    );
    s.push_str("1 1 50\n");
    let join = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    let _ = writeln!(s, "{}", join(vert));
    let _ = writeln!(s, "{}", join(horiz));
    for &c in horiz {
        let row: Vec<f64> = vert.iter().map(|&g| f(c, g)).collect();
        let _ = writeln!(s, "{}", join(&row));
    }
    s
}

/// A `sx` x `sy` x `sz` room whose z = sz wall has an open window from (x0, y0) to (x1, y1).
pub fn window_room(
    [sx, sy, sz]: [f64; 3],
    [x0, x1, y0, y1]: [f64; 4],
) -> tracer_core::scene::Scene {
    let mut quads: Vec<Quad> = box_faces(sx, sy, sz)
        .into_iter()
        .filter(|(n, _)| *n != "wall_z1")
        .map(|(_, q)| q)
        .collect();
    for (a0, a1, b0, b1) in [
        (0.0, sx, 0.0, y0),
        (0.0, sx, y1, sy),
        (0.0, x0, y0, y1),
        (x1, sx, y0, y1),
    ] {
        quads.push([[a0, b0, sz], [a0, b1, sz], [a1, b1, sz], [a1, b0, sz]]);
    }
    scene(vec![brep("room", &quads)])
}
