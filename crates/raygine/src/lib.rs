//! raygine, the application: the interactive viewer and the headless commands (`render`,
//! `measure`, `merge`, `sweep`, `info`). Both are thin shells that turn user intent into
//! `tracer-core` calls.
//!
//! The viewer is the `viewer` feature (on by default). Built without it
//! (`--no-default-features`), raygine is the command line alone, for cluster nodes: no eframe,
//! egui, rfd, glow, winit or any window-system or OpenGL library in its dependency tree.

// The command line: every build.
pub mod cli;
pub mod cli_args;
pub mod cli_shards;
pub mod cli_support;
pub mod format;
pub mod glare_cmd;
pub mod info_cmd;
pub mod measure_cmd;
pub mod merge_cmd;
pub mod picture_hints;
pub mod render_cmd;
pub mod report_cmd;
pub mod report_pdf;
pub mod shard_cmd;
pub mod sweep_cmd;
pub mod sweep_variants;

// The viewer: builds with the `viewer` feature.
#[cfg(feature = "viewer")]
pub mod app;
#[cfg(feature = "viewer")]
pub mod backdrop;
#[cfg(feature = "viewer")]
pub mod background_job;
#[cfg(feature = "viewer")]
pub mod banners;
#[cfg(feature = "viewer")]
pub mod camera_control;
#[cfg(feature = "viewer")]
pub mod command;
#[cfg(feature = "viewer")]
pub mod denoise_view;
#[cfg(feature = "viewer")]
pub mod document;
#[cfg(feature = "viewer")]
pub mod file_ops;
#[cfg(feature = "viewer")]
pub mod frame_stats;
#[cfg(feature = "viewer")]
pub mod glare_worker;
#[cfg(feature = "viewer")]
pub mod grid_overlay;
#[cfg(feature = "viewer")]
pub mod history;
#[cfg(feature = "viewer")]
pub mod luminance_meter;
#[cfg(feature = "viewer")]
pub mod map_thumbnail;
#[cfg(feature = "viewer")]
pub mod measure_worker;
#[cfg(feature = "viewer")]
pub mod panels;
#[cfg(feature = "viewer")]
pub mod prefs;
#[cfg(feature = "viewer")]
pub mod render_image;
#[cfg(feature = "viewer")]
pub mod render_worker;
#[cfg(feature = "viewer")]
pub mod report;
#[cfg(feature = "viewer")]
pub mod scene_exposure;
#[cfg(feature = "viewer")]
pub mod shortcuts;
#[cfg(feature = "viewer")]
pub mod unsaved;
#[cfg(feature = "viewer")]
pub mod viewer;
#[cfg(feature = "viewer")]
pub mod viewport_draw;
#[cfg(feature = "viewer")]
pub mod viewport_ui;

use clap::Parser;
use std::process::ExitCode;

/// Parses the command line and runs what it asks for. Errors print one line on stderr and give a
/// non-zero exit code; nothing panics on bad input.
pub fn run() -> ExitCode {
    let args = cli::Cli::parse();
    let result = match args.command {
        Some(cli::Command::Render(render)) => render_cmd::run(&render),
        Some(cli::Command::Measure(measure)) => measure_cmd::run(&measure),
        Some(cli::Command::Info(info)) => info_cmd::run(&info),
        Some(cli::Command::Glare(glare)) => glare_cmd::run(&glare),
        Some(cli::Command::Merge(merge)) => merge_cmd::run(&merge),
        Some(cli::Command::Sweep(sweep)) => sweep_cmd::run(&sweep),
        Some(cli::Command::Report(report)) => report_cmd::run(&report),
        None => open_viewer(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

/// `raygine [SCENE]`: the viewer's window.
#[cfg(feature = "viewer")]
fn open_viewer(args: &cli::Cli) -> anyhow::Result<()> {
    viewer::run_viewer(app::AppOptions {
        scene: args.scene.clone(),
        threads: args.threads.unwrap_or(0) as usize,
        ignore_last_scene: args.no_restore,
        unit: args.units,
    })
}

/// `raygine [SCENE]` in a headless build: says what this build can do instead.
#[cfg(not(feature = "viewer"))]
fn open_viewer(_args: &cli::Cli) -> anyhow::Result<()> {
    anyhow::bail!(
        "this raygine is the headless build (built without the `viewer` feature): it has no \
         window; use `raygine render`, `measure`, `merge`, `sweep` or `info` (see `raygine --help`)"
    )
}
