//! `raygine measure` and `raygine render --gi path` through the real binary: the CSV's exact
//! header and values against E = I cos θ / R², the shared options, and clear errors.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use raygine_e2e::{floor_quad, raygine_in, read_png, render_in, shp_of_quads, temp_dir};
use std::path::Path;

/// A 4 x 4 m black floor (unit m) with a 100 cd point light 2 m above its centre.
fn floor_scene(dir: &Path, extra_sidecar: &str) -> std::path::PathBuf {
    let shp = dir.join("floor.shp");
    std::fs::write(&shp, shp_of_quads(&[("floor", &[floor_quad(2.0)])])).unwrap();
    let sidecar = format!(
        "unit = \"m\"\n\n[camera]\nposition = [0.0, 3.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_deg = 60.0\n\n\
         [[lights]]\nposition = [0.0, 2.0, 0.0]\nintensity_cd = 100.0\n\n\
         [default_material]\nkd = [0.0, 0.0, 0.0]\n\n{extra_sidecar}"
    );
    std::fs::write(dir.join("floor.raygine.toml"), sidecar).unwrap();
    shp
}

const GRID: &str = "[[grids]]\nname = \"floor\"\norigin = [-2.0, 0.0, -2.0]\nu = [4.0, 0.0, 0.0]\n\
                    v = [0.0, 0.0, 4.0]\nnu = 4\nnv = 2\nnormal = [0.0, 1.0, 0.0]\n";

#[test]
fn measure_writes_the_csv_with_exact_direct_illuminance() {
    let dir = temp_dir();
    let shp = floor_scene(dir.path(), GRID);
    for integrator in ["direct", "path"] {
        let csv = dir.path().join(format!("{integrator}.csv"));
        let run = raygine_in(
            dir.path(),
            [
                "measure".as_ref(),
                "--precision".as_ref(),
                "full".as_ref(),
                "-S".as_ref(),
                shp.as_os_str(),
                "--gi".as_ref(),
                integrator.as_ref(),
                "--samples".as_ref(),
                "8".as_ref(),
                "--csv".as_ref(),
                csv.as_os_str(),
            ],
        );
        run.assert_ok();
        assert!(
            run.stdout.contains("grid floor: 8 points"),
            "{}",
            run.stdout
        );
        assert!(run.stdout.contains("lx"), "{}", run.stdout);
        let text = std::fs::read_to_string(&csv).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next(),
            Some("grid,i,j,x,y,z,illuminance_lx,std_error_lx")
        );
        let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
        assert_eq!(rows.len(), 8);
        for r in &rows {
            let (i, j): (u32, u32) = (r[1].parse().unwrap(), r[2].parse().unwrap());
            let x: f64 = r[3].parse().unwrap();
            let z: f64 = r[5].parse().unwrap();
            // Cell centres: origin + (i + ½)/nu · u + (j + ½)/nv · v.
            assert!((x - (-2.0 + (f64::from(i) + 0.5))).abs() < 1e-5, "{r:?}");
            assert!(
                (z - (-2.0 + (f64::from(j) + 0.5) * 2.0)).abs() < 1e-5,
                "{r:?}"
            );
            let d2 = x * x + z * z + 4.0;
            let exact = 100.0 * 2.0 / d2.sqrt() / d2;
            let e: f64 = r[6].parse().unwrap();
            assert!(
                (e / exact - 1.0).abs() < 1e-4,
                "{integrator} {r:?}: exact {exact}"
            );
        }
    }
}

#[test]
fn measure_refuses_bad_grids_and_scenes_without_grids() {
    let dir = temp_dir();
    let shp = floor_scene(dir.path(), "");
    let csv = dir.path().join("out.csv");
    let args = |shp: &Path| {
        vec![
            "measure".into(),
            "-S".into(),
            shp.as_os_str().to_owned(),
            "--csv".into(),
            csv.as_os_str().to_owned(),
        ]
    };
    let run = raygine_in(dir.path(), args(&shp));
    assert!(!run.success());
    assert!(run.stderr.contains("no grids"), "{}", run.stderr);
    let bad = GRID
        .replace("nu = 4", "nu = 0")
        .replace("\"floor\"", "\"desk\"");
    let shp = floor_scene(dir.path(), &bad);
    let run = raygine_in(dir.path(), args(&shp));
    assert!(!run.success());
    assert!(
        run.stderr.contains("floor.raygine.toml") && run.stderr.contains("grid desk"),
        "{}",
        run.stderr
    );
    assert!(!csv.exists(), "nothing written on an error");
    let both = "[[lights]]\nposition = [0.0, 1.0, 0.0]\nintensity_cd = 1.0\nflux_lm = 3.0\n";
    std::fs::write(dir.path().join("floor.raygine.toml"), both).unwrap();
    let run = render_in(dir.path(), ["-S".as_ref(), shp.as_os_str()]);
    assert!(!run.success());
    assert!(run.stderr.contains("not both"), "{}", run.stderr);
}

/// Global illumination lights what direct light leaves dark, and the summary says which mode
/// ran; --time-limit stops a render before its sample cap.
#[test]
fn render_with_gi_is_brighter_and_time_limited() {
    let dir = temp_dir();
    let direct = dir.path().join("direct.png");
    let path = dir.path().join("path.png");
    let size = ["-W", "64", "-H", "48"];
    render_in(
        dir.path(),
        size.iter()
            .map(|s| s.to_string())
            .chain(["--samples", "4", "-R"].map(String::from))
            .chain([direct.display().to_string()]),
    )
    .assert_ok();
    let run = render_in(
        dir.path(),
        size.iter()
            .map(|s| s.to_string())
            .chain(
                [
                    "--gi",
                    "path",
                    "--samples",
                    "100000",
                    "--time-limit",
                    "1",
                    "-R",
                ]
                .map(String::from),
            )
            .chain([path.display().to_string()]),
    );
    run.assert_ok();
    assert!(
        run.stdout.contains("path, unlimited bounces"),
        "{}",
        run.stdout
    );
    // A time limit samples adaptively: "149.7 spp on average (adaptive: 16 to 1477)".
    let spp: f64 = run
        .stdout
        .split(" spp on average")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .and_then(|s| s.parse().ok())
        .expect("spp in the summary");
    assert!((1.0..100_000.0).contains(&spp), "{}", run.stdout);
    assert!(run.stdout.contains("(adaptive: "), "{}", run.stdout);
    let mean = |p: &Path| {
        let img = read_png(p);
        let c = img.mean_frac(0.0, 0.0, 1.0, 1.0);
        0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
    };
    // The ceiling and the shadows receive reflected light.
    let ceiling = |p: &Path| read_png(p).mean_frac(0.3, 0.02, 0.45, 0.08)[1];
    assert!(
        mean(&path) > mean(&direct) + 10.0,
        "{} vs {}",
        mean(&path),
        mean(&direct)
    );
    assert!(ceiling(&path) > ceiling(&direct) + 30.0);
}

#[test]
fn light_options_need_a_point_light() {
    let dir = temp_dir();
    let shp = dir.path().join("s.shp");
    std::fs::write(&shp, shp_of_quads(&[("floor", &[floor_quad(2.0)])])).unwrap();
    std::fs::write(dir.path().join("s.raygine.toml"), "lights = []\n").unwrap();
    let run = render_in(
        dir.path(),
        ["-S".as_ref(), shp.as_os_str(), "-I".as_ref(), "5".as_ref()],
    );
    assert!(!run.success());
    assert!(run.stderr.contains("first point light"), "{}", run.stderr);
}

/// `raygine info --json` lists the scene's unit, materials, lights and camera; a luminaire from
/// an IES file beside the sidecar shows its flux and file.
#[test]
fn info_describes_the_scene_with_its_luminaire() {
    let dir = temp_dir();
    let ies =
        "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0\n100 100 100\n";
    std::fs::write(dir.path().join("lamp.ies"), ies).unwrap();
    let shp = floor_scene(
        dir.path(),
        "[[lights]]\nkind = \"luminaire\"\nfile = \"lamp.ies\"\nposition = [0.0, 1.0, 0.0]\n",
    );
    let run = raygine_in(
        dir.path(),
        [
            "info".as_ref(),
            "-S".as_ref(),
            shp.as_os_str(),
            "--json".as_ref(),
        ],
    );
    run.assert_ok();
    for key in [
        "\"unit\": \"m\"",
        "\"handedness\"",
        "\"bounds\"",
        "\"triangles\": 2",
        "\"materials\"",
        "\"camera\"",
        "\"kind\": \"luminaire\"",
        "lamp.ies",
        "\"flux_lm\"",
    ] {
        assert!(run.stdout.contains(key), "{key} missing: {}", run.stdout);
    }
    let text = raygine_in(
        dir.path(),
        ["info".as_ref(), "-S".as_ref(), shp.as_os_str()],
    );
    text.assert_ok();
    // 100 cd over the lower hemisphere: 2π · 100 = 628 lm.
    assert!(
        text.stdout.contains("628.") && text.stdout.contains("lm"),
        "{}",
        text.stdout
    );
}

/// `--json` holds the statistics and every point; the summary line has the format, and
/// a maintenance factor scales the maintained values and is said.
#[test]
fn measure_writes_json_with_statistics() {
    let dir = temp_dir();
    let shp = floor_scene(dir.path(), GRID);
    // A top-level key goes before the tables.
    let side = dir.path().join("floor.raygine.toml");
    let text = std::fs::read_to_string(&side).unwrap();
    std::fs::write(&side, format!("maintenance_factor = 0.5\n{text}")).unwrap();
    let json = dir.path().join("out.json");
    let run = raygine_in(
        dir.path(),
        [
            "measure".as_ref(),
            "--precision".as_ref(),
            "full".as_ref(),
            "-S".as_ref(),
            shp.as_os_str(),
            "--json".as_ref(),
            json.as_os_str(),
        ],
    );
    run.assert_ok();
    assert!(
        run.stdout.contains("maintenance factor 0.5"),
        "{}",
        run.stdout
    );
    let line = run
        .stdout
        .lines()
        .find(|l| l.starts_with("grid floor: 8 points, Emin "))
        .unwrap_or_else(|| panic!("{}", run.stdout));
    for part in [
        " lx, Eavg ",
        " lx, Emax ",
        " lx, U0 ",
        ", Emin/Emax ",
        ", normal (0.000, 1.000, 0.000)",
    ] {
        assert!(line.contains(part), "{line}");
    }
    let text = std::fs::read_to_string(&json).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["unit"], "m");
    assert_eq!(v["integrator"], "direct");
    assert_eq!(v["samples"], 1);
    let g = &v["grids"][0];
    assert_eq!(g["name"], "floor");
    assert_eq!(g["normal"], serde_json::json!([0.0, 1.0, 0.0]));
    let points = g["points"].as_array().unwrap();
    assert_eq!(points.len(), 8);
    let es: Vec<f64> = points
        .iter()
        .map(|p| p["illuminance_lx"].as_f64().unwrap())
        .collect();
    let (min, max) = es
        .iter()
        .fold((f64::MAX, 0.0f64), |(a, b), &e| (a.min(e), b.max(e)));
    let avg = es.iter().sum::<f64>() / 8.0;
    assert!((g["e_min_lx"].as_f64().unwrap() - min).abs() < 1e-9);
    assert!((g["e_max_lx"].as_f64().unwrap() - max).abs() < 1e-9);
    assert!((g["e_avg_lx"].as_f64().unwrap() - avg).abs() < 1e-9);
    assert!((g["u0"].as_f64().unwrap() - min / avg).abs() < 1e-9);
    assert!((g["emin_over_emax"].as_f64().unwrap() - min / max).abs() < 1e-9);
    // Maintained: half of E = I cos θ / R² at the first point.
    let p = &points[0];
    let (x, z) = (p["x"].as_f64().unwrap(), p["z"].as_f64().unwrap());
    let d2 = x * x + z * z + 4.0;
    let exact = 0.5 * 100.0 * 2.0 / d2.sqrt() / d2;
    assert!((p["illuminance_lx"].as_f64().unwrap() / exact - 1.0).abs() < 1e-4);
    for key in ["i", "j", "y", "std_error_lx"] {
        assert!(p.get(key).is_some(), "{key}");
    }
}

/// Without --csv or --json, `measure` prints its summary to stdout and writes no file (it used
/// to refuse to run).
#[test]
fn measure_without_files_prints_the_summary_only() {
    let dir = temp_dir();
    let shp = floor_scene(dir.path(), GRID);
    let before: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    let run = raygine_in(
        dir.path(),
        ["measure".as_ref(), "-S".as_ref(), shp.as_os_str()],
    );
    run.assert_ok();
    assert!(
        run.stdout.contains("grid floor: 8 points"),
        "{}",
        run.stdout
    );
    assert!(!run.stdout.contains("wrote"), "{}", run.stdout);
    let after: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(before.len(), after.len(), "a file was written");
}

/// A long render says where it is every few seconds, also when its output is not a terminal
/// (a log, a batch job): samples done, elapsed time and time left, on stderr; stdout keeps the
/// figures.
#[test]
fn a_long_render_prints_progress_lines() {
    let dir = temp_dir();
    let png = dir.path().join("long.png");
    let run = render_in(
        dir.path(),
        [
            "--gi".as_ref(),
            "bdpt".as_ref(),
            "-W".as_ref(),
            "48".as_ref(),
            "-H".as_ref(),
            "36".as_ref(),
            "--samples".as_ref(),
            "1000000".as_ref(),
            "--time-limit".as_ref(),
            "6.5".as_ref(),
            "-R".as_ref(),
            png.as_os_str(),
        ],
    );
    run.assert_ok();
    let lines: Vec<&str> = run
        .stderr_lines()
        .into_iter()
        .filter(|l| l.starts_with("rendering: "))
        .collect();
    assert!(!lines.is_empty(), "no progress line: {}", run.stderr);
    for l in &lines {
        // Adaptive under a time limit: the average, the least, and the time left.
        assert!(
            l.contains(" spp on average (at least ") && l.ends_with(" s left"),
            "{l}"
        );
    }
    assert!(!run.stdout.contains("rendering: "), "{}", run.stdout);
    assert!(png.is_file());
}

/// `render --target-error PCT` samples adaptively until every pixel but the 0.5 % brightest is
/// within it, says so with the worst pixel, and keeps --samples as the cap of every pixel;
/// `--no-adaptive` cannot be combined with it.
#[test]
fn a_target_error_is_rendered_to_and_reported() {
    let dir = temp_dir();
    fn args<'a>(pct: &'a str, cap: &'a str) -> [&'a str; 12] {
        [
            "--gi",
            "bdpt",
            "-W",
            "32",
            "-H",
            "24",
            "--target-error",
            pct,
            "--samples",
            cap,
            "-R",
            "t.png",
        ]
    }
    let run = render_in(dir.path(), args("20", "4096"));
    run.assert_ok();
    assert!(run.stdout.contains("(adaptive: "), "{}", run.stdout);
    let line = run
        .stdout
        .lines()
        .find(|l| l.starts_with("target error 20 %: reached; worst pixel "))
        .unwrap_or_else(|| panic!("{}", run.stdout));
    let worst: f64 = line
        .rsplit(' ')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{line}"));
    assert!(worst <= 20.0, "{line}");
    // A cap too low for the target: rendered, and said.
    let capped = render_in(dir.path(), args("1", "20"));
    capped.assert_ok();
    assert!(
        capped.stdout.contains("target error 1 %: NOT reached"),
        "{}",
        capped.stdout
    );
    assert!(
        capped.stdout.contains("(adaptive: 16 to 20)"),
        "{}",
        capped.stdout
    );
    let both = render_in(
        dir.path(),
        ["--gi", "bdpt", "--target-error", "5", "--no-adaptive"],
    );
    assert!(!both.success());
    assert!(both.stderr.contains("--no-adaptive"), "{}", both.stderr);
}

/// `--daylight-factor`: the open floor under the CIE overcast sky has DF = 100 % (E_in is
/// E_out,h), whatever the sidecar's lights, its sky (here none) and its maintenance factor;
/// the CSV gains `daylight_factor_pct`, the JSON the DF statistics, stdout a DF line.
#[test]
fn measure_gives_daylight_factors() {
    let dir = temp_dir();
    let shp = floor_scene(dir.path(), GRID);
    let side = dir.path().join("floor.raygine.toml");
    let text = std::fs::read_to_string(&side).unwrap();
    std::fs::write(&side, format!("maintenance_factor = 0.5\n{text}")).unwrap();
    let (csv, json) = (dir.path().join("df.csv"), dir.path().join("df.json"));
    let run = raygine_in(
        dir.path(),
        [
            "measure".as_ref(),
            "-S".as_ref(),
            shp.as_os_str(),
            "--gi".as_ref(),
            "path".as_ref(),
            "--samples".as_ref(),
            "2048".as_ref(),
            "--daylight-factor".as_ref(),
            "--csv".as_ref(),
            csv.as_os_str(),
            "--json".as_ref(),
            json.as_os_str(),
        ],
    );
    run.assert_ok();
    assert!(
        run.stdout
            .contains("CIE overcast sky without sun, E_out,h 10000 lx"),
        "{}",
        run.stdout
    );
    assert!(!run.stdout.contains("maintenance factor"), "{}", run.stdout);
    let line = run
        .stdout
        .lines()
        .find(|l| l.starts_with("grid floor: DF min "))
        .unwrap_or_else(|| panic!("{}", run.stdout));
    assert!(
        line.contains(" %, avg ") && line.contains("uniformity (min/avg)"),
        "{line}"
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some(
            "grid,i,j,x,y,z,illuminance_lx,std_error_lx,daylight_factor_pct,\
             daylight_factor_std_error_pct"
        )
    );
    for l in lines {
        let r: Vec<f64> = l.split(',').skip(1).map(|c| c.parse().unwrap()).collect();
        let (e, df) = (r[5], r[7]);
        assert!((df - 100.0).abs() < 2.0, "{l}");
        assert!((df - e / 100.0).abs() < 1e-9, "{l}");
    }
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(v["daylight_factor"]["sky"], "cie-overcast");
    let g = &v["grids"][0];
    for key in ["df_min_pct", "df_avg_pct", "df_max_pct"] {
        let df = g[key].as_f64().unwrap();
        assert!((df - 100.0).abs() < 2.0, "{key} {df}");
    }
    assert!(g["points"][0]["daylight_factor_pct"].as_f64().is_some());
}
