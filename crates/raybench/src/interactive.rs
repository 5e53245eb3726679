//! `raybench interactive`: L1 (first coarse preview) and L2 (first full sample) after a light
//! move on a converged RenderSession, 1280x720, depth 5, on the built-in Cornell box and the
//! bunny; and the restart storm: 1,000 light moves 1 ms apart, after which the film must equal a
//! one-shot render of the last state bit for bit, with resident memory reported before and after.

use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{Context, bail, ensure};
use glam::Vec3;
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::{RenderSession, RenderSettings, Snapshot, render};
use tracer_core::scene::{self, LoadOptions, Scene, Setup, builtin_cornell_box};

use crate::report::emit;
use crate::rng::SplitMix64;
use crate::stats::median;

/// Full samples per pixel a generation converges to before the light moves.
const TARGET_SPP: u32 = 4;
/// How long to wait for a generation to finish.
const TIMEOUT: Duration = Duration::from_secs(120);

#[derive(Clone, Debug)]
pub struct Options {
    pub runs: usize,
    pub threads: Vec<usize>,
    pub storm_changes: usize,
    pub integrator: IntegratorKind,
    /// The denoiser's guides traced too (the viewer with denoise on).
    pub guides: bool,
}

/// `Options::guides` for this run (set once by [`run`], read by [`settings`]).
static GUIDES: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

fn settings(integrator: IntegratorKind) -> RenderSettings {
    let guides = GUIDES.load(std::sync::atomic::Ordering::Relaxed);
    RenderSettings {
        width: 1280,
        height: 720,
        samples_per_pixel: TARGET_SPP,
        max_depth: 5,
        integrator,
        max_bounces: None,
        pixel_illuminance: true,
        guides,
    }
}

/// The setup with the first light moved to `position`.
fn with_light(setup: &Setup, position: Vec3) -> anyhow::Result<Setup> {
    let mut s = setup.clone();
    s.lights
        .first_mut()
        .context("the scene has no light")?
        .position = position.to_array();
    Ok(s)
}

/// Starts `setup` and waits until it is finished; returns its generation.
fn start_and_finish(
    kind: IntegratorKind,
    session: &RenderSession,
    scene: &Arc<Scene>,
    setup: Setup,
) -> anyhow::Result<u64> {
    let generation = session.start(Snapshot {
        scene: Arc::clone(scene),
        setup,
        settings: settings(kind),
        time_limit: None,
        adaptive: false,
    });
    ensure!(
        session.wait_for(TIMEOUT, |s| s.generation == generation && s.finished),
        "generation {generation} did not finish within {TIMEOUT:?}"
    );
    Ok(generation)
}

fn load_scene(name: &str) -> anyhow::Result<(Arc<Scene>, Setup)> {
    let loaded = if name == "cornell" {
        builtin_cornell_box(None)?
    } else {
        let shared = crate::shared::require_shared()?;
        scene::load(
            &shared.join("scenes/meshes/stanford-bunny.shp"),
            &LoadOptions::default(),
        )?
    };
    Ok((Arc::new(loaded.scene), loaded.setup))
}

/// L1 and L2 of one scene with `threads` workers.
fn latency(kind: IntegratorKind, name: &str, threads: usize, runs: usize) -> anyhow::Result<()> {
    let (scene, setup) = load_scene(name)?;
    let base = Vec3::from_array(setup.lights.first().context("no light")?.position);
    let step = scene.bounds.extent() * 0.05;
    let session = RenderSession::new(threads, Arc::new(|| {}))?;
    start_and_finish(kind, &session, &scene, setup.clone())?;
    let (mut previews, mut fulls) = (Vec::new(), Vec::new());
    for run in 0..runs {
        let sign = if run % 2 == 0 { 1.0 } else { -1.0 };
        let moved = with_light(&setup, base + step * sign)?;
        start_and_finish(kind, &session, &scene, moved)?;
        let stats = session.stats();
        previews.push(stats.first_preview_secs.context("no preview time")? * 1e3);
        fulls.push(stats.first_full_secs.context("no full-sample time")? * 1e3);
    }
    emit(&format!(
        "L1 scene={name} integrator={kind} threads={threads} first_preview_ms={:.1}",
        median(&previews)
    ));
    emit(&format!(
        "L2 scene={name} integrator={kind} threads={threads} first_full_ms={:.1}",
        median(&fulls)
    ));
    Ok(())
}

/// Resident and peak resident memory of this process, MB (from /proc/self/status).
fn rss_mb() -> anyhow::Result<(f64, f64)> {
    let status = std::fs::read_to_string("/proc/self/status")?;
    let field = |key: &str| -> anyhow::Result<f64> {
        let line = status
            .lines()
            .find(|l| l.starts_with(key))
            .with_context(|| format!("{key} missing from /proc/self/status"))?;
        let kb: f64 = line
            .split_whitespace()
            .nth(1)
            .context("no value")?
            .parse()?;
        Ok(kb / 1024.0)
    };
    Ok((field("VmRSS:")?, field("VmHWM:")?))
}

/// The restart storm on the built-in Cornell box.
fn storm(kind: IntegratorKind, threads: usize, changes: usize) -> anyhow::Result<()> {
    let (scene, setup) = load_scene("cornell")?;
    let base = Vec3::from_array(setup.lights.first().context("no light")?.position);
    let extent = scene.bounds.extent();
    let session = RenderSession::new(threads, Arc::new(|| {}))?;
    start_and_finish(kind, &session, &scene, setup.clone())?;
    let (rss_before, hwm_before) = rss_mb()?;
    let mut rng = SplitMix64::new(0x5702_4D00);
    let mut last = setup.clone();
    let started = Instant::now();
    let mut start_ms: Vec<f64> = Vec::with_capacity(changes);
    for _ in 0..changes {
        let jitter = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) - 0.5;
        last = with_light(&setup, base + jitter * extent * 0.3)?;
        let call = Instant::now();
        session.start(Snapshot {
            scene: Arc::clone(&scene),
            setup: last.clone(),
            settings: settings(kind),
            time_limit: None,
            adaptive: false,
        });
        start_ms.push(call.elapsed().as_secs_f64() * 1e3);
        std::thread::sleep(Duration::from_millis(1));
    }
    let storm_secs = started.elapsed().as_secs_f64();
    let generation = session.generation();
    if !session.wait_for(TIMEOUT, |s| s.generation == generation && s.finished) {
        bail!("the last generation of the storm did not finish");
    }
    let (rss_after, hwm_after) = rss_mb()?;
    let shown = session
        .with_film(|f| f.map(|f| (f.generation, f.accum.clone())))
        .context("no film after the storm")?;
    let (reference, _) = render(&scene, &last, &settings(kind));
    let bits = |f: &tracer_core::render::Film| -> Vec<[i128; 5]> {
        f.pixels()
            .map(|p| {
                let [r, g, b] = p.rgb;
                [r, g, b, p.illuminance, i128::from(p.count)]
            })
            .collect()
    };
    let matches = shown.0 == generation && bits(&shown.1) == bits(&reference);
    emit(&format!(
        "storm scene=cornell threads={threads} changes={changes} final_matches={matches} \
         rss_mb_before={rss_before:.1} rss_mb_after={rss_after:.1} \
         peak_mb_before={hwm_before:.1} peak_mb_after={hwm_after:.1} storm_s={storm_secs:.2} \
         start_call_ms_median={:.3} start_call_ms_max={:.1}",
        median(&start_ms),
        start_ms.iter().copied().fold(0.0, f64::max)
    ));
    Ok(())
}

pub fn run(opts: &Options) -> anyhow::Result<()> {
    GUIDES.store(opts.guides, std::sync::atomic::Ordering::Relaxed);
    println!("guides (denoise on): {}", opts.guides);
    for &threads in &opts.threads {
        latency(opts.integrator, "cornell", threads, opts.runs)?;
        if crate::shared::shared_dir().is_some() {
            latency(opts.integrator, "stanford-bunny", threads, opts.runs)?;
        } else {
            emit("# bunny skipped: the shared folder was not found");
        }
    }
    let threads = opts.threads.iter().copied().max().unwrap_or(2);
    storm(opts.integrator, threads, opts.storm_changes)
}
