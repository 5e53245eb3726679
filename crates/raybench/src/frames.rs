//! `raybench frames`: whole frames, raygine beside Mitsuba 3 (BENCHMARK.md F1, F2).
//!
//! - F1: the built-in Cornell box, its sidecar's light and camera; F2: the bunny with the W1
//!   camera, the W2 light (1 cd) and Lambertian 0.7. Both direct light, 1280x720, 16 spp.
//! - The scene Mitsuba renders is exported from raygine's own loaded scene (`export`): its
//!   world triangles with raygine's shading normals per corner, the materials' Kd, the lights
//!   and the camera, so both renderers do the same work.
//! - Mitsuba runs in one long-lived Python process (`scripts/mitsuba/frame_server.py`) that
//!   loads the scene, renders twice to warm up its JIT, then renders on request; runs are
//!   interleaved (raygine, Mitsuba, raygine, ...) and the medians reported, with both images'
//!   mean luminance (pixels clipped at 1000 cd/m²) as a check that they show the same thing.

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};
use std::time::Instant;

use anyhow::{Context, bail};
use tracer_core::integrator::IntegratorKind;
use tracer_core::light::Light;
use tracer_core::render::{RenderSettings, render};
use tracer_core::scene::{self, Camera, LoadOptions, Material, Scene, Setup, builtin_cornell_box};

use crate::report::emit;
use crate::stats::median;
use crate::workloads::Frame;

#[derive(Clone, Debug)]
pub struct Options {
    pub runs: usize,
    pub threads: usize,
    /// Python with mitsuba installed (None: raygine alone).
    pub python: Option<PathBuf>,
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    /// Only this workload ("F1" or "F2"); None: both.
    pub only: Option<String>,
}

fn settings(opts: &Options) -> RenderSettings {
    RenderSettings {
        width: opts.width,
        height: opts.height,
        samples_per_pixel: opts.spp,
        max_depth: 5,
        integrator: IntegratorKind::Direct,
        max_bounces: None,
        pixel_illuminance: true,
        guides: false,
    }
}

/// F1's and F2's scene and setup.
fn workload(name: &str) -> anyhow::Result<(Scene, Setup)> {
    if name == "cornell" {
        let loaded = builtin_cornell_box(None)?;
        return Ok((loaded.scene, loaded.setup));
    }
    let shared = crate::shared::require_shared()?;
    let loaded = scene::load(
        &shared.join("scenes/meshes/stanford-bunny.shp"),
        &LoadOptions::default(),
    )?;
    let (scene, mut setup) = (loaded.scene, loaded.setup);
    let frame = Frame::of(&scene.triangles().collect::<Vec<_>>());
    setup.camera = Camera {
        position: frame.eye().to_array(),
        look_at: frame.centre.to_array(),
        up: [0.0, 1.0, 0.0],
        fov_deg: 45.0,
        ..Camera::default()
    };
    setup.lights = vec![Light::point(frame.light().to_array(), 1.0)];
    let grey = Material {
        kd: [0.7; 3],
        ..Material::default()
    };
    setup.materials.iter_mut().for_each(|m| *m = grey);
    Ok((scene, setup))
}

/// Writes the scene for Mitsuba: `scene.json` and one `slotN.bin` per material slot (float32
/// corner positions, 9 per triangle, then the corners' shading normals, 9 per triangle).
pub fn export(scene: &Scene, setup: &Setup, dir: &Path) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir)?;
    let mpu = setup.unit.metres_per_unit();
    let mut meshes = Vec::new();
    for slot in 0..scene.slots.len() as u32 {
        let tris: Vec<u32> = (0..scene.triangle_count() as u32)
            .filter(|&t| scene.slot(t) == slot)
            .collect();
        if tris.is_empty() || setup.is_hidden(slot) {
            continue;
        }
        let mut bytes = Vec::with_capacity(tris.len() * 72);
        for &t in &tris {
            for p in scene.triangle(t) {
                p.to_array()
                    .iter()
                    .for_each(|c| bytes.extend(c.to_le_bytes()));
            }
        }
        for &t in &tris {
            let corners = scene.smooth_corners(t).unwrap_or([scene.normal(t); 3]);
            for n in corners {
                n.to_array()
                    .iter()
                    .for_each(|c| bytes.extend(c.to_le_bytes()));
            }
        }
        let file = format!("slot{slot}.bin");
        std::fs::write(dir.join(&file), bytes)?;
        let kd = setup
            .materials
            .get(slot as usize)
            .copied()
            .unwrap_or_default()
            .kd;
        meshes.push(serde_json::json!({"file": file, "triangles": tris.len(), "kd": kd}));
    }
    let lights: Vec<_> = setup
        .lights
        .iter()
        .map(|l| {
            // Mitsuba's point light takes radiant intensity per its length unit: cd / mpu².
            let rgb = l.tint() * (l.peak_cd() / (mpu * mpu));
            serde_json::json!({"position": l.position, "intensity": rgb.to_array()})
        })
        .collect();
    let c = &setup.camera;
    let json = serde_json::json!({
        "meshes": meshes,
        "lights": lights,
        "camera": {"position": c.position, "look_at": c.look_at, "up": c.up, "fov_deg": c.fov_deg},
        "near_clip": 1e-5 * scene.bounds.extent().length(),
        "far_clip": 1e3 * scene.bounds.extent().length(),
    });
    std::fs::write(dir.join("scene.json"), serde_json::to_string_pretty(&json)?)?;
    Ok(())
}

/// The Mitsuba render server, started on an exported scene.
struct Peer {
    child: Child,
    input: ChildStdin,
    output: BufReader<ChildStdout>,
}

impl Peer {
    fn start(python: &Path, dir: &Path, opts: &Options) -> anyhow::Result<Peer> {
        let script = crate::shared::workspace_dir().join("scripts/mitsuba/frame_server.py");
        let mut child = Command::new(python)
            .arg(&script)
            .arg(dir)
            .args([
                "--width",
                &opts.width.to_string(),
                "--height",
                &opts.height.to_string(),
            ])
            .args([
                "--spp",
                &opts.spp.to_string(),
                "--threads",
                &opts.threads.to_string(),
            ])
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .with_context(|| format!("cannot start {} {}", python.display(), script.display()))?;
        let input = child.stdin.take().context("no stdin")?;
        let output = BufReader::new(child.stdout.take().context("no stdout")?);
        let mut peer = Peer {
            child,
            input,
            output,
        };
        let ready = peer.line()?;
        if !ready.starts_with("ready") {
            bail!("the Mitsuba server said: {ready}");
        }
        Ok(peer)
    }

    fn line(&mut self) -> anyhow::Result<String> {
        let mut s = String::new();
        if self.output.read_line(&mut s)? == 0 {
            bail!("the Mitsuba server ended (see its messages above)");
        }
        Ok(s.trim().to_owned())
    }

    /// One render: (milliseconds, mean luminance).
    fn render(&mut self, seed: usize) -> anyhow::Result<(f64, f64)> {
        writeln!(self.input, "render {seed}")?;
        self.input.flush()?;
        let reply = self.line()?;
        let field = |key: &str| -> anyhow::Result<f64> {
            reply
                .split_whitespace()
                .find_map(|w| w.strip_prefix(key))
                .context(format!("no {key} in `{reply}`"))?
                .parse()
                .context(format!("bad {key} in `{reply}`"))
        };
        Ok((field("ms=")?, field("mean_y=")?))
    }
}

impl Drop for Peer {
    fn drop(&mut self) {
        let _ = writeln!(self.input, "quit");
        let _ = self.child.wait();
    }
}

fn frame_workload(id: &str, name: &str, opts: &Options) -> anyhow::Result<()> {
    let (scene, setup) = workload(name)?;
    let settings = settings(opts);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.threads)
        .build()?;
    let dir = std::env::temp_dir().join(format!("raybench-frames-{name}"));
    export(&scene, &setup, &dir)?;
    let mut peer = match &opts.python {
        Some(python) => match Peer::start(python, &dir, opts) {
            Ok(p) => Some(p),
            Err(e) => {
                emit(&format!("# {id} mitsuba skipped: {e:#}"));
                None
            }
        },
        None => None,
    };
    let (mut ours, mut theirs) = (Vec::new(), Vec::new());
    let (mut our_y, mut their_y) = (0.0, 0.0);
    for run in 0..opts.runs {
        let started = Instant::now();
        let (film, _) = pool.install(|| render(&scene, &setup, &settings));
        ours.push(started.elapsed().as_secs_f64() * 1e3);
        our_y = film_mean_luminance(&film);
        if let Some(p) = &mut peer {
            let (ms, y) = p.render(run)?;
            theirs.push(ms);
            their_y = y;
        }
    }
    let t = opts.threads;
    let size = format!("{}x{}", opts.width, opts.height);
    let ours_ms = median(&ours);
    emit(&format!(
        "{id} scene={name} lib=raygine threads={t} res={size} spp={} ms={ours_ms:.0} mean_clipped_cd_m2={our_y:.3}",
        opts.spp
    ));
    if peer.is_some() {
        let theirs_ms = median(&theirs);
        emit(&format!(
            "{id} scene={name} lib=mitsuba-llvm threads={t} res={size} spp={} ms={theirs_ms:.0} mean_clipped_cd_m2={their_y:.3}",
            opts.spp
        ));
        emit(&format!(
            "{id} scene={name} ratio raygine/mitsuba threads={t} {:.2}",
            ours_ms / theirs_ms
        ));
    }
    Ok(())
}

/// Luminance above which pixels are clipped for the check of means: the Cornell box's light
/// hangs 0.1 mm under the ceiling, so a handful of pixels near it reach 10^7 cd/m² and their
/// sampling noise would swamp an unclipped mean.
pub const CLIP_CD_M2: f64 = 1000.0;

fn film_mean_luminance(film: &tracer_core::render::Film) -> f64 {
    let all = film.mean_rgb_all();
    let sum: f64 = all
        .iter()
        .map(|c| f64::from(tracer_core::light::luminance(*c)).min(CLIP_CD_M2))
        .sum();
    sum / all.len().max(1) as f64
}

pub fn run(opts: &Options) -> anyhow::Result<()> {
    emit(&format!(
        "# frames: {} runs interleaved, medians; {}x{} {} spp direct",
        opts.runs, opts.width, opts.height, opts.spp
    ));
    let wanted = |id: &str| opts.only.as_deref().is_none_or(|only| only == id);
    if wanted("F1") {
        frame_workload("F1", "cornell", opts)?;
    }
    if wanted("F2") {
        match crate::shared::shared_dir() {
            Some(_) => frame_workload("F2", "stanford-bunny", opts)?,
            None => emit("# F2 skipped: the shared folder was not found (RAYGINE_SHARED)"),
        }
    }
    Ok(())
}
