//! `atmoscope`: without arguments it opens the explorer on the default scene; subcommands
//! work headless on the same model (see `atmoscope --help`). Built for `wasm32` it is the
//! explorer in a browser page (`web/`).

#[cfg(not(target_arch = "wasm32"))]
use atmoscope::cli::{Cli, Command, bench::Bench};
#[cfg(not(target_arch = "wasm32"))]
use clap::Parser;

/// In a browser: the explorer on the page's canvas (`web/`).
#[cfg(target_arch = "wasm32")]
fn main() {
    atmoscope::web::start();
}

#[cfg(not(target_arch = "wasm32"))]
fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let opens_window = matches!(
        cli.command,
        None | Some(Command::Bench {
            bench: Bench::Gui(_)
        })
    );
    if !opens_window {
        quiet_the_device_select_layer();
    }
    atmoscope::run(cli)
}

/// Mesa's device-select Vulkan layer asks a display server for the GPU to list first, and with
/// no display session it prints "XDG_RUNTIME_DIR is invalid or not set" twice. A headless
/// command chooses its adapter itself (`render::gpu`), so it turns the layer off, unless the
/// user has set `NODEVICE_SELECT` either way.
#[cfg(not(target_arch = "wasm32"))]
fn quiet_the_device_select_layer() {
    if std::env::var_os("NODEVICE_SELECT").is_none() {
        // SAFETY: the first thing `main` does after parsing the arguments, before any thread
        // exists that could read the environment.
        unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    }
}
