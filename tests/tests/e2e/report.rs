//! `raygine report`: the PDF is valid (poppler's `pdfinfo` counts its pages), its text
//! (`pdftotext`) carries the same readings as `raygine measure --json` to the printed
//! precision, points inside the box's blocks are counted and left out, a grid built to pass
//! passes and one built to fail fails; an unknown task lists the known ones, and a folder that
//! is not there is an error with no file written.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use raygine_e2e::*;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository's Cornell box with two grids: "bright", a small patch under the lamp judged
/// as a corridor (built to pass), and "floor", a work plane on the floor judged as technical
/// drawing (built to fail: the blocks' shadows break its uniformity).
fn scene(dir: &Path, floor_task: &str) -> PathBuf {
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes");
    let shp = dir.join("box.shp");
    std::fs::copy(assets.join("cornell_box.shp"), &shp).unwrap();
    let mut sidecar = std::fs::read_to_string(assets.join("cornell_box.raygine.toml")).unwrap();
    sidecar.push_str(&format!(
        "\n[[grids]]\nname = \"bright\"\norigin = [290.0, 250.0, -260.0]\nu = [100.0, 0.0, 0.0]\n\
         v = [0.0, 0.0, 100.0]\nnu = 3\nnv = 3\nnormal = [0.0, 1.0, 0.0]\ntask = \"corridor\"\n\
         \n[[grids]]\nname = \"floor\"\nwork_plane = true\nheight = 0.0\nmargin = 10.0\n\
         task = \"{floor_task}\"\n"
    ));
    std::fs::write(dir.join("box.raygine.toml"), sidecar).unwrap();
    shp
}

/// Runs a poppler tool, or None (with the reason printed) where it is not installed; CI must
/// have it.
fn poppler(tool: &str, pdf: &Path) -> Option<String> {
    let mut command = Command::new(tool);
    if tool == "pdftotext" {
        command.arg("-layout");
    }
    command.arg(pdf);
    if tool == "pdftotext" {
        command.arg("-");
    }
    match command.output() {
        Ok(out) if out.status.success() => Some(String::from_utf8_lossy(&out.stdout).into_owned()),
        Ok(out) => panic!(
            "{tool} failed on {}: {}",
            pdf.display(),
            String::from_utf8_lossy(&out.stderr)
        ),
        Err(e) => {
            assert!(
                std::env::var("CI").as_deref() != Ok("true"),
                "CI needs poppler-utils ({tool}: {e})"
            );
            println!("skipped: {tool} is not installed ({e}); apt-get install poppler-utils");
            None
        }
    }
}

/// The number after `label` on its line of `text` (the PDF's table rows read "Eavg 670 lx ± 14").
fn number_after(text: &str, label: &str) -> f64 {
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with(label))
        .unwrap_or_else(|| panic!("no line starting with {label:?} in\n{text}"));
    line.trim_start()[label.len()..]
        .split_whitespace()
        .next()
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("no number after {label:?}: {line}"))
}

#[test]
fn the_report_is_a_valid_pdf_whose_numbers_are_measures() {
    let dir = temp_dir();
    let shp = scene(dir.path(), "office-technical-drawing");
    let pdf = dir.path().join("report.pdf");
    let common = ["--gi", "path", "--samples", "16", "--threads", "2"];
    let mut args: Vec<String> = ["report", "-S"].map(String::from).to_vec();
    args.push(shp.display().to_string());
    args.extend(["-o".to_owned(), pdf.display().to_string()]);
    args.extend(common.map(String::from));
    args.extend(["--view-samples", "4"].map(String::from));
    let run = raygine_in(dir.path(), &args);
    run.assert_ok();
    assert!(run.stdout.contains("grid bright: PASS"), "{}", run.stdout);
    assert!(run.stdout.contains("grid floor: FAIL"), "{}", run.stdout);
    let json = dir.path().join("m.json");
    let mut args: Vec<String> = ["measure", "-S"].map(String::from).to_vec();
    args.push(shp.display().to_string());
    args.extend(["--json".to_owned(), json.display().to_string()]);
    args.extend(common.map(String::from));
    raygine_in(dir.path(), &args).assert_ok();
    let measured: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();

    // The JSON's readings are rounded: three significant figures at most, no float noise.
    for grid in measured["grids"].as_array().unwrap() {
        for p in grid["points"].as_array().unwrap() {
            let text = p["illuminance_lx"].to_string();
            let digits = text
                .trim_start_matches('-')
                .replace('.', "")
                .trim_start_matches('0')
                .trim_end_matches('0')
                .len();
            assert!(digits <= 3, "{text} has {digits} significant digits");
        }
    }
    let Some(info) = poppler("pdfinfo", &pdf) else {
        return;
    };
    // Cover, one page a grid, the schedule, the requirements check.
    assert!(
        info.lines()
            .any(|l| l.starts_with("Pages:") && l.ends_with(" 5")),
        "{info}"
    );
    let Some(text) = poppler("pdftotext", &pdf) else {
        return;
    };
    // Each grid's page: its statistics equal the measurement's, as rounded there.
    for grid in measured["grids"].as_array().unwrap() {
        let name = grid["name"].as_str().unwrap();
        let page = text
            .split('\u{c}')
            .find(|p| p.contains(&format!("Grid {name}")))
            .unwrap_or_else(|| panic!("no page for grid {name}"));
        for (label, key) in [
            ("Emin", "e_min_lx"),
            ("Eavg", "e_avg_lx"),
            ("Emax", "e_max_lx"),
        ] {
            let printed = number_after(page, label);
            let json = grid[key].as_f64().unwrap();
            assert_eq!(
                printed, json,
                "grid {name} {label}: PDF {printed}, measure {json}"
            );
        }
        let inside = grid["points_inside_objects"].as_u64().unwrap();
        if inside > 0 {
            assert!(
                page.contains(&format!("{inside} points, crossed out")),
                "grid {name}: {inside} points inside objects\n{page}"
            );
        }
    }
    // The floor's points inside objects lie under both blocks (the short one at x < 250 mm,
    // the tall one at x > 265 mm) and are left out of its statistics.
    let floor = measured["grids"]
        .as_array()
        .unwrap()
        .iter()
        .find(|g| g["name"] == "floor")
        .unwrap();
    let buried: Vec<f64> = floor["points"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["inside_object"] == true)
        .map(|p| p["x"].as_f64().unwrap())
        .collect();
    assert!(
        buried.iter().any(|&x| x < 250.0) && buried.iter().any(|&x| x > 265.0),
        "points inside objects at x = {buried:?}"
    );
    for needle in [
        "Lighting report",
        "Luminaire schedule",
        "Requirements check",
        "PASS",
        "FAIL",
        "EN 12464-1:2011, table 5.1, ref. no. 5.1.1",
        "Rendered plan view: orthographic",
    ] {
        assert!(text.contains(needle), "no {needle:?} in the PDF's text");
    }
}

#[test]
fn bad_tasks_and_unwritable_paths_are_errors_and_write_nothing() {
    let dir = temp_dir();
    let shp = scene(dir.path(), "kitchen");
    let pdf = dir.path().join("report.pdf");
    let run = raygine_in(
        dir.path(),
        [
            "report".as_ref(),
            "-S".as_ref(),
            shp.as_os_str(),
            "-o".as_ref(),
            pdf.as_os_str(),
        ],
    );
    assert!(!run.success());
    assert!(
        run.stderr.contains("grid floor: unknown task \"kitchen\"")
            && run.stderr.contains("office-writing"),
        "{}",
        run.stderr
    );
    assert!(!pdf.exists(), "a report was written");
    let shp = scene(dir.path(), "corridor");
    let nowhere = dir.path().join("no-such-folder").join("report.pdf");
    let run = raygine_in(
        dir.path(),
        [
            "report".as_ref(),
            "-S".as_ref(),
            shp.as_os_str(),
            "-o".as_ref(),
            nowhere.as_os_str(),
        ],
    );
    assert!(!run.success());
    assert!(run.stderr.contains("does not exist"), "{}", run.stderr);
    assert!(!nowhere.exists());
    // A grid judged by an observer the sidecar does not have.
    let sidecar = dir.path().join("box.raygine.toml");
    let text = std::fs::read_to_string(&sidecar).unwrap();
    std::fs::write(&sidecar, format!("{text}observers = [\"nobody\"]\n")).unwrap();
    let run = raygine_in(
        dir.path(),
        [
            "report".as_ref(),
            "-S".as_ref(),
            shp.as_os_str(),
            "-o".as_ref(),
            pdf.as_os_str(),
        ],
    );
    assert!(
        !run.success()
            && run
                .stderr
                .contains("grid floor: unknown observer \"nobody\""),
        "{}",
        run.stderr
    );
    assert!(!pdf.exists());
    std::fs::write(&sidecar, &text).unwrap();
    // Paper sizes: letter is 612 x 792 pt; anything else is refused.
    let letter = dir.path().join("letter.pdf");
    let run = |paper: &str, out: &Path| {
        raygine_in(
            dir.path(),
            [
                "report".as_ref(),
                "-S".as_ref(),
                shp.as_os_str(),
                "-o".as_ref(),
                out.as_os_str(),
                "--paper".as_ref(),
                paper.as_ref(),
                "--view-samples".as_ref(),
                "1".as_ref(),
            ],
        )
    };
    let a5 = run("a5", &letter);
    assert!(
        !a5.success() && a5.stderr.contains("a4 or letter"),
        "{}",
        a5.stderr
    );
    run("letter", &letter).assert_ok();
    if let Some(info) = poppler("pdfinfo", &letter) {
        assert!(info.contains("612 x 792 pts (letter)"), "{info}");
    }
}
