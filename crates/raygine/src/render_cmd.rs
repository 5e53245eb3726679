//! `raygine render`: load a scene, apply the command line's overrides, render, write the image.

use crate::cli::{DisplayArgs, RenderArgs, SceneArgs};
use anyhow::{Context, Result, bail};
use glam::Vec3;
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::time::Instant;
use tracer_core::display::{ChannelLut, DisplaySettings};
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::{Film, RenderSettings, render_for};
use tracer_core::scene::{self, LightKind, LoadOptions, LoadedScene, luminance};

/// Samples per pixel of `-A/--antialiased`.
pub const ANTIALIASED_SAMPLES: u32 = 16;

/// Loads the scene the arguments name (the built-in Cornell box without one).
pub fn load_scene(args: &SceneArgs) -> Result<LoadedScene> {
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
        let Some(light) = setup.lights.iter_mut().find(|l| l.kind == LightKind::Point) else {
            bail!(
                "-I and the positional light position address the first point light, \
                 and the scene has none"
            );
        };
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

/// The render settings the shared options give (without size and depth).
pub fn sampling_settings(args: &SceneArgs, direct_samples: u32) -> RenderSettings {
    RenderSettings {
        samples_per_pixel: args.samples_or(direct_samples),
        integrator: args.integrator,
        max_bounces: args.max_bounces,
        ..RenderSettings::default()
    }
}

/// A rayon pool of `--threads` workers (all cores by default).
pub fn thread_pool(args: &SceneArgs) -> Result<rayon::ThreadPool> {
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(n) = args.threads {
        pool = pool.num_threads(n as usize);
    }
    pool.build().context("cannot start the render threads")
}

pub fn run(args: &RenderArgs) -> Result<()> {
    let started = Instant::now();
    let mut loaded = load_scene(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    apply_overrides(&mut loaded, args)?;
    let direct_samples = if args.antialiased {
        ANTIALIASED_SAMPLES
    } else {
        1
    };
    let settings = RenderSettings {
        width: args.width,
        height: args.height,
        max_depth: args.depth,
        // The PNG and the EXR show luminance only.
        pixel_illuminance: false,
        ..sampling_settings(&args.scene, direct_samples)
    };
    if args.shard.partial.is_some() {
        return crate::shard_cmd::render_part(args, &loaded, &settings);
    }
    let display = display_settings(&args.display)?;
    let png_path = args
        .render_path
        .clone()
        .unwrap_or_else(|| default_render_path(args.scene.scene_path.as_deref()));
    check_output_path(&png_path)?;
    if let Some(exr) = &args.exr {
        check_output_path(exr)?;
    }
    let pool = thread_pool(&args.scene)?;
    let threads = pool.current_num_threads();
    let time_limit = args
        .scene
        .time_limit
        .map(std::time::Duration::from_secs_f64);
    let (film, stats) =
        pool.install(|| render_for(&loaded.scene, &loaded.setup, &settings, time_limit));
    if film.rejected_samples() > 0 {
        bail!(
            "{} samples were not finite or beyond the film's range (2^62 cd/m² a sample); \
             nothing was written",
            film.rejected_samples()
        );
    }
    let rendered_at = Instant::now();
    let (image, exposure) = write_images(&film, &display, &png_path, args.exr.as_deref(), &pool)?;
    let scene = &loaded.scene;
    let transport = match settings.integrator {
        IntegratorKind::Direct => format!("direct, mirror depth {}", settings.max_depth),
        IntegratorKind::Path | IntegratorKind::Bidirectional => match settings.max_bounces {
            Some(n) => format!("{}, at most {n} bounces", settings.integrator),
            None => format!("{}, unlimited bounces", settings.integrator),
        },
    };
    println!(
        "{}: {} triangles, {} breps, BVH {:.1} ms; {}x{} px, {} spp, {transport}, {} threads",
        scene.name,
        scene.triangle_count(),
        scene.breps.len(),
        scene.bvh_build_secs * 1e3,
        settings.width,
        settings.height,
        stats.samples_per_pixel,
        threads
    );
    if let Some(noise) = film.relative_noise() {
        println!(
            "remaining noise: {:.2} % (RMS standard error of pixel luminance / mean luminance)",
            noise * 100.0
        );
    }
    println!(
        "rendered in {:.1} ms, {:.2} Mrays/s; luminance mean {:.3} cd/m², max {:.3} cd/m²; exposure {:+.2} stops",
        stats.elapsed_secs * 1e3,
        stats.mrays_per_sec(),
        image.luminance_sum / film.pixels.len().max(1) as f64,
        image.luminance_max,
        exposure
    );
    println!(
        "total {:.1} ms (load {:.1} ms, render {:.1} ms, images {:.1} ms)",
        started.elapsed().as_secs_f64() * 1e3,
        (rendered_at - started).as_secs_f64() * 1e3 - stats.elapsed_secs * 1e3,
        stats.elapsed_secs * 1e3,
        rendered_at.elapsed().as_secs_f64() * 1e3,
    );
    println!("wrote {}", png_path.display());
    if image.luminance_max <= 0.0 {
        let outside = crate::picture_hints::lights_outside(&loaded.setup, &loaded.scene.bounds);
        let lights = match outside.as_slice() {
            [] => String::new(),
            l => format!(
                " (outside the scene's bounds: light {})",
                l.iter()
                    .map(usize::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        eprintln!("warning: every pixel is 0 cd/m²: no light reaches what the camera sees{lights}");
    }
    if let Some(exr) = &args.exr {
        println!("wrote {} (linear cd/m² per channel)", exr.display());
    }
    Ok(())
}

/// The display settings the options give.
pub fn display_settings(args: &DisplayArgs) -> Result<DisplaySettings> {
    let display = DisplaySettings {
        exposure_stops: args.exposure.unwrap_or(0.0),
        auto_exposure: args.auto_exposure,
        tone_map: args.tone_map,
        false_colour: None,
    };
    if !display.exposure_stops.is_finite() {
        bail!("exposure must be a finite number of stops");
    }
    Ok(display)
}

/// Writes the film as the displayed PNG (and the linear EXR); returns the image and the
/// exposure used. The same film gives the same bytes, whoever rendered it.
pub fn write_images(
    film: &Film,
    display: &DisplaySettings,
    png: &Path,
    exr: Option<&Path>,
    pool: &rayon::ThreadPool,
) -> Result<(MappedImage, f32)> {
    let exposure = display.effective_exposure(film);
    let image = pool.install(|| map_film_rgb(film, display, exposure));
    tracer_core::export::write_png_rgb(png, &image.rgb, film.width, film.height)?;
    if let Some(exr) = exr {
        tracer_core::export::write_exr(exr, film)?;
    }
    Ok((image, exposure))
}

/// Fails before rendering when an output path cannot be written (a folder, or a folder that does
/// not exist), so a long render is not wasted. Writing itself stays atomic in `export`.
pub fn check_output_path(path: &Path) -> Result<()> {
    if path.is_dir() {
        bail!("{}: is a directory", path.display());
    }
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() && !dir.is_dir() => {
            bail!(
                "{}: the folder {} does not exist",
                path.display(),
                dir.display()
            )
        }
        _ => Ok(()),
    }
}

/// The display image of a film with the luminance figures the summary prints.
#[derive(Debug)]
pub struct MappedImage {
    /// RGB8, sRGB-encoded, row-major, top row first.
    pub rgb: Vec<u8>,
    /// Sum over pixels of the mean Rec. 709 luminance, cd/m².
    pub luminance_sum: f64,
    /// Largest pixel luminance, cd/m².
    pub luminance_max: f32,
}

/// Maps the film to display pixels (as [`DisplaySettings::map_film`] does, without alpha) and
/// gathers its luminance figures in the same pass, rows in parallel on the current rayon pool.
/// Row sums are added in row order, so the figures do not depend on the thread count.
pub fn map_film_rgb(film: &Film, display: &DisplaySettings, exposure_stops: f32) -> MappedImage {
    let scale = DisplaySettings::scale_for(exposure_stops);
    let lut = ChannelLut::new(display, scale);
    let width = film.width as usize;
    let mut rgb = vec![0u8; film.pixels.len() * 3];
    let rows: Vec<(f64, f32)> = rgb
        .par_chunks_mut((width * 3).max(1))
        .zip(film.pixels.par_chunks(width.max(1)))
        .map(|(out, sums)| {
            let (mut y_sum, mut y_max) = (0.0f64, 0.0f32);
            for (o, p) in out.chunks_exact_mut(3).zip(sums) {
                let (mean, e): (Vec3, f32) = (p.mean_rgb(), p.mean_illuminance());
                let code = match &lut {
                    Some(lut) => [lut.code(mean.x), lut.code(mean.y), lut.code(mean.z)],
                    None => {
                        let [r, g, b, _] = display.map_pixel(mean, e, scale);
                        [r, g, b]
                    }
                };
                o.copy_from_slice(&code);
                let y = luminance(mean);
                y_sum += f64::from(y);
                y_max = y_max.max(y);
            }
            (y_sum, y_max)
        })
        .collect();
    let (luminance_sum, luminance_max) = rows
        .iter()
        .fold((0.0, 0.0f32), |(s, m), &(rs, rm)| (s + rs, m.max(rm)));
    MappedImage {
        rgb,
        luminance_sum,
        luminance_max,
    }
}
