//! `raygine merge PART...`: adds the exact sums of all shards of a render into its PNG (and
//! EXR), or of a measurement into its CSV and JSON: the same bytes one machine writes with all
//! N samples.

use crate::cli_shards::MergeArgs;
use crate::cli_support::{check_output_path, display_settings, write_images};
use crate::measure_cmd::{summary_line, write_readings};
use anyhow::{Result, bail};
use std::path::{Path, PathBuf};
use std::time::Instant;
use tracer_core::measure::grid_results;
use tracer_core::measure::partial::MeasurePart;
use tracer_core::render::{Film, partial};
use tracer_core::shard::{PartHeader, PartKind, check_set, read_part};

pub fn run(args: &MergeArgs) -> Result<()> {
    let started = Instant::now();
    // Every part is read and checked whole before anything is added, so a bad set is refused
    // before any output is touched; the payloads are read again one at a time to add them.
    let mut headers: Vec<(PathBuf, PartHeader)> = Vec::with_capacity(args.parts.len());
    for path in &args.parts {
        let (header, _) = read_part(path)?;
        headers.push((path.clone(), header));
    }
    check_set(&headers)?;
    let Some((_, first)) = headers.first() else {
        bail!("no parts to merge");
    };
    match first.kind {
        PartKind::Render => merge_render(args, first, started),
        PartKind::Measure => merge_measure(args, first, started),
    }
}

/// Options that belong to the other kind of part.
fn refuse(given: &[(bool, &str)], kind: &str) -> Result<()> {
    if let Some((_, name)) = given.iter().find(|(g, _)| *g) {
        bail!("{name} does not apply to {kind} parts");
    }
    Ok(())
}

/// Reads the payload of a part checked before.
fn payload(path: &Path) -> Result<Vec<u8>> {
    Ok(read_part(path)?.1)
}

fn merge_render(args: &MergeArgs, first: &PartHeader, started: Instant) -> Result<()> {
    refuse(
        &[
            (args.csv.is_some(), "--csv"),
            (args.json.is_some(), "--json"),
        ],
        "render",
    )?;
    let Some(png) = args.render_path.as_deref() else {
        bail!("render parts: say where the image goes with -R PATH (and --exr PATH)");
    };
    let display = display_settings(&args.display)?;
    check_output_path(png)?;
    if let Some(exr) = &args.exr {
        check_output_path(exr)?;
    }
    let denoiser = if args.denoise {
        Some(crate::cli_support::load_denoiser(0)?)
    } else {
        None
    };
    let mut film: Option<Film> = None;
    for path in &args.parts {
        let part = partial::decode_film(&payload(path)?)
            .map_err(|reason| anyhow::anyhow!("{}: damaged payload: {reason}", path.display()))?;
        match &mut film {
            None => film = Some(part),
            Some(sum) => sum
                .merge(&part)
                .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?,
        }
    }
    let Some(film) = film else {
        bail!("no parts to merge");
    };
    if film.rejected_samples() > 0 {
        bail!(
            "{} samples were not finite or beyond the film's range; nothing was written",
            film.rejected_samples()
        );
    }
    if film.min_samples() != first.samples {
        bail!(
            "the parts hold {} samples a pixel where their headers say {}; nothing was written",
            film.min_samples(),
            first.samples
        );
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .build()
        .map_err(|e| anyhow::anyhow!("cannot start threads: {e}"))?;
    let denoised = match &denoiser {
        None => None,
        Some(d) => {
            if film.guides.is_none() {
                bail!(
                    "--denoise: the parts have no denoiser guides; render them with \
                     `raygine render --partial ... --denoise`"
                );
            }
            Some(crate::cli_support::denoise(
                d,
                &film,
                tracer_core::denoise::Quality::High,
            )?)
        }
    };
    let (image, exposure) = write_images(
        &film,
        &display,
        png,
        args.exr.as_deref(),
        &pool,
        denoised.as_ref().map(|(d, _)| d.as_slice()),
    )?;
    println!(
        "{}: {} parts, {}x{} px, {} spp, {}; luminance mean {:.3} cd/m², max {:.3} cd/m²; exposure {:+.2} stops",
        first.scene,
        args.parts.len(),
        film.width,
        film.height,
        first.samples,
        first.settings,
        image.luminance_sum / film.len().max(1) as f64,
        image.luminance_max,
        exposure
    );
    if let Some(noise) = film.relative_noise() {
        println!(
            "remaining noise: {:.2} % (RMS standard error of pixel luminance / mean luminance)",
            noise * 100.0
        );
    }
    if let Some((_, secs)) = &denoised {
        println!(
            "denoised in {:.1} ms (Open Image Denoise): the PNG shows the denoised picture; \
             the figures above are the raw image's",
            secs * 1e3
        );
    }
    println!("wrote {}", png.display());
    if let Some(exr) = &args.exr {
        let layers = if denoised.is_some() {
            "; denoised.R/G/B: denoised"
        } else {
            ""
        };
        println!("wrote {} (linear cd/m² per channel{layers})", exr.display());
    }
    println!("merged in {:.2} s", started.elapsed().as_secs_f64());
    Ok(())
}

fn merge_measure(args: &MergeArgs, first: &PartHeader, started: Instant) -> Result<()> {
    refuse(
        &[
            (args.render_path.is_some(), "-R/--render_path"),
            (args.exr.is_some(), "--exr"),
            (args.denoise, "--denoise"),
            (args.display.exposure.is_some(), "--exposure"),
            (args.display.auto_exposure, "--auto-exposure"),
        ],
        "measurement",
    )?;
    if args.csv.is_none() && args.json.is_none() {
        bail!("measurement parts: say where the readings go: --csv PATH and/or --json PATH");
    }
    for path in [&args.csv, &args.json].into_iter().flatten() {
        check_output_path(path)?;
    }
    let mut total: Option<(PathBuf, MeasurePart)> = None;
    for path in &args.parts {
        let part = MeasurePart::decode(&payload(path)?)
            .map_err(|reason| anyhow::anyhow!("{}: damaged payload: {reason}", path.display()))?;
        match &mut total {
            None => total = Some((path.clone(), part)),
            Some((first_path, sum)) => {
                let same = sum.grids == part.grids
                    && sum.unit == part.unit
                    && sum.integrator == part.integrator
                    && sum.maintenance_factor.to_bits() == part.maintenance_factor.to_bits();
                if !same {
                    bail!(
                        "{}: the grids differ from {}'s",
                        path.display(),
                        first_path.display()
                    );
                }
                for (i, (a, b)) in sum.sums.iter_mut().zip(&part.sums).enumerate() {
                    if !a.merge(b) {
                        bail!("{}: point {i}: the sum overflows", path.display());
                    }
                }
            }
        }
    }
    let Some((_, part)) = total else {
        bail!("no parts to merge");
    };
    if part
        .sums
        .iter()
        .any(|s| s.count.saturating_add(s.rejected) != first.samples)
    {
        bail!(
            "the parts do not hold {} samples at every point; nothing was written",
            first.samples
        );
    }
    let mf = f64::from(part.maintenance_factor);
    let results: Vec<_> = grid_results(&part.grids, &part.sums, first.samples, 0)
        .into_iter()
        .map(|r| r.scaled(mf))
        .collect();
    write_readings(
        &results,
        &part.unit,
        &part.integrator,
        first.samples,
        crate::measure_cmd::ReadingFiles {
            csv: args.csv.as_deref(),
            json: args.json.as_deref(),
            precision: args.precision,
        },
        None,
    )?;
    if mf != 1.0 {
        println!("maintenance factor {mf}: maintained illuminance");
    }
    for r in &results {
        println!("{}", summary_line(r));
    }
    println!(
        "{} parts, {} integrator, {} samples a point; positions in {}",
        args.parts.len(),
        part.integrator,
        first.samples,
        part.unit
    );
    for path in [&args.csv, &args.json].into_iter().flatten() {
        println!("wrote {}", path.display());
    }
    println!("merged in {:.2} s", started.elapsed().as_secs_f64());
    Ok(())
}
