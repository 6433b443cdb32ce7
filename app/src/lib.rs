//! Atmoscope's app as a library: the egui explorer (`gui`), the headless subcommands (`cli`),
//! and what both use. `main.rs` only parses the command line and calls [`run`]; tests drive the
//! app through this library.
//!
//! In a browser (`wasm32`) the library is the explorer alone, started by `web::start`: the
//! subcommands are native only.
//!
//! Modules import downward: `cli` and `gui` use the root modules and never each other; no
//! subcommand imports another (their shared helpers are `cli::common`, `cli::progress` and
//! `cli::sky_probe`).

pub mod args;
pub mod bench_results;
pub mod cache;
pub mod chart_style;
#[cfg(not(target_arch = "wasm32"))]
pub mod cli;
pub mod engine_export;
pub mod engine_setup;
pub mod files;
pub mod gui;
pub mod gui_bench;
pub mod images;
pub mod lessons;
pub mod presets;
pub mod scene_args;
pub mod shipped;
pub mod source_key;
pub mod summary;
pub mod tab;
pub mod timelapse;
#[cfg(target_arch = "wasm32")]
pub mod web;

#[cfg(not(target_arch = "wasm32"))]
use std::process::ExitCode;

/// The web page's query parameter `name` (`?name=value`); None natively.
pub fn web_query(name: &str) -> Option<String> {
    #[cfg(target_arch = "wasm32")]
    return web::query(name);
    #[cfg(not(target_arch = "wasm32"))]
    {
        let _ = name;
        None
    }
}

/// Runs the app for parsed command-line arguments: the explorer without a subcommand, else the
/// subcommand. An error is printed with its causes and exits with failure.
#[cfg(not(target_arch = "wasm32"))]
pub fn run(args: cli::Cli) -> ExitCode {
    let result = match args.command {
        None => gui::run(args.scene),
        // The one subcommand that opens the window: a scripted session of the explorer.
        Some(cli::Command::Bench {
            bench: cli::bench::Bench::Gui(bench),
        }) => gui::scripted::run(bench),
        Some(command) => cli::run(command),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
