//! Global illumination against exact answers (never against itself): furnaces, CIE 171:2006
//! cases 5.3 and 5.8, path mode with one bounce against direct mode, the convergence rate and
//! bit-identical results across threads and sample ranges. `../shared/LIGHTING.md` has the
//! formulas. Pass criteria: within 0.5 % of the exact value and within 4 reported standard
//! errors, the reported standard error below 0.2 %.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::gi_support::*;
use glam::{DVec3, Vec3};
use std::f64::consts::PI;
use tracer_core::integrator::IntegratorKind;
use tracer_core::measure::{Grid, MeasureSettings, measure_grids};
use tracer_core::render::{Film, RenderSettings, render, render_samples};
use tracer_core::scene::{Light, Material, builtin_cornell_box};

fn path_settings(w: u32, h: u32, spp: u32) -> RenderSettings {
    RenderSettings {
        width: w,
        height: h,
        samples_per_pixel: spp,
        integrator: IntegratorKind::Path,
        ..RenderSettings::default()
    }
}

/// The image's mean luminance and its standard error (pixels are independent).
fn image_mean(film: &Film) -> (f64, f64) {
    let n = film.len() as f64;
    let mean = film.pixels().map(|p| p.mean_luminance()).sum::<f64>() / n;
    let var: f64 = film
        .pixels()
        .map(|p| p.luminance_std_error().unwrap().powi(2))
        .sum();
    (mean, var.sqrt() / n)
}

/// Every pixel within 4.5 of its own standard errors of `exact` (with 256 pixels, a correct
/// renderer fails this by chance with probability about 0.2 %).
fn every_pixel_near(film: &Film, exact: f64, what: &str) {
    for (i, p) in film.pixels().enumerate() {
        let se = p.luminance_std_error().unwrap();
        let d = (p.mean_luminance() - exact).abs();
        assert!(
            d < 4.5 * se,
            "{what}: pixel {i} reads {} for {exact} (std error {se})",
            p.mean_luminance()
        );
    }
}

/// Furnace: a closed box whose surfaces all emit Le and reflect diffusely with ρ shows
/// L = Le / (1 − ρ) in every pixel.
#[test]
fn diffuse_furnace_shows_le_over_one_minus_rho() {
    let sc = box_scene(2.0, 2.0, 2.0, vec![]);
    let le = 100.0;
    for rho in [0.5f32, 0.9] {
        let mats = vec![emitting(diffuse(rho), le); 6];
        let cam = camera([1.0, 1.0, 1.5], [1.0, 1.0, 0.0], 70.0);
        let st = setup(&sc, cam, vec![], mats);
        let (film, _) = render(&sc, &st, &path_settings(16, 16, 384));
        let exact = f64::from(le) / (1.0 - f64::from(rho));
        let (mean, se) = image_mean(&film);
        check(&format!("furnace rho {rho}"), mean, se, exact, 0.005, 0.002);
        every_pixel_near(&film, exact, &format!("furnace rho {rho}"));
        // Each pixel's illuminance is the irradiance of the enclosure: E = π L.
        let e = film
            .pixels()
            .map(|p| f64::from(p.mean_illuminance()))
            .sum::<f64>()
            / film.len() as f64;
        assert!(
            (e / (PI * exact) - 1.0).abs() < 0.01,
            "E {e} vs {}",
            PI * exact
        );
    }
}

/// Albedo of the normalised Blinn-Phong lobe at normal incidence, ∫ (g+8)/(8π) (n·h)^g cos θ dω,
/// by midpoint quadrature (independent of the renderer's sampling).
fn blinn_phong_albedo_normal(g: f64) -> f64 {
    let q = 800;
    let mut sum = 0.0;
    for i in 0..q {
        let th = (i as f64 + 0.5) / q as f64 * PI / 2.0;
        // At normal incidence h lies halfway between n and wi: n·h = cos(θ/2); no φ dependence.
        let nh = (th / 2.0).cos();
        sum += (g + 8.0) / (8.0 * PI) * nh.powf(g) * th.cos() * th.sin() * (PI / 2.0 / q as f64);
    }
    sum * 2.0 * PI
}

/// Glossy furnace: every surface emits Le and has only a Blinn-Phong lobe Ks. With one bounce
/// the camera sees Le (1 + Ks A(θ)) exactly, A the lobe's albedo (normal incidence here); with
/// unlimited bounces the answer lies between that and Le / (1 − Ks max A).
#[test]
fn glossy_furnace_matches_the_lobe_albedo() {
    let sc = box_scene(2.0, 2.0, 2.0, vec![]);
    let le = 100.0;
    let (ks, g) = (0.6f32, 20.0f32);
    let m = Material {
        kd: [0.0; 3],
        ks: [ks; 3],
        glossiness: g,
        emission_cd_m2: le,
        ..Material::default()
    };
    // A narrow view straight at the wall: every pixel sees it at normal incidence.
    let cam = camera([1.0, 1.0, 1.0], [1.0, 1.0, 0.0], 0.5);
    let st = setup(&sc, cam, vec![], vec![m; 6]);
    let a = blinn_phong_albedo_normal(f64::from(g));
    let mut one = path_settings(8, 8, 1024);
    one.max_bounces = Some(1);
    let (film, _) = render(&sc, &st, &one);
    let exact = f64::from(le) * (1.0 + f64::from(ks) * a);
    let (mean, se) = image_mean(&film);
    check("glossy furnace, one bounce", mean, se, exact, 0.005, 0.002);
    let (film, _) = render(&sc, &st, &path_settings(8, 8, 256));
    let (mean, se) = image_mean(&film);
    let upper = f64::from(le) / (1.0 - f64::from(ks) * a);
    println!("glossy furnace, all bounces: {mean:.3} ± {se:.3}, bounds {exact:.3} .. {upper:.3}");
    assert!(mean > exact && mean < upper + 4.0 * se, "{mean}");
}

/// CIE 171:2006 case 5.8: a 4 m cube, an isotropic 10,000 lm source at its centre, uniform ρ:
/// the area-mean indirect illuminance is ρ Φ / (S (1 − ρ)), S = 96 m². Measured through grids
/// on all six faces; the exact direct part (I cos θ / d²) is subtracted point by point.
/// (Grid refinement seen while writing this test, ρ = 0.5: +1.4 % at 4 x 4 points a face,
/// +0.49 % at 8 x 8, +0.22 % at 16 x 16, +0.02 % at 32 x 32: the midpoint rule, not the light.)
#[test]
fn cie_5_8_internal_reflected_component() {
    let sc = box_scene(4.0, 4.0, 4.0, vec![]);
    let flux = 10_000.0f32;
    let source = Light::point([2.0, 2.0, 2.0], flux / (4.0 * std::f32::consts::PI));
    for (rho, samples) in [(0.5f32, 32), (0.9, 32)] {
        let cam = camera([2.0, 2.0, 3.9], [2.0, 2.0, 0.0], 60.0);
        let mut st = setup(&sc, cam, vec![source.clone()], vec![diffuse(rho); 6]);
        // 32 x 32 points a face: the cell-centre (midpoint) rule's own error on the area mean
        // is then below 0.03 % (0.5 % at 8 x 8, 0.2 % at 16 x 16 for ρ = 0.5).
        st.grids = face_grids(4.0, 4.0, 4.0, 32);
        let settings = MeasureSettings {
            integrator: IntegratorKind::Path,
            max_bounces: None,
            samples,
            time_limit: None,
            target_error: None,
        };
        let results = measure_grids(&sc, &st, &settings);
        let i_cd = f64::from(flux) / (4.0 * PI);
        let (mut sum, mut var, mut n) = (0.0, 0.0, 0.0);
        for r in &results {
            for p in &r.points {
                let d = p.position.as_dvec3() - DVec3::splat(2.0);
                let cos = r.normal.as_dvec3().dot(-d.normalize());
                let direct = i_cd * cos / d.length_squared();
                sum += p.illuminance_lx - direct;
                var += p.std_error_lx.powi(2);
                n += 1.0;
            }
        }
        let indirect = sum / n;
        let se = var.sqrt() / n;
        let exact = f64::from(rho) * f64::from(flux) / (96.0 * (1.0 - f64::from(rho)));
        check(
            &format!("CIE 5.8 rho {rho}"),
            indirect,
            se,
            exact,
            0.005,
            0.002,
        );
    }
}

/// The CIE 5.3 room: 4 x 3 x 4 m (y up), black surfaces, a 1 x 1 m Lambertian panel of
/// 1000 cd/m² centred just under the ceiling, emitting downwards (its front side).
fn cie_5_3_room() -> (
    tracer_core::scene::Scene,
    tracer_core::scene::Setup,
    Vec<DVec3>,
) {
    let y = 3.0 - 1e-3;
    // Wound so that (c1 − c0) × (c2 − c0) points down: the front (right-handed) faces the room.
    let panel: Quad = [[1.5, y, 1.5], [2.5, y, 1.5], [2.5, y, 2.5], [1.5, y, 2.5]];
    let sc = box_scene(4.0, 3.0, 4.0, vec![brep("panel", &[panel])]);
    let mut mats = vec![diffuse(0.0); 7];
    mats[6] = Material {
        emission_cd_m2: 1000.0,
        emission_sides: tracer_core::light::EmissionSides::Front,
        ..diffuse(0.0)
    };
    let cam = camera([2.0, 1.5, 3.9], [2.0, 1.5, 0.0], 60.0);
    let mut st = setup(&sc, cam, vec![], mats);
    st.grids = vec![
        Grid::new(
            "floor",
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [0.0, 0.0, 4.0],
            5,
            5,
            Some([0.0, 1.0, 0.0]),
        )
        .unwrap(),
        Grid::new(
            "wall",
            [0.0, 0.0, 1e-4],
            [4.0, 0.0, 0.0],
            [0.0, 3.0, 0.0],
            4,
            3,
            Some([0.0, 0.0, 1.0]),
        )
        .unwrap(),
    ];
    let polygon = panel.iter().map(|c| DVec3::from_array(*c)).collect();
    (sc, st, polygon)
}

/// CIE 171:2006 case 5.3: E = π L F at floor and wall points, F the exact form factor, in both
/// integrators (the surfaces are black, so direct light is all there is).
#[test]
fn cie_5_3_area_source_form_factors() {
    let (sc, st, panel) = cie_5_3_room();
    for kind in IntegratorKind::ALL {
        let settings = MeasureSettings {
            integrator: kind,
            max_bounces: None,
            samples: 4096,
            time_limit: None,
            target_error: None,
        };
        let results = measure_grids(&sc, &st, &settings);
        let (mut worst, mut sum_rel, mut n) = (0.0f64, 0.0, 0.0);
        for r in &results {
            for p in &r.points {
                let exact = PI * 1000.0 * form_factor(v3(p.position), r.normal.as_dvec3(), &panel);
                let d = p.illuminance_lx - exact;
                assert!(
                    d.abs() < 4.0 * p.std_error_lx + 1e-9,
                    "{kind} {} ({},{}): {} vs exact {exact} (std error {})",
                    r.name,
                    p.i,
                    p.j,
                    p.illuminance_lx,
                    p.std_error_lx
                );
                worst = worst.max(p.std_error_lx / exact);
                sum_rel += d / exact;
                n += 1.0;
            }
        }
        println!(
            "CIE 5.3 {kind}: mean relative error {:+.4} %, worst std error {:.3} %",
            sum_rel / n * 100.0,
            worst * 100.0
        );
        assert!(worst < 0.01, "{kind}: std error {worst}");
        assert!((sum_rel / n).abs() < 0.005);
    }
    // The panel seen from below shows its luminance; from above (its back) it is dark.
    let mut s = path_settings(4, 4, 4);
    s.integrator = IntegratorKind::Direct;
    let mut look_up = st.clone();
    look_up.camera = camera([2.0, 1.0, 2.0], [2.0, 3.0, 2.0001], 5.0);
    let (film, _) = render(&sc, &look_up, &s);
    for p in film.pixels() {
        assert!(
            (p.mean_luminance() - 1000.0).abs() < 0.01,
            "{}",
            p.mean_luminance()
        );
    }
}

/// The form-factor helper itself against a closed form: under the centre of a square of
/// half-side a at height h, F = (2/π) [2 X/√(1+X²) atan(X/√(1+X²))] with X = a/h.
#[test]
fn form_factor_helper_matches_the_closed_form() {
    let sq = [
        DVec3::new(-1.0, 1.0, -1.0),
        DVec3::new(1.0, 1.0, -1.0),
        DVec3::new(1.0, 1.0, 1.0),
        DVec3::new(-1.0, 1.0, 1.0),
    ];
    let f = form_factor(DVec3::ZERO, DVec3::Y, &sq);
    let s = 1.0 / 2f64.sqrt();
    let exact = 4.0 / (2.0 * PI) * 2.0 * s * s.atan();
    assert!((f - exact).abs() < 1e-12, "{f} vs {exact}");
}

/// Path mode with one bounce equals direct mode within noise, for Kd-only materials and for
/// g = 0 mirrors (the built-in Cornell box, then with a mirror tall block).
#[test]
fn path_with_one_bounce_equals_direct() {
    let loaded = builtin_cornell_box(None).unwrap();
    let sc = &loaded.scene;
    let mut mirrored = loaded.setup.clone();
    let tall = sc
        .breps
        .iter()
        .position(|b| b.name.contains("tall"))
        .expect("tall block");
    let first = sc.breps[tall].first_slot as usize;
    mirrored.materials[first] = Material {
        kd: [0.2; 3],
        ks: [0.7; 3],
        glossiness: 0.0,
        ..Material::default()
    };
    for (what, st) in [("Kd only", &loaded.setup), ("with a mirror", &mirrored)] {
        let mut direct = path_settings(48, 36, 64);
        direct.integrator = IntegratorKind::Direct;
        let mut one = path_settings(48, 36, 64);
        one.max_bounces = Some(1);
        let (d, _) = render(sc, st, &direct);
        let (p, _) = render(sc, st, &one);
        // The ceiling's hot spot (a point light 0.1 mm under it) dominates any mean: compare
        // each pixel instead, within 4.5 combined standard errors (or 1e-3 relative).
        let mut bad = 0;
        for (a, b) in d.pixels().zip(p.pixels()) {
            let se = (a.luminance_std_error().unwrap().powi(2)
                + b.luminance_std_error().unwrap().powi(2))
            .sqrt();
            let diff = (a.mean_luminance() - b.mean_luminance()).abs();
            if diff > 4.5 * se + 1e-3 * a.mean_luminance() {
                bad += 1;
            }
        }
        let (md, sd) = image_mean(&d);
        let (mp, sp) = image_mean(&p);
        println!(
            "{what}: direct {md:.3} ± {sd:.3}, path one bounce {mp:.3} ± {sp:.3}, pixels off {bad}"
        );
        assert!(bad <= 2, "{what}: {bad} pixels differ beyond noise");
        assert!((md - mp).abs() < 4.0 * (sd * sd + sp * sp).sqrt(), "{what}");
    }
}

/// The error of the mean falls as N^-1/2: log-log slope between −0.6 and −0.4 (CIE 5.3
/// floor points, path mode, N = 16 … 4096).
#[test]
fn error_falls_as_one_over_root_n() {
    let (sc, mut st, panel) = cie_5_3_room();
    st.grids.truncate(1);
    let ns = [16u32, 64, 256, 1024, 4096];
    let mut points = Vec::new();
    for &n in &ns {
        let settings = MeasureSettings {
            integrator: IntegratorKind::Path,
            max_bounces: None,
            samples: n,
            time_limit: None,
            target_error: None,
        };
        let r = &measure_grids(&sc, &st, &settings)[0];
        let mse: f64 = r
            .points
            .iter()
            .map(|p| {
                let exact = PI * 1000.0 * form_factor(v3(p.position), DVec3::Y, &panel);
                ((p.illuminance_lx - exact) / exact).powi(2)
            })
            .sum::<f64>()
            / r.points.len() as f64;
        points.push(((n as f64).ln(), mse.sqrt().ln()));
    }
    let m = points.len() as f64;
    let (sx, sy) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
    let (mx, my) = (sx / m, sy / m);
    let slope = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum::<f64>()
        / points.iter().map(|(x, _)| (x - mx).powi(2)).sum::<f64>();
    println!("log-log slope of the RMS error: {slope:.3} ({points:?})");
    assert!((-0.6..=-0.4).contains(&slope), "slope {slope}");
}

/// Bit-identical films for 1, 2 and 3 threads, and when sample ranges are rendered apart and
/// added.
#[test]
fn path_mode_is_bit_identical_across_threads_and_ranges() {
    let loaded = builtin_cornell_box(None).unwrap();
    let settings = path_settings(40, 30, 6);
    let run = |threads| render_on_threads(&loaded.scene, &loaded.setup, &settings, threads);
    let one = run(1);
    assert_eq!(one, run(2));
    assert_eq!(one, run(3));
    let (mut a, _) = render_samples(&loaded.scene, &loaded.setup, &settings, 4..6);
    let (b, _) = render_samples(&loaded.scene, &loaded.setup, &settings, 0..1);
    let (c, _) = render_samples(&loaded.scene, &loaded.setup, &settings, 1..4);
    a.merge(&b).unwrap();
    a.merge(&c).unwrap();
    assert_eq!(one, a);
    assert_eq!(one.rejected_samples(), 0);
}

/// A spot: E = I f(θ) cos θ / R² on the floor, f the smoothstep profile between the cone and
/// the falloff angle, computed here from the definition.
#[test]
fn spot_light_illuminance_follows_its_profile() {
    let sc = box_scene(8.0, 3.0, 8.0, vec![]);
    let spot = Light::spot(
        [4.0, 2.0, 4.0],
        tracer_core::scene::Spot {
            intensity_cd: 500.0,
            aim: [0.0, -1.0, 0.0],
            cone_deg: 20.0,
            falloff_deg: 40.0,
        },
    );
    let cam = camera([4.0, 1.5, 7.9], [4.0, 1.5, 0.0], 60.0);
    let mut st = setup(&sc, cam, vec![spot], vec![diffuse(0.0); 6]);
    st.grids = vec![
        Grid::new(
            "line",
            [4.0, 0.0, 4.0],
            [2.5, 0.0, 0.0],
            [0.0, 0.0, 0.01],
            25,
            1,
            Some([0.0, 1.0, 0.0]),
        )
        .unwrap(),
    ];
    let r = &measure_grids(
        &sc,
        &st,
        &MeasureSettings {
            integrator: IntegratorKind::Direct,
            max_bounces: None,
            samples: 1,
            time_limit: None,
            target_error: None,
        },
    )[0];
    for p in &r.points {
        let d = Vec3::new(4.0, 2.0, 4.0) - p.position;
        let theta = f64::from((d.y / d.length()).acos()).to_degrees();
        let t = ((40.0 - theta) / 20.0).clamp(0.0, 1.0);
        let f = if theta <= 20.0 {
            1.0
        } else {
            t * t * (3.0 - 2.0 * t)
        };
        let cos = f64::from(d.y / d.length());
        let exact = 500.0 * f * cos / f64::from(d.length_squared());
        assert!(
            (p.illuminance_lx - exact).abs() < 1e-4 * exact.max(1e-3),
            "θ {theta:.1}°: {} vs {exact}",
            p.illuminance_lx
        );
    }
}
