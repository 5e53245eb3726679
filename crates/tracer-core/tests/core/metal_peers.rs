//! A GGX metal (F = 1) against Mitsuba 3 and Blender Cycles, direct light only: a faceted
//! sphere (roughness 0.3, α = 0.09) on a plane (roughness 0.6, α = 0.36), lit by a point light
//! or by a one-sided rectangular emitter, 160 x 120. The references were rendered from the same
//! triangles, lights and camera by `scripts/mitsuba/metal_scene.py` (Mitsuba 3.9.1
//! `roughconductor`, `ggx`, `material = none`, `path` with max_depth 2, llvm_ad_rgb, 65,536 spp)
//! and `scripts/cycles/metal_cycles.py` (Blender 5.0.1 Cycles, Principled BSDF, GGX, metallic 1,
//! white base colour: F82 tint white gives F = 1; 0 bounces, 32,768 spp). Region means of
//! Rec. 709 Y in cd/m² below; each reference's own noise is below 0.1 % in every region but the
//! sphere's highlight (0.2 %).
//!
//! Masking: raygine and Cycles use height-correlated Smith, G2 = 1 / (1 + Λo + Λi); Mitsuba uses
//! the separable G1(ωo) G1(ωi) = 1 / ((1 + Λo)(1 + Λi)), which is smaller by the factor
//! (1 + Λo + Λi) / ((1 + Λo)(1 + Λi)). That matters where Λ is large: rough and grazing, the far
//! plane (α = 0.36 seen at about 75°), where Mitsuba reads 1.2 % below Cycles. The test predicts
//! that factor from the geometry and checks that it explains raygine against Mitsuba there.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use glam::DVec3;
use std::f64::consts::PI;
use tracer_core::formats::{MeshDescription, PartDescription, SceneDescription};
use tracer_core::integrator::IntegratorKind;
use tracer_core::light::EmissionSides;
use tracer_core::render::{Film, RenderSettings, render};
use tracer_core::scene::{Camera, Handedness, LengthUnit, Light, Material, Pbr, Scene, Setup};

const W: u32 = 160;
const H: u32 = 120;
const CAMERA: [f64; 3] = [0.0, 1.2, 3.5];
const LOOK_AT: [f64; 3] = [0.0, 0.4, 0.0];
const FOV_DEG: f64 = 40.0;
const POINT_LIGHT: [f64; 3] = [0.0, 2.0, 1.0];
const PLANE_ALPHA: f64 = 0.36;

/// (name, x0, x1, y0, y1 half-open, row 0 at the top).
type Region = (&'static str, u32, u32, u32, u32);
const REGIONS: [Region; 6] = [
    ("sphere highlight", 76, 84, 41, 48),
    ("sphere body", 66, 94, 50, 58),
    ("plane far (grazing)", 8, 44, 62, 70),
    ("plane middle", 0, 160, 76, 90),
    ("plane near", 50, 110, 96, 120),
    ("image", 0, 160, 0, 120),
];
/// Mitsuba's and Cycles' means over [`REGIONS`], cd/m².
const POINT_REFERENCE: [(f64, f64); 6] = [
    (9.22822, 9.22841),
    (0.0607543, 0.0607779),
    (0.0405161, 0.0410109),
    (0.116025, 0.116208),
    (0.504002, 0.504078),
    (0.131117, 0.131213),
];
const AREA_REFERENCE: [(f64, f64); 6] = [
    (62.3139, 62.336),
    (0.647029, 0.647286),
    (0.264991, 0.268055),
    (1.03065, 1.03215),
    (4.60623, 4.60746),
    (1.17786, 1.17873),
];

/// The sphere of the reference scripts: centre (0, 0.5, 0), radius 0.5, 32 rings x 64
/// segments, flat triangles wound outwards, the poles' degenerate triangles left out.
fn sphere() -> MeshDescription {
    let (rings, segments) = (32usize, 64usize);
    let mut positions = Vec::new();
    for i in 0..=rings {
        let t = PI * i as f64 / rings as f64;
        for j in 0..=segments {
            let p = 2.0 * PI * j as f64 / segments as f64;
            positions.push([
                0.5 * t.sin() * p.cos(),
                0.5 + 0.5 * t.cos(),
                0.5 * t.sin() * p.sin(),
            ]);
        }
    }
    let at = |i: usize, j: usize| (i * (segments + 1) + j) as u32;
    let mut triangles = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            // Outwards: from the +Y pole down, φ turning from +X towards +Z.
            if i > 0 {
                triangles.push([a, b, d]);
            }
            if i + 1 < rings {
                triangles.push([b, c, d]);
            }
        }
    }
    mesh("sphere", positions, triangles)
}

fn mesh(name: &str, positions: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> MeshDescription {
    MeshDescription {
        name: name.into(),
        positions,
        triangles,
        parts: vec![PartDescription::default()],
        ..MeshDescription::default()
    }
}

fn quad(name: &str, c: [[f64; 3]; 4]) -> MeshDescription {
    mesh(name, c.to_vec(), vec![[0, 1, 2], [0, 2, 3]])
}

fn metal(roughness: f32) -> Material {
    Material {
        kd: [0.0; 3],
        pbr: Some(Pbr {
            base_color: [1.0; 3],
            metallic: 1.0,
            roughness,
            transmission: 0.0,
        }),
        ..Material::default()
    }
}

/// raygine's picture of the scene (path mode, direct light only), lit by the point light or
/// by the emitter.
fn render_case(area: bool, spp: u32) -> Film {
    let mut meshes = vec![
        sphere(),
        quad(
            "plane",
            [
                [-2.0, 0.0, -2.0],
                [-2.0, 0.0, 2.0],
                [2.0, 0.0, 2.0],
                [2.0, 0.0, -2.0],
            ],
        ),
    ];
    let mut materials = vec![metal(0.3), metal(0.6)];
    let mut lights = Vec::new();
    if area {
        // Facing −Y: (c1 − c0) × (c2 − c0) = (1, 0, 0) × (1, 0, 1) = (0, −1, 0).
        meshes.push(quad(
            "emitter",
            [
                [-0.5, 2.0, 0.5],
                [0.5, 2.0, 0.5],
                [0.5, 2.0, 1.5],
                [-0.5, 2.0, 1.5],
            ],
        ));
        materials.push(Material {
            kd: [0.0; 3],
            emission_cd_m2: 100.0,
            emission_sides: EmissionSides::Front,
            ..Material::default()
        });
    } else {
        lights.push(Light::point(POINT_LIGHT.map(|c| c as f32), 10.0));
    }
    let desc = SceneDescription {
        meshes,
        ..SceneDescription::default()
    };
    let scene = Scene::build_with(&desc, "metal", 0.0).unwrap();
    assert_eq!(scene.slots.len(), materials.len());
    let setup = Setup {
        unit: LengthUnit::M,
        handedness: Handedness::Right,
        camera: Camera {
            position: CAMERA.map(|c| c as f32),
            look_at: LOOK_AT.map(|c| c as f32),
            up: [0.0, 1.0, 0.0],
            fov_deg: FOV_DEG as f32,
            ..Default::default()
        },
        lights,
        hidden: vec![false; materials.len()],
        materials,
        grids: Vec::new(),
        maintenance_factor: 1.0,
        environment: None,
        daylight: None,
        sun: None,
        observers: Vec::new(),
    };
    let settings = RenderSettings {
        width: W,
        height: H,
        samples_per_pixel: spp,
        integrator: IntegratorKind::Path,
        max_bounces: Some(1),
        ..RenderSettings::default()
    };
    render(&scene, &setup, &settings).0
}

/// The mean luminance over a region and its standard error.
fn region_mean(film: &Film, (_, x0, x1, y0, y1): Region) -> (f64, f64) {
    let (mut sum, mut var, mut n) = (0.0, 0.0, 0.0);
    for y in y0..y1 {
        for x in x0..x1 {
            let p = &film.pixel((y * W + x) as usize);
            sum += p.mean_luminance();
            var += p.luminance_std_error().unwrap_or(f64::INFINITY).powi(2);
            n += 1.0;
        }
    }
    (sum / n, var.sqrt() / n)
}

/// GGX's Λ(ω) for α, with cos θ = `cos`.
fn lambda(alpha: f64, cos: f64) -> f64 {
    let tan2 = (1.0 - cos * cos) / (cos * cos);
    (-1.0 + (1.0 + alpha * alpha * tan2).sqrt()) / 2.0
}

/// Over a region of the plane lit by the point light: the mean of the factor by which the
/// separable masking darkens the height-correlated one, weighted by `weight` (the reference
/// picture), through each pixel's centre.
fn separable_over_correlated(region: Region, weight: &dyn Fn(u32, u32) -> f64) -> f64 {
    let (_, x0, x1, y0, y1) = region;
    let eye = DVec3::from(CAMERA);
    let forward = (DVec3::from(LOOK_AT) - eye).normalize();
    let right = forward.cross(DVec3::Y).normalize();
    let up = right.cross(forward);
    let half = (FOV_DEG.to_radians() / 2.0).tan();
    let aspect = f64::from(W) / f64::from(H);
    let (mut sum, mut total) = (0.0, 0.0);
    for y in y0..y1 {
        for x in x0..x1 {
            let sx = (2.0 * (f64::from(x) + 0.5) / f64::from(W) - 1.0) * half * aspect;
            let sy = (1.0 - 2.0 * (f64::from(y) + 0.5) / f64::from(H)) * half;
            let d = forward + right * sx + up * sy;
            let t = -eye.y / d.y;
            let p = eye + d * t;
            let wo = (eye - p).normalize();
            let wi = (DVec3::from(POINT_LIGHT) - p).normalize();
            let (lo, li) = (lambda(PLANE_ALPHA, wo.y), lambda(PLANE_ALPHA, wi.y));
            let factor = (1.0 + lo + li) / ((1.0 + lo) * (1.0 + li));
            let w = weight(x, y);
            sum += w * factor;
            total += w;
        }
    }
    sum / total
}

fn compare(area: bool, spp: u32, references: &[(f64, f64); 6]) -> Film {
    let film = render_case(area, spp);
    let case = if area { "area emitter" } else { "point light" };
    for (region, &(mitsuba, cycles)) in REGIONS.iter().zip(references) {
        let (mean, se) = region_mean(&film, *region);
        println!(
            "{case}, {}: raygine {mean:.5} ± {se:.5} cd/m², Mitsuba {mitsuba:.5} ({:+.2} %), \
             Cycles {cycles:.5} ({:+.2} %)",
            region.0,
            (mean / mitsuba - 1.0) * 100.0,
            (mean / cycles - 1.0) * 100.0
        );
        assert!(
            se < 0.005 * mean,
            "{case}, {}: noise {se} too high",
            region.0
        );
        for (peer, reference) in [("Mitsuba", mitsuba), ("Cycles", cycles)] {
            assert!(
                (mean / reference - 1.0).abs() < 0.02,
                "{case}, {}: raygine {mean} ± {se} vs {peer} {reference}",
                region.0
            );
        }
    }
    film
}

#[test]
fn a_ggx_metal_under_a_point_light_matches_mitsuba_and_cycles() {
    let film = compare(false, 256, &POINT_REFERENCE);
    // Where Mitsuba's separable masking should read below height-correlated Smith, the factor
    // predicted from the geometry explains raygine against Mitsuba, within 0.4 %.
    let far = REGIONS[2];
    let pixel = |x: u32, y: u32| film.pixel((y * W + x) as usize).mean_luminance();
    let predicted = separable_over_correlated(far, &pixel);
    let (mean, _) = region_mean(&film, far);
    let seen = POINT_REFERENCE[2].0 / mean;
    println!("plane far: Mitsuba / raygine {seen:.4}, predicted by the masking {predicted:.4}");
    assert!(
        predicted < 0.995,
        "the region should show the masking: {predicted}"
    );
    assert!(
        (seen / predicted - 1.0).abs() < 0.004,
        "Mitsuba / raygine {seen} is not the masking's {predicted}"
    );
}

#[test]
fn a_ggx_metal_under_an_area_emitter_matches_mitsuba_and_cycles() {
    compare(true, 1024, &AREA_REFERENCE);
}
