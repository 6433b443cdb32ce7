//! What the README and the guide say about the app is what the app does. Each fact they state
//! (the tabs' keys, that the tour visits every tab, the number of lessons, the models' ids, the
//! default scene, the keys of the shortcuts they name, the commands they show) is checked here
//! against the app's own tables, so the next tab, lesson or model cannot leave them behind.

use atmoscope::cli::Cli;
use atmoscope::gui::help::SHORTCUTS;
use atmoscope::tab::Tab;
use atmoscope_model::Scene;
use atmoscope_model::methods::{self, MODELS};
use clap::Parser;

const README: &str = include_str!("../../README.md");
const GUIDE: &str = include_str!("../../docs/guide.md");

/// The text of the section under the heading `heading` (any level), to the next heading; a
/// `#` line inside a fenced block is not a heading.
fn section<'a>(text: &'a str, heading: &str) -> &'a str {
    let mut fenced = false;
    let mut at = 0;
    let mut start = None;
    for line in text.split_inclusive('\n') {
        if line.starts_with("```") {
            fenced = !fenced;
        } else if !fenced && line.starts_with('#') {
            if let Some(start) = start {
                return &text[start..at];
            }
            if line.trim_start_matches('#').trim() == heading {
                start = Some(at + line.len());
            }
        }
        at += line.len();
    }
    let start = start.unwrap_or_else(|| panic!("no section \"{heading}\""));
    &text[start..]
}

/// The words between `**` pairs, each with the text that follows it up to the next `**`.
fn bold_phrases(text: &str) -> Vec<(&str, &str)> {
    let parts: Vec<&str> = text.split("**").collect();
    parts
        .iter()
        .enumerate()
        .filter(|(i, _)| i % 2 == 1)
        .map(|(i, bold)| (*bold, parts.get(i + 1).copied().unwrap_or("")))
        .collect()
}

/// "one" to "twenty" as a number.
fn number_word(word: &str) -> Option<usize> {
    const WORDS: [&str; 20] = [
        "one",
        "two",
        "three",
        "four",
        "five",
        "six",
        "seven",
        "eight",
        "nine",
        "ten",
        "eleven",
        "twelve",
        "thirteen",
        "fourteen",
        "fifteen",
        "sixteen",
        "seventeen",
        "eighteen",
        "nineteen",
        "twenty",
    ];
    WORDS
        .iter()
        .position(|w| w.eq_ignore_ascii_case(word))
        .map(|i| i + 1)
}

/// The word after `phrase` in `text`, as a number.
fn count_after(text: &str, phrase: &str) -> usize {
    let at = text
        .find(phrase)
        .unwrap_or_else(|| panic!("the text no longer says \"{phrase}\""));
    let word = text[at + phrase.len()..]
        .split_whitespace()
        .next()
        .unwrap_or("");
    number_word(word).unwrap_or_else(|| panic!("\"{phrase} {word}\": not a number word"))
}

/// The key that opens `tab`, as the Help menu and the README write it.
fn key_of(tab: Tab) -> usize {
    Tab::ALL.iter().position(|t| *t == tab).expect("every tab") + 1
}

/// Every "**Tab** (key N)" or "**Tab** tab (key N)" in `text` names the key that opens that
/// tab; the tabs given a key.
fn check_tab_keys(text: &str, file: &str) -> Vec<Tab> {
    let mut checked = Vec::new();
    for (bold, after) in bold_phrases(text) {
        let Some(rest) = after
            .strip_prefix(" (key ")
            .or_else(|| after.strip_prefix(" tab (key "))
        else {
            continue;
        };
        let said: usize = rest
            .split(')')
            .next()
            .and_then(|n| n.trim().parse().ok())
            .unwrap_or_else(|| panic!("{file}: \"**{bold}** (key {rest:.8}…\": not a key"));
        let tab = Tab::ALL
            .into_iter()
            .find(|t| t.label() == bold)
            .unwrap_or_else(|| panic!("{file}: \"**{bold}**\" is given a key but is no tab"));
        assert_eq!(
            said,
            key_of(tab),
            "{file} says the {bold} tab is key {said}; the app opens it with {}",
            key_of(tab)
        );
        checked.push(tab);
    }
    checked
}

#[test]
fn the_readme_gives_each_tab_the_key_that_opens_it() {
    let checked = check_tab_keys(README, "README.md");
    let without_key: Vec<&str> = Tab::ALL
        .iter()
        .filter(|t| !checked.contains(t))
        .map(|t| t.label())
        .collect();
    assert!(
        without_key.is_empty(),
        "the README gives no key for the tabs {without_key:?}"
    );
}

#[test]
fn the_tour_visits_every_tab() {
    let tour = section(README, "A five-minute tour");
    let named: Vec<&str> = bold_phrases(tour).into_iter().map(|(b, _)| b).collect();
    let missing: Vec<&str> = Tab::ALL
        .iter()
        .map(|t| t.label())
        .filter(|label| !named.contains(label))
        .collect();
    assert!(
        missing.is_empty(),
        "the README's tour never names (in bold) the tabs {missing:?}"
    );
}

#[test]
fn the_readme_and_the_guide_count_the_lessons_of_the_learn_menu() {
    let lessons = atmoscope::lessons::shipped().len();
    assert_eq!(
        count_after(README, "The Learn menu has"),
        lessons,
        "README.md's count of lessons"
    );
    let learn = section(GUIDE, "Learn");
    assert_eq!(
        count_after(learn, "The Learn menu holds"),
        lessons,
        "docs/guide.md's count of lessons"
    );
    let listed = learn.split("guided scenes:").nth(1).map_or(0, |list| {
        list.lines()
            .skip_while(|l| l.trim().is_empty())
            .take_while(|l| l.starts_with("- "))
            .count()
    });
    assert_eq!(listed, lessons, "docs/guide.md's list of lessons");
}

#[test]
fn the_readme_s_table_of_models_lists_every_id_and_only_ids_that_run() {
    let table = section(README, "Sky models");
    // The ids of each row's second column, notes in parentheses aside; "`a`, `b`, each also
    // with `-ms`" names a-ms and b-ms as well.
    let mut ids: Vec<String> = Vec::new();
    for row in table.lines().filter(|l| l.starts_with("| [")) {
        let cell = row.split('|').nth(2).expect("an id column");
        // What stands in parentheses is a note (where an id runs), not an id.
        let mut column = String::new();
        let mut depth = 0;
        for c in cell.chars() {
            match c {
                '(' => depth += 1,
                ')' => depth -= 1,
                c if depth == 0 => column.push(c),
                _ => {}
            }
        }
        let (before, after) = column
            .split_once("each also with `-ms`")
            .unwrap_or(("", &column));
        let quoted = |text: &str| -> Vec<String> {
            text.split('`')
                .skip(1)
                .step_by(2)
                .map(str::to_string)
                .collect()
        };
        for id in quoted(before) {
            ids.push(format!("{id}-ms"));
            ids.push(id);
        }
        ids.extend(quoted(after));
    }
    for model in MODELS {
        assert!(
            ids.iter().any(|id| id == model.id),
            "the README's table of models leaves out `{}`",
            model.id
        );
    }
    for id in &ids {
        let args = [
            "atmoscope",
            "probe",
            "--method",
            id.as_str(),
            "--view-zenith-deg",
            "0",
            "--view-azimuth-deg",
            "0",
        ];
        assert!(
            Cli::try_parse_from(args).is_ok(),
            "the README's table of models names `{id}`, which `probe --method` refuses"
        );
    }
}

#[test]
fn the_readme_names_the_default_model_wavelengths_and_quality() {
    let render = Scene::default().render;
    let said = format!(
        "The default is `{}` at {}",
        methods::info(render.method).id,
        render.wavelengths.label()
    );
    let quality = format!("{:?} quality", render.quality).to_lowercase();
    let text = section(README, "Sky models");
    let joined = text.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        joined.contains(&said) && joined.contains(&quality),
        "the README should say \"{said} (…), {quality}\""
    );
}

#[test]
fn every_shortcut_the_readme_names_is_one_of_the_help_menu() {
    let keys: Vec<&str> = SHORTCUTS
        .iter()
        .flat_map(|(keys, _)| keys.split(" / "))
        .collect();
    let mut named = 0;
    for word in README.split(|c: char| c.is_whitespace() || ",.;()".contains(c)) {
        if word.starts_with("Ctrl+") {
            assert!(
                keys.contains(&word),
                "the README names {word}, which the Help menu does not list"
            );
            named += 1;
        }
    }
    assert!(named > 0, "the README names no shortcut");
}

/// The command lines of the fenced blocks of `text` that start with `atmoscope `, each as its
/// words up to a `#` comment, a word's shell quotes taken off (no example quotes a space). A
/// synopsis (`[--out FILE]`, `bevy|unreal`) is not a command and is left out.
fn shown_commands(text: &str) -> Vec<Vec<&str>> {
    text.split("```")
        .skip(1)
        .step_by(2)
        .flat_map(str::lines)
        .filter(|l| l.starts_with("atmoscope ") && !l.contains('[') && !l.contains('|'))
        .map(|l| {
            l.split(" #")
                .next()
                .unwrap_or("")
                .split_whitespace()
                .map(|w| w.trim_matches('\''))
                .collect()
        })
        .collect()
}

#[test]
fn every_command_the_readme_and_the_guide_show_parses_and_its_presets_are_shipped() {
    for (file, text) in [("README.md", README), ("docs/guide.md", GUIDE)] {
        let commands = shown_commands(text);
        assert!(!commands.is_empty(), "{file} shows no command");
        for words in commands {
            if let Err(e) = Cli::try_parse_from(&words) {
                panic!("{file} shows `{}`: {e}", words.join(" "));
            }
            for pair in words.windows(2).filter(|w| w[0] == "--preset") {
                let preset = format!("{}.ron", pair[1]);
                assert!(
                    matches!(atmoscope::presets::load_shipped(&preset), Some(Ok(_))),
                    "{file} shows the preset {}, which is not shipped",
                    pair[1]
                );
            }
        }
    }
}

/// The Help menu's row of tab keys (which the guide's table repeats) names every tab, in the
/// order of their keys.
#[test]
fn the_help_menu_s_row_of_tab_keys_names_every_tab_in_order() {
    let (keys, tabs) = SHORTCUTS
        .iter()
        .find(|(keys, _)| keys.starts_with("1 "))
        .expect("the tabs' row");
    assert_eq!(*keys, format!("1 – {}", Tab::ALL.len()));
    let labels: Vec<&str> = Tab::ALL.iter().map(|t| t.label()).collect();
    assert_eq!(tabs.split(", ").collect::<Vec<_>>(), labels);
}
