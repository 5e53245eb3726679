//! `raygine render`: load a scene, apply the command line's overrides, render, write the image.

use crate::cli::RenderArgs;
use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};
use tracer_core::display::DisplaySettings;
use tracer_core::render::{RenderSettings, render};
use tracer_core::scene::{self, LoadOptions, LoadedScene, PointLight, luminance};

/// Samples per pixel of `-A/--antialiased`.
pub const ANTIALIASED_SAMPLES: u32 = 16;

/// Loads the scene the arguments name (the built-in Cornell box without one).
pub fn load_scene(args: &RenderArgs) -> Result<LoadedScene> {
    match &args.scene_path {
        Some(path) => {
            let options = LoadOptions {
                unit: args.units,
                sidecar: args.sidecar.as_deref(),
            };
            Ok(scene::load(path, &options)?)
        }
        None => {
            let mut loaded = scene::builtin_cornell_box(args.units)?;
            if let Some(sidecar) = &args.sidecar {
                let text = std::fs::read_to_string(sidecar)
                    .with_context(|| format!("{}: cannot read the sidecar", sidecar.display()))?;
                let parsed = scene::Sidecar::parse(&text, sidecar)?;
                loaded.setup = parsed.apply(&loaded.scene, args.units, &mut loaded.warnings);
            }
            Ok(loaded)
        }
    }
}

/// Applies `-I`, the positional `lx ly lz cx cy cz cf` (any prefix) and `--look-at`.
pub fn apply_overrides(loaded: &mut LoadedScene, args: &RenderArgs) -> Result<()> {
    let setup = &mut loaded.setup;
    if let Some(bad) = args.positional.iter().find(|v| !v.is_finite()) {
        bail!("positional value {bad} is not a finite number");
    }
    let p = &args.positional;
    if p.len() > 7 {
        bail!("at most 7 positional values: lx ly lz cx cy cz cf");
    }
    if !p.is_empty() || args.intensity.is_some() {
        if setup.lights.is_empty() {
            setup
                .lights
                .push(scene::default_light(&loaded.scene, setup.unit));
        }
        let light: &mut PointLight = &mut setup.lights[0];
        for (i, v) in p.iter().take(3).enumerate() {
            light.position[i] = *v;
        }
        if let Some(intensity) = args.intensity {
            if !(intensity.is_finite() && intensity >= 0.0) {
                bail!("intensity must be a finite number of candela >= 0, got {intensity}");
            }
            light.intensity_cd = intensity;
        }
    }
    if p.len() > 3 {
        for (i, v) in p.iter().skip(3).take(3).enumerate() {
            setup.camera.position[i] = *v;
        }
        // A camera placed on the command line looks towards -Z, as in the original tool.
        let c = setup.camera.position;
        setup.camera.look_at = [c[0], c[1], c[2] - 1.0];
        setup.camera.up = [0.0, 1.0, 0.0];
    }
    if let Some(fov) = p.get(6) {
        if !(*fov > 0.0 && *fov < 180.0) {
            bail!("field of view must be between 0 and 180 degrees, got {fov}");
        }
        setup.camera.fov_deg = *fov;
    }
    if let Some(at) = args.look_at {
        setup.camera.look_at = at;
    }
    Ok(())
}

/// Where the PNG goes when `-R` is not given.
pub fn default_render_path(scene_path: Option<&Path>) -> PathBuf {
    match scene_path {
        Some(p) => p.with_extension("png"),
        None => PathBuf::from("cornell_box.png"),
    }
}

pub fn run(args: &RenderArgs) -> Result<()> {
    let mut loaded = load_scene(args)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    apply_overrides(&mut loaded, args)?;
    let settings = RenderSettings {
        width: args.width,
        height: args.height,
        samples_per_pixel: args.samples.unwrap_or(if args.antialiased {
            ANTIALIASED_SAMPLES
        } else {
            1
        }),
        max_depth: args.depth,
    };
    let display = DisplaySettings {
        exposure_stops: args.exposure.unwrap_or(0.0),
        auto_exposure: args.auto_exposure,
        tone_map: args.tone_map,
        false_colour: None,
    };
    if !display.exposure_stops.is_finite() {
        bail!("exposure must be a finite number of stops");
    }
    let png_path = args
        .render_path
        .clone()
        .unwrap_or_else(|| default_render_path(args.scene_path.as_deref()));
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(n) = args.threads {
        pool = pool.num_threads(n as usize);
    }
    let pool = pool.build().context("cannot start the render threads")?;
    let threads = pool.current_num_threads();
    let (film, stats) = pool.install(|| render(&loaded.scene, &loaded.setup, &settings));
    let exposure = display.effective_exposure(&film);
    let rgba = display.map_film(&film);
    tracer_core::export::write_png(&png_path, rgba, film.width, film.height)?;
    if let Some(exr) = &args.exr {
        tracer_core::export::write_exr(exr, &film)?;
    }
    let scene = &loaded.scene;
    let (mut y_max, mut y_sum) = (0.0f32, 0.0f64);
    for i in 0..film.pixels.len() {
        let y = luminance(film.mean_rgb(i));
        y_max = y_max.max(y);
        y_sum += f64::from(y);
    }
    println!(
        "{}: {} triangles, {} breps, BVH {:.1} ms; {}x{} px, {} spp, depth {}, {} threads",
        scene.name,
        scene.triangle_count(),
        scene.breps.len(),
        scene.bvh_build_secs * 1e3,
        settings.width,
        settings.height,
        settings.samples_per_pixel,
        settings.max_depth,
        threads
    );
    println!(
        "rendered in {:.1} ms, {:.2} Mrays/s; luminance mean {:.3} cd/m², max {:.3} cd/m²; exposure {:+.2} stops",
        stats.elapsed_secs * 1e3,
        stats.mrays_per_sec(),
        y_sum / film.pixels.len().max(1) as f64,
        y_max,
        exposure
    );
    println!("wrote {}", png_path.display());
    if let Some(exr) = &args.exr {
        println!("wrote {} (linear cd/m² per channel)", exr.display());
    }
    Ok(())
}
