//! `raybench render`: wall time of the whole release `raygine render` command (process start to
//! exit, PNG written) on the course Cornell box at 1000x1000, depth 5, with the default materials
//! and with Ks 0.4 on every surface (a temporary sidecar), medians of interleaved runs.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use anyhow::{Context, bail, ensure};

use crate::report::emit;
use crate::stats::median;

/// The sidecar of the `ks0.4` case: grey diffuse plus a 0.4 mirror on every surface.
pub const KS_SIDECAR: &str = "[default_material]\nkd = [0.5, 0.5, 0.5]\nks = [0.4, 0.4, 0.4]\n";

#[derive(Clone, Debug)]
pub struct Options {
    pub runs: usize,
    pub threads: Vec<usize>,
    /// The raygine binary (default: the workspace's `target/release/raygine`).
    pub raygine: Option<PathBuf>,
}

fn time_once(binary: &Path, args: &[String]) -> anyhow::Result<f64> {
    let start = Instant::now();
    let out = Command::new(binary)
        .args(args)
        .output()
        .with_context(|| format!("cannot run {}", binary.display()))?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    if !out.status.success() {
        bail!(
            "raygine render failed: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        );
    }
    Ok(ms)
}

pub fn run(opts: &Options) -> anyhow::Result<()> {
    let shared = crate::shared::require_shared()?;
    let scene = shared.join("scenes/cornell/cornel_box0.shp");
    ensure!(scene.is_file(), "{} is missing", scene.display());
    let binary = opts
        .raygine
        .clone()
        .unwrap_or_else(|| crate::shared::workspace_dir().join("target/release/raygine"));
    ensure!(
        binary.is_file(),
        "{} not found: run `cargo build --release -p raygine` first",
        binary.display()
    );
    let temp = std::env::temp_dir().join(format!("raybench-render-{}", std::process::id()));
    std::fs::create_dir_all(&temp)?;
    let sidecar = temp.join("ks04.raygine.toml");
    std::fs::write(&sidecar, KS_SIDECAR)?;
    let png = temp.join("render.png");
    let cases: [(&str, Option<&Path>); 2] = [("default", None), ("ks0.4", Some(&sidecar))];
    for &threads in &opts.threads {
        let args_of = |extra: Option<&Path>| {
            let mut args: Vec<String> = ["render", "-S"].map(String::from).to_vec();
            args.push(scene.display().to_string());
            args.extend(
                ["-W", "1000", "-H", "1000", "--depth", "5", "--threads"].map(String::from),
            );
            args.push(threads.to_string());
            args.push("-R".to_owned());
            args.push(png.display().to_string());
            if let Some(s) = extra {
                args.push("--sidecar".to_owned());
                args.push(s.display().to_string());
            }
            args
        };
        let mut times = vec![Vec::new(); cases.len()];
        for _ in 0..opts.runs {
            for (i, (_, extra)) in cases.iter().enumerate() {
                times[i].push(time_once(&binary, &args_of(*extra))?);
            }
        }
        for (i, (materials, _)) in cases.iter().enumerate() {
            emit(&format!(
                "render scene=cornel_box0 materials={materials} threads={threads} ms={:.0}",
                median(&times[i])
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&temp);
    Ok(())
}
