//! The integrator against analytic answers (never against itself):
//! a Lambertian plane under a point light, the cos θ / R² falloff, mirrors, shadows, units.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use glam::Vec3;
use std::f32::consts::PI;
use tracer_core::Ray;
use tracer_core::integrator::trace_direct;
use tracer_core::lit_scene::LitScene;
use tracer_core::sampling::SampleRng;
use tracer_core::scene::{Camera, Handedness, LengthUnit, Light, Material, Scene, Setup};
use tracer_core::shp::BrepDef;

use crate::gi_support::{brep, scene};

/// A floor at y = 0, 200 x 200 units centred on the origin, scaled by `s`.
fn floor(s: f64) -> BrepDef {
    let a = 100.0 * s;
    brep(
        "floor",
        &[[[-a, 0.0, -a], [-a, 0.0, a], [a, 0.0, a], [a, 0.0, -a]]],
    )
}

fn setup(scene: &Scene, unit: LengthUnit, lights: Vec<Light>, mats: Vec<Material>) -> Setup {
    Setup {
        unit,
        handedness: Handedness::Left,
        camera: Camera {
            position: [0.0, 10.0, 10.0],
            look_at: [0.0; 3],
            up: [0.0, 1.0, 0.0],
            fov_deg: 45.0,
            ..Default::default()
        },
        lights,
        hidden: vec![false; scene.slots.len()],
        materials: mats,
        grids: Vec::new(),
        maintenance_factor: 1.0,
        environment: None,
        daylight: None,
        sun: None,
        observers: Vec::new(),
    }
}

fn diffuse(rho: f32) -> Material {
    Material {
        kd: [rho; 3],
        ks: [0.0; 3],
        glossiness: 0.0,
        ..Material::default()
    }
}

fn light(p: [f32; 3], cd: f32) -> Light {
    Light::point(p, cd)
}

/// Luminance seen along the ray from `eye` towards `target`.
fn seen(lit: &LitScene<'_>, eye: Vec3, target: Vec3) -> (Vec3, f32) {
    let s = trace_direct(
        lit,
        &Ray::new(eye, (target - eye).normalize()),
        &mut SampleRng::new(0, 0),
    );
    (s.rgb, s.illuminance_lx)
}

fn close(a: f32, b: f32, rel: f32) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-12)
}

#[test]
fn lambertian_plane_below_the_light() {
    let sc = scene(vec![floor(1.0)]);
    let (rho, i, h) = (0.6f32, 250.0f32, 2.0f32);
    let st = setup(
        &sc,
        LengthUnit::M,
        vec![light([0.0, h, 0.0], i)],
        vec![diffuse(rho)],
    );
    let lit = LitScene::new(&sc, &st, 5);
    let (l, e) = seen(&lit, Vec3::new(0.3, 5.0, 0.4), Vec3::ZERO);
    let want = rho * i / (PI * h * h);
    for c in l.to_array() {
        assert!(close(c, want, 1e-4), "L = {c}, want {want}");
    }
    assert!(close(e, i / (h * h), 1e-4), "E = {e}");
}

#[test]
fn falloff_along_the_plane_is_cos_over_r_squared() {
    let sc = scene(vec![floor(1.0)]);
    let (rho, i, h) = (0.5f32, 1000.0f32, 3.0f32);
    let st = setup(
        &sc,
        LengthUnit::M,
        vec![light([0.0, h, 0.0], i)],
        vec![diffuse(rho)],
    );
    let lit = LitScene::new(&sc, &st, 5);
    for x in [0.5f32, 1.0, 2.0, 4.0, 8.0, 20.0] {
        let p = Vec3::new(x, 0.0, 0.0);
        let (l, e) = seen(&lit, Vec3::new(x, 6.0, 1.0), p);
        let r2 = x * x + h * h;
        let cos = h / r2.sqrt();
        let e_want = i * cos / r2;
        assert!(close(e, e_want, 1e-4), "x = {x}: E = {e}, want {e_want}");
        assert!(close(l.y, rho * e_want / PI, 1e-4), "x = {x}: L = {}", l.y);
    }
}

#[test]
fn units_convert_distances_to_metres() {
    // The same floor and light written in millimetres give the same luminance.
    let sc = scene(vec![floor(1000.0)]);
    let st = setup(
        &sc,
        LengthUnit::Mm,
        vec![light([0.0, 2000.0, 0.0], 250.0)],
        vec![diffuse(0.6)],
    );
    let lit = LitScene::new(&sc, &st, 5);
    let (l, _) = seen(&lit, Vec3::new(300.0, 5000.0, 400.0), Vec3::ZERO);
    assert!(close(l.x, 0.6 * 250.0 / (PI * 4.0), 1e-4), "{l}");
}

#[test]
fn occluder_casts_a_hard_shadow_and_light_behind_gives_zero() {
    // A small square card at y = 1 between the light (y = 2) and the floor point below it.
    let card = brep(
        "card",
        &[[
            [-0.1, 1.0, -0.1],
            [0.1, 1.0, -0.1],
            [0.1, 1.0, 0.1],
            [-0.1, 1.0, 0.1],
        ]],
    );
    let sc = scene(vec![floor(1.0), card]);
    let st = setup(
        &sc,
        LengthUnit::M,
        vec![light([0.0, 2.0, 0.0], 100.0)],
        vec![diffuse(0.5), diffuse(0.5)],
    );
    let lit = LitScene::new(&sc, &st, 5);
    // Below the card: in shadow.
    let (l, e) = seen(&lit, Vec3::new(3.0, 0.5, 0.0), Vec3::new(0.0, 0.0, 0.0));
    assert_eq!((l, e), (Vec3::ZERO, 0.0));
    // Outside the card's shadow: lit.
    let (l, _) = seen(&lit, Vec3::new(3.0, 0.5, 0.0), Vec3::new(1.0, 0.0, 0.0));
    assert!(l.x > 0.0);
    // The floor seen from below (its unlit side): the light is behind that side.
    let (l, e) = seen(&lit, Vec3::new(0.5, -3.0, 0.5), Vec3::new(1.0, 0.0, 1.0));
    assert_eq!((l, e), (Vec3::ZERO, 0.0));
}

#[test]
fn mirror_shows_the_wall_at_ks_times_its_luminance() {
    // A wall at x = -2 (facing +x), a mirror floor with Ks 0.5 (Kd 0), light at (0, 3, 0).
    let wall = brep(
        "wall",
        &[[
            [-2.0, 0.0, -50.0],
            [-2.0, 0.0, 50.0],
            [-2.0, 50.0, 50.0],
            [-2.0, 50.0, -50.0],
        ]],
    );
    let sc = scene(vec![floor(1.0), wall]);
    let mirror = Material {
        kd: [0.0; 3],
        ks: [0.5, 0.4, 0.3],
        glossiness: 0.0,
        ..Material::default()
    };
    let st = setup(
        &sc,
        LengthUnit::M,
        vec![light([0.0, 3.0, 0.0], 400.0)],
        vec![mirror, diffuse(0.8)],
    );
    let lit = LitScene::new(&sc, &st, 5);
    // Eye at (1, 1, 0) looking at floor point (0, 0, 0): the reflection continues to (-1, 1, 0)
    // direction and hits the wall at (-2, 2, 0).
    let eye = Vec3::new(1.0, 1.0, 0.0);
    let (via_mirror, e) = seen(&lit, eye, Vec3::ZERO);
    let (wall_direct, _) = seen(&lit, Vec3::new(0.0, 2.0, 0.0), Vec3::new(-2.0, 2.0, 0.0));
    assert!(wall_direct.x > 0.0);
    for (c, ks) in [0.5f32, 0.4, 0.3].into_iter().enumerate() {
        assert!(
            close(via_mirror[c], ks * wall_direct[c], 3e-3),
            "{via_mirror} vs {wall_direct}"
        );
    }
    // The mirror has no diffuse part, but the floor point is still lit: E is recorded.
    assert!(close(e, 400.0 / 9.0, 1e-4));
    // Depth 0: no reflection traced, so the mirror floor is black.
    let prep0 = LitScene::new(&sc, &st, 0);
    assert_eq!(seen(&prep0, eye, Vec3::ZERO).0, Vec3::ZERO);
}

#[test]
fn blinn_phong_highlight_is_normalised() {
    // Specular-only floor, viewer on the mirror direction of the light: n·h = 1, so
    // L = E Ks (g + 8) / (8π) (plus the mirror term, which sees only sky here).
    let sc = scene(vec![floor(1.0)]);
    let g = 500.0;
    let m = Material {
        kd: [0.0; 3],
        ks: [0.3; 3],
        glossiness: g,
        ..Material::default()
    };
    let st = setup(
        &sc,
        LengthUnit::M,
        vec![light([-1.0, 1.0, 0.0], 100.0)],
        vec![m],
    );
    let lit = LitScene::new(&sc, &st, 5);
    let (l, e) = seen(&lit, Vec3::new(1.0, 1.0, 0.0), Vec3::ZERO);
    let want = e * 0.3 * (g + 8.0) / (8.0 * PI);
    assert!(close(l.x, want, 1e-3), "{l} vs {want}");
    // Off the mirror direction the lobe falls away.
    let (off, _) = seen(&lit, Vec3::new(1.0, 3.0, 0.5), Vec3::ZERO);
    assert!(off.x < 0.1 * want);
}

#[test]
fn coloured_light_keeps_its_intensity_in_candela() {
    let sc = scene(vec![floor(1.0)]);
    let mut l = light([0.0, 1.0, 0.0], 10.0);
    l.color = [1.0, 0.2, 0.1];
    let st = setup(&sc, LengthUnit::M, vec![l], vec![diffuse(1.0)]);
    let lit = LitScene::new(&sc, &st, 5);
    let (rgb, e) = seen(&lit, Vec3::new(0.0, 3.0, 0.1), Vec3::ZERO);
    // White Kd 1: pixel luminance = E / π whatever the tint.
    let y = tracer_core::scene::luminance(rgb);
    assert!(close(y, 10.0 / PI, 1e-4), "{y}");
    assert!(close(e, 10.0, 1e-5));
    assert!(rgb.x > rgb.y && rgb.y > rgb.z);
}
