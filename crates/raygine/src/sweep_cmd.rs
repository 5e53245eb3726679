//! `raygine sweep`: render (and measure) every variant of a scene, each its sidecar with a
//! patch, into an image series and `sweep.csv`. `--variant I` runs one variant (one task of a
//! job array) and writes `sweep-I.csv`; `--collect` joins those files, in variant order, into
//! the same `sweep.csv` one run of every variant writes.

use crate::cli_shards::SweepArgs;
use crate::cli_support::{
    display_settings, load_scene, sampling_settings, thread_pool, write_images,
};
use crate::sweep_variants::{Variant, patched, read_variants};
use anyhow::{Context, Result, bail};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use tracer_core::measure::{MeasureSettings, measure_grids};
use tracer_core::render::{RenderSettings, render_for};
use tracer_core::scene::{LoadedScene, Setup, Sidecar, sidecar_path};

/// The header of sweep.csv, exactly.
pub const SWEEP_HEADER: &str = "variant,grid,e_min_lx,e_avg_lx,e_max_lx,u0,emin_over_emax";

pub fn run(args: &SweepArgs) -> Result<()> {
    let started = Instant::now();
    let variants = read_variants(&args.variants).map_err(anyhow::Error::msg)?;
    if args.collect {
        return collect(args, &variants);
    }
    let chosen: Vec<usize> = match args.variant {
        Some(i) if i as usize >= variants.len() => bail!(
            "{}: --variant {i}, but the file has {} variants (0..{})",
            args.variants.display(),
            variants.len(),
            variants.len()
        ),
        Some(i) => vec![i as usize],
        None => (0..variants.len()).collect(),
    };
    let loaded = load_scene(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let (base, base_path) = base_sidecar(args, &loaded)?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("{}: cannot make the folder", args.out.display()))?;
    let display = display_settings(&args.display)?;
    let settings = RenderSettings {
        width: args.width,
        height: args.height,
        max_depth: args.depth,
        // The images show luminance only; --measure measures grids separately.
        pixel_illuminance: false,
        ..sampling_settings(&args.scene, 1)
    };
    let time_limit = args.scene.time_limit.map(Duration::from_secs_f64);
    let pool = thread_pool(&args.scene)?;
    let mut rows = String::new();
    for &i in &chosen {
        let variant = &variants[i];
        let setup = variant_setup(args, &loaded, &base, &base_path, i, variant)?;
        if let Err(e) = args
            .scene
            .integrator
            .check_projection(setup.camera.projection)
        {
            bail!("variant {i}: {e}");
        }
        if args.measure && setup.grids.is_empty() {
            bail!(
                "variant {i} ({}): --measure, but its sidecar has no [[grids]]",
                variant.name
            );
        }
        if !args.no_images {
            let (film, stats) =
                pool.install(|| render_for(&loaded.scene, &setup, &settings, time_limit));
            if film.rejected_samples() > 0 {
                bail!(
                    "variant {i} ({}): {} samples were not finite or beyond the film's range",
                    variant.name,
                    film.rejected_samples()
                );
            }
            let png = args.out.join(format!("{}.png", variant.name));
            let exr = args
                .exr
                .then(|| args.out.join(format!("{}.exr", variant.name)));
            write_images(&film, &display, &png, exr.as_deref(), &pool, None)?;
            println!(
                "variant {i} ({}): {} spp in {:.1} s, wrote {}",
                variant.name,
                stats.samples_per_pixel,
                stats.elapsed_secs,
                png.display()
            );
        }
        if args.measure {
            rows.push_str(&measure_rows(args, &loaded, &setup, i, variant, &pool)?);
        }
    }
    if args.measure {
        let csv = match args.variant {
            Some(i) => args.out.join(format!("sweep-{i}.csv")),
            None => args.out.join("sweep.csv"),
        };
        tracer_core::export::write_text(&csv, &format!("{SWEEP_HEADER}\n{rows}"))
            .with_context(|| format!("{}: cannot write the CSV", csv.display()))?;
        println!("wrote {}", csv.display());
    }
    println!(
        "{} of {} variants in {:.1} s",
        chosen.len(),
        variants.len(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The sidecar the variants patch, as TOML, and the path it is read from (luminaire files are
/// relative to it): `--sidecar`, else the scene's `NAME.raygine.toml` (empty when absent); the
/// built-in scene's own sidecar without either.
fn base_sidecar(args: &SweepArgs, loaded: &LoadedScene) -> Result<(toml::Table, PathBuf)> {
    let path = match (&args.scene.sidecar, &args.scene.scene_path) {
        (Some(p), _) => p.clone(),
        (None, Some(scene)) => sidecar_path(scene),
        (None, None) => {
            let text = Sidecar::from_setup(&loaded.scene, &loaded.setup).to_toml();
            let table = toml::from_str(&text).context("the built-in scene's sidecar")?;
            return Ok((table, PathBuf::from("cornell_box.raygine.toml")));
        }
    };
    let text = match std::fs::read_to_string(&path) {
        Ok(text) => text,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound && args.scene.sidecar.is_none() => {
            String::new()
        }
        Err(e) => bail!("{}: cannot read the sidecar: {e}", path.display()),
    };
    let table = toml::from_str(&text)
        .map_err(|e| anyhow::anyhow!("{}: {}", path.display(), e.message()))?;
    Ok((table, path))
}

/// The setup of variant `i`: the base sidecar with its patch, applied as a sidecar is.
fn variant_setup(
    args: &SweepArgs,
    loaded: &LoadedScene,
    base: &toml::Table,
    base_path: &Path,
    i: usize,
    variant: &Variant,
) -> Result<Setup> {
    let text = toml::to_string(&patched(base, &variant.patch))
        .with_context(|| format!("variant {i} ({})", variant.name))?;
    let sidecar = Sidecar::parse(&text, base_path).map_err(|e| {
        anyhow::anyhow!(
            "{}: variant {i} ({}): {e}",
            args.variants.display(),
            variant.name
        )
    })?;
    let mut warnings = Vec::new();
    let setup = sidecar.apply(&loaded.scene, args.scene.units, &mut warnings);
    for w in &warnings {
        eprintln!("warning: variant {i} ({}): {w}", variant.name);
    }
    Ok(setup)
}

/// Measures the grids of one variant: its rows of sweep.csv (maintained values).
fn measure_rows(
    args: &SweepArgs,
    loaded: &LoadedScene,
    setup: &Setup,
    i: usize,
    variant: &Variant,
    pool: &rayon::ThreadPool,
) -> Result<String> {
    let settings = MeasureSettings {
        integrator: args.scene.integrator,
        max_bounces: args.scene.max_bounces,
        samples: args.scene.samples_or(1),
        time_limit: args.scene.time_limit.map(Duration::from_secs_f64),
        target_error: None,
    };
    let mf = f64::from(setup.maintenance_factor);
    let results = pool.install(|| measure_grids(&loaded.scene, setup, &settings));
    let mut rows = String::new();
    for r in results.into_iter().map(|r| r.scaled(mf)) {
        let s = r.statistics();
        let _ = writeln!(
            rows,
            "{},{},{},{},{},{},{}",
            variant.name, r.name, s.e_min_lx, s.e_avg_lx, s.e_max_lx, s.u0, s.emin_over_emax
        );
        println!(
            "variant {i} ({}): {}",
            variant.name,
            crate::measure_cmd::summary_line(&r)
        );
    }
    Ok(rows)
}

/// `--collect`: DIR/sweep-0.csv … DIR/sweep-(n−1).csv, in order, into DIR/sweep.csv.
fn collect(args: &SweepArgs, variants: &[Variant]) -> Result<()> {
    let mut out = format!("{SWEEP_HEADER}\n");
    for (i, variant) in variants.iter().enumerate() {
        let path = args.out.join(format!("sweep-{i}.csv"));
        let text = std::fs::read_to_string(&path).with_context(|| {
            format!(
                "{}: variant {i} ({}) is missing (run it with --variant {i} --measure)",
                path.display(),
                variant.name
            )
        })?;
        let mut lines = text.lines();
        if lines.next() != Some(SWEEP_HEADER) {
            bail!("{}: not a sweep CSV (the header differs)", path.display());
        }
        for line in lines {
            if line.split(',').next() != Some(variant.name.as_str()) {
                bail!(
                    "{}: a row of another variant than {i} ({}): {line}",
                    path.display(),
                    variant.name
                );
            }
            out.push_str(line);
            out.push('\n');
        }
    }
    let path = args.out.join("sweep.csv");
    tracer_core::export::write_text(&path, &out)
        .with_context(|| format!("{}: cannot write the CSV", path.display()))?;
    println!("wrote {} ({} variants)", path.display(), variants.len());
    Ok(())
}
