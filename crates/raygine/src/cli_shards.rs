//! Command-line options of work spread over machines: shards of `render` and `measure`,
//! `raygine merge` and `raygine sweep`.

use crate::cli_args::{DisplayArgs, SceneArgs};
use clap::Args;
use std::path::PathBuf;

/// `--shard-index K --shard-count M --partial PATH`: render or measure shard K of M of the
/// samples and write the exact sums to PATH instead of images or readings.
#[derive(Debug, Args, Default)]
pub struct ShardArgs {
    /// This shard, 0-based (0..M-1): Slurm's SLURM_ARRAY_TASK_ID with --array=0-(M-1), or
    /// Kubernetes' JOB_COMPLETION_INDEX. Needs --shard-count and --partial.
    #[arg(long, value_name = "K", requires_all = ["shard_count", "partial"])]
    pub shard_index: Option<u32>,
    /// Number of shards M: shard K takes the samples ⌊K·N/M⌋ .. ⌊(K+1)·N/M⌋ of N.
    #[arg(long, value_name = "M", requires_all = ["shard_index", "partial"])]
    pub shard_count: Option<u32>,
    /// Part file to write (exact sums; `raygine merge` adds the parts).
    #[arg(long, value_name = "PATH", requires_all = ["shard_index", "shard_count"])]
    pub partial: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct MergeArgs {
    /// Part files written by `raygine render` or `raygine measure` with --partial: all M shards
    /// of one render (or measurement), in any order.
    #[arg(required = true, value_name = "PART")]
    pub parts: Vec<PathBuf>,
    /// Render parts: the PNG to write.
    #[arg(
        short = 'R',
        long = "render_path",
        visible_alias = "render-path",
        value_name = "PATH"
    )]
    pub render_path: Option<PathBuf>,
    /// Render parts: also write the linear image (cd/m² per channel) as OpenEXR.
    #[arg(long, value_name = "PATH")]
    pub exr: Option<PathBuf>,
    /// Render parts: denoise the PNG (and add denoised.R, .G, .B to the EXR); the parts must
    /// have been rendered with --denoise, which keeps the denoiser's guides in them.
    #[arg(long)]
    pub denoise: bool,
    #[command(flatten)]
    pub display: DisplayArgs,
    /// Measurement parts: write every grid point's illuminance here (CSV).
    #[arg(long, value_name = "PATH")]
    pub csv: Option<PathBuf>,
    /// Measurement parts: write the statistics and every point here (JSON).
    #[arg(long, value_name = "PATH")]
    pub json: Option<PathBuf>,
    /// How the CSV and JSON write readings: `rounded` (default) or `full` (every digit).
    #[arg(long, value_name = "rounded|full", default_value = "rounded", value_parser = crate::cli::parse_precision)]
    pub precision: tracer_core::measure::rounding::Precision,
}

#[derive(Debug, Args)]
#[command(allow_negative_numbers = true)]
pub struct SweepArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The variants: `[[variants]]` tables, each with an optional `name` and a `patch` table
    /// merged over the scene's sidecar.
    #[arg(long, value_name = "PATH")]
    pub variants: PathBuf,
    /// Run only variant I (0-based), writing DIR/sweep-I.csv: one task of a job array.
    #[arg(long, value_name = "I", conflicts_with = "collect")]
    pub variant: Option<u32>,
    /// Also measure the sidecar's grids of every variant (the rows of sweep.csv).
    #[arg(long)]
    pub measure: bool,
    /// Write no images (with --measure: readings only).
    #[arg(long, requires = "measure")]
    pub no_images: bool,
    /// Combine the DIR/sweep-I.csv of runs with --variant into DIR/sweep.csv (nothing is
    /// rendered; every variant's file must be there).
    #[arg(long)]
    pub collect: bool,
    /// Folder for the images and CSV files (made when missing).
    #[arg(long, value_name = "DIR", default_value = "sweep")]
    pub out: PathBuf,
    /// Also write each variant's linear image as OpenEXR beside its PNG.
    #[arg(long)]
    pub exr: bool,
    /// Image width in pixels.
    #[arg(short = 'W', long, default_value_t = 1280, value_parser = clap::value_parser!(u32).range(1..=16384))]
    pub width: u32,
    /// Image height in pixels.
    #[arg(short = 'H', long, default_value_t = 720, value_parser = clap::value_parser!(u32).range(1..=16384))]
    pub height: u32,
    /// Maximum mirror reflection depth (direct mode).
    #[arg(long, default_value_t = tracer_core::render::DEFAULT_MAX_DEPTH, value_parser = clap::value_parser!(u32).range(0..=64))]
    pub depth: u32,
    #[command(flatten)]
    pub display: DisplayArgs,
}
