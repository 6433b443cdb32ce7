//! `atmoscope`: without arguments it opens the explorer on the default scene; subcommands
//! work headless on the same model (see `atmoscope --help`).

use clap::Parser;

fn main() -> std::process::ExitCode {
    atmoscope::run(atmoscope::cli::Cli::parse())
}
