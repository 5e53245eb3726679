//! `raygine render`: load a scene, apply the command line's overrides, render, write the image.

use crate::cli::RenderArgs;
use crate::cli_support::{
    check_output_path, denoise, display_settings, load_denoiser, load_scene, sampling_settings,
    thread_pool, write_images,
};
use anyhow::{Result, bail};
use std::path::{Path, PathBuf};
use std::time::Instant;
use tracer_core::denoise::{Denoiser, Images, Quality};
use tracer_core::integrator::IntegratorKind;
use tracer_core::render::adaptive::{Stop, render_adaptive, worst_relative_error};
use tracer_core::render::{RenderSettings, render_with_progress};

/// Seconds between `raygine render`'s progress lines.
const PROGRESS_LINE_SECS: f64 = 5.0;
use tracer_core::scene::{KindTag, LoadedScene};

/// The samples cap of every pixel with --time-limit or --target-error and no --samples.
pub const ADAPTIVE_CAP: u32 = 65_536;

/// Samples per pixel of `-A/--antialiased`.
pub const ANTIALIASED_SAMPLES: u32 = 16;

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
        let Some(light) = setup.lights.iter_mut().find(|l| l.tag() == KindTag::Point) else {
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
            if let Some(cd) = light.intensity_cd_mut() {
                *cd = intensity;
            }
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
    if let Some(projection) = args.projection {
        setup.camera.projection = projection;
    }
    if let Some(width) = args.ortho_width {
        setup.camera.width = Some(width);
    }
    if let Some(fov) = p.get(6) {
        setup.camera.fov_deg = *fov;
    }
    if let Some(at) = args.look_at {
        setup.camera.look_at = at;
    }
    if let Err(e) = setup.camera.check() {
        // (The checks name the sidecar's keys; here they came from the command line.)
        let e = e
            .replace("fov_deg", "the field of view (CF)")
            .replace("camera: width", "camera: --ortho-width");
        bail!("{e}");
    }
    args.scene
        .integrator
        .check_projection(setup.camera.projection)
        .map_err(anyhow::Error::msg)?;
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
    let adaptive = !args.no_adaptive
        && (args.scene.time_limit.is_some() || args.target_error.is_some())
        && args.shard.partial.is_none();
    let mut settings = RenderSettings {
        width: args.width,
        height: args.height,
        max_depth: args.depth,
        // The PNG and the EXR show luminance only.
        pixel_illuminance: false,
        guides: args.denoise,
        ..sampling_settings(&args.scene, direct_samples)
    };
    let open_ended = args.scene.time_limit.is_some() || args.target_error.is_some();
    if open_ended && args.scene.samples.is_none() && args.shard.partial.is_none() {
        // A time or an error to reach: the cap is far away.
        settings.samples_per_pixel = ADAPTIVE_CAP;
    }
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
    let denoiser = if args.denoise {
        Some(load_denoiser(threads)?)
    } else {
        None
    };
    let mut time_limit = args
        .scene
        .time_limit
        .map(std::time::Duration::from_secs_f64);
    let mut quality = Quality::High;
    if let (Some(limit), Some(d)) = (time_limit.as_mut(), &denoiser) {
        // The limit includes denoising. One denoise of this size at balanced quality is timed
        // before the clock starts (like loading the scene); high quality costs about 2.3 times
        // as much (measured: 9.3 s and 4.0 s at 1022x810 on 2 threads). High is used when it
        // fits in a third of the limit, else balanced; its time is kept back from the render.
        let balanced = warm_up_denoise(d, settings.width, settings.height)?;
        let high = balanced * 2.3;
        let limit_secs = limit.as_secs_f64();
        let cost = if high <= limit_secs / 3.0 {
            high
        } else {
            quality = Quality::Balanced;
            balanced
        };
        if cost * 1.1 >= limit_secs {
            eprintln!(
                "warning: one denoise of {}x{} takes about {cost:.1} s, longer than the \
                 --time-limit of {limit_secs:.1} s: the render gets one pass",
                settings.width, settings.height
            );
        }
        *limit = limit.saturating_sub(std::time::Duration::from_secs_f64(cost * 1.1));
    }
    let target = settings.samples_per_pixel.max(1);
    let mut last_line = Instant::now();
    let mut report = |s: &tracer_core::render::RenderStats| {
        // A line every few seconds on stderr (stdout keeps the figures), so long renders say
        // where they are, on a terminal and in a log alike.
        if last_line.elapsed().as_secs_f64() >= PROGRESS_LINE_SECS && s.samples_per_pixel < target {
            last_line = Instant::now();
            let done = s.mean_samples_per_pixel;
            let per = s.elapsed_secs / done.max(1.0);
            let left = per * (f64::from(target) - done).max(0.0);
            let left = match time_limit {
                Some(limit) => left.min((limit.as_secs_f64() - s.elapsed_secs).max(0.0)),
                None => left,
            };
            if adaptive {
                eprintln!(
                    "rendering: {done:.1} spp on average (at least {}), {:.1} s, at most \
                     {left:.0} s left",
                    s.samples_per_pixel, s.elapsed_secs
                );
            } else {
                eprintln!(
                    "rendering: {}/{target} spp, {:.1} s, about {left:.0} s left",
                    s.samples_per_pixel, s.elapsed_secs
                );
            }
        }
    };
    let (film, stats) = pool.install(|| {
        if adaptive {
            let stop = Stop {
                time_limit,
                target_error: args.target_error.map(|pct| pct / 100.0),
                mean_samples: None,
            };
            render_adaptive(&loaded.scene, &loaded.setup, &settings, stop, &mut report)
        } else {
            render_with_progress(
                &loaded.scene,
                &loaded.setup,
                &settings,
                time_limit,
                &mut report,
            )
        }
    });
    if film.rejected_samples() > 0 {
        bail!(
            "{} samples were not finite or beyond the film's range (2^62 cd/m² a sample); \
             nothing was written",
            film.rejected_samples()
        );
    }
    let denoised = match &denoiser {
        Some(d) => Some(denoise(d, &film, quality)?),
        None => None,
    };
    let rendered_at = Instant::now();
    let (image, exposure) = write_images(
        &film,
        &display,
        &png_path,
        args.exr.as_deref(),
        &pool,
        denoised.as_ref().map(|(d, _)| d.as_slice()),
    )?;
    let scene = &loaded.scene;
    let transport = match settings.integrator {
        IntegratorKind::Direct => format!("direct, mirror depth {}", settings.max_depth),
        IntegratorKind::Path | IntegratorKind::Bidirectional | IntegratorKind::Light => {
            match settings.max_bounces {
                Some(n) => format!("{}, at most {n} bounces", settings.integrator),
                None => format!("{}, unlimited bounces", settings.integrator),
            }
        }
    };
    let spp = if adaptive {
        format!(
            "{:.1} spp on average (adaptive: {} to {})",
            stats.mean_samples_per_pixel,
            stats.samples_per_pixel,
            film.counts().max().unwrap_or(0)
        )
    } else {
        format!("{} spp", stats.samples_per_pixel)
    };
    println!(
        "{}: {}, {} breps, BVH {:.1} ms; {}x{} px, {spp}, {transport}, {} threads",
        scene.name,
        scene.triangles_label(),
        scene.breps.len(),
        scene.bvh_build_secs * 1e3,
        settings.width,
        settings.height,
        threads
    );
    if let Some(noise) = film.relative_noise() {
        println!(
            "remaining noise: {:.2} % (RMS standard error of pixel luminance / mean luminance)",
            noise * 100.0
        );
    }
    if let Some(target) = args.target_error {
        let worst = worst_relative_error(&film) * 100.0;
        let verdict = if worst <= target {
            "reached"
        } else {
            "NOT reached (the sample cap or the time limit came first)"
        };
        println!("target error {target} %: {verdict}; worst pixel {worst:.2} %");
    }
    println!(
        "rendered in {:.1} ms, {:.2} Mrays/s; luminance mean {:.3} cd/m², max {:.3} cd/m²; exposure {:+.2} stops",
        stats.elapsed_secs * 1e3,
        stats.mrays_per_sec(),
        image.luminance_sum / film.len().max(1) as f64,
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
    if let Some(line) = crate::cli_support::memory_line(scene) {
        println!("{line}");
    }
    if let (Some((_, secs)), Some(d)) = (&denoised, &denoiser) {
        println!(
            "denoised in {:.1} ms (Open Image Denoise {}, {quality:?} quality): the PNG shows the denoised picture; \
             the figures above are the raw image's; render and denoise {:.2} s",
            secs * 1e3,
            d.version_text(),
            stats.elapsed_secs + secs
        );
    }
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
        let layers = if denoised.is_some() {
            "; denoised.R/G/B: denoised"
        } else {
            ""
        };
        println!("wrote {} (linear cd/m² per channel{layers})", exr.display());
    }
    Ok(())
}

/// Seconds one balanced-quality denoise of a `width` x `height` picture takes (a black one: the network's cost
/// does not depend on the picture).
fn warm_up_denoise(d: &Denoiser, width: u32, height: u32) -> Result<f64> {
    let black = vec![glam::Vec3::ZERO; width as usize * height as usize];
    let t = Instant::now();
    d.denoise(
        &Images {
            width,
            height,
            color: &black,
            albedo: &black,
            normal: &black,
        },
        Quality::Balanced,
    )
    .map_err(|e| anyhow::anyhow!("--denoise: {e}"))?;
    Ok(t.elapsed().as_secs_f64())
}
