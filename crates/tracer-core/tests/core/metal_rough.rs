//! The metallic-roughness BSDF (glTF 2.0 Appendix B, GGX with height-correlated Smith) against
//! answers computed here: a plane under a uniform sky of luminance L, seen at θo, reads
//! L · A(θo), A the directional albedo by quadrature of Appendix B's formulas written again in
//! f64 below (not the renderer's code).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::gi_support::*;
use std::f64::consts::PI;
use tracer_core::integrator::IntegratorKind;
use tracer_core::light::{Environment, EnvironmentSource};
use tracer_core::render::{RenderSettings, render};
use tracer_core::scene::{Camera, Material, Pbr, Sidecar};

/// Appendix B's f(ωo, ωi), green channel of base colour `c`, F0 of the dielectric 0.04.
fn appendix_b(c: f64, metallic: f64, roughness: f64, wo: [f64; 3], wi: [f64; 3]) -> f64 {
    let (diffuse, specular) = appendix_b_parts(c, metallic, roughness, 0.0, wo, wi);
    diffuse + specular
}

/// Appendix B's f split into its diffuse base (smooth in ωi) and its GGX terms; `t` is
/// `KHR_materials_transmission`'s factor, which takes its share of the diffuse base.
fn appendix_b_parts(
    c: f64,
    metallic: f64,
    roughness: f64,
    transmission: f64,
    wo: [f64; 3],
    wi: [f64; 3],
) -> (f64, f64) {
    let a = (roughness * roughness).max(1e-3);
    let a2 = a * a;
    let h = [wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]];
    let hl = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
    let h = [h[0] / hl, h[1] / hl, h[2] / hl];
    let t = h[2] * h[2] * (a2 - 1.0) + 1.0;
    let d = a2 / (PI * t * t);
    let lambda = |w: [f64; 3]| {
        let c2 = w[2] * w[2];
        (-1.0 + (1.0 + a2 * (1.0 - c2) / c2).sqrt()) / 2.0
    };
    let vis = 1.0 / (1.0 + lambda(wo) + lambda(wi)) / (4.0 * wo[2] * wi[2]);
    let vh = (wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2]).abs();
    let w = (1.0 - vh).powi(5);
    let f_dielectric = 0.04 + 0.96 * w;
    let metal = (c + (1.0 - c) * w) * d * vis;
    (
        (1.0 - metallic) * (1.0 - f_dielectric) * c * (1.0 - transmission) / PI,
        (1.0 - metallic) * f_dielectric * d * vis + metallic * metal,
    )
}

/// A(θo) = ∫ f cos θi dωi: the diffuse base over ωi (midpoint rule), the GGX terms over half
/// vectors h (dωi = 4 (ωo·h) dωh), θh on GGX's own inverse CDF so that even α = 0.01 is
/// resolved.
pub(crate) fn albedo(c: f64, metallic: f64, roughness: f64, t: f64, theta_o: f64) -> f64 {
    let a = (roughness * roughness).max(1e-3);
    let wo = [theta_o.sin(), 0.0, theta_o.cos()];
    let q = 400;
    let (dt, dp) = (0.5 * PI / q as f64, PI / q as f64);
    let mut diffuse = 0.0;
    for i in 0..q {
        let th = (i as f64 + 0.5) * dt;
        for j in 0..2 * q {
            let p = (j as f64 + 0.5) * dp;
            let wi = [th.sin() * p.cos(), th.sin() * p.sin(), th.cos()];
            diffuse +=
                appendix_b_parts(c, metallic, roughness, t, wo, wi).0 * wi[2] * th.sin() * dt * dp;
        }
    }
    let (nx, np) = (4000, 720);
    let theta_h = |x: f64| (a * (x / (1.0 - x)).sqrt()).atan();
    let mut sum = 0.0;
    for i in 0..nx {
        let (x0, x1) = (i as f64 / nx as f64, (i + 1) as f64 / nx as f64);
        let (t0, t1) = (theta_h(x0), theta_h(x1.min(1.0 - 1e-12)));
        let th = 0.5 * (t0 + t1);
        let dt = t1 - t0;
        for j in 0..np {
            let ph = (j as f64 + 0.5) / np as f64 * 2.0 * PI;
            let h = [th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()];
            let oh = wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2];
            if oh <= 0.0 {
                continue;
            }
            let wi = [
                2.0 * oh * h[0] - wo[0],
                2.0 * oh * h[1] - wo[1],
                2.0 * oh * h[2] - wo[2],
            ];
            if wi[2] <= 0.0 {
                continue;
            }
            let f = appendix_b_parts(c, metallic, roughness, t, wo, wi).1;
            sum += f * wi[2] * 4.0 * oh * th.sin() * dt * (2.0 * PI / np as f64);
        }
    }
    diffuse + sum
}

/// A 100 x 100 m plane (front +Y) under a uniform sky of 100 cd/m², seen at `theta_deg` from
/// its normal through a 2° camera 5 m away.
fn plane_reading(pbr: Pbr, theta_deg: f64, integrator: IntegratorKind, spp: u32) -> (f64, f64) {
    let plane = brep(
        "plane",
        &[[
            [-50.0, 0.0, -50.0],
            [-50.0, 0.0, 50.0],
            [50.0, 0.0, 50.0],
            [50.0, 0.0, -50.0],
        ]],
    );
    let sc = scene(vec![plane]);
    let t = theta_deg.to_radians();
    let cam = Camera {
        position: [(5.0 * t.sin()) as f32, (5.0 * t.cos()) as f32, 0.0],
        look_at: [0.0; 3],
        up: [0.0, 0.0, 1.0],
        fov_deg: 2.0,
        ..Default::default()
    };
    let material = Material {
        pbr: Some(pbr),
        kd: [0.0; 3],
        ..Material::default()
    };
    let mut st = setup(&sc, cam, vec![], vec![material]);
    st.environment = Some(Environment {
        source: EnvironmentSource::Uniform {
            luminance_cd_m2: 100.0,
            color: [1.0; 3],
        },
        scale: 1.0,
        rotation_deg: 0.0,
        background: true,
    });
    let settings = RenderSettings {
        width: 6,
        height: 6,
        samples_per_pixel: spp,
        integrator,
        ..RenderSettings::default()
    };
    let (film, _) = render(&sc, &st, &settings);
    film_mean_luminance(&film)
}

/// Rough metal (F0 = 1) and a rough dielectric over a coloured base, roughness 0.1-1, at
/// θo = 0°, 45° and 75°: the reading is L · A(θo) within 1 %, in path and bdpt.
#[test]
fn a_plane_under_a_uniform_sky_reads_its_directional_albedo() {
    for (c, metallic) in [(1.0f32, 1.0f32), (0.5, 0.0)] {
        for roughness in [0.1f32, 0.3, 0.6, 1.0] {
            for theta in [0.0f64, 45.0, 75.0] {
                let exact = 100.0
                    * albedo(
                        f64::from(c),
                        f64::from(metallic),
                        f64::from(roughness),
                        0.0,
                        theta.to_radians(),
                    );
                let pbr = Pbr {
                    base_color: [c; 3],
                    metallic,
                    roughness,
                    transmission: 0.0,
                };
                for (integrator, spp) in [
                    (IntegratorKind::Path, 2048),
                    (IntegratorKind::Bidirectional, 4096),
                ] {
                    let (mean, se) = plane_reading(pbr, theta, integrator, spp);
                    let what = format!(
                        "{integrator} metallic {metallic} c {c} roughness {roughness} θo {theta}°"
                    );
                    println!(
                        "{what}: {mean:.3} ± {se:.3} cd/m² vs L·A = {exact:.3} ({:+.2} %)",
                        (mean / exact - 1.0) * 100.0
                    );
                    assert!(
                        (mean / exact - 1.0).abs() < 0.01 && (mean - exact).abs() < 4.0 * se + 1e-6,
                        "{what}: {mean} ± {se} vs {exact}"
                    );
                }
            }
        }
    }
}

/// Direct mode evaluates the same BSDF for its lights: a point light over the plane gives
/// E f(ωo, ωi) in the camera's pixel.
#[test]
fn direct_mode_shades_with_the_metallic_roughness_brdf() {
    let text = "kd = [0.5, 0.5, 0.5]\nroughness = 0.5";
    let both = Sidecar::parse(
        &format!("[materials.a]\n{text}\n"),
        std::path::Path::new("m.raygine.toml"),
    )
    .unwrap_err()
    .to_string();
    assert!(
        both.contains("not both") && both.contains("kd and roughness"),
        "{both}"
    );
    let plane = brep(
        "plane",
        &[[
            [-5.0, 0.0, -5.0],
            [-5.0, 0.0, 5.0],
            [5.0, 0.0, 5.0],
            [5.0, 0.0, -5.0],
        ]],
    );
    let sc = scene(vec![plane]);
    let (c, metallic, roughness) = (0.6f32, 0.3f32, 0.5f32);
    let material = Material {
        pbr: Some(Pbr {
            base_color: [c; 3],
            metallic,
            roughness,
            transmission: 0.0,
        }),
        kd: [0.0; 3],
        ..Material::default()
    };
    // Camera 2 m up at 30° from the normal, light 1 m up at 40° on the other side, both
    // aimed at the origin: the centre pixel sees the origin.
    let (to, ti) = (30f64.to_radians(), 40f64.to_radians());
    let cam = Camera {
        position: [(2.0 * to.sin()) as f32, (2.0 * to.cos()) as f32, 0.0],
        look_at: [0.0; 3],
        up: [0.0, 0.0, 1.0],
        fov_deg: 0.5,
        ..Default::default()
    };
    let light_at = [-(ti.sin()) as f32, ti.cos() as f32, 0.0];
    let light = tracer_core::scene::Light::point(light_at, 100.0);
    let st = setup(&sc, cam, vec![light], vec![material]);
    let settings = RenderSettings {
        width: 3,
        height: 3,
        samples_per_pixel: 16,
        integrator: IntegratorKind::Direct,
        ..RenderSettings::default()
    };
    let (film, _) = render(&sc, &st, &settings);
    let centre = film.pixel(4).mean_luminance();
    // E = I cos θi / R² at 1 m; L = E f.
    let wo = [to.sin(), 0.0, to.cos()];
    let wi = [-ti.sin(), 0.0, ti.cos()];
    let exact = 100.0
        * ti.cos()
        * appendix_b(
            f64::from(c),
            f64::from(metallic),
            f64::from(roughness),
            wo,
            wi,
        );
    assert!(
        (centre / exact - 1.0).abs() < 0.01,
        "direct: {centre} vs E f = {exact}"
    );
}

/// glTF's thin-walled transmission: the plane, with the sky on both sides, reads L (A(θo) +
/// T (1 − metallic)(1 − F(cos θo)) c): the reflection with the diffuse base's share 1 − T, and
/// the sky behind seen through it, with F = F0 + (1 − F0)(1 − cos θo)⁵.
#[test]
fn thin_walled_transmission_lets_the_sky_behind_through() {
    let (c, metallic, roughness, t) = (0.8f32, 0.2f32, 0.3f32, 0.7f32);
    for theta in [0.0f64, 60.0] {
        let cos = theta.to_radians().cos();
        let through =
            f64::from(t * (1.0 - metallic) * c) * (1.0 - (0.04 + 0.96 * (1.0 - cos).powi(5)));
        let exact = 100.0
            * (albedo(
                f64::from(c),
                f64::from(metallic),
                f64::from(roughness),
                f64::from(t),
                theta.to_radians(),
            ) + through);
        let pbr = Pbr {
            base_color: [c; 3],
            metallic,
            roughness,
            transmission: t,
        };
        for (integrator, spp) in [
            (IntegratorKind::Path, 2048),
            (IntegratorKind::Bidirectional, 4096),
        ] {
            let (mean, se) = plane_reading(pbr, theta, integrator, spp);
            let what = format!("{integrator} transmission {t} θo {theta}°");
            println!(
                "{what}: {mean:.3} ± {se:.3} cd/m² vs {exact:.3} ({:+.2} %)",
                (mean / exact - 1.0) * 100.0
            );
            assert!(
                (mean / exact - 1.0).abs() < 0.01 && (mean - exact).abs() < 4.0 * se + 1e-6,
                "{what}: {mean} ± {se} vs {exact}"
            );
        }
    }
}

/// A smooth metal (roughness 0) is a mirror of reflectance F = c + (1 − c)(1 − cos θo)⁵:
/// direct mode follows it as its mirrors (the sky seen in it), and path mode's GGX at its
/// smallest α reads the same.
#[test]
fn a_smooth_metal_is_a_mirror_in_direct_mode() {
    let c = 0.6f32;
    let pbr = Pbr {
        base_color: [c; 3],
        metallic: 1.0,
        roughness: 0.0,
        transmission: 0.0,
    };
    for theta in [0.0f64, 75.0] {
        let w = (1.0 - theta.to_radians().cos()).powi(5);
        let exact = 100.0 * (f64::from(c) + (1.0 - f64::from(c)) * w);
        for (integrator, spp, tolerance) in [
            (IntegratorKind::Direct, 16, 1e-3),
            (IntegratorKind::Path, 256, 0.01),
        ] {
            let (mean, se) = plane_reading(pbr, theta, integrator, spp);
            println!("{integrator} smooth metal θo {theta}°: {mean:.3} ± {se:.3} vs {exact:.3}");
            assert!(
                (mean / exact - 1.0).abs() < tolerance,
                "{integrator} θo {theta}°: {mean} ± {se} vs mirror {exact}"
            );
        }
    }
}
