//! raygine, the application: the interactive viewer and the headless `render` command.
//! Both are thin shells that turn user intent into `tracer-core` calls.

pub mod cli;
pub mod render_cmd;

use clap::Parser;
use std::process::ExitCode;

/// Parses the command line and runs what it asks for. Errors print one line on stderr and give a
/// non-zero exit code; nothing panics on bad input.
pub fn run() -> ExitCode {
    let args = cli::Cli::parse();
    let result = match args.command {
        Some(cli::Command::Render(render)) => render_cmd::run(&render),
        None => render_cmd::run_default(args.scene.as_deref()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
