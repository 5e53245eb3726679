//! The `raygine` binary: a thin shell over [`raygine::run`].

use std::process::ExitCode;

fn main() -> ExitCode {
    raygine::run()
}
