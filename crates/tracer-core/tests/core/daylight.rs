//! Daylight skies against their closed forms, through the sidecar and the renderer: an
//! unobstructed floor under the CIE overcast sky reads E_h = 7π/9 · Lz, under a uniform sky
//! π · L (LIGHTING.md), within 0.5 %, in path and bidirectional modes; a ceiling facing down
//! reads the ground's ρ_g E_h.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::gi_support::*;
use glam::DVec3;
use std::f64::consts::PI;
use std::path::Path;
use tracer_core::integrator::IntegratorKind;
use tracer_core::measure::{DaylightFactorSetup, MeasureSettings, measure_grids};
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
    let n = film.len() as f64;
    let e = film
        .pixels()
        .map(|p| f64::from(p.mean_illuminance()))
        .sum::<f64>()
        / n;
    let l = film.pixels().map(|p| p.mean_luminance()).sum::<f64>() / n;
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

/// The keys of a place where the sun stands 38° high, a little west of south (52° N, 5° E, the
/// March equinox at noon, UTC+1).
const EQUINOX_NOON: &str = "latitude = 52.0\nlongitude = 5.0\ndate = \"2026-03-20\"\n\
                            time = \"12:00\"\ntimezone = 1.0";

/// A general sky scaled by its diffuse illuminance, with the sun: an unobstructed floor reads
/// E_h + E_n sin(altitude), and a surface facing down the ground's ρ_g (E_h + E_n sin h), in
/// path and bidirectional modes. The sun is a 0.533° disc of luminance E_n / (π sin² α).
#[test]
fn the_sun_and_a_clear_sky_on_an_open_floor() {
    let keys = "sky = \"cie:12\"\ndiffuse_horizontal_lx = 10000.0\nsun = true\n\
                sun_normal_illuminance_lx = 80000.0";
    let sidecar = Sidecar::parse(
        &format!("[daylight]\n{EQUINOX_NOON}\n{keys}\n"),
        Path::new("s.raygine.toml"),
    )
    .unwrap();
    let d = sidecar.daylight.unwrap().to_model().unwrap();
    let alt = d.sun().altitude_deg.to_radians();
    assert!(
        alt.to_degrees() > 37.0 && alt.to_degrees() < 39.5,
        "{}",
        alt.to_degrees()
    );
    let exact = 10000.0 + 80000.0 * alt.sin();
    for integrator in [IntegratorKind::Path, IntegratorKind::Bidirectional] {
        let (e, _) = floor_under(keys, integrator, false);
        println!(
            "clear sky + sun, {integrator}: E {e:.0} lx vs {exact:.0} ({:+.2} %)",
            (e / exact - 1.0) * 100.0
        );
        assert!(
            (e / exact - 1.0).abs() < 0.01,
            "{integrator}: {e} vs {exact}"
        );
    }
    let (e, _) = floor_under(keys, IntegratorKind::Path, true);
    println!("ground under sky + sun: E {e:.1} lx vs {:.1}", 0.2 * exact);
    assert!((e / (0.2 * exact) - 1.0).abs() < 0.01, "{e}");
}

/// The fraction of a disc of angular radius `alpha` left visible by a straight edge whose
/// great circle passes `delta` from the disc's centre (positive: the centre is on the open
/// side): one minus a circular segment.
fn disc_visible(delta: f64, alpha: f64) -> f64 {
    let h = (delta / alpha).clamp(-1.0, 1.0);
    let segment = |h: f64| (h.acos() - h * (1.0 - h * h).sqrt()) / PI;
    if h >= 0.0 {
        1.0 - segment(h)
    } else {
        segment(-h)
    }
}

/// The sun alone behind a black roof 10 m up whose straight edge runs along X: along a line of
/// floor points across its shadow's edge, the illuminance follows the visible part of the
/// 0.533° disc, E_n (s · n) times the fraction, whose penumbra is about 25 cm wide here, in
/// path, bidirectional and direct modes.
#[test]
fn the_sun_casts_penumbrae_of_its_width() {
    let h = 10.0f64;
    // The roof covers z from 0 to 40 (towards the sun, which is south: +Z).
    let sc = scene(vec![brep(
        "roof",
        &[[
            [-40.0, h, 0.0],
            [40.0, h, 0.0],
            [40.0, h, 40.0],
            [-40.0, h, 40.0],
        ]],
    )]);
    let probe = Sidecar::parse(
        &format!("unit = \"m\"\nhandedness = \"right\"\n[daylight]\n{EQUINOX_NOON}\n"),
        Path::new("p.raygine.toml"),
    )
    .unwrap();
    let d = probe.daylight.unwrap().to_model().unwrap();
    let s = d.sun_direction(true).as_dvec3();
    // The edge's shadow falls where z + h s_z / s_y = 0.
    let z_edge = -h * s.z / s.y;
    let half_span = 0.3;
    let n = 25;
    let text = format!(
        "unit = \"m\"\nhandedness = \"right\"\n\
         [materials.roof]\nkd = [0.0, 0.0, 0.0]\n\
         [[grids]]\nname = \"line\"\norigin = [-0.01, 0.0, {z0}]\nu = [0.02, 0.0, 0.0]\n\
         v = [0.0, 0.0, {span}]\nnu = 1\nnv = {n}\nnormal = [0.0, 1.0, 0.0]\n\
         [daylight]\n{EQUINOX_NOON}\nsun = true\nsun_normal_illuminance_lx = 80000.0\n",
        z0 = z_edge - half_span,
        span = 2.0 * half_span,
    );
    let sidecar = Sidecar::parse(&text, Path::new("roof.raygine.toml")).unwrap();
    let mut warnings = Vec::new();
    let mut st = sidecar.apply(&sc, None, &mut warnings);
    st.lights.clear();
    assert!(warnings.is_empty(), "{warnings:?}");
    let alpha = (0.533f64 / 2.0).to_radians();
    // The penumbra: the edge's elevation β seen from the floor changes by sin² β / h per metre,
    // and the disc spans 2α / ρ of it, ρ the sun direction's length in the Y-Z plane.
    let rho = (s.y * s.y + s.z * s.z).sqrt();
    let eps = f64::from(sc.ray_epsilon());
    for integrator in [
        IntegratorKind::Path,
        IntegratorKind::Bidirectional,
        IntegratorKind::Direct,
    ] {
        let settings = MeasureSettings {
            integrator,
            max_bounces: None,
            samples: 4096,
            time_limit: None,
            target_error: None,
        };
        let result = &measure_grids(&sc, &st, &settings)[0];
        let full = 80000.0 * s.y;
        let mut worst = 0.0f64;
        let mut profile = Vec::new();
        for p in &result.points {
            let pos = p.position.as_dvec3();
            // The plane through the point and the edge line (along X at y = h, z = 0): the sun's
            // centre lies `delta` from it, on the open side when delta > 0.
            // (Sensor rays start the scene's ray epsilon above the point.)
            let to_edge = DVec3::new(0.0, h, 0.0) - DVec3::new(0.0, pos.y + eps, pos.z);
            let normal = DVec3::X.cross(to_edge).normalize();
            // normal = X × to_edge points south and down: the sun is visible (above the
            // plane) when s · normal < 0.
            let delta = -s.dot(normal).asin();
            let expected = full * disc_visible(delta, alpha);
            let dev = (p.illuminance_lx - expected) / full;
            if std::env::var_os("PENUMBRA_PROFILE").is_some() {
                println!(
                    "  z {:.3}: E {:.0} ± {:.0}, expected {expected:.0}",
                    pos.z, p.illuminance_lx, p.std_error_lx
                );
            }
            worst = worst.max(dev.abs());
            profile.push((pos.z, p.illuminance_lx / full, expected / full));
            assert!(
                dev.abs() < 0.01 + 4.0 * p.std_error_lx / full,
                "{integrator} z {:.3}: E {:.0} vs {expected:.0} (± {:.0})",
                pos.z,
                p.illuminance_lx,
                p.std_error_lx
            );
        }
        // Where the profile falls through 90 % and 10 % of full sun, measured and predicted.
        let crossing = |level: f64, pick: fn(&(f64, f64, f64)) -> f64| {
            profile.windows(2).find_map(|w| {
                let (a, b) = (pick(&w[0]), pick(&w[1]));
                (a >= level && b < level)
                    .then(|| w[0].0 + (w[1].0 - w[0].0) * (a - level) / (a - b))
            })
        };
        let width =
            |pick: fn(&(f64, f64, f64)) -> f64| Some(crossing(0.1, pick)? - crossing(0.9, pick)?);
        let (seen, predicted) = (width(|p| p.1), width(|p| p.2));
        println!(
            "sun penumbra, {integrator}: worst deviation {:.2} % of full sun ({full:.0} lx); \
             90 % to 10 % over {:.1} mm (predicted {:.1} mm; the whole penumbra {:.1} mm)",
            worst * 100.0,
            seen.unwrap_or(f64::NAN) * 1000.0,
            predicted.unwrap_or(f64::NAN) * 1000.0,
            h * 2.0 * alpha * rho / (s.y * s.y) * 1000.0
        );
        let (seen, predicted) = (seen.unwrap(), predicted.unwrap());
        assert!(
            (seen / predicted - 1.0).abs() < 0.1,
            "{seen} vs {predicted}"
        );
    }
}

/// A black 4 x 3 x 5 m room whose roof has a 2 x 3 m opening, with floor points under it and
/// beside it, under the `[daylight]` keys `sky`.
fn roof_opening_room(sky: &str) -> (tracer_core::scene::Scene, tracer_core::scene::Setup) {
    let (sx, sy, sz) = (4.0, 3.0, 5.0);
    let (x0, x1, z0, z1) = (1.0, 3.0, 1.0, 4.0);
    let mut quads: Vec<Quad> = box_faces(sx, sy, sz)
        .into_iter()
        .filter(|(name, _)| *name != "ceiling")
        .map(|(_, q)| q)
        .collect();
    // The ceiling around the opening, four pieces facing down.
    for (a0, a1, b0, b1) in [
        (0.0, sx, 0.0, z0),
        (0.0, sx, z1, sz),
        (0.0, x0, z0, z1),
        (x1, sx, z0, z1),
    ] {
        quads.push([[a0, sy, b0], [a1, sy, b0], [a1, sy, b1], [a0, sy, b1]]);
    }
    let sc = scene(vec![brep("room", &quads)]);
    let text = format!(
        "unit = \"m\"\nhandedness = \"right\"\n\
         [default_material]\nkd = [0.0, 0.0, 0.0]\n\
         [[grids]]\nname = \"floor\"\norigin = [0.25, 0.0, 0.5]\nu = [3.0, 0.0, 0.0]\n\
         v = [0.0, 0.0, 4.0]\nnu = 3\nnv = 3\nnormal = [0.0, 1.0, 0.0]\n\
         [daylight]\n{EQUINOX_NOON}\n{sky}\n"
    );
    let sidecar = Sidecar::parse(&text, Path::new("opening.raygine.toml")).unwrap();
    let mut warnings = Vec::new();
    let mut st = sidecar.apply(&sc, None, &mut warnings);
    assert!(warnings.is_empty(), "{warnings:?}");
    st.lights.clear();
    (sc, st)
}

/// The sky component through a rectangular roof opening in a black room: under a uniform sky
/// E = L π F, F the exact (Lambert contour) form factor of the opening from the floor point;
/// under the CIE overcast sky, through `measure`'s daylight-factor setup, DF = E / E_out,h
/// against a midpoint integral of Lz (1 + 2 cos θ) / 3 · cos² θ / r² over the opening computed
/// here. Within 1 % in path mode and 2 % in bidirectional and direct modes (see the sample
/// counts).
#[test]
fn sky_component_through_a_roof_opening() {
    let l = 1000.0;
    let (sc, st) = roof_opening_room(&format!("sky = \"uniform\"\nzenith_luminance_cd_m2 = {l}"));
    let df_setup = DaylightFactorSetup::new(&st).unwrap();
    assert!((df_setup.outdoor_lx - 10_000.0).abs() < 1e-6);
    let opening = [
        DVec3::new(1.0, 3.0, 1.0),
        DVec3::new(3.0, 3.0, 1.0),
        DVec3::new(3.0, 3.0, 4.0),
        DVec3::new(1.0, 3.0, 4.0),
    ];
    // The overcast sky's illuminance through the opening, by the midpoint rule (600 x 900).
    let lz = 10_000.0 / (7.0 * PI / 9.0);
    let overcast = |p: DVec3| {
        let (n, m) = (600, 900);
        let (da, mut e) = ((2.0 / n as f64) * (3.0 / m as f64), 0.0);
        for i in 0..n {
            for j in 0..m {
                let q = DVec3::new(
                    1.0 + 2.0 * (i as f64 + 0.5) / n as f64,
                    3.0,
                    1.0 + 3.0 * (j as f64 + 0.5) / m as f64,
                );
                let d = q - p;
                let r2 = d.length_squared();
                let cos = d.y / r2.sqrt();
                e += lz * (1.0 + 2.0 * cos) / 3.0 * cos * cos / r2 * da;
            }
        }
        e
    };
    // Each sample passes the opening with a chance of about F (0.1-0.17 here), so the relative
    // error is near 2.5 / √N: 2^20 samples bring path mode to 0.25 %, within which 1 % is a
    // real check; bidirectional and direct modes, slower, get 2^18 and 2 %.
    for (integrator, samples, tolerance) in [
        (IntegratorKind::Path, 1 << 20, 0.01),
        (IntegratorKind::Bidirectional, 1 << 18, 0.02),
        (IntegratorKind::Direct, 1 << 18, 0.02),
    ] {
        let settings = MeasureSettings {
            integrator,
            max_bounces: None,
            samples,
            time_limit: None,
            target_error: None,
        };
        let started = std::time::Instant::now();
        let uniform = &measure_grids(&sc, &st, &settings)[0];
        let df = &measure_grids(&sc, &df_setup.setup, &settings)[0];
        let mut worst = (0.0f64, 0.0f64);
        for (u, o) in uniform.points.iter().zip(&df.points) {
            let p = u.position.as_dvec3();
            let exact = l * PI * form_factor(p, DVec3::Y, &opening);
            let rel = u.illuminance_lx / exact - 1.0;
            println!(
                "  {p}: F {:.4}, E {:.2} ± {:.2} vs {exact:.2}; DF {:.3} ± {:.3} %",
                exact / (l * PI),
                u.illuminance_lx,
                u.std_error_lx,
                df_setup.percent(o.illuminance_lx),
                df_setup.percent(o.std_error_lx)
            );
            assert!(
                rel.abs() < tolerance
                    && (u.illuminance_lx - exact).abs() < 4.0 * u.std_error_lx + 1e-9,
                "{integrator} uniform at {p}: {} ± {} vs {exact}",
                u.illuminance_lx,
                u.std_error_lx
            );
            let exact_df = 100.0 * overcast(p) / df_setup.outdoor_lx;
            let got_df = df_setup.percent(o.illuminance_lx);
            let rel_df = got_df / exact_df - 1.0;
            assert!(
                rel_df.abs() < tolerance,
                "{integrator} DF at {p}: {got_df:.4} % vs {exact_df:.4} %"
            );
            worst = (worst.0.max(rel.abs()), worst.1.max(rel_df.abs()));
        }
        println!(
            "roof opening, {integrator}: uniform sky worst {:.2} % from L π F, overcast DF worst \
             {:.2} % from the integral ({:.1} s)",
            worst.0 * 100.0,
            worst.1 * 100.0,
            started.elapsed().as_secs_f64()
        );
    }
}
