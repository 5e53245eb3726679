//! What the commands share: loading the scene the options name, the thread pool, render and
//! display settings from options, checking output paths, and writing the images.

use crate::cli_args::{DisplayArgs, SceneArgs};
use anyhow::{Context, Result, bail};
use std::path::Path;
use tracer_core::denoise::{Denoiser, Quality};
use tracer_core::display::{DisplayMapper, DisplaySettings};
use tracer_core::render::{Film, RenderSettings};
use tracer_core::scene::{self, LoadOptions, LoadedScene};

/// Loads the scene the arguments name (the built-in Cornell box without one).
pub fn load_scene(args: &SceneArgs) -> Result<LoadedScene> {
    match &args.scene_path {
        Some(path) => {
            let options = LoadOptions {
                unit: args.units,
                sidecar: args.sidecar.as_deref(),
                usd_time: args.usd_time,
            };
            Ok(scene::load(path, &options)?)
        }
        None => match &args.sidecar {
            Some(sidecar) => Ok(scene::builtin_with_sidecar(sidecar, args.units)?),
            None => Ok(scene::builtin_cornell_box(args.units)?),
        },
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
///
/// With `denoised` (the film's denoised colours), the PNG shows those at the raw film's
/// exposure and the EXR adds them as `denoised.R/G/B`; the returned figures stay the raw
/// film's.
pub fn write_images(
    film: &Film,
    display: &DisplaySettings,
    png: &Path,
    exr: Option<&Path>,
    pool: &rayon::ThreadPool,
    denoised: Option<&[glam::Vec3]>,
) -> Result<(MappedImage, f32)> {
    let exposure = display.effective_exposure(film);
    let image = pool.install(|| map_film_rgb(film, display, exposure));
    match denoised {
        None => tracer_core::export::write_png_rgb(png, &image.rgb, film.width, film.height)?,
        Some(d) => {
            let shown = Film::from_values(film.width, film.height, d, &[]);
            let picture = pool.install(|| map_film_rgb(&shown, display, exposure));
            tracer_core::export::write_png_rgb(png, &picture.rgb, film.width, film.height)?;
        }
    }
    if let Some(exr) = exr {
        tracer_core::export::write_exr_with_denoised(exr, film, denoised)?;
    }
    Ok((image, exposure))
}

/// Loads the denoiser for `--denoise`, or says why it cannot.
pub fn load_denoiser(threads: usize) -> Result<Denoiser> {
    Denoiser::load(threads).map_err(|e| anyhow::anyhow!("--denoise: {e}"))
}

/// The denoised colours of a film rendered with guides, and the seconds it took.
pub fn denoise(
    denoiser: &Denoiser,
    film: &Film,
    quality: Quality,
) -> Result<(Vec<glam::Vec3>, f64)> {
    let t = std::time::Instant::now();
    let out = tracer_core::denoise::denoise_film(denoiser, film, quality)
        .map_err(|e| anyhow::anyhow!("--denoise: {e}"))?;
    Ok((out, t.elapsed().as_secs_f64()))
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

/// Maps the film to display pixels through the one display path ([`DisplayMapper`]) and
/// gathers its luminance figures.
pub fn map_film_rgb(film: &Film, display: &DisplaySettings, exposure_stops: f32) -> MappedImage {
    let (rgb, luminance_sum, luminance_max) =
        DisplayMapper::new(display, exposure_stops).map_film_and_luminance::<3>(film);
    MappedImage {
        rgb,
        luminance_sum,
        luminance_max,
    }
}

/// "memory: 0.41 GB resident, peak 0.75 GB; geometry 0.12 GB (88 bytes a triangle)": the
/// process's resident and peak memory (Linux `/proc/self/status`; None elsewhere) and what the
/// scene's triangles, their shading data and BVHs hold.
pub fn memory_line(scene: &tracer_core::scene::Scene) -> Option<String> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let field = |name: &str| -> Option<f64> {
        let line = status.lines().find_map(|l| l.strip_prefix(name))?;
        let kb: f64 = line.split_whitespace().next()?.parse().ok()?;
        Some(kb * 1024.0 / 1e9)
    };
    let (resident, peak) = (field("VmRSS:")?, field("VmHWM:")?);
    let geometry = scene.geometry_bytes();
    let per_triangle = geometry as f64 / scene.stored_triangle_count().max(1) as f64;
    Some(format!(
        "memory: {resident:.2} GB resident, peak {peak:.2} GB; geometry {:.2} GB ({per_triangle:.0} bytes a stored triangle)",
        geometry as f64 / 1e9
    ))
}
