//! Replays the saved fuzz inputs (`fuzz/corpus/<target>/*` and `fuzz/regressions/<target>/*`)
//! through every reader, deterministically: each file must give `Ok` or `Err`, never a panic,
//! and quickly. This is what CI runs instead of fuzzing anew (fuzz/README.md).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::fs;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use tracer_core::formats::integra;
use tracer_core::render::{RenderSettings, render};
use tracer_core::scene::{Scene, Sidecar, light_from_description, material_from_description};
use tracer_core::shp::{parse_brs, parse_shp};

/// Far above what any saved input takes (milliseconds), far below a hang.
const PER_FILE: Duration = Duration::from_secs(10);

/// The scene the `sidecar` fuzz target applies sidecars to (keep the two alike).
const SIDECAR_SCENE: &str = "\
define breps a
vertices 4
0 0 0
10 0 0
10 10 0
0 10 0
triangles 2
0 1 2
0 2 3
parts 3
0 2
enddef
define breps b
vertices 3
0 0 -5
10 0 -5
0 10 -5
triangles 1
0 1 2
enddef
set breps b
rotation 0 0 45
translation 1 2 3
scale 1 1 1
enddef
";

fn fuzz_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz")
}

/// Every file under `fuzz/{corpus,regressions}/*/`, sorted.
fn saved_inputs() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for kind in ["corpus", "regressions"] {
        let Ok(targets) = fs::read_dir(fuzz_dir().join(kind)) else {
            continue;
        };
        for target in targets.flatten() {
            for entry in fs::read_dir(target.path()).into_iter().flatten().flatten() {
                if entry.path().is_file() {
                    files.push(entry.path());
                }
            }
        }
    }
    files.sort();
    files
}

fn sidecar_scene() -> Scene {
    let desc = parse_shp(SIDECAR_SCENE.as_bytes(), Path::new("fuzz.shp")).unwrap();
    Scene::build(&desc, "fuzz").unwrap()
}

/// What every fuzz target does with `data`, all of them in turn.
fn replay(data: &[u8], scene: &Scene) {
    if let Ok(desc) = parse_shp(data, Path::new("fuzz.shp")) {
        let _ = Scene::build(&desc, "fuzz");
    }
    let _ = parse_brs(data, Path::new("fuzz.brs"), "fuzz");
    for name in ["fuzz.ies", "fuzz.ldt"] {
        if let Ok(p) = tracer_core::formats::parse_photometry(data, Path::new(name)) {
            let _ = p.intensity(45.0, 30.0);
        }
    }
    replay_integra(data);
    replay_obj_gltf(data);
    replay_usd(data);
    replay_envmap(data);
    // The `part` target: a payload that decodes encodes back to the same film.
    if let Ok(film) = tracer_core::render::partial::decode_film(data) {
        let again = tracer_core::render::partial::encode_film(&film);
        assert_eq!(
            tracer_core::render::partial::decode_film(&again).ok(),
            Some(film)
        );
    }
    replay_requirements(data);
    if let Ok(text) = std::str::from_utf8(data)
        && let Ok(sidecar) = Sidecar::parse(text, Path::new("fuzz.raygine.toml"))
    {
        let mut warnings = Vec::new();
        let setup = sidecar.apply(scene, None, &mut warnings);
        let settings = RenderSettings {
            width: 4,
            height: 3,
            samples_per_pixel: 1,
            max_depth: 3,
            ..RenderSettings::default()
        };
        let _ = render(scene, &setup, &settings);
        let _ = Sidecar::from_setup(scene, &setup).to_toml();
    }
}

/// What the `requirements` target does with `data`.
fn replay_requirements(data: &[u8]) {
    use tracer_core::measure::requirements::{Requirements, check};
    use tracer_core::measure::{GridResult, PointResult};
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(table) = Requirements::parse(text, "fuzz.toml") else {
        return;
    };
    let grid = GridResult {
        name: "g".into(),
        normal: glam::Vec3::Y,
        points: [120.0, 480.0, 0.0]
            .iter()
            .map(|&e| PointResult {
                i: 0,
                j: 0,
                position: glam::Vec3::ZERO,
                illuminance_lx: e,
                std_error_lx: 3.0,
                buried: false,
            })
            .collect(),
        samples: 4,
        rays: 0,
    };
    for a in &table.activities {
        assert!(table.activity(&a.key).is_ok());
        let _ = check(&grid, a, Some(80.0), &[("o".into(), Ok(Some((18.0, 0.2))))]).passes();
    }
    let _ = table.activity("no such key");
}

/// What the `obj` and `gltf` targets do with `data`.
fn replay_obj_gltf(data: &[u8]) {
    use tracer_core::formats::{ReadOptions, gltf, obj};
    let libraries = |_: &str| Some((PathBuf::from("fuzz.mtl"), data.to_vec()));
    let options = ReadOptions::default();
    if let Ok(desc) = obj::parse(data, Path::new("fuzz.obj"), &libraries, &options) {
        let _ = Scene::build(&desc, "fuzz");
    }
    let external = |_: &Path| Err("no files while fuzzing".to_owned());
    if let Ok(desc) = gltf::parse(data, Path::new("fuzz.gltf"), &external, &options) {
        let _ = Scene::build(&desc, "fuzz");
    }
}

/// What the `usd` target does with `data`: written to a file named by its magic, read, built.
fn replay_usd(data: &[u8]) {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use tracer_core::formats::{ReadOptions, usd};
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let ext = if data.starts_with(b"PXR-USDC") {
        "usdc"
    } else if data.starts_with(b"PK") {
        "usdz"
    } else if data.starts_with(b"#usda") {
        "usda"
    } else {
        return; // Not USD: the text reader would only say so, file after file.
    };
    let dir = std::env::temp_dir().join(format!("raygine-fuzz-usd-{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{}.{ext}", NEXT.fetch_add(1, Ordering::Relaxed)));
    fs::write(&path, data).unwrap();
    // A file openusd loops on is refused after 3 s (the replay allows 10 s a file).
    let options = ReadOptions {
        usd_trial_secs: Some(3.0),
        ..ReadOptions::default()
    };
    if let Ok(desc) = usd::read(&path, &options) {
        let _ = Scene::build(&desc, "fuzz");
    }
    let _ = fs::remove_file(&path);
}

/// What the `envmap` target does with `data`: a map that loads gives a light of finite flux
/// whose sampled directions and densities are finite.
fn replay_envmap(data: &[u8]) {
    use tracer_core::light::{
        Environment, EnvironmentLight, EnvironmentMap, EnvironmentSource, LightSource,
    };
    if let Ok((map, _notes)) = EnvironmentMap::from_bytes(data, Path::new("fuzz.hdr")) {
        let env = Environment {
            source: EnvironmentSource::Map(std::sync::Arc::new(map)),
            scale: 1.0,
            rotation_deg: 30.0,
            background: true,
        };
        let light = EnvironmentLight::new(&env, 1.0, Default::default(), 1.0, 1.0);
        let flux = light.power_lm();
        assert!(flux.is_finite() && flux >= 0.0, "flux {flux}");
        for u in [[0.0, 0.0], [0.5, 0.5], [0.999, 0.001], [0.3, 0.999]] {
            if let Some((w, pdf)) = light.sample_dir(u) {
                assert!(w.is_finite() && pdf.is_finite() && pdf > 0.0, "{w} {pdf}");
                let _ = light.radiance(w);
                let _ = light.dir_pdf(w);
            }
        }
    }
}

/// What the `atr`, `prb`, `lgt` and `cam` targets do with `data`.
fn replay_integra(data: &[u8]) {
    let mut notes = Vec::new();
    let atr = Path::new("fuzz.atr");
    for attr in integra::parse_atr(data, atr).into_iter().flatten() {
        let m = integra::material_from_attr(&attr, atr, &mut notes);
        let _ = material_from_description(&m, &mut notes);
    }
    let _ = integra::parse_prb(data, Path::new("fuzz.prb"));
    let lgt = Path::new("fuzz.lgt");
    if let Ok(parsed) = integra::parse_lgt(data, lgt)
        && let Ok(lights) = integra::lights_from_lgt(&parsed, lgt, &mut notes)
    {
        for l in &lights {
            let _ = light_from_description(l).flux_lm();
        }
    }
    let cam = Path::new("fuzz.cam");
    if let Ok(Some(c)) = integra::parse_cam(data, cam) {
        let _ = c.to_camera(cam);
    }
}

#[test]
fn saved_fuzz_inputs_never_panic_or_hang() {
    let files = saved_inputs();
    assert!(
        files.len() >= 10,
        "expected the committed corpus under {}, found {} files",
        fuzz_dir().display(),
        files.len()
    );
    let scene = sidecar_scene();
    let mut failures = Vec::new();
    let started = Instant::now();
    for file in &files {
        // A running fuzzer replaces corpus files as it reduces them: skip one that went away.
        let Ok(data) = fs::read(file) else { continue };
        let t0 = Instant::now();
        if catch_unwind(AssertUnwindSafe(|| replay(&data, &scene))).is_err() {
            failures.push(format!("{}: panicked", file.display()));
        }
        let took = t0.elapsed();
        if took > PER_FILE {
            failures.push(format!("{}: took {took:?}", file.display()));
        }
    }
    println!(
        "replayed {} saved inputs in {:.2} s",
        files.len(),
        started.elapsed().as_secs_f64()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn every_target_has_a_corpus() {
    for target in [
        "shp",
        "brs",
        "sidecar",
        "ies",
        "ldt",
        "atr",
        "prb",
        "lgt",
        "cam",
        "obj",
        "gltf",
        "part",
        "envmap",
        "requirements",
    ] {
        let dir = fuzz_dir().join("corpus").join(target);
        let count = fs::read_dir(&dir).map(|d| d.count()).unwrap_or(0);
        assert!(count > 0, "{} is empty or missing", dir.display());
    }
}
