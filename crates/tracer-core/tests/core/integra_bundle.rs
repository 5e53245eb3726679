//! Integra bundles written on the fly: diagrams, switches, groups, emission, missing and
//! unsupported pieces, and bad input. Known answers are worked out by hand in the comments.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::f32::consts::PI;
use std::path::{Path, PathBuf};
use tracer_core::formats::{self, LightDistribution, SceneFormat, integra};
use tracer_core::light::EmissionSides;
use tracer_core::scene::{self, LightKind, LoadOptions, LoadedScene};

const SHP: &str = "define breps room\nvertices 4\n0 0 0\n4 0 0\n4 0 -4\n0 0 -4\n\
                   triangles 2\n0 1 2\n0 2 3\nparts 2\n0 1\nenddef\n";
const PRB: &str = "product p\n  attrs\n    A000001\n    A000002\n  enddef\n  parts\n    floor_a\n    floor_b\n  enddef\n";
const ATR: &str = "Attr a000001\n  kd 0.6\n  color 255 255 255\nenddef\n\
                   Attr a000002\n  kd 0.2\n  SelfLuminance 50\n  SelfLumDirection Pos\nenddef\n";

/// A bundle's `.shp` in a folder of its own, removed with the value (the test passing or not).
struct Bundle {
    dir: PathBuf,
    shp: PathBuf,
}

impl Drop for Bundle {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

impl std::ops::Deref for Bundle {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.shp
    }
}

/// A bundle `room` in a fresh folder named after the test, with `lgt` (and `cam`) as given.
fn bundle(test: &str, lgt: &str, cam: Option<&str>) -> Bundle {
    let dir = std::env::temp_dir().join(format!("raygine-integra-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("room")).unwrap();
    std::fs::write(dir.join("room.shp"), SHP).unwrap();
    std::fs::write(dir.join("room/room.prb"), PRB).unwrap();
    std::fs::write(dir.join("room/room.atr"), ATR).unwrap();
    std::fs::write(dir.join("room/room.lgt"), lgt).unwrap();
    if let Some(cam) = cam {
        std::fs::write(dir.join("room/room.cam"), cam).unwrap();
    }
    let shp = dir.join("room.shp");
    Bundle { dir, shp }
}

fn load(path: &Path) -> LoadedScene {
    scene::load(path, &LoadOptions::default()).unwrap()
}

fn constant_diagram(name: &str, theta: usize, value: f64, normal_flux: f64) -> String {
    let values = vec![format!("{value}"); theta].join(" ");
    format!(
        "Diagram {name}\n  type AxiSymmetrical\n  theta {theta}\n  phi 1\n  NormalFlux {normal_flux}\n  def\n    {values}\nenddef\n"
    )
}

#[test]
fn a_referenced_diagram_is_scaled_by_total_over_normal_flux() {
    // 100 cd everywhere stands for 1000 lm; TotalFlux 500 makes it 50 cd: 4π · 50 = 628.3 lm.
    let lgt = format!(
        "{}Light L\n  type point\n  TotalFlux 500\n  Diagram flat\nenddef\n\
         Fixture F\n  Light L\n  Position 2 2 -2\n  Direction 0 -1 0\n  Rotation 15\nenddef\n",
        constant_diagram("flat", 37, 100.0, 1000.0)
    );
    let loaded = load(&bundle("diagram", &lgt, None));
    let light = &loaded.setup.lights[0];
    let LightKind::Luminaire(placement) = &light.kind else {
        panic!("not a luminaire: {light:?}");
    };
    assert_eq!(placement.rotation_deg, 15.0);
    assert!(
        (light.flux_lm() - 4.0 * PI * 50.0).abs() < 0.01 * 4.0 * PI * 50.0,
        "{}",
        light.flux_lm()
    );
    // Unreferenced diagrams are skipped; this one is used, so nothing is said about it.
    assert!(
        !loaded.warnings.iter().any(|w| w.contains("Diagram flat")),
        "{:?}",
        loaded.warnings
    );
}

#[test]
fn theta_spans_0_to_180_degrees_in_n_minus_1_steps() {
    // theta 3: 0°, 90°, 180°. A table 10, 0, 0 gives 5 cd at 45° (halfway, linear).
    let text = "Diagram d\n type AxiSymmetrical\n theta 3\n phi 1\n NormalFlux 100\n def\n 10 0 0\nenddef\n";
    let lgt = integra::parse_lgt(text.as_bytes(), Path::new("d.lgt")).unwrap();
    let p = integra::diagram_photometry(&lgt.diagrams[0], 100.0).unwrap();
    assert!((p.intensity(0.0, 45.0) - 5.0).abs() < 1e-4);
    assert!((p.intensity(123.0, 90.0)).abs() < 1e-6);
    assert!((p.intensity(0.0, 0.0) - 10.0).abs() < 1e-6);
}

#[test]
fn switches_and_group_power_decide_what_is_lit() {
    // Three fixtures of 1000 lm: F3 is off; the group at 50 % holds F1 only.
    let lgt = "Light L\n  TotalFlux 1000\n  intensity 1 0.5 0.25\nenddef\n\
               Fixture F1\n  Light L\n  Switch on\n  Position 1 1 -1\nenddef\n\
               Fixture F2\n  Light L\n  Position 2 1 -1\nenddef\n\
               Fixture F3\n  Light L\n  Switch off\n  Position 3 1 -1\nenddef\n\
               Group main\n  Switch on\n  Power 50.0%\n  def\n    F1\nenddef\n";
    let loaded = load(&bundle("switches", lgt, None));
    let flux: Vec<f32> = loaded.setup.lights.iter().map(|l| l.flux_lm()).collect();
    assert_eq!(flux.len(), 2);
    assert!(
        (flux[0] - 500.0).abs() < 1e-2 && (flux[1] - 1000.0).abs() < 1e-2,
        "{flux:?}"
    );
    assert_eq!(loaded.setup.lights[0].color, [1.0, 0.5, 0.25]);
    assert!(
        loaded
            .warnings
            .iter()
            .any(|w| w.contains("fixture F3 is switched off"))
    );
    let off = lgt.replace("Switch on\n  Power", "Switch off\n  Power");
    assert_eq!(load(&bundle("group_off", &off, None)).setup.lights.len(), 1);
}

#[test]
fn materials_parts_emission_and_unit_come_from_the_bundle() {
    let loaded = load(&bundle("materials", "", None));
    let (scene, setup) = (&loaded.scene, &loaded.setup);
    assert_eq!(scene.slot_label(1), "room/floor_b");
    assert_eq!(setup.unit, scene::LengthUnit::M);
    assert_eq!(setup.materials[0].kd, [0.6; 3]);
    let glow = setup.materials[1];
    assert_eq!(glow.emission_cd_m2, 50.0);
    assert_eq!(glow.emission_sides, EmissionSides::Front);
    // An empty .lgt designs no lights: the room is lit by its glowing floor alone, as
    // designed, not by a default light (and not warned about: a glowing surface is a light).
    assert!(setup.lights.is_empty());
    assert!(
        !loaded
            .warnings
            .iter()
            .any(|w| w.contains("designs no light that is on"))
    );
}

#[test]
fn unsupported_referenced_features_are_said_once() {
    let lgt = format!(
        "Diagram c\n type AxiSymmetrical\n theta 3\n phi 1\n diagrams 2\n angle 30\n NormalFlux 1\n def\n 1 1 1\nenddef\n\
         Light L\n TotalFlux 100\n SpotLight on\n Diagram c\nenddef\n\
         Fixture F1\n Light L\n Position 1 1 -1\nenddef\nFixture F2\n Light L\n Position 2 1 -1\nenddef\n{}",
        constant_diagram("unused", 3, 1.0, 1.0)
    );
    let loaded = load(&bundle("unsupported", &lgt, None));
    let count = |needle: &str| {
        loaded
            .warnings
            .iter()
            .filter(|w| w.contains(needle))
            .count()
    };
    assert_eq!(count("composed diagrams"), 1, "{:?}", loaded.warnings);
    assert_eq!(count("`SpotLight on` is not supported"), 1);
    assert_eq!(count("not used, skipped: Diagram unused"), 1);
    // Drawn as isotropic points of the full flux.
    assert!(
        loaded
            .setup
            .lights
            .iter()
            .all(|l| (l.flux_lm() - 100.0).abs() < 1e-3)
    );
}

#[test]
fn a_square_screen_one_away_is_a_90_degree_camera() {
    // Corners (−1, 1), (1, 1), (−1, −1) at z = −1 from an eye at the origin: fov 2 atan(1) = 90°.
    let cam = "Camera c\n viewpoint 0 0 0\n screen\n -1 1 -1\n 1 1 -1\n -1 -1 -1\n resolution 64 64\nenddef\n";
    let loaded = load(&bundle("camera", "", Some(cam)));
    let c = loaded.setup.camera;
    assert!((c.fov_deg - 90.0).abs() < 1e-4);
    assert_eq!(c.look_at, [0.0, 0.0, -1.0]);
    assert_eq!(c.up, [0.0, 1.0, 0.0]);
}

#[test]
fn bad_bundle_files_stop_the_load_with_file_and_line() {
    let cases = [
        (
            "Light L\n TotalFlux lots\nenddef\n",
            "room.lgt:2: TotalFlux: expected a number, found `lots`",
        ),
        (
            "Fixture F\n Light X\n Position 0 0 0\nenddef\n",
            "room.lgt:2: fixture F uses light X, which the file does not define",
        ),
        (
            "Light L\n TotalFlux 1\n Diagram nope\nenddef\nFixture F\n Light L\n Position 0 1 0\nenddef\n",
            "room.lgt:3: light L uses diagram nope",
        ),
        (
            "Diagram d\n theta 3\n def\n 1 2\nenddef\n",
            "room.lgt:1: diagram d: theta × phi = 3 values expected after `def`, found 2",
        ),
        (
            "Group g\n Power 50\nenddef\nGroup g\nenddef\n",
            "room.lgt:4: Group g is defined twice (first at line 1)",
        ),
        (
            "Light L\n TotalFlux 1\n",
            "room.lgt:1: block `Light L` has no `enddef`",
        ),
    ];
    for (lgt, needle) in cases {
        let path = bundle("bad", lgt, None);
        let err = scene::load(&path, &LoadOptions::default())
            .unwrap_err()
            .to_string();
        assert!(err.contains(needle), "{err}\nwanted: {needle}");
        assert!(!err.contains('\n'), "{err}");
    }
}

#[test]
fn readers_pick_by_extension_and_content() {
    let path = bundle("pick", "", None);
    let desc = formats::read_scene(&path).unwrap();
    assert_eq!(desc.format, SceneFormat::Integra);
    assert_eq!(desc.meshes[0].parts[1].name.as_deref(), Some("floor_b"));
    // A bare .brs opens as one brep named after the file; renamed, its content says what it is.
    let dir = path.parent().unwrap();
    let brs = "vertices 3\n0 0 0\n1 0 0\n0 1 0\ntriangles 1\n0 1 2\n";
    std::fs::write(dir.join("piece.brs"), brs).unwrap();
    std::fs::write(dir.join("piece.txt"), brs).unwrap();
    for name in ["piece.brs", "piece.txt"] {
        let desc = formats::read_scene(&dir.join(name)).unwrap();
        assert_eq!(
            (desc.format, desc.meshes[0].name.as_str()),
            (SceneFormat::Brs, "piece")
        );
    }
    // A .shp without a bundle stays a plain .shp: no materials, lights or camera.
    std::fs::write(dir.join("plain.shp"), SHP).unwrap();
    let plain = formats::read_scene(&dir.join("plain.shp")).unwrap();
    assert_eq!(plain.format, SceneFormat::Shp);
    assert!(plain.materials.is_empty() && plain.lights.is_none() && plain.camera.is_none());
    let isotropic = matches!(
        integra::lights_from_lgt(
            &integra::parse_lgt(
                b"Light L\nTotalFlux 1\nenddef\nFixture F\nLight L\nPosition 0 0 0\nenddef\n",
                Path::new("x.lgt")
            )
            .unwrap(),
            Path::new("x.lgt"),
            &mut Vec::new()
        )
        .unwrap()[0]
            .distribution,
        LightDistribution::Isotropic { .. }
    );
    assert!(isotropic);
}

/// Every prefix of the real room2 files (cut at every line and mid-line) reads or is refused
/// with a message naming the file: never a panic.
#[test]
fn truncated_real_files_never_panic() {
    let Some(dir) = raygine_fixtures::shared("scenes/ipur-room2/room2") else {
        return;
    };
    for ext in ["atr", "prb", "lgt", "cam"] {
        let path = dir.join(format!("room2.{ext}"));
        let bytes = std::fs::read(&path).unwrap();
        for cut in (0..bytes.len()).step_by(7) {
            let part = &bytes[..cut];
            let check = |r: Result<(), integra::IntegraError>| {
                if let Err(e) = r {
                    assert!(
                        e.to_string().starts_with(&path.display().to_string()),
                        "{e}"
                    );
                    assert!(!e.to_string().contains('\n'));
                }
            };
            match ext {
                "atr" => check(integra::parse_atr(part, &path).map(drop)),
                "prb" => check(integra::parse_prb(part, &path).map(drop)),
                "lgt" => check(integra::parse_lgt(part, &path).map(drop)),
                _ => check(integra::parse_cam(part, &path).map(drop)),
            }
        }
    }
}

/// A `Geography` block becomes the setup's daylight: west-positive longitude, north = −south,
/// the year 2025 (Integra gives month and day); the sidecar's `[daylight]` replaces it, and a
/// block without its time is a note, not an error.
#[test]
fn geography_becomes_the_daylight() {
    let geography = "Geography TokyoMidday\n  zenith 0 1 0\n  south 1 0 0\n  latitude 36.0\n  \
                     longitude -140.0\n  month 6\n  date 21\n  time 12:00\n  GMT 9\n  \
                     DaylightSaving off\nenddef\n";
    let lgt = format!(
        "Light L\n  TotalFlux 1000\nenddef\nFixture F\n  Light L\n  Switch on\n  Position 1 1 -1\nenddef\n{geography}"
    );
    let loaded = load(&bundle("geography", &lgt, None));
    let d = loaded.setup.daylight.expect("daylight from Geography");
    let p = d.place_time;
    assert_eq!(
        (p.latitude_deg, p.longitude_deg, p.timezone_h),
        (36.0, 140.0, 9.0)
    );
    assert_eq!(
        (p.date.to_string(), p.time.to_string()),
        ("2025-06-21".into(), "12:00".into())
    );
    assert_eq!(d.north, glam::Vec3::NEG_X);
    // A .shp room is left-handed: east = zenith × north = +Z; the sun just past south (+X)
    // leans west (−Z).
    let w = d.sun_direction(false);
    assert!(w.y > 0.95 && w.x > 0.2 && w.z < 0.0, "{w}");

    let no_time = lgt.replace("  time 12:00\n", "");
    let loaded = load(&bundle("geography_no_time", &no_time, None));
    assert!(loaded.setup.daylight.is_none());
    assert!(
        loaded
            .warnings
            .iter()
            .any(|w| w.contains("Geography TokyoMidday has no time")),
        "{:?}",
        loaded.warnings
    );
}
