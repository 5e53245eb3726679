//! Shards of `raygine render` and `raygine measure`: shard K of M computes the contiguous
//! sample range ⌊K·N/M⌋ .. ⌊(K+1)·N/M⌋ and writes the exact sums as a part file, which
//! `raygine merge` adds to the others.

use crate::cli::{MeasureArgs, RenderArgs};
use crate::cli_shards::ShardArgs;
use crate::cli_support::{check_output_path, thread_pool};
use anyhow::{Result, bail};
use std::path::Path;
use std::time::Instant;
use tracer_core::measure::partial::MeasurePart;
use tracer_core::measure::{MeasureSettings, measure_samples};
use tracer_core::render::{RenderSettings, partial, render_samples};
use tracer_core::scene::LoadedScene;
use tracer_core::shard::{PartHeader, PartKind, Shard, scene_hash, write_part};

/// The raygine version parts record; parts of other versions are not merged.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The shard the options name, after refusing the options a shard cannot honour (each given as
/// (whether it was given, its name)).
fn shard_of<'a>(
    args: &'a ShardArgs,
    samples: u32,
    refused: &[(bool, &str)],
) -> Result<(Shard, &'a Path)> {
    if let Some((_, name)) = refused.iter().find(|(given, _)| *given) {
        bail!(
            "{name} cannot be used with --shard-index/--shard-count: a shard writes only its part \
             file (--partial); `raygine merge` writes the results"
        );
    }
    let (Some(index), Some(count), Some(path)) =
        (args.shard_index, args.shard_count, args.partial.as_deref())
    else {
        bail!("a shard needs --shard-index K, --shard-count M and --partial PATH");
    };
    let shard = Shard::new(index, count, samples)?;
    check_output_path(path)?;
    Ok((shard, path))
}

/// `raygine render ... --shard-index K --shard-count M --partial PATH`.
pub fn render_part(
    args: &RenderArgs,
    loaded: &LoadedScene,
    settings: &RenderSettings,
) -> Result<()> {
    let started = Instant::now();
    let d = &args.display;
    let (shard, path) = shard_of(
        &args.shard,
        settings.samples_per_pixel,
        &[
            (args.render_path.is_some(), "-R/--render_path"),
            (args.exr.is_some(), "--exr"),
            (args.scene.time_limit.is_some(), "--time-limit"),
            (args.target_error.is_some(), "--target-error"),
            (d.exposure.is_some(), "--exposure"),
            (d.auto_exposure, "--auto-exposure"),
        ],
    )?;
    let range = shard.samples(settings.samples_per_pixel);
    let pool = thread_pool(&args.scene)?;
    let (film, stats) =
        pool.install(|| render_samples(&loaded.scene, &loaded.setup, settings, range.clone()));
    if film.rejected_samples() > 0 {
        bail!(
            "{} samples were not finite or beyond the film's range; nothing was written",
            film.rejected_samples()
        );
    }
    let header = PartHeader {
        kind: PartKind::Render,
        version: VERSION.to_owned(),
        scene: loaded.scene.name.clone(),
        scene_hash: scene_hash(&loaded.scene, &loaded.setup),
        settings: partial::settings_line(settings),
        samples: settings.samples_per_pixel,
        shard,
    };
    write_part(path, &header, &partial::encode_film(&film))?;
    println!(
        "{}: shard {} of {}, samples {}..{} of {}, {}; rendered in {:.1} s, {:.2} Mrays/s, {} threads",
        loaded.scene.name,
        shard.index,
        shard.count,
        range.start,
        range.end,
        settings.samples_per_pixel,
        header.settings,
        stats.elapsed_secs,
        stats.mrays_per_sec(),
        pool.current_num_threads()
    );
    println!(
        "wrote {} ({:.1} s in all)",
        path.display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// `raygine measure ... --shard-index K --shard-count M --partial PATH`.
pub fn measure_part(
    args: &MeasureArgs,
    loaded: &LoadedScene,
    settings: &MeasureSettings,
) -> Result<()> {
    let started = Instant::now();
    let (shard, path) = shard_of(
        &args.shard,
        settings.samples,
        &[
            (args.csv.is_some(), "--csv"),
            (args.json.is_some(), "--json"),
            (args.scene.time_limit.is_some(), "--time-limit"),
            (args.target_error.is_some(), "--target-error"),
        ],
    )?;
    let range = shard.samples(settings.samples);
    let pool = thread_pool(&args.scene)?;
    let (sums, _rays) =
        pool.install(|| measure_samples(&loaded.scene, &loaded.setup, settings, range.clone()));
    let part = MeasurePart {
        unit: loaded.setup.unit.symbol().to_owned(),
        integrator: settings.integrator.name().to_owned(),
        maintenance_factor: loaded.setup.maintenance_factor,
        grids: loaded.setup.grids.clone(),
        sums,
    };
    let header = PartHeader {
        kind: PartKind::Measure,
        version: VERSION.to_owned(),
        scene: loaded.scene.name.clone(),
        scene_hash: scene_hash(&loaded.scene, &loaded.setup),
        settings: tracer_core::measure::partial::settings_line(settings),
        samples: settings.samples,
        shard,
    };
    write_part(path, &header, &part.encode())?;
    println!(
        "{}: shard {} of {}, samples {}..{} of {} at {} grid points, {}; {:.1} s",
        loaded.scene.name,
        shard.index,
        shard.count,
        range.start,
        range.end,
        settings.samples,
        part.sums.len(),
        header.settings,
        started.elapsed().as_secs_f64()
    );
    println!("wrote {}", path.display());
    Ok(())
}
