//! `atmoscope`: without arguments it opens the explorer on the default scene; subcommands
//! work headless on the same model (see `atmoscope --help`).

mod bench_results;
mod cache;
mod cli;
mod gui;
mod images;
mod lessons;
mod presets;
mod source_key;
mod summary;
mod timelapse;

use clap::Parser;

fn main() -> std::process::ExitCode {
    let args = cli::Cli::parse();
    let result = match args.command {
        None => gui::run(args.scene),
        Some(command) => cli::run(command),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::FAILURE
        }
    }
}
