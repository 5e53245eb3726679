//! Shards, merges and sweeps through the real binary: merged parts give the same bytes as one
//! render or measurement, bad part sets are refused naming the file, and a sweep's images and
//! readings equal separate runs with the patched sidecars.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use raygine_e2e::{Run, floor_quad, raygine_in, render_in, shp_of_quads, temp_dir};
use std::path::{Path, PathBuf};

const SIZE: [&str; 4] = ["-W", "40", "-H", "30"];

/// Renders shard `k` of `m` of the built-in box into `dir/name`.
fn shard(dir: &Path, extra: &[&str], k: u32, m: u32, name: &str) -> PathBuf {
    let part = dir.join(name);
    let mut args: Vec<String> = extra.iter().map(|s| s.to_string()).collect();
    args.extend(SIZE.map(String::from));
    args.extend(["--shard-index".into(), k.to_string()]);
    args.extend(["--shard-count".into(), m.to_string()]);
    args.extend(["--partial".into(), part.display().to_string()]);
    render_in(dir, &args).assert_ok();
    part
}

fn merge(dir: &Path, parts: &[&Path], png: &str) -> Run {
    let mut args: Vec<String> = vec!["merge".into()];
    args.extend(parts.iter().map(|p| p.display().to_string()));
    args.extend([
        "-R".into(),
        png.into(),
        "--exr".into(),
        format!("{png}.exr"),
    ]);
    raygine_in(dir, &args)
}

#[test]
fn merged_shards_equal_one_render_bit_for_bit_for_every_integrator() {
    let dir = temp_dir();
    let d = dir.path();
    for (integrator, samples) in [("direct", "5"), ("path", "7"), ("bdpt", "6")] {
        let opts = ["--gi", integrator, "--samples", samples, "--auto-exposure"];
        let parts: Vec<PathBuf> = (0..3)
            .map(|k| shard(d, &opts[..4], k, 3, &format!("{integrator}-{k}.part")))
            .collect();
        // Any order of the parts gives the same image.
        let order = [&parts[2], &parts[0], &parts[1]].map(PathBuf::as_path);
        let mut args: Vec<&str> = vec!["merge"];
        let names: Vec<String> = order.iter().map(|p| p.display().to_string()).collect();
        args.extend(names.iter().map(String::as_str));
        args.extend(["-R", "merged.png", "--exr", "merged.exr", "--auto-exposure"]);
        raygine_in(d, &args).assert_ok();
        let mut single: Vec<&str> = opts.to_vec();
        single.extend(SIZE);
        single.extend(["-R", "single.png", "--exr", "single.exr"]);
        render_in(d, &single).assert_ok();
        for f in ["png", "exr"] {
            let merged = std::fs::read(d.join(format!("merged.{f}"))).unwrap();
            let one = std::fs::read(d.join(format!("single.{f}"))).unwrap();
            assert!(merged == one, "{integrator}: the merged {f} differs");
        }
        // A shard run again (after a crash, say) writes the same bytes.
        let again = shard(d, &opts[..4], 1, 3, &format!("{integrator}-1-again.part"));
        assert_eq!(
            std::fs::read(&again).unwrap(),
            std::fs::read(&parts[1]).unwrap()
        );
    }
}

#[test]
fn bad_part_sets_are_refused_naming_the_file() {
    let dir = temp_dir();
    let d = dir.path();
    let opts = ["--gi", "path", "--samples", "4"];
    let p: Vec<PathBuf> = (0..3)
        .map(|k| shard(d, &opts, k, 3, &format!("p{k}.part")))
        .collect();
    let refused = |parts: &[&Path], needle: &str| {
        let run = merge(d, parts, "out.png");
        assert!(!run.success(), "merged {parts:?}");
        assert!(
            run.stderr.contains(needle),
            "want `{needle}`:\n{}",
            run.stderr
        );
        assert_eq!(run.stderr_lines().len(), 1, "{}", run.stderr);
        assert!(!d.join("out.png").exists());
    };
    refused(&[&p[0], &p[2]], "missing shard 1 of 3");
    refused(&[&p[0], &p[1], &p[1], &p[2]], "p1.part: shard 1 of 3 again");
    // Another setup: the first light at another intensity.
    let other = shard(
        d,
        &["-I", "50", "--gi", "path", "--samples", "4"],
        1,
        3,
        "other.part",
    );
    refused(
        &[&p[0], &other, &p[2]],
        "other.part: the scene or its setup differs from",
    );
    let fewer = shard(d, &["--gi", "path", "--samples", "5"], 1, 3, "fewer.part");
    refused(
        &[&p[0], &fewer, &p[2]],
        "fewer.part: the total sample count differs",
    );
    let bytes = std::fs::read(&p[1]).unwrap();
    let cut = d.join("cut.part");
    std::fs::write(&cut, &bytes[..bytes.len() - 100]).unwrap();
    refused(&[&p[0], &cut, &p[2]], "cut.part: truncated");
    let mut flipped = bytes.clone();
    let n = flipped.len();
    flipped[n / 2 + 200] ^= 0x10;
    let bad = d.join("bad.part");
    std::fs::write(&bad, &flipped).unwrap();
    refused(&[&p[0], &bad, &p[2]], "bad.part: damaged");
    let png = d.join("not-a-part.png");
    std::fs::write(&png, b"\x89PNG\r\n").unwrap();
    refused(
        &[&p[0], &png, &p[2]],
        "not-a-part.png: not a raygine part file",
    );

    // A shard writes only its part.
    for extra in [
        &["-R", "x.png"][..],
        &["--time-limit", "5"],
        &["--exr", "x.exr"],
    ] {
        let mut args: Vec<&str> = opts.to_vec();
        args.extend([
            "--shard-index",
            "0",
            "--shard-count",
            "2",
            "--partial",
            "x.part",
        ]);
        args.extend(extra);
        let run = render_in(d, &args);
        assert!(
            !run.success() && run.stderr.contains(extra[0]),
            "{}",
            run.stderr
        );
        assert!(!d.join("x.part").exists());
    }
    let run = render_in(
        d,
        [
            "--shard-index",
            "3",
            "--shard-count",
            "3",
            "--partial",
            "x.part",
        ],
    );
    assert!(
        !run.success() && run.stderr.contains("outside 0..3"),
        "{}",
        run.stderr
    );
}

/// A 4 x 4 m grey floor (unit m), a 100 cd light 2 m above it and a 4 x 2 grid on it.
fn floor_scene(dir: &Path) -> PathBuf {
    let shp = dir.join("floor.shp");
    std::fs::write(&shp, shp_of_quads(&[("floor", &[floor_quad(2.0)])])).unwrap();
    std::fs::write(
        dir.join("floor.raygine.toml"),
        floor_sidecar([0.0, 2.0, 0.0]),
    )
    .unwrap();
    shp
}

fn floor_sidecar(light: [f64; 3]) -> String {
    format!(
        "unit = \"m\"\nmaintenance_factor = 0.8\n\n[camera]\nposition = [0.0, 3.0, 3.0]\n\
         look_at = [0.0, 0.0, 0.0]\nfov_deg = 60.0\n\n[[lights]]\nposition = {light:?}\n\
         intensity_cd = 100.0\n\n[default_material]\nkd = [0.5, 0.5, 0.5]\n\n[[grids]]\n\
         name = \"floor\"\norigin = [-2.0, 0.01, -2.0]\nu = [4.0, 0.0, 0.0]\nv = [0.0, 0.0, 4.0]\n\
         nu = 4\nnv = 2\nnormal = [0.0, 1.0, 0.0]\n"
    )
}

#[test]
fn merged_measurement_shards_write_the_same_csv_and_json() {
    let dir = temp_dir();
    let d = dir.path();
    let shp = floor_scene(d);
    let scene = shp.display().to_string();
    let base = [
        "measure",
        "-S",
        scene.as_str(),
        "--gi",
        "path",
        "--samples",
        "9",
    ];
    let mut parts = Vec::new();
    for k in ["0", "1", "2", "3"] {
        let part = format!("m{k}.part");
        let mut args = base.to_vec();
        args.extend(["--shard-index", k, "--shard-count", "4", "--partial", &part]);
        raygine_in(d, &args).assert_ok();
        parts.push(part);
    }
    let mut args = vec!["merge"];
    args.extend(parts.iter().rev().map(String::as_str));
    args.extend(["--csv", "merged.csv", "--json", "merged.json"]);
    let run = raygine_in(d, &args);
    run.assert_ok();
    assert!(
        run.stdout.contains("maintenance factor 0.8"),
        "{}",
        run.stdout
    );
    let mut args = base.to_vec();
    args.extend(["--csv", "single.csv", "--json", "single.json"]);
    raygine_in(d, &args).assert_ok();
    for f in ["csv", "json"] {
        let merged = std::fs::read_to_string(d.join(format!("merged.{f}"))).unwrap();
        let one = std::fs::read_to_string(d.join(format!("single.{f}"))).unwrap();
        assert_eq!(merged, one, "{f}");
    }
    let run = raygine_in(
        d,
        [
            "merge", "m0.part", "m1.part", "m2.part", "m3.part", "-R", "x.png",
        ],
    );
    assert!(
        !run.success() && run.stderr.contains("-R"),
        "{}",
        run.stderr
    );
}

#[test]
fn a_sweep_of_three_light_positions_equals_three_renders() {
    let dir = temp_dir();
    let d = dir.path();
    let shp = floor_scene(d);
    let scene = shp.display().to_string();
    let positions = [[-1.0, 2.0, 0.0], [0.0, 1.5, 0.5], [1.0, 2.5, -1.0]];
    let mut variants = String::new();
    for (i, p) in positions.iter().enumerate() {
        variants +=
            &format!("[[variants]]\nname = \"pos{i}\"\nlights = [{{ position = {p:?} }}]\n\n");
    }
    std::fs::write(d.join("variants.toml"), variants).unwrap();
    let common = [
        "-S",
        scene.as_str(),
        "--gi",
        "path",
        "--samples",
        "4",
        "-W",
        "32",
        "-H",
        "24",
    ];
    let mut args = vec![
        "sweep",
        "--variants",
        "variants.toml",
        "--measure",
        "--out",
        "all",
    ];
    args.extend(common);
    raygine_in(d, &args).assert_ok();
    let csv = std::fs::read_to_string(d.join("all/sweep.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(
        rows[0],
        "variant,grid,e_min_lx,e_avg_lx,e_max_lx,u0,emin_over_emax"
    );
    assert_eq!(rows.len(), 4, "{csv}");
    for (i, p) in positions.iter().enumerate() {
        let sidecar = d.join(format!("pos{i}.raygine.toml"));
        std::fs::write(&sidecar, floor_sidecar(*p)).unwrap();
        let sidecar = sidecar.display().to_string();
        let mut args = vec!["render", "--sidecar", sidecar.as_str(), "-R", "one.png"];
        args.extend(common);
        raygine_in(d, &args).assert_ok();
        let swept = std::fs::read(d.join(format!("all/pos{i}.png"))).unwrap();
        assert!(
            swept == std::fs::read(d.join("one.png")).unwrap(),
            "variant {i}"
        );
        let mut args = vec![
            "measure",
            "--precision",
            "full",
            "--sidecar",
            sidecar.as_str(),
            "--json",
            "one.json",
        ];
        args.extend(&common[..6]);
        raygine_in(d, &args).assert_ok();
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(d.join("one.json")).unwrap()).unwrap();
        let g = &json["grids"][0];
        let row: Vec<&str> = rows[i + 1].split(',').collect();
        assert_eq!(row[..2], [format!("pos{i}").as_str(), "floor"]);
        let keys = ["e_min_lx", "e_avg_lx", "e_max_lx", "u0", "emin_over_emax"];
        for (k, text) in keys.iter().zip(&row[2..]) {
            // serde_json reads floats to within an ulp or so, not always exactly.
            let (swept, measured) = (text.parse::<f64>().unwrap(), g[k].as_f64().unwrap());
            assert!(
                (swept - measured).abs() <= 1e-14 * measured.abs(),
                "{k}: {row:?} {g}"
            );
        }
    }
    // Run apart (a job array), then collected: the same sweep.csv.
    for i in ["2", "0", "1"] {
        let mut args = vec![
            "sweep",
            "--variants",
            "variants.toml",
            "--measure",
            "--no-images",
        ];
        args.extend(["--out", "apart", "--variant", i]);
        args.extend(common);
        raygine_in(d, &args).assert_ok();
    }
    let run = raygine_in(
        d,
        [
            "sweep",
            "--variants",
            "variants.toml",
            "--collect",
            "--out",
            "apart",
        ],
    );
    run.assert_ok();
    assert_eq!(
        std::fs::read_to_string(d.join("apart/sweep.csv")).unwrap(),
        csv
    );
    std::fs::remove_file(d.join("apart/sweep-1.csv")).unwrap();
    let run = raygine_in(
        d,
        [
            "sweep",
            "--variants",
            "variants.toml",
            "--collect",
            "--out",
            "apart",
        ],
    );
    assert!(
        !run.success() && run.stderr.contains("sweep-1.csv"),
        "{}",
        run.stderr
    );
}
