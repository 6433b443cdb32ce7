//! `docs/cli.md` is the command line's own help, every command and subcommand in turn. The
//! test fails when the page and `atmoscope --help` disagree; `UPDATE_DOCS=1` rewrites the page.

use clap::CommandFactory;
use std::path::Path;

/// The help of `command` and of each subcommand below it, depth first, as Markdown.
fn help_pages(command: &mut clap::Command, path: &str, out: &mut String) {
    let name = if path.is_empty() {
        command.get_name().to_string()
    } else {
        format!("{path} {}", command.get_name())
    };
    let help = command.render_long_help().to_string();
    let level = "#".repeat((name.split(' ').count() + 1).min(4));
    out.push_str(&format!(
        "{level} `{name}`\n\n```text\n{}\n```\n\n",
        help.trim_end()
    ));
    for sub in command.get_subcommands_mut() {
        if sub.get_name() != "help" {
            help_pages(sub, &name, out);
        }
    }
}

fn cli_md() -> String {
    let mut out = String::from(
        "# Command line reference\n\n\
         Generated from `atmoscope --help` and the help of every subcommand; a test checks it \
         (regenerate with `UPDATE_DOCS=1 bash tests/run.sh cli_md`). How-tos and what the \
         figures mean are in [guide.md](guide.md) and [benchmarks.md](benchmarks.md).\n\n",
    );
    let mut command = atmoscope::cli::Cli::command();
    command.build();
    help_pages(&mut command, "", &mut out);
    out
}

#[test]
fn docs_cli_md_matches_the_help() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/cli.md");
    let expected = cli_md();
    if std::env::var_os("UPDATE_DOCS").is_some() {
        atmoscope::files::write_atomic(&path, expected.as_bytes()).expect("write docs/cli.md");
        return;
    }
    let actual = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        actual == expected,
        "docs/cli.md is not the CLI's help: regenerate it with `UPDATE_DOCS=1 bash tests/run.sh cli_md`"
    );
}
