//! raygine, the application: the interactive viewer and the headless `render` command.
//! Both are thin shells that turn user intent into `tracer-core` calls.

pub mod app;
pub mod backdrop;
pub mod banners;
pub mod camera_control;
pub mod cli;
pub mod cli_args;
pub mod cli_shards;
pub mod cli_support;
pub mod command;
pub mod document;
pub mod file_ops;
pub mod format;
pub mod frame_stats;
pub mod grid_overlay;
pub mod history;
pub mod info_cmd;
pub mod luminance_meter;
pub mod measure_cmd;
pub mod measure_worker;
pub mod merge_cmd;
pub mod panels;
pub mod picture_hints;
pub mod prefs;
pub mod render_cmd;
pub mod render_image;
pub mod render_worker;
pub mod report;
pub mod shard_cmd;
pub mod shortcuts;
pub mod sweep_cmd;
pub mod sweep_variants;
pub mod unsaved;
pub mod viewer;
pub mod viewport_draw;
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
        Some(cli::Command::Merge(merge)) => merge_cmd::run(&merge),
        Some(cli::Command::Sweep(sweep)) => sweep_cmd::run(&sweep),
        None => viewer::run_viewer(app::AppOptions {
            scene: args.scene.clone(),
            threads: args.threads.unwrap_or(0) as usize,
            ignore_last_scene: args.no_restore,
            unit: args.units,
        }),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
