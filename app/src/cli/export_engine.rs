//! `atmoscope export-engine --target bevy|unreal|blender`: the scene's atmosphere as the
//! snippet an engine's user pastes (`engine_export`), on stdout or into a file, and how close
//! the engine can come to the scene's full physics, on stderr.

use crate::engine_export::{Target, fidelity, fidelity_table};
use crate::scene_args::SceneArgs;
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct ExportEngineArgs {
    /// The engine: bevy (Rust, bevy 0.16–0.17's Atmosphere), unreal (JSON of the
    /// SkyAtmosphere component's properties) or blender (Python for Blender 5's Sky Texture,
    /// Multiple Scattering).
    #[arg(long, value_enum)]
    pub target: Target,
    /// Write the snippet to FILE (atomically) instead of stdout.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Leave out the ΔE2000 over the view suite (it draws the suite three ways on the CPU:
    /// about 15 s on two cores).
    #[arg(long)]
    pub no_fidelity: bool,
    #[command(flatten)]
    pub scene: SceneArgs,
}

pub fn run(args: &ExportEngineArgs) -> anyhow::Result<ExitCode> {
    let scene = args.scene.scene()?;
    let text = args.target.write(&scene);
    match &args.out {
        Some(path) => {
            crate::files::write_atomic(path, text.as_bytes())?;
            eprintln!("wrote {}", path.display());
        }
        None => print!("{text}"),
    }
    if !args.no_fidelity {
        // What the engine receives is what was written: read it back.
        let exported = args.target.read(&text)?;
        let errors = fidelity(&scene, &exported, atmoscope_model::views::suite(), &|_| {
            true
        });
        eprint!("{}", fidelity_table(args.target, &errors));
    }
    Ok(ExitCode::SUCCESS)
}
