//! Failures through the real binary: a non-zero exit, exactly one line on stderr that names the
//! file (and the line, for text), and no image written, half-written or replaced.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use raygine_e2e::{Run, files_containing, render_in, temp_dir};
use std::path::Path;

fn render_scene(dir: &Path, scene: &Path, out: &Path) -> Run {
    render_in(
        dir,
        [
            "-W".as_ref(),
            "32".as_ref(),
            "-H".as_ref(),
            "24".as_ref(),
            "-S".as_ref(),
            scene.as_os_str(),
            "-R".as_ref(),
            out.as_os_str(),
        ],
    )
}

/// Exactly one line on stderr, containing every needle.
#[track_caller]
fn assert_one_line_error(run: &Run, needles: &[&str]) {
    assert!(!run.success(), "should fail: {}", run.stdout);
    let lines = run.stderr_lines();
    assert_eq!(lines.len(), 1, "one line on stderr, got {lines:#?}");
    for n in needles {
        assert!(lines[0].contains(n), "`{}` should mention `{n}`", lines[0]);
    }
}

#[test]
fn missing_scene_file() {
    let dir = temp_dir();
    let out = dir.path().join("out.png");
    let run = render_scene(dir.path(), &dir.path().join("nope.shp"), &out);
    assert_one_line_error(&run, &["nope.shp"]);
    assert!(!out.exists());
    assert!(files_containing(dir.path(), ".png").is_empty());
}

/// An ESRI shapefile shares the extension: binary input is refused in one line.
#[test]
fn binary_scene_file() {
    let dir = temp_dir();
    let scene = dir.path().join("x.shp");
    let mut bytes = vec![0x00, 0x00, 0x27, 0x0A, 0x00, 0x00, 0x00, 0x00, 0x01, 0xFF];
    bytes.extend((0..200u8).map(|i| i.wrapping_mul(37)));
    std::fs::write(&scene, bytes).unwrap();
    let out = dir.path().join("x.png");
    let run = render_scene(dir.path(), &scene, &out);
    assert_one_line_error(&run, &["x.shp"]);
    assert!(!out.exists());
}

/// A triangle that uses a vertex the brep does not have: the error names file and line, and an
/// existing image at the output path is left as it was.
#[test]
fn broken_scene_names_the_line_and_keeps_the_old_image() {
    let dir = temp_dir();
    let scene = dir.path().join("broken.shp");
    let text = "define breps b\r\nvertices 3\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\ntriangles 1\r\n\
                0 1 7\r\nparts 1\r\n0\r\nenddef\r\n";
    std::fs::write(&scene, text).unwrap();
    let out = dir.path().join("existing.png");
    let old = b"not really a png, but it must survive".to_vec();
    std::fs::write(&out, &old).unwrap();
    let run = render_scene(dir.path(), &scene, &out);
    assert_one_line_error(&run, &["broken.shp", "line 7"]);
    assert_eq!(std::fs::read(&out).unwrap(), old);
    assert!(files_containing(dir.path(), "tmp").is_empty());
}

/// A folder as `-R`, or a path in a folder that does not exist: a clear error, no temporary
/// file left, nothing else written.
#[test]
fn unwritable_output_paths() {
    let dir = temp_dir();
    let target = dir.path().join("a_folder");
    std::fs::create_dir(&target).unwrap();
    let run = render_in(dir.path(), ["-W", "32", "-H", "24", "-R", "a_folder"]);
    assert_one_line_error(&run, &["a_folder"]);
    assert!(std::fs::read_dir(&target).unwrap().next().is_none());
    assert_eq!(
        files_containing(dir.path(), "").len(),
        1,
        "only the folder itself"
    );

    let missing = dir.path().join("no_such_dir").join("out.png");
    let run = render_in(
        dir.path(),
        [
            "-W".as_ref(),
            "32".as_ref(),
            "-H".as_ref(),
            "24".as_ref(),
            "-R".as_ref(),
            missing.as_os_str(),
        ],
    );
    assert_one_line_error(&run, &["out.png"]);
    assert!(!dir.path().join("no_such_dir").exists());
    assert_eq!(files_containing(dir.path(), "").len(), 1);
}

/// Bad numbers on the command line fail cleanly too.
#[test]
fn bad_command_line_values() {
    let dir = temp_dir();
    let run = render_in(
        dir.path(),
        ["-W", "32", "-H", "24", "1", "2", "3", "4", "5", "6", "200"],
    );
    assert!(!run.success());
    assert!(run.stderr.contains("field of view"), "{}", run.stderr);
    assert!(files_containing(dir.path(), ".png").is_empty());
    let run = render_in(dir.path(), ["-W", "0"]);
    assert!(!run.success());
    assert!(files_containing(dir.path(), ".png").is_empty());
}

/// The help says what the binary does: every scene format the viewer opens, and the sample
/// default of every global-illumination mode (it read "Lumicept .shp" and "64 in path mode").
#[test]
fn help_names_the_formats_and_the_gi_sample_default() {
    let dir = temp_dir();
    let top = raygine_e2e::raygine_in(dir.path(), ["--help"]);
    assert!(top.success(), "{}", top.stderr);
    for format in ["OBJ", "glTF", "Integra"] {
        assert!(
            top.stdout.contains(format),
            "--help lacks {format}: {}",
            top.stdout
        );
    }
    let render = render_in(dir.path(), ["--help"]);
    assert!(render.success(), "{}", render.stderr);
    assert!(
        render.stdout.contains("64 in the") && render.stdout.contains("global-illumination modes"),
        "{}",
        render.stdout
    );
    assert!(
        !render.stdout.contains("64 in path mode"),
        "{}",
        render.stdout
    );
}
