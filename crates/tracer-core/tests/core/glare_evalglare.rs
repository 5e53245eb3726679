//! Glare from the image against Radiance's evalglare 3.06 (`pip install pyradiance`; CI installs
//! it with scripts/evalglare.sh and names it in RAYGINE_EVALGLARE). raygine writes the fisheye
//! it judged as a `-vta` Radiance picture, evalglare judges the same picture with the same rule
//! (`-b 5 -r 0.2`, no peak extraction `-x`, no low-light correction), and the two must agree:
//! Ev and Lb within 1 %, the same number of sources, DGP within 0.02, and the UGR difference
//! explained: by the two position-index functions (CIE 117's table here, Levin's form there)
//! and by where each program puts a source's centre (raygine: its L·ω-weighted mean direction;
//! evalglare: the pixel its L·ω-weighted mean film position falls in). raygine's UGR recomputed
//! with evalglare's index at evalglare's centres must be within 0.1 of evalglare's. Three
//! scenes: a luminaire's opening, the Integra room from its camera (when `../shared` is
//! there), and a window with sun.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::gi_support::*;
use std::path::{Path, PathBuf};
use std::process::Command;
use tracer_core::glare::hdr::{View, write_radiance_hdr};
use tracer_core::glare::{GlareOptions, ObserverGlare, observer_basis};
use tracer_core::scene::{Observer, Scene, Setup, Sidecar};

/// evalglare's path, or None (with the reason printed) when it is not installed; under
/// RAYGINE_REQUIRE_EVALGLARE=1 (CI) its absence fails the test.
fn evalglare() -> Option<PathBuf> {
    let path = std::env::var_os("RAYGINE_EVALGLARE").map(PathBuf::from);
    match path.filter(|p| p.is_file()) {
        Some(p) => Some(p),
        None => {
            assert!(
                std::env::var_os("RAYGINE_REQUIRE_EVALGLARE").is_none(),
                "RAYGINE_REQUIRE_EVALGLARE is set but RAYGINE_EVALGLARE names no evalglare"
            );
            println!(
                "skipped: no evalglare (set RAYGINE_EVALGLARE; scripts/evalglare.sh installs it)"
            );
            None
        }
    }
}

/// What evalglare -d printed: its sources and summary figures.
#[derive(Debug)]
struct Evalglare {
    sources: usize,
    dgp: f64,
    ev: f64,
    lb: f64,
    ugr: f64,
}

fn run_evalglare(exe: &Path, picture: &Path) -> Evalglare {
    let out = Command::new(exe)
        .args(["-d", "-b", "5", "-r", "0.2", "-x"])
        .arg(picture)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "evalglare failed: {text} {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let sources = text
        .lines()
        .find(|l| l.contains("No pixels"))
        .and_then(|l| l.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap();
    let summary = text
        .lines()
        .find(|l| l.starts_with("dgp,av_lum,E_v"))
        .unwrap();
    let (names, values) = summary.split_once(':').unwrap();
    let value = |name: &str| -> f64 {
        let k = names.split(',').position(|n| n.trim() == name).unwrap();
        values.split_whitespace().nth(k).unwrap().parse().unwrap()
    };
    Evalglare {
        sources,
        dgp: value("dgp"),
        ev: value("E_v"),
        lb: value("lum_backg"),
        ugr: value("ugr"),
    }
}

/// raygine's image-based figures at `observer`, and evalglare's of the picture raygine wrote.
fn compare(
    exe: &Path,
    what: &str,
    sc: &Scene,
    st: &Setup,
    observer: &Observer,
    spp: u32,
) -> (ObserverGlare, Evalglare) {
    let size = 400;
    let g = crate::glare::judge(sc, st, observer, size, spp, &GlareOptions::default());
    let basis = observer_basis(st, observer, size);
    let view = View {
        position: observer.position,
        direction: basis.forward.to_array(),
        up: basis.up.to_array(),
    };
    let picture =
        std::env::temp_dir().join(format!("raygine-eg-{what}-{}.hdr", std::process::id()));
    write_radiance_hdr(&picture, &g.image, &view).unwrap();
    let e = run_evalglare(exe, &picture);
    let _ = std::fs::remove_file(&picture);
    let f = &g.from_image;
    let ugr = f.ugr.unwrap_or(0.0);
    let ugr_eg = f.ugr_evalglare_index.unwrap_or(0.0);
    // evalglare's centre: the pixel its L·ω-weighted mean column and bottom-up row fall in.
    let (w, h) = (g.image.width as usize, g.image.height as usize);
    let mut sum = 0.0;
    for s in &f.sources {
        let (mut sx, mut sy, mut sw) = (0.0, 0.0, 0.0);
        for &i in &s.pixels {
            let weight = g.image.luminance[i] * g.image.solid_angle[i];
            sx += weight * (i % w) as f64;
            sy += weight * (h - 1 - i / w) as f64;
            sw += weight;
        }
        let (x, row) = ((sx / sw).floor(), h as f64 - 1.0 - (sy / sw).floor());
        let ray = basis.ray(x as f32 + 0.5, row as f32 + 0.5).unwrap();
        let d = ray.dir.as_dvec3();
        let dir = glam::DVec3::new(
            d.dot(basis.right.as_dvec3()),
            d.dot(basis.up.as_dvec3()),
            d.dot(basis.forward.as_dvec3()),
        );
        let p = tracer_core::glare::position_index::evalglare_index(dir).unwrap();
        sum += s.luminance * s.luminance * s.solid_angle / (p * p);
    }
    let ugr_eg_centres = if sum > 0.0 {
        8.0 * (0.25 / f.lb * sum).log10()
    } else {
        0.0
    };
    println!(
        "{what}: raygine Ev {:.2} lx, Lb {:.3} cd/m², {} sources, UGR {ugr:.2} ± {:.2} (with \
         evalglare's index {ugr_eg:.2}), DGP {:.4} ± {:.4}",
        f.ev,
        f.lb,
        f.sources.len(),
        f.ugr_se,
        f.dgp,
        f.dgp_se
    );
    println!(
        "{what}: evalglare Ev {:.2} lx, Lb {:.3} cd/m², {} sources, UGR {:.2}, DGP {:.4}; UGR \
         difference {:+.2}: the index functions explain {:+.2}, the sources' centres {:+.2}, \
         the rest {:+.3}",
        e.ev,
        e.lb,
        e.sources,
        e.ugr,
        e.dgp,
        ugr - e.ugr,
        ugr - ugr_eg,
        ugr_eg - ugr_eg_centres,
        ugr_eg_centres - e.ugr
    );
    for s in &f.sources {
        let (up, right) = s.angles_deg();
        println!(
            "  {}: L {:.0} cd/m², ω {:.5} sr, {up:+.1}° up, {right:+.1}° right, p {:.3} (evalglare's \
             index {:.3})",
            s.label,
            s.luminance,
            s.solid_angle,
            s.position_index,
            tracer_core::glare::position_index::evalglare_index(s.direction).unwrap_or(f64::NAN)
        );
    }
    assert!(
        (f.ev / e.ev - 1.0).abs() < 0.01,
        "{what}: Ev {} vs {}",
        f.ev,
        e.ev
    );
    assert!(
        (f.lb / e.lb - 1.0).abs() < 0.01,
        "{what}: Lb {} vs {}",
        f.lb,
        e.lb
    );
    assert_eq!(f.sources.len(), e.sources, "{what}: sources");
    assert!(
        (f.dgp - e.dgp).abs() < 0.02,
        "{what}: DGP {} vs {}",
        f.dgp,
        e.dgp
    );
    if e.sources > 0 {
        assert!(
            (ugr_eg_centres - e.ugr).abs() < 0.1,
            "{what}: UGR with evalglare's index at its centres {ugr_eg_centres} vs {}",
            e.ugr
        );
    }
    (g, e)
}

fn sidecar_scene(sc: Scene, text: &str, files: &[(&str, String)]) -> (Scene, Setup) {
    let dir = std::env::temp_dir().join(format!("raygine-eg-scene-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, body) in files {
        std::fs::write(dir.join(name), body).unwrap();
    }
    let sidecar =
        Sidecar::parse(text, &dir.join("s.raygine.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut warnings = Vec::new();
    let st = sidecar.apply(&sc, None, &mut warnings);
    let _ = std::fs::remove_dir_all(&dir);
    (sc, st)
}

#[test]
fn a_luminaire_against_evalglare() {
    let Some(exe) = evalglare() else { return };
    let vert: Vec<f64> = (0..=90).map(f64::from).collect();
    let file = ies_sized(
        &vert,
        &[0.0],
        |_, g| 3000.0 * g.to_radians().cos(),
        [0.6, 0.6, 0.0],
    );
    let text = "unit = \"m\"\nhandedness = \"right\"\n[default_material]\nkd = [0.5, 0.5, 0.5]\n\
                [[lights]]\nkind = \"luminaire\"\nfile = \"panel.ies\"\nposition = [2.0, 2.9, 1.5]\n\
                aim = [0.0, -1.0, 0.0]\n\
                [[observers]]\nname = \"desk\"\nposition = [1.4, 1.2, 3.8]\ndirection = [0.0, 0.0, -1.0]\n";
    let (sc, st) = sidecar_scene(
        box_scene(4.0, 3.0, 5.0, vec![]),
        text,
        &[("panel.ies", file)],
    );
    let observer = st.observers[0].clone();
    compare(&exe, "luminaire", &sc, &st, &observer, 8);
}

#[test]
fn a_window_with_sun_against_evalglare() {
    let Some(exe) = evalglare() else { return };
    // A 4 x 3 x 5 m grey room, a 2 x 1.6 m window in its south wall (z = 5; north is −Z).
    let sc = window_room([4.0, 3.0, 5.0], [1.0, 3.0, 0.8, 2.4]);
    // Winter noon at 50° N: the sun 16.5° high in the south, seen through the window to the
    // right of the line of sight; a hazy sun of 5000 lx and a clear sky.
    let text = "unit = \"m\"\nhandedness = \"right\"\n[default_material]\nkd = [0.5, 0.5, 0.5]\n\
                [daylight]\nlatitude = 50.0\nlongitude = 0.0\ndate = \"2026-12-21\"\ntime = \"12:00\"\n\
                timezone = 0.0\nsky = \"cie:12\"\ndiffuse_horizontal_lx = 8000.0\nsun = true\n\
                sun_normal_illuminance_lx = 5000.0\n\
                [[observers]]\nname = \"desk\"\nposition = [1.2, 1.2, 2.0]\ndirection = [-0.5, 0.0, 1.0]\n";
    let (sc, mut st) = sidecar_scene(sc, text, &[]);
    st.lights.clear();
    let observer = st.observers[0].clone();
    compare(&exe, "window with sun", &sc, &st, &observer, 16);
}

#[test]
fn the_integra_room_against_evalglare() {
    let Some(exe) = evalglare() else { return };
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes/ipur-room2/room2.shp");
    if !path.is_file() {
        println!(
            "skipped: {} is absent (../shared is not beside the checkout)",
            path.display()
        );
        return;
    }
    let loaded = tracer_core::scene::load(&path, &Default::default()).unwrap();
    let observer = Observer::at_camera("camera", &loaded.setup.camera);
    compare(
        &exe,
        "Integra room2",
        &loaded.scene,
        &loaded.setup,
        &observer,
        8,
    );
}
