//! raybench: raygine's benchmark harness for the workloads of `../shared/BENCHMARK.md`.
//!
//! ```text
//! cargo run --release -p raybench -- core         # build, W1-W3, bytes/tri, L3 (raygine)
//! cargo run --release -p raybench -- render       # the whole `raygine render` command
//! cargo run --release -p raybench -- interactive  # L1, L2, restart storm
//! cargo run --release -p raybench -- scene-dump -S room2.shp --out DIR  # for peer renderers
//! cargo run --release -p raybench --features embree,obvhs -- compare   # beside obvhs, Embree
//! ```
//!
//! Every figure is a median of `--runs` runs (interleaved across libraries) and is printed as one
//! `KIND key=value ...` line carrying `threads=`; tables follow at the end.

#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used))]

mod compare;
mod contender;
mod core;
mod frames;
mod interactive;
mod meshes;
mod peers;
mod render_cmd;
mod report;
mod rng;
mod scene_dump;
mod shared;
mod stats;
mod trace;
mod workloads;

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

#[derive(Debug, Parser)]
#[command(name = "raybench", about = "raygine benchmarks (see BENCHMARK.md)")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Args)]
struct Common {
    /// Runs per figure; the median is reported (at least 5 for quoted figures).
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..))]
    runs: u32,
    /// Thread counts, comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = [1usize, 2])]
    threads: Vec<usize>,
}

#[derive(Debug, Args)]
struct MeshArgs {
    #[command(flatten)]
    common: Common,
    /// Meshes: file stems in scenes/meshes/ or sphere-N, comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = meshes::DEFAULT_MESHES.map(String::from))]
    meshes: Vec<String>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// raygine alone: BVH build, W1-W3 Mrays/s, bytes per triangle, L3 load.
    Core(MeshArgs),
    /// raygine beside obvhs and Embree (features `obvhs`, `embree`), interleaved runs.
    Compare(MeshArgs),
    /// Wall time of `raygine render` on the course Cornell box, 1000x1000, depth 5.
    Render {
        #[command(flatten)]
        common: Common,
        /// The raygine binary (default: target/release/raygine of this workspace).
        #[arg(long)]
        raygine: Option<PathBuf>,
    },
    /// F1 and F2: whole frames of raygine beside Mitsuba 3 (llvm), interleaved, medians.
    Frames {
        /// Runs per figure; the median is reported.
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..))]
        runs: u32,
        /// Render threads of both renderers.
        #[arg(long, default_value_t = 2)]
        threads: usize,
        /// Python with mitsuba and numpy (default: $MITSUBA_PYTHON, else
        /// /work/mitsuba-venv/bin/python when it exists; `none`: raygine alone).
        #[arg(long)]
        python: Option<PathBuf>,
        #[arg(long, default_value_t = 1280)]
        width: u32,
        #[arg(long, default_value_t = 720)]
        height: u32,
        #[arg(long, default_value_t = 16)]
        spp: u32,
        /// Only this workload (F1 or F2), for profiling one scene.
        #[arg(long, value_parser = ["F1", "F2"])]
        only: Option<String>,
    },
    /// Writes the scene raygine loads (triangles.ply and scene.json) for other renderers.
    SceneDump {
        /// Scene file, loaded as `raygine render -S` loads it.
        #[arg(short = 'S', long = "scene")]
        scene: PathBuf,
        /// Sidecar instead of NAME.raygine.toml beside the scene.
        #[arg(long)]
        sidecar: Option<PathBuf>,
        /// Scene length unit: mm, cm or m (default: the sidecar's, else mm).
        #[arg(long)]
        units: Option<tracer_core::scene::LengthUnit>,
        /// Output folder.
        #[arg(long)]
        out: PathBuf,
    },
    /// L1 and L2 after a light move, and the restart storm.
    Interactive {
        #[command(flatten)]
        common: Common,
        /// Snapshots in the restart storm.
        #[arg(long, default_value_t = 1000)]
        changes: usize,
        /// Light transport: direct or path.
        #[arg(long, default_value = "direct", value_parser = parse_integrator)]
        integrator: tracer_core::integrator::IntegratorKind,
        /// Trace the denoiser's guides too, as the viewer does with denoise on.
        #[arg(long)]
        guides: bool,
    },
}

fn mesh_options(args: MeshArgs) -> core::Options {
    core::Options {
        runs: args.common.runs as usize,
        threads: args.common.threads,
        meshes: args.meshes,
    }
}

fn parse_integrator(s: &str) -> Result<tracer_core::integrator::IntegratorKind, String> {
    tracer_core::integrator::IntegratorKind::from_name(s)
        .ok_or_else(|| format!("unknown integrator `{s}` (direct, path)"))
}

fn main() -> anyhow::Result<()> {
    match Cli::parse().command {
        Command::Core(args) => core::run(&mesh_options(args)),
        Command::Compare(args) => compare::run(&mesh_options(args)),
        Command::Render { common, raygine } => render_cmd::run(&render_cmd::Options {
            runs: common.runs as usize,
            threads: common.threads,
            raygine,
        }),
        Command::Frames {
            runs,
            threads,
            python,
            width,
            height,
            spp,
            only,
        } => frames::run(&frames::Options {
            runs: runs as usize,
            threads,
            python: python
                .or_else(|| std::env::var_os("MITSUBA_PYTHON").map(PathBuf::from))
                .or_else(|| {
                    let venv = PathBuf::from("/work/mitsuba-venv/bin/python");
                    venv.exists().then_some(venv)
                })
                .filter(|p| p.as_os_str() != "none"),
            width,
            height,
            spp,
            only,
        }),
        Command::SceneDump {
            scene,
            sidecar,
            units,
            out,
        } => scene_dump::run(&scene_dump::Options {
            scene,
            sidecar,
            units,
            out,
        }),
        Command::Interactive {
            common,
            changes,
            integrator,
            guides,
        } => interactive::run(&interactive::Options {
            runs: common.runs as usize,
            threads: common.threads,
            storm_changes: changes,
            integrator,
            guides,
        }),
    }
}
