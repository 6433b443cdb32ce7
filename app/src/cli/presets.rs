//! `atmoscope presets validate|list|gallery`.

use crate::cli::common::gpu;
use crate::images::save_rgb8;
use crate::presets::{SHIPPED, load_shipped};
use anyhow::Context;
use atmoscope_model::Scene;
use atmoscope_model::camera::Projection;
use atmoscope_render::{Engine, View};
use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

pub fn validate(files: &[PathBuf]) -> anyhow::Result<ExitCode> {
    let mut failures = 0;
    let mut report =
        |label: String, result: Result<Scene, atmoscope_model::SceneError>| match result {
            Ok(scene) => println!("ok    {label}  ({})", scene.name),
            Err(e) => {
                failures += 1;
                println!("FAIL  {e}");
            }
        };
    if files.is_empty() {
        for (name, _) in SHIPPED {
            let result =
                load_shipped(name).unwrap_or_else(|| unreachable!("name comes from the list"));
            report(format!("presets/{name}"), result);
        }
    } else {
        for f in files {
            report(f.display().to_string(), Scene::load(f));
        }
    }
    let total = if files.is_empty() {
        SHIPPED.len()
    } else {
        files.len()
    };
    println!("{} valid, {failures} invalid", total - failures);
    Ok(if failures == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// Renders every shipped preset with its own settings (exposure metered where the preset asks)
/// to `<out>/<preset>.png` and writes `<out>/README.md` with each image, name and description.
pub fn gallery(out: &Path, (width, height): (u32, u32)) -> anyhow::Result<ExitCode> {
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let gpu = gpu()?;
    let mut engine = Engine::new(&gpu.device, &gpu.queue);
    let view = View::new(Projection::Perspective, width, height);
    let mut page = String::from(
        "# Gallery\n\nEvery shipped preset rendered with its own settings by the real-time engine \
         (`atmoscope presets gallery`, which writes this page).\n\n",
    );
    for (name, _) in SHIPPED {
        let scene = load_shipped(name)
            .unwrap_or_else(|| unreachable!("name comes from the list"))
            .with_context(|| format!("presets/{name}"))?;
        let (shown, _) = engine.render_still(&scene, &view)?;
        let rgb = engine
            .read_display()?
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        let stem = name.trim_end_matches(".ron");
        save_rgb8(&out.join(format!("{stem}.png")), rgb, width, height)?;
        let info = atmoscope_model::methods::info(scene.render.method);
        writeln!(
            page,
            "## {}\n\n![{}]({stem}.png)\n\n{} — `{stem}`, {}, {:?}, exposure {:+.1} EV{}.\n",
            scene.name,
            scene.name,
            scene.description,
            info.label,
            scene.display.tone_map,
            shown.display.exposure_ev,
            if scene.display.auto_exposure {
                " (metered)"
            } else {
                ""
            },
        )?;
        eprintln!("{stem}");
    }
    crate::files::write_atomic(&out.join("README.md"), page.as_bytes())?;
    eprintln!(
        "wrote {} images and {}",
        SHIPPED.len(),
        out.join("README.md").display()
    );
    Ok(ExitCode::SUCCESS)
}

pub fn list() -> anyhow::Result<ExitCode> {
    for (name, _) in SHIPPED {
        match load_shipped(name) {
            Some(Ok(s)) => println!("{name:32} {}: {}", s.name, s.description),
            Some(Err(e)) => println!("{name:32} INVALID: {e}"),
            None => {}
        }
    }
    Ok(ExitCode::SUCCESS)
}
