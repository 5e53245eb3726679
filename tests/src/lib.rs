//! End-to-end tests of the `raygine` binary live in `tests/tests/`; this library holds what they
//! share: the binary itself (built once per test process with the cargo that runs the tests),
//! scene fixtures written on the fly, the course scenes in `../shared`, and image helpers.
//!
//! Why build the binary here: `CARGO_BIN_EXE_<name>` exists only for tests of the package that
//! owns the binary. Asking cargo for the `raygine` executable (`--message-format=json`) gives the
//! real binary of the real `main.rs`, for any profile and target folder, on a fresh clone.
//! `RAYGINE_BIN` overrides it (for testing an installed build).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

/// The `raygine` executable, built on first use.
pub fn raygine_exe() -> &'static Path {
    static EXE: OnceLock<PathBuf> = OnceLock::new();
    EXE.get_or_init(|| {
        if let Some(p) = std::env::var_os("RAYGINE_BIN") {
            return PathBuf::from(p);
        }
        build_raygine()
    })
}

/// Runs `cargo build -p raygine` in the profile of this test binary and returns the path cargo
/// reports for the executable.
fn build_raygine() -> PathBuf {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut cmd = Command::new(cargo);
    cmd.current_dir(&workspace)
        .args(["build", "-p", "raygine", "--bin", "raygine"])
        .args(["--message-format=json-render-diagnostics"]);
    // This test binary lives in <target>/<profile dir>/deps/.
    let profile_dir = std::env::current_exe()
        .ok()
        .and_then(|exe| Some(exe.parent()?.parent()?.file_name()?.to_owned()));
    match profile_dir.as_ref().and_then(|d| d.to_str()) {
        Some("debug") | None => {}
        Some("release") => {
            cmd.arg("--release");
        }
        Some(other) => {
            cmd.args(["--profile", other]);
        }
    }
    let out = cmd.output().expect("cannot run cargo to build raygine");
    assert!(
        out.status.success(),
        "cargo build -p raygine failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    stdout
        .lines()
        .filter(|l| l.contains(r#""reason":"compiler-artifact""#))
        .filter(|l| l.contains(r#""name":"raygine""#) && l.contains(r#""kind":["bin"]"#))
        .find_map(json_executable)
        .unwrap_or_else(|| panic!("cargo reported no raygine executable:\n{stdout}"))
}

/// The `"executable"` string of one cargo JSON message.
fn json_executable(line: &str) -> Option<PathBuf> {
    let start = line.find(r#""executable":""#)? + r#""executable":""#.len();
    let mut path = String::new();
    let mut chars = line[start..].chars();
    while let Some(c) = chars.next() {
        match c {
            '"' => return Some(PathBuf::from(path)),
            '\\' => path.push(chars.next()?),
            c => path.push(c),
        }
    }
    None
}

/// What one run of the binary did.
#[derive(Debug)]
pub struct Run {
    pub status: std::process::ExitStatus,
    pub stdout: String,
    pub stderr: String,
}

impl Run {
    pub fn success(&self) -> bool {
        self.status.success()
    }

    /// Panics with the output when the run failed.
    #[track_caller]
    pub fn assert_ok(&self) -> &Self {
        assert!(
            self.success(),
            "raygine failed ({}):\nstdout:\n{}\nstderr:\n{}",
            self.status,
            self.stdout,
            self.stderr
        );
        self
    }

    /// The non-empty lines of stderr.
    pub fn stderr_lines(&self) -> Vec<&str> {
        self.stderr
            .lines()
            .filter(|l| !l.trim().is_empty())
            .collect()
    }
}

impl From<Output> for Run {
    fn from(o: Output) -> Self {
        Run {
            status: o.status,
            stdout: String::from_utf8_lossy(&o.stdout).into_owned(),
            stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
        }
    }
}

/// Runs `raygine` with `args` in the folder `cwd`.
pub fn raygine_in<I, S>(cwd: &Path, args: I) -> Run
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    Command::new(raygine_exe())
        .current_dir(cwd)
        .args(args)
        .output()
        .expect("cannot start raygine")
        .into()
}

/// `raygine render <args>` in `cwd`.
pub fn render_in<I, S>(cwd: &Path, args: I) -> Run
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    let mut all: Vec<std::ffi::OsString> = vec!["render".into()];
    all.extend(args.into_iter().map(|a| a.as_ref().to_owned()));
    raygine_in(cwd, all)
}

/// A fresh temporary folder, removed when dropped.
pub fn temp_dir() -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix("raygine-e2e-")
        .tempdir()
        .expect("cannot make a temporary folder")
}

/// `relative` in `../shared` beside the project (course scenes; not part of the project), or
/// `None` with the reason printed when it is absent; a failure instead under `CI=true`.
pub use raygine_fixtures::shared;

/// The course's Cornell box, or `None` (with the reason printed) when `../shared` is absent.
pub fn course_cornell_box() -> Option<PathBuf> {
    shared("scenes/cornell/cornel_box0.shp")
}

/// An RGB8 image read back from disk.
#[derive(Debug, Clone, PartialEq)]
pub struct Rgb8 {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[u8; 3]>,
}

impl Rgb8 {
    pub fn at(&self, x: u32, y: u32) -> [u8; 3] {
        self.pixels[(y * self.width + x) as usize]
    }

    /// Mean colour of the rectangle `x0..x1` by `y0..y1`, channels 0..=255.
    pub fn mean(&self, x0: u32, y0: u32, x1: u32, y1: u32) -> [f64; 3] {
        let mut sum = [0.0; 3];
        let mut n = 0.0f64;
        for y in y0..y1 {
            for x in x0..x1 {
                let p = self.at(x, y);
                for c in 0..3 {
                    sum[c] += f64::from(p[c]);
                }
                n += 1.0;
            }
        }
        sum.map(|s| s / n.max(1.0))
    }

    /// Mean of the rectangle given in fractions of the image size.
    pub fn mean_frac(&self, fx0: f64, fy0: f64, fx1: f64, fy1: f64) -> [f64; 3] {
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        self.mean(
            (fx0 * w) as u32,
            (fy0 * h) as u32,
            (fx1 * w) as u32,
            (fy1 * h) as u32,
        )
    }
}

/// Decodes a PNG written by raygine.
pub fn read_png(path: &Path) -> Rgb8 {
    let img = image::open(path)
        .unwrap_or_else(|e| panic!("{}: cannot decode: {e}", path.display()))
        .to_rgb8();
    Rgb8 {
        width: img.width(),
        height: img.height(),
        pixels: img.pixels().map(|p| p.0).collect(),
    }
}

/// A linear float image (EXR) read back from disk.
#[derive(Debug, Clone)]
pub struct RgbF32 {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[f32; 3]>,
}

impl RgbF32 {
    pub fn at(&self, x: u32, y: u32) -> [f32; 3] {
        self.pixels[(y * self.width + x) as usize]
    }
}

pub fn read_exr(path: &Path) -> RgbF32 {
    let img = image::open(path)
        .unwrap_or_else(|e| panic!("{}: cannot decode: {e}", path.display()))
        .to_rgb32f();
    RgbF32 {
        width: img.width(),
        height: img.height(),
        pixels: img.pixels().map(|p| p.0).collect(),
    }
}

/// A Lumicept-style `.shp` with one brep per `(name, quads)`, each quad two triangles.
pub fn shp_of_quads(breps: &[(&str, &[[[f64; 3]; 4]])]) -> String {
    let mut s = String::from(";; Written by the raygine end-to-end tests\r\n\r\n");
    for (name, quads) in breps {
        s.push_str(&format!(
            "define breps {name}\r\nvertices {}\r\n",
            quads.len() * 4
        ));
        for q in *quads {
            for v in q {
                s.push_str(&format!("  {} {} {}\r\n", v[0], v[1], v[2]));
            }
        }
        s.push_str(&format!("triangles {}\r\n", quads.len() * 2));
        for i in 0..quads.len() {
            let b = i * 4;
            s.push_str(&format!(
                "  {} {} {}\r\n  {} {} {}\r\n",
                b,
                b + 1,
                b + 2,
                b,
                b + 2,
                b + 3
            ));
        }
        s.push_str(&format!(
            "parts 1\r\n{}\r\nenddef\r\n\r\n",
            vec!["0"; quads.len() * 2].join(" ")
        ));
    }
    s
}

/// A square floor at y = 0 of half-size `a`, centred on the origin.
pub fn floor_quad(a: f64) -> [[f64; 3]; 4] {
    [[-a, 0.0, -a], [-a, 0.0, a], [a, 0.0, a], [a, 0.0, -a]]
}

/// Whether any file in `dir` has a name containing `needle` (temporary files left behind).
pub fn files_containing(dir: &Path, needle: &str) -> Vec<String> {
    std::fs::read_dir(dir)
        .map(|it| {
            it.filter_map(Result::ok)
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| n.contains(needle))
                .collect()
        })
        .unwrap_or_default()
}
