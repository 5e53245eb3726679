//! `raygine glare`: a summary per observer on stdout, JSON, CSV and Radiance pictures only when
//! asked; bad observers (inside a block, a zero direction, an unknown name, none at all) are
//! errors naming the observer and write nothing. `raygine report` checks UGR at a grid's
//! observers against the activity's limit.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use raygine_e2e::*;
use std::path::{Path, PathBuf};

/// The repository's Cornell box (mm, left-handed) with `extra` appended to its sidecar.
fn scene(dir: &Path, extra: &str) -> PathBuf {
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes");
    let shp = dir.join("box.shp");
    std::fs::copy(assets.join("cornell_box.shp"), &shp).unwrap();
    let mut sidecar = std::fs::read_to_string(assets.join("cornell_box.raygine.toml")).unwrap();
    sidecar.push('\n');
    sidecar.push_str(extra);
    std::fs::write(dir.join("box.raygine.toml"), sidecar).unwrap();
    shp
}

/// An observer at the box's open front looking up at the ceiling's lit centre.
const DOOR: &str = "[[observers]]\nname = \"door\"\nposition = [278.0, 200.0, -60.0]\n\
                    direction = [0.0, 1.2, -1.0]\n";

fn glare_args(shp: &Path, more: &[&str]) -> Vec<String> {
    let mut args: Vec<String> = ["glare", "-S"].map(String::from).to_vec();
    args.push(shp.display().to_string());
    args.extend(["--samples", "4", "--size", "128", "--threads", "2"].map(String::from));
    args.extend(more.iter().map(|s| s.to_string()));
    args
}

#[test]
fn glare_prints_each_observer_and_writes_only_what_is_asked() {
    let dir = temp_dir();
    let shp = scene(dir.path(), DOOR);
    let run = raygine_in(dir.path(), glare_args(&shp, &[]));
    run.assert_ok();
    for needle in ["observer door", "Ev ", "UGR", "DGP", "from the image"] {
        assert!(
            run.stdout.contains(needle),
            "no {needle:?} in\n{}",
            run.stdout
        );
    }
    let written: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(
        written.len(),
        2,
        "only the scene and its sidecar: {written:?}"
    );

    let (json, csv) = (dir.path().join("g.json"), dir.path().join("g.csv"));
    let hdr = dir.path().join("pictures");
    std::fs::create_dir(&hdr).unwrap();
    let more = [
        "--json",
        json.to_str().unwrap(),
        "--csv",
        csv.to_str().unwrap(),
        "--hdr",
        hdr.to_str().unwrap(),
    ];
    raygine_in(dir.path(), glare_args(&shp, &more)).assert_ok();
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let door = &doc["observers"][0];
    assert_eq!(door["name"], "door");
    let image = &door["from_image"];
    let ev = image["ev_lx"].as_f64().unwrap();
    assert!(
        ev > 0.0 && image["ev_std_error_lx"].as_f64().unwrap() > 0.0,
        "{image}"
    );
    let dgp = image["dgp"].as_f64().unwrap();
    assert!((0.16..1.0).contains(&dgp), "{image}");
    for s in image["sources"].as_array().unwrap() {
        assert!(s["luminance_cd_m2"].as_f64().unwrap() > 0.0);
        assert!(s["solid_angle_sr"].as_f64().unwrap() > 0.0);
        assert!(s["position_index"].as_f64().unwrap() >= 1.0);
    }
    let csv = std::fs::read_to_string(&csv).unwrap();
    assert!(csv.starts_with("observer,sources_from,"), "{csv}");
    assert!(csv.lines().any(|l| l.starts_with("door,image,")), "{csv}");
    let picture = std::fs::read(hdr.join("door.hdr")).unwrap();
    let header = String::from_utf8_lossy(&picture[..200]);
    assert!(
        header.starts_with("#?RADIANCE") && header.contains("VIEW= -vta"),
        "{header}"
    );
}

#[test]
fn bad_observers_are_errors_naming_them_and_write_nothing() {
    let dir = temp_dir();
    let json = dir.path().join("g.json");
    let json_arg = ["--json", json.to_str().unwrap()];
    // An eye low inside the tall block, which stands open-bottomed on the floor.
    let inside = "[[observers]]\nname = \"buried\"\nposition = [368.0, 20.0, -351.0]\n\
                  direction = [0.0, 0.0, 1.0]\n";
    let shp = scene(dir.path(), inside);
    let run = raygine_in(dir.path(), glare_args(&shp, &json_arg));
    assert!(!run.success());
    assert!(
        run.stderr.contains("observer buried") && run.stderr.contains("inside a solid"),
        "{}",
        run.stderr
    );
    assert!(!json.exists());
    // A zero direction: the sidecar's error names the key and its line.
    let zero = "[[observers]]\nname = \"zero\"\nposition = [278.0, 200.0, -60.0]\n\
                direction = [0.0, 0.0, 0.0]\n";
    let shp = scene(dir.path(), zero);
    let run = raygine_in(dir.path(), glare_args(&shp, &json_arg));
    assert!(!run.success());
    assert!(
        run.stderr.contains("observer zero") && run.stderr.contains("direction"),
        "{}",
        run.stderr
    );
    // An unknown name lists the known ones; no observers at all says how to add one.
    let shp = scene(dir.path(), DOOR);
    let run = raygine_in(dir.path(), glare_args(&shp, &["--observer", "window"]));
    assert!(
        !run.success() && run.stderr.contains("door"),
        "{}",
        run.stderr
    );
    let shp = scene(dir.path(), "");
    let run = raygine_in(dir.path(), glare_args(&shp, &json_arg));
    assert!(
        !run.success() && run.stderr.contains("[[observers]]"),
        "{}",
        run.stderr
    );
    assert!(!json.exists());
}

#[test]
fn the_report_checks_ugr_at_a_grids_observers() {
    let dir = temp_dir();
    let grid = "[[grids]]\nname = \"desk\"\norigin = [200.0, 100.0, -360.0]\nu = [150.0, 0.0, 0.0]\n\
                v = [0.0, 0.0, 150.0]\nnu = 2\nnv = 2\nnormal = [0.0, 1.0, 0.0]\n\
                task = \"office-writing\"\nobservers = [\"door\"]\n";
    let shp = scene(dir.path(), &format!("{DOOR}{grid}"));
    let pdf = dir.path().join("r.pdf");
    let mut args: Vec<String> = ["report", "-S"].map(String::from).to_vec();
    args.push(shp.display().to_string());
    args.extend(["-o".to_owned(), pdf.display().to_string()]);
    args.extend(["--samples", "4", "--view-samples", "4", "--threads", "2"].map(String::from));
    raygine_in(dir.path(), &args).assert_ok();
    let out = std::process::Command::new("pdftotext")
        .args([pdf.to_str().unwrap(), "-"])
        .output();
    match out {
        Ok(o) if o.status.success() => {
            let text = String::from_utf8_lossy(&o.stdout);
            assert!(text.contains("UGR at observer door"), "{text}");
        }
        _ => {
            assert!(
                std::env::var("CI").as_deref() != Ok("true"),
                "CI needs pdftotext"
            );
            println!("skipped: no pdftotext");
        }
    }
}
