//! `atmoscope learn [LESSON]`: the Learn menu's lessons on the command line, for teachers
//! preparing a class: the list, or one lesson's text with its numbers computed for its scene.

use crate::lessons;
use anyhow::bail;
use clap::Args;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct LearnArgs {
    /// A lesson's file name (with or without .ron); without it, the list.
    pub lesson: Option<String>,
}

pub fn run(args: &LearnArgs) -> anyhow::Result<ExitCode> {
    let Some(name) = &args.lesson else {
        let mut failures = 0;
        for (file, lesson) in lessons::shipped() {
            match lesson {
                Ok(l) => println!("{:40} {}", file.trim_end_matches(".ron"), l.title),
                Err(e) => {
                    failures += 1;
                    println!("FAIL  {e}");
                }
            }
        }
        return Ok(if failures == 0 {
            ExitCode::SUCCESS
        } else {
            ExitCode::FAILURE
        });
    };
    let Some(lesson) = lessons::find(name) else {
        let known: Vec<&str> = lessons::shipped()
            .into_iter()
            .map(|(f, _)| f.trim_end_matches(".ron"))
            .collect();
        bail!("no lesson {name}; lessons: {}", known.join(", "));
    };
    let file = format!("{}.ron", name.trim_end_matches(".ron"));
    let lesson = lesson?;
    let scene = lesson.scene(&file)?;
    println!("{}\n", lesson.title);
    println!("{}\n", lesson.text_for(&scene));
    println!("Try ({}): {}", lesson.section.title(), lesson.try_this);
    println!(
        "\nScene: {} with {} change(s); tab {}. Open it in the explorer: Learn > {}",
        lesson.preset,
        lesson.set.len(),
        lesson.tab.label(),
        lesson.title
    );
    Ok(ExitCode::SUCCESS)
}
