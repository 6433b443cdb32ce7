//! `atmoscope presets validate|list`.

use crate::presets::{SHIPPED, load_shipped};
use atmoscope_model::Scene;
use std::path::PathBuf;
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
