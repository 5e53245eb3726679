//! Photometric luminaires against answers: CIE 171:2006 case 5.2 through IES and EULUMDAT files
//! written here, fluxes, every symmetry form of one distribution, the orientation rule in
//! left- and right-handed scenes, and one test per kind of bad file.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::gi_support::*;
use glam::Vec3;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use tracer_core::formats::parse_photometry;
use tracer_core::integrator::IntegratorKind;
use tracer_core::light::Photometry;
use tracer_core::measure::{Grid, MeasureSettings, measure_grids};
use tracer_core::render::{RenderSettings, render};
use tracer_core::scene::{Handedness, Sidecar};

/// A EULUMDAT file with symmetry `isym` of `f(C, γ)` (cd), `mc` C planes, the given γ angles;
/// lamp flux 2000 lm and conversion factor 1, so the file holds f / 2 (cd per 1000 lm).
fn ldt(isym: u32, mc: usize, gammas: &[f64], f: impl Fn(f64, f64) -> f64) -> String {
    let dc = 360.0 / mc as f64;
    let mut l: Vec<String> = vec![
        "raygine tests".into(),
        "1".into(),
        isym.to_string(),
        mc.to_string(),
        format!("{dc}"),
        gammas.len().to_string(),
        format!("{}", gammas.get(1).copied().unwrap_or(0.0) - gammas[0]),
        "report".into(),
        "luminaire".into(),
        "L-1".into(),
        "test.ldt".into(),
        "2026-11-30".into(),
    ];
    for v in [
        "600", "600", "80", "500", "400", "0", "0", "0", "0", "100", "80", "1", "0", "1",
    ] {
        l.push(v.into());
    }
    for v in ["1", "LED", "2000", "4000", "80", "20"] {
        l.push(v.into());
    }
    for _ in 0..10 {
        l.push("0.5".into());
    }
    let cs: Vec<f64> = (0..mc).map(|i| i as f64 * dc).collect();
    l.extend(cs.iter().map(|c| format!("{c}")));
    l.extend(gammas.iter().map(|g| format!("{g}")));
    let planes: Vec<f64> = match isym {
        0 => cs.clone(),
        1 => vec![0.0],
        2 => cs[..=mc / 2].to_vec(),
        3 => cs[3 * mc / 4..]
            .iter()
            .chain(&cs[..=mc / 4])
            .copied()
            .collect(),
        _ => cs[..=mc / 4].to_vec(),
    };
    for c in planes {
        for &g in gammas {
            l.push(format!("{}", f(c, g) / 2.0));
        }
    }
    l.join("\r\n") + "\r\n"
}

fn parse(text: &str, name: &str) -> Photometry {
    parse_photometry(text.as_bytes(), Path::new(name)).unwrap_or_else(|e| panic!("{e}"))
}

fn steps(from: f64, to: f64, step: f64) -> Vec<f64> {
    let n = ((to - from) / step).round() as usize;
    (0..=n).map(|i| from + i as f64 * step).collect()
}

/// A folder of its own for one test, removed with the value (the test passing or not).
struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

fn temp_dir(name: &str) -> Scratch {
    let d = std::env::temp_dir().join(format!("raygine-lum-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    Scratch(d)
}

/// CIE 171:2006 case 5.2: I(γ) = 1000 cos γ cd aimed down 3 m above a 4 x 4 m floor gives
/// E = I0 h² / d⁴ at every floor point (111.11 lx under the source), through an IES and an LDT
/// file loaded from a sidecar.
#[test]
fn cie_5_2_point_source_through_ies_and_ldt_files() {
    let down = steps(0.0, 90.0, 2.5);
    let f = |_: f64, g: f64| 1000.0 * g.to_radians().cos();
    let dir = temp_dir("cie52");
    std::fs::write(dir.join("cos.ies"), ies(&down, &[0.0], f)).unwrap();
    std::fs::write(dir.join("cos.ldt"), ldt(1, 24, &down, f)).unwrap();
    // A black 4 x 4 m floor in a black 4 x 3 x 4 m room.
    let sc = box_scene(4.0, 3.0, 4.0, vec![]);
    for file in ["cos.ies", "cos.ldt"] {
        let text = format!(
            "unit = \"m\"\nhandedness = \"right\"\n[default_material]\nkd = [0.0, 0.0, 0.0]\n\
             [[lights]]\nkind = \"luminaire\"\nshape = \"point\"\nfile = \"{file}\"\nposition = [2.0, 3.0, 2.0]\n\
             aim = [0.0, -1.0, 0.0]\n\
             [[grids]]\nname = \"floor\"\norigin = [0.0, 0.0, 0.0]\nu = [4.0, 0.0, 0.0]\n\
             v = [0.0, 0.0, 4.0]\nnu = 5\nnv = 5\nnormal = [0.0, 1.0, 0.0]\n"
        );
        let path = dir.join("room.raygine.toml");
        let sidecar = Sidecar::parse(&text, &path).unwrap_or_else(|e| panic!("{e}"));
        let mut warnings = Vec::new();
        let st = sidecar.apply(&sc, None, &mut warnings);
        let flux = st.lights[0].flux_lm();
        assert!(
            (f64::from(flux) / (PI * 1000.0) - 1.0).abs() < 2e-3,
            "{file}: flux {flux}"
        );
        for kind in IntegratorKind::ALL {
            let settings = MeasureSettings {
                integrator: kind,
                max_bounces: None,
                samples: 1,
                time_limit: None,
                target_error: None,
            };
            let r = &measure_grids(&sc, &st, &settings)[0];
            let mut worst = 0.0f64;
            for p in &r.points {
                let d2 = f64::from((p.position - Vec3::new(2.0, 3.0, 2.0)).length_squared());
                let exact = 1000.0 * 9.0 / (d2 * d2);
                let rel = p.illuminance_lx / exact - 1.0;
                worst = worst.max(rel.abs());
                assert!(
                    rel.abs() < 0.01,
                    "{file} {kind} ({}, {}): {} vs {exact}",
                    p.i,
                    p.j,
                    p.illuminance_lx
                );
            }
            println!(
                "{file} {kind}: worst point {:.3} % from I0 h² / d⁴",
                worst * 100.0
            );
            let centre = r.points.iter().find(|p| (p.i, p.j) == (2, 2)).unwrap();
            assert!(
                (centre.illuminance_lx - 111.11).abs() < 0.2,
                "{}",
                centre.illuminance_lx
            );
        }
    }
}

/// Fluxes: isotropic 4π I, cosine π I0, and an asymmetric distribution against a direct
/// numerical sum of the function the file was written from.
#[test]
fn fluxes_match_their_integrals() {
    let all = steps(0.0, 180.0, 5.0);
    let iso = parse(&ies(&all, &[0.0], |_, _| 100.0), "iso.ies");
    assert!((iso.flux_lm() / (4.0 * PI * 100.0) - 1.0).abs() < 1e-4);
    let down = steps(0.0, 90.0, 5.0);
    let cos = parse(
        &ldt(1, 36, &down, |_, g| 1000.0 * g.to_radians().cos()),
        "cos.ldt",
    );
    assert!(
        (cos.flux_lm() / (PI * 1000.0) - 1.0).abs() < 3e-3,
        "{}",
        cos.flux_lm()
    );
    let f = |c: f64, g: f64| {
        200.0 + 150.0 * c.to_radians().cos() * g.to_radians().sin() + 80.0 * (g / 180.0)
    };
    let cs = steps(0.0, 360.0, 7.5);
    let table = parse(&ies(&all, &cs, f), "asym.ies");
    let (n_c, n_g) = (720, 360);
    let mut sum = 0.0;
    for j in 0..n_g {
        let g = (j as f64 + 0.5) * 180.0 / n_g as f64;
        for i in 0..n_c {
            let c = (i as f64 + 0.5) * 360.0 / n_c as f64;
            sum += f(c, g) * g.to_radians().sin();
        }
    }
    let direct = sum * (2.0 * PI / n_c as f64) * (PI / n_g as f64);
    assert!(
        (table.flux_lm() / direct - 1.0).abs() < 5e-3,
        "{} vs {direct}",
        table.flux_lm()
    );
}

/// One distribution with both mirror symmetries, written in every form the formats allow,
/// reads back the same everywhere.
#[test]
fn every_symmetry_form_gives_the_same_intensities() {
    let f =
        |c: f64, g: f64| 300.0 + 200.0 * (2.0 * c.to_radians()).cos().abs() * g.to_radians().sin();
    let gammas = steps(0.0, 180.0, 10.0);
    let forms = [
        ("0-90.ies", ies(&gammas, &steps(0.0, 90.0, 15.0), f)),
        ("0-180.ies", ies(&gammas, &steps(0.0, 180.0, 15.0), f)),
        ("0-360.ies", ies(&gammas, &steps(0.0, 360.0, 15.0), f)),
        ("90-270.ies", ies(&gammas, &steps(90.0, 270.0, 15.0), f)),
        ("180-360.ies", ies(&gammas, &steps(180.0, 360.0, 15.0), f)),
        ("isym0.ldt", ldt(0, 24, &gammas, f)),
        ("isym2.ldt", ldt(2, 24, &gammas, f)),
        ("isym3.ldt", ldt(3, 24, &gammas, f)),
        ("isym4.ldt", ldt(4, 24, &gammas, f)),
    ];
    let tables: Vec<(&str, Photometry)> = forms.iter().map(|(n, t)| (*n, parse(t, n))).collect();
    for k in 0..200 {
        let c = (k as f32 * 37.3) % 360.0;
        let g = (k as f32 * 13.7) % 180.0;
        let want = tables[2].1.intensity(c, g);
        for (name, t) in &tables {
            let got = t.intensity(c, g);
            assert!(
                (got - want).abs() < 1e-3 * want,
                "{name} at C {c} γ {g}: {got} vs {want}"
            );
        }
    }
    // Rotational symmetry: one plane (IES) and Isym 1 (LDT).
    let r = |_: f64, g: f64| 100.0 + g;
    let a = parse(&ies(&gammas, &[0.0], r), "rot.ies");
    let b = parse(&ldt(1, 12, &gammas, r), "rot.ldt");
    for (c, g) in [(0.0, 0.0), (123.0, 45.0), (359.0, 170.0)] {
        assert!((a.intensity(c, g) - b.intensity(c, g)).abs() < 1e-3);
        assert!((a.intensity(c, g) - (100.0 + g)).abs() < 1e-3);
    }
}

/// The orientation rule: C0 lies along +X (projected perpendicular to the aim) and C angles
/// increase counter-clockwise in the picture raygine draws, looking along the aim from behind
/// the luminaire, in left- and right-handed scenes alike. Left-handed pictures are mirrored, so
/// +X, and with it the C0 lobe, changes sides there, and the C90 lobe is still 90° counter-
/// clockwise from it on screen.
#[test]
fn c_angles_run_counter_clockwise_on_screen_in_both_handednesses() {
    let gammas = steps(0.0, 90.0, 5.0);
    let lobe_at = |centre: f64| {
        move |c: f64, _g: f64| {
            let d = ((c - centre + 180.0).rem_euclid(360.0) - 180.0).abs();
            if d < 30.0 {
                1000.0 * (1.0 - d / 30.0)
            } else {
                0.0
            }
        }
    };
    let dir = temp_dir("orient");
    for (name, centre) in [("c0.ies", 0.0), ("c90.ies", 90.0)] {
        std::fs::write(
            dir.join(name),
            ies(&gammas, &steps(0.0, 360.0, 5.0), lobe_at(centre)),
        )
        .unwrap();
    }
    let sc = box_scene(4.0, 3.0, 4.0, vec![]);
    for hand in ["left", "right"] {
        // Screen direction (x right, y up) of each lobe's lit spot, from the picture's centre.
        let mut spots = Vec::new();
        let mut x_on_screen = 0.0;
        for file in ["c0.ies", "c90.ies"] {
            let text = format!(
                "unit = \"m\"\nhandedness = \"{hand}\"\n[camera]\nposition = [2.0, 2.9, 2.0]\n\
                 look_at = [2.0, 0.0, 2.0]\nup = [0.0, 0.0, -1.0]\nfov_deg = 100.0\n\
                 [default_material]\nkd = [0.8, 0.8, 0.8]\n\
                 [[lights]]\nkind = \"luminaire\"\nshape = \"point\"\nfile = \"{file}\"\nposition = [2.0, 2.5, 2.0]\n"
            );
            let sidecar = Sidecar::parse(&text, &dir.join("s.raygine.toml")).unwrap();
            let st = sidecar.apply(&sc, None, &mut Vec::new());
            let expected = if hand == "left" {
                Handedness::Left
            } else {
                Handedness::Right
            };
            assert_eq!(st.handedness, expected);
            let basis = st.camera.basis(st.handedness, 48, 48);
            x_on_screen = f64::from(basis.right.x);
            let settings = RenderSettings {
                width: 48,
                height: 48,
                samples_per_pixel: 1,
                ..RenderSettings::default()
            };
            let (film, _) = render(&sc, &st, &settings);
            let (mut sx, mut sy, mut sw) = (0.0, 0.0, 0.0);
            for y in 0..48 {
                for x in 0..48 {
                    let w = film.pixel(film.index(x, y)).mean_luminance();
                    sx += w * (f64::from(x) + 0.5 - 24.0);
                    sy += w * (24.0 - f64::from(y) - 0.5);
                    sw += w;
                }
            }
            spots.push((sx / sw, sy / sw));
        }
        let angle = |v: (f64, f64)| v.1.atan2(v.0).to_degrees();
        let turn = (angle(spots[1]) - angle(spots[0])).rem_euclid(360.0);
        println!(
            "{hand}-handed: C0 spot {:?}, C90 spot {:?}, turn {turn:.1}°",
            spots[0], spots[1]
        );
        // The C0 lobe is on the side of the picture where +X is.
        assert!(
            spots[0].0 * x_on_screen > 3.0,
            "{hand}: C0 lobe at {:?}",
            spots[0]
        );
        assert!(
            (turn - 90.0).abs() < 3.0,
            "{hand}: C90 is {turn}° from C0 on screen"
        );
    }
}

/// One test per kind of rejection: each names the file, the line and the reason.
#[test]
fn bad_files_are_refused_with_file_line_and_reason() {
    let g = steps(0.0, 90.0, 45.0);
    let good = ies(&g, &[0.0], |_, _| 10.0);
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "counts.ies",
            good.replace("1 -1 1 3 1 1 2", "1 -1 1 0 1 1 2"),
            "number of vertical angles",
        ),
        (
            "order.ies",
            good.replace("\n0 45 90\n", "\n0 90 45\n"),
            "must ascend",
        ),
        (
            "nan.ies",
            good.replace("10 10 10", "10 NaN 10"),
            "not a finite number",
        ),
        (
            "negative.ies",
            good.replace("10 10 10", "10 -10 10"),
            "negative intensity",
        ),
        (
            "truncated.ies",
            good.replace("10 10 10\n", "10 10\n"),
            "ends early",
        ),
        (
            "tilt.ies",
            good.replace("TILT=NONE", "TILT=lamp.tlt"),
            "separate tilt file",
        ),
        ("typea.ies", good.replace("3 1 1 2", "3 1 3 2"), "type A"),
        ("typeb.ies", good.replace("3 1 1 2", "3 1 2 2"), "type B"),
        (
            "vertical.ies",
            good.replace("\n0 45 90\n", "\n10 45 90\n"),
            "vertical angles run",
        ),
        ("notext.ies", "\u{0}\u{1}binary".to_owned(), "binary data"),
        (
            "notilt.ies",
            "IESNA:LM-63-2002\n1 2 3\n".to_owned(),
            "no TILT",
        ),
    ];
    for (name, text, reason) in &cases {
        let e = parse_photometry(text.as_bytes(), Path::new(name))
            .expect_err(name)
            .to_string();
        assert!(e.starts_with(name) && e.contains(reason), "{name}: {e}");
    }
    let h = steps(0.0, 90.0, 45.0);
    let good = ldt(4, 4, &h, |_, _| 10.0);
    let lines: Vec<&str> = good.lines().collect();
    let with = |i: usize, v: &str| {
        let mut l = lines.clone();
        l[i] = v;
        l.join("\n")
    };
    let ldt_cases = [
        ("sym.ldt", with(2, "5"), ":3: the symmetry indicator"),
        ("neg.ldt", with(lines.len() - 1, "-5"), "negative intensity"),
        (
            "short.ldt",
            lines[..lines.len() - 2].join("\n"),
            "ends early",
        ),
        ("gamma.ldt", with(46, "50"), "must ascend"),
    ];
    for (name, text, reason) in &ldt_cases {
        let e = parse_photometry(text.as_bytes(), Path::new(name))
            .expect_err(name)
            .to_string();
        assert!(e.starts_with(name) && e.contains(reason), "{name}: {e}");
    }
    // A sidecar naming a missing file, or giving both multiplier and flux, is refused.
    let dir = temp_dir("bad");
    let side = dir.join("s.raygine.toml");
    let missing = "[[lights]]\nkind = \"luminaire\"\nshape = \"point\"\nfile = \"nope.ies\"\nposition = [0.0, 1.0, 0.0]\n";
    let e = Sidecar::parse(missing, &side)
        .expect_err("missing")
        .to_string();
    assert!(e.contains("nope.ies") && e.contains("lights[0]"), "{e}");
    std::fs::write(dir.join("ok.ies"), ies(&g, &[0.0], |_, _| 10.0)).unwrap();
    let both = "[[lights]]\nkind = \"luminaire\"\nshape = \"point\"\nfile = \"ok.ies\"\nposition = [0.0, 1.0, 0.0]\nmultiplier = 2.0\nflux_lm = 10.0\n";
    let e = Sidecar::parse(both, &side).expect_err("both").to_string();
    assert!(e.contains("not both"), "{e}");
    let _ = Grid::new(
        "unused",
        [0.0; 3],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        1,
        1,
        None,
    );
}

/// What the files say about their luminaire, for the report's schedule: IES keywords and
/// input watts; EULUMDAT's manufacturer, name, number, lamp wattage and colour rendering.
#[test]
fn files_name_their_luminaire_and_its_power() {
    let ies_text = ies(&[0.0, 90.0], &[0.0], |_, _| 100.0).replace(
        "[MANUFAC] tests\n",
        "[MANUFAC] tests\n[LUMINAIRE] Downlight 12 W\n[LUMCAT] DL-12\n",
    );
    let p = parse(&ies_text, "a.ies");
    assert_eq!(p.info.manufacturer.as_deref(), Some("tests"));
    assert_eq!(p.info.name.as_deref(), Some("Downlight 12 W"));
    assert_eq!(p.info.catalogue_number.as_deref(), Some("DL-12"));
    assert_eq!(p.info.power_w, Some(50.0), "the input watts");
    assert_eq!(p.info.colour_rendering, None);
    let p = parse(&ldt(1, 24, &[0.0, 90.0, 180.0], |_, _| 100.0), "a.ldt");
    assert_eq!(p.info.manufacturer.as_deref(), Some("raygine tests"));
    assert_eq!(p.info.name.as_deref(), Some("luminaire"));
    assert_eq!(p.info.catalogue_number.as_deref(), Some("L-1"));
    assert_eq!(p.info.power_w, Some(20.0), "the lamp set's wattage");
    assert_eq!(p.info.colour_rendering.as_deref(), Some("80"));
}
