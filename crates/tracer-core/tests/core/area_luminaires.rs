//! Luminaires with a luminous opening against answers computed here, not by the renderer:
//! a Lambertian file with a rectangular opening is an emissive rectangle of luminance I0 / A
//! (Lambert's contour form factor), and a non-Lambertian cylinder agrees with the point model
//! beyond ten times its size and with a numeric integral over its surface near it.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::gi_support::*;
use glam::DVec3;
use std::f64::consts::PI;
use std::path::PathBuf;
use tracer_core::integrator::IntegratorKind;
use tracer_core::measure::{GridResult, MeasureSettings, measure_grids};
use tracer_core::scene::{Scene, Setup, Sidecar};

struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn scratch(name: &str) -> Scratch {
    let d = std::env::temp_dir().join(format!("raygine-area-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    Scratch(d)
}

/// `count` angles from `from` to `to`.
fn angles(from: f64, to: f64, count: usize) -> Vec<f64> {
    (0..count)
        .map(|i| from + (to - from) * i as f64 / (count - 1) as f64)
        .collect()
}

/// The scene and setup of `sidecar` (one luminaire file `file` written beside it) in a black
/// box room of `size` metres.
fn room(dir: &Scratch, size: [f64; 3], file: (&str, String), sidecar: &str) -> (Scene, Setup) {
    std::fs::write(dir.0.join(file.0), file.1).unwrap();
    let sc = box_scene(size[0], size[1], size[2], vec![]);
    let text = format!(
        "unit = \"m\"\nhandedness = \"right\"\n[default_material]\nkd = [0.0, 0.0, 0.0]\n{sidecar}"
    );
    let path = dir.0.join("room.raygine.toml");
    let sidecar = Sidecar::parse(&text, &path).unwrap_or_else(|e| panic!("{e}"));
    let mut warnings = Vec::new();
    let st = sidecar.apply(&sc, None, &mut warnings);
    (sc, st)
}

fn measure(sc: &Scene, st: &Setup, kind: IntegratorKind, samples: u32) -> Vec<GridResult> {
    let settings = MeasureSettings {
        integrator: kind,
        max_bounces: None,
        samples,
        time_limit: None,
        target_error: None,
    };
    measure_grids(sc, st, &settings)
}

/// A grid table.
fn grid(
    name: &str,
    origin: [f64; 3],
    u: [f64; 3],
    v: [f64; 3],
    n: u32,
    normal: [f64; 3],
) -> String {
    format!(
        "[[grids]]\nname = \"{name}\"\norigin = {origin:?}\nu = {u:?}\nv = {v:?}\nnu = {n}\n\
         nv = {n}\nnormal = {normal:?}\n"
    )
}

/// Every point of `results` against `exact(position, normal)`: within `tol` and within 5
/// standard errors (one stream of 400 drew 4.3). Returns the worst relative error.
fn compare(
    what: &str,
    results: &[GridResult],
    tol: f64,
    exact: impl Fn(DVec3, DVec3) -> f64,
) -> f64 {
    let mut worst = 0.0f64;
    for g in results {
        for p in &g.points {
            let e = exact(v3(p.position), v3(g.normal));
            let rel = p.illuminance_lx / e - 1.0;
            worst = worst.max(rel.abs());
            assert!(
                rel.abs() < tol && (p.illuminance_lx - e).abs() < 5.0 * p.std_error_lx + 1e-9 * e,
                "{what}, {} ({}, {}) at {}: {:.4} ± {:.4} lx vs exact {e:.4} ({:+.3} %)",
                g.name,
                p.i,
                p.j,
                p.position,
                p.illuminance_lx,
                p.std_error_lx,
                rel * 100.0
            );
        }
    }
    println!(
        "{what}: worst point {:.3} % from the exact value",
        worst * 100.0
    );
    worst
}

/// I = I0 cos γ from a 1.2 x 0.6 m opening is a Lambertian rectangle of luminance I0 / A:
/// E = π (I0 / A) F, F the point-to-rectangle form factor. Points 0.3-0.5 m from it, where the
/// point model is off by up to 40 %.
#[test]
fn lambertian_rectangle_reads_its_form_factor() {
    let dir = scratch("rect");
    let i0 = 1000.0;
    let file = ies_sized(
        &angles(0.0, 90.0, 91),
        &[0.0],
        |_, g| i0 * g.to_radians().cos(),
        [0.6, 1.2, 0.0],
    );
    let grids = grid(
        "floor",
        [1.0, 0.0, 1.4],
        [2.0, 0.0, 0.0],
        [0.0, 0.0, 1.2],
        5,
        [0.0, 1.0, 0.0],
    ) + &grid(
        "wall",
        [2.9, 0.0, 1.5],
        [0.0, 0.4, 0.0],
        [0.0, 0.0, 1.0],
        3,
        [-1.0, 0.0, 0.0],
    );
    let (sc, st) = room(
        &dir,
        [4.0, 3.0, 4.0],
        ("panel.ies", file),
        &format!(
            "[[lights]]\nkind = \"luminaire\"\nfile = \"panel.ies\"\nposition = [2.0, 0.5, 2.0]\n\
             aim = [0.0, -1.0, 0.0]\n{grids}"
        ),
    );
    // The length (C0) along +X, the width along Z.
    let corners = [
        DVec3::new(1.4, 0.5, 1.7),
        DVec3::new(2.6, 0.5, 1.7),
        DVec3::new(2.6, 0.5, 2.3),
        DVec3::new(1.4, 0.5, 2.3),
    ];
    let luminance = i0 / (1.2 * 0.6);
    let exact = |p: DVec3, n: DVec3| PI * luminance * form_factor(p, n, &corners);
    let point_model = |p: DVec3, n: DVec3| {
        let d = DVec3::new(2.0, 0.5, 2.0) - p;
        let cos_gamma = d.y.max(0.0) / d.length();
        i0 * cos_gamma * n.dot(d.normalize()).max(0.0) / d.length_squared()
    };
    for (kind, samples) in [
        (IntegratorKind::Direct, 200_000),
        (IntegratorKind::Path, 200_000),
        (IntegratorKind::Bidirectional, 200_000),
        (IntegratorKind::Light, 200_000),
    ] {
        let results = measure(&sc, &st, kind, samples);
        compare(&format!("{kind}"), &results, 0.01, exact);
        if kind == IntegratorKind::Direct {
            let under = &results[0].points[12];
            let (p, n) = (v3(under.position), DVec3::Y);
            println!(
                "under the centre: {:.1} lx, form factor {:.1} lx, point model {:.1} lx",
                under.illuminance_lx,
                exact(p, n),
                point_model(p, n)
            );
        }
    }
}

/// I(γ) = I0 (1 + cos² γ) / 2, a luminous vertical cylinder 0.3 m across and 0.4 m high:
/// A_proj(γ) = (π D² / 4) |cos γ| + D h sin γ, and every point of its surface sends
/// L = I / A_proj towards its outside.
const I0: f64 = 600.0;
const DIAMETER: f64 = 0.3;
const HEIGHT: f64 = 0.4;

fn cylinder_intensity(gamma_deg: f64) -> f64 {
    let c = gamma_deg.to_radians().cos();
    I0 * (1.0 + c * c) / 2.0
}

fn cylinder_file() -> String {
    ies_sized(
        &angles(0.0, 180.0, 361),
        &[0.0],
        |_, g| cylinder_intensity(g),
        [-DIAMETER, -DIAMETER, HEIGHT],
    )
}

/// E at `p` (normal `n`) from the cylinder centred at `centre`, axis along −Y (its nadir), by
/// the midpoint rule over its mantle and both ends.
fn cylinder_integral(centre: DVec3, p: DVec3, n: DVec3) -> f64 {
    let r = DIAMETER / 2.0;
    let projected = |w: DVec3| {
        let cos = w.y.abs();
        PI * r * r * cos + DIAMETER * HEIGHT * (1.0 - cos * cos).max(0.0).sqrt()
    };
    // One surface element at `x` with outward normal `m` and area `da`.
    let element = |x: DVec3, m: DVec3, da: f64| {
        let d = p - x;
        let dist2 = d.length_squared();
        let w = d / dist2.sqrt();
        let cos_e = m.dot(w);
        let cos_r = -n.dot(w);
        if cos_e <= 0.0 || cos_r <= 0.0 {
            return 0.0;
        }
        // γ from the nadir −Y.
        let gamma = (-w.y).clamp(-1.0, 1.0).acos().to_degrees();
        cylinder_intensity(gamma) / projected(w) * cos_e * cos_r / dist2 * da
    };
    let (na, nz, nr) = (720, 160, 120);
    let mut sum = 0.0;
    for i in 0..na {
        let phi = (i as f64 + 0.5) / na as f64 * 2.0 * PI;
        let (s, c) = phi.sin_cos();
        let m = DVec3::new(c, 0.0, s);
        for k in 0..nz {
            let y = ((k as f64 + 0.5) / nz as f64 - 0.5) * HEIGHT;
            let da = (2.0 * PI * r / na as f64) * (HEIGHT / nz as f64);
            sum += element(centre + m * r + DVec3::Y * y, m, da);
        }
        for k in 0..nr {
            let (r0, r1) = (r * k as f64 / nr as f64, r * (k + 1) as f64 / nr as f64);
            let rm = 0.5 * (r0 + r1);
            let da = 0.5 * (r1 * r1 - r0 * r0) * (2.0 * PI / na as f64);
            for sign in [-1.0, 1.0] {
                let x = centre + DVec3::new(c * rm, sign * HEIGHT / 2.0, s * rm);
                sum += element(x, DVec3::Y * sign, da);
            }
        }
    }
    sum
}

/// Near the cylinder (0.15-0.6 m from its surface, under it and beside it) the readings equal
/// the integral over its surface; the point model is off there by up to 30 %.
#[test]
fn cylinder_near_field_matches_the_surface_integral() {
    let dir = scratch("cyl-near");
    let centre = DVec3::new(2.0, 1.5, 2.0);
    let grids = grid(
        "below",
        [1.5, 1.0, 1.5],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        4,
        [0.0, 1.0, 0.0],
    ) + &grid(
        "beside",
        [2.3, 1.1, 1.6],
        [0.0, 0.8, 0.0],
        [0.0, 0.0, 0.8],
        4,
        [-1.0, 0.0, 0.0],
    );
    let (sc, st) = room(
        &dir,
        [4.0, 3.0, 4.0],
        ("cyl.ies", cylinder_file()),
        &format!(
            "[[lights]]\nkind = \"luminaire\"\nfile = \"cyl.ies\"\nposition = [2.0, 1.5, 2.0]\n\
             aim = [0.0, -1.0, 0.0]\n{grids}"
        ),
    );
    for (kind, samples) in [
        (IntegratorKind::Direct, 200_000),
        (IntegratorKind::Path, 200_000),
        (IntegratorKind::Bidirectional, 600_000),
    ] {
        let results = measure(&sc, &st, kind, samples);
        compare(&format!("{kind} near"), &results, 0.01, |p, n| {
            cylinder_integral(centre, p, n)
        });
    }
}

/// Beyond ten times its size the cylinder is its point model, E = I(γ) cos θ / d², within 1 %,
/// on the floor and a wall of a 12 x 10 x 12 m room.
#[test]
fn cylinder_far_field_is_the_point_model() {
    let dir = scratch("cyl-far");
    let centre = DVec3::new(6.0, 9.0, 6.0);
    let grids = grid(
        "floor",
        [1.0, 0.0, 1.0],
        [10.0, 0.0, 0.0],
        [0.0, 0.0, 10.0],
        4,
        [0.0, 1.0, 0.0],
    ) + &grid(
        "wall",
        [11.9, 2.0, 1.0],
        [0.0, 8.0, 0.0],
        [0.0, 0.0, 10.0],
        3,
        [-1.0, 0.0, 0.0],
    );
    let (sc, st) = room(
        &dir,
        [12.0, 10.0, 12.0],
        ("cyl.ies", cylinder_file()),
        &format!(
            "[[lights]]\nkind = \"luminaire\"\nfile = \"cyl.ies\"\nposition = [6.0, 9.0, 6.0]\n\
             aim = [0.0, -1.0, 0.0]\n{grids}"
        ),
    );
    let point_model = |p: DVec3, n: DVec3| {
        let d = p - centre;
        assert!(d.length() > 10.0 * HEIGHT);
        let w = d.normalize();
        let gamma = (-w.y).clamp(-1.0, 1.0).acos().to_degrees();
        cylinder_intensity(gamma) * (-n.dot(w)).max(0.0) / d.length_squared()
    };
    for kind in [IntegratorKind::Direct, IntegratorKind::Path] {
        let results = measure(&sc, &st, kind, 300_000);
        compare(&format!("{kind} far"), &results, 0.01, point_model);
    }
}

/// Shapes from the sidecar: an explicit shape needs its sizes, "point" and "file" take none, and
/// a shape on a point light is refused; a file's unsupported shape becomes a point with a note.
#[test]
fn sidecar_shapes_are_checked() {
    let dir = scratch("sidecar");
    std::fs::write(dir.0.join("cyl.ies"), cylinder_file()).unwrap();
    let parse = |extra: &str| {
        let text = format!(
            "[[lights]]\nkind = \"luminaire\"\nfile = \"cyl.ies\"\nposition = [0.0, 1.0, 0.0]\n{extra}"
        );
        Sidecar::parse(&text, &dir.0.join("s.raygine.toml")).map(|_| ())
    };
    assert!(parse("").is_ok());
    assert!(parse("shape = \"point\"\n").is_ok());
    assert!(parse("shape = \"disc\"\nsize = [0.2]\n").is_ok());
    for (extra, reason) in [
        ("shape = \"disc\"\n", "size = [diameter]"),
        ("shape = \"box\"\nsize = [0.2, 0.1]\n", "got 2 numbers"),
        ("shape = \"sphere\"\nsize = [0.2]\n", "unknown shape"),
        ("size = [0.2]\n", "size belongs to an explicit shape"),
        ("shape = \"rectangle\"\nsize = [0.2, -1.0]\n", "> 0"),
    ] {
        let e = parse(extra).expect_err(extra);
        assert!(
            e.to_string().contains(reason) && e.to_string().contains("lights[0]"),
            "{extra}: {e}"
        );
    }
    let point = "[[lights]]\nposition = [0.0, 1.0, 0.0]\nintensity_cd = 1.0\nshape = \"disc\"\n";
    assert!(Sidecar::parse(point, &dir.0.join("p.raygine.toml")).is_err());
    // LM-63's sphere (all three negative) is not drawn: a point, with a note naming why.
    let sphere = ies_sized(&[0.0, 90.0], &[0.0], |_, _| 1.0, [-0.2, -0.2, -0.2]);
    let p =
        tracer_core::formats::parse_photometry(sphere.as_bytes(), std::path::Path::new("s.ies"))
            .unwrap();
    assert_eq!(p.shape, tracer_core::light::LuminousShape::Point);
    assert!(p.shape_note.is_some_and(|n| n.contains("drawn as a point")));
    // The far-field warning is for luminaires drawn as points: 5 cm under the ceiling of a
    // 3 m room, a 0.3 x 0.4 m cylinder warns as "point", not with its opening.
    let sc = box_scene(4.0, 3.0, 4.0, vec![]);
    for (extra, warned) in [("shape = \"point\"\n", true), ("", false)] {
        let text = format!(
            "unit = \"m\"\n[[lights]]\nkind = \"luminaire\"\nfile = \"cyl.ies\"\n\
             position = [2.0, 2.95, 2.0]\n{extra}"
        );
        let sidecar = Sidecar::parse(&text, &dir.0.join("w.raygine.toml")).unwrap();
        let mut warnings = Vec::new();
        let _ = sidecar.apply(&sc, None, &mut warnings);
        let far_field = warnings.iter().any(|w| w.contains("far-field"));
        assert_eq!(far_field, warned, "{extra:?}: {warnings:?}");
    }
}
