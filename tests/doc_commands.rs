//! Every command the pages show in a code block works as written: it parses with
//! the real command line (a stale option or subcommand fails here), and one
//! written as `rasterlab ...` is on a page that first says how to install it,
//! since after README's two commands only `cargo run --release -- ...` works.

use clap::Parser;
use rasterlab::app::cli::Cli;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Lines inside ``` blocks, with their line numbers (diffs are left out: their
/// lines are code, not commands).
fn code_lines(text: &str) -> Vec<(usize, &str)> {
    let mut inside = None;
    let mut lines = Vec::new();
    for (n, line) in text.lines().enumerate() {
        if let Some(fence) = line.strip_prefix("```") {
            inside = match inside {
                None => Some(fence != "diff"),
                Some(_) => None,
            };
        } else if inside == Some(true) {
            lines.push((n + 1, line));
        }
    }
    lines
}

/// The arguments after the program name, up to a comment, pipe or redirection.
fn arguments(command: &str) -> Vec<String> {
    command
        .split_whitespace()
        .take_while(|w| !w.starts_with('#') && !["|", ">", "2>", "&&", ";"].contains(w))
        .map(str::to_string)
        .collect()
}

#[test]
fn every_command_on_a_page_parses_as_written() {
    let mut pages = vec![root().join("README.md")];
    for dir in ["docs", "steps"] {
        for entry in std::fs::read_dir(root().join(dir)).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "md") {
                pages.push(path);
            }
        }
    }
    let mut checked = 0;
    for page in pages {
        let text = std::fs::read_to_string(&page).unwrap();
        let name = page.strip_prefix(root()).unwrap().display().to_string();
        for (n, line) in code_lines(&text) {
            let line = line.trim_start().trim_start_matches("$ ");
            let rest = if let Some(rest) = line.strip_prefix("cargo run --release -- ") {
                rest
            } else if let Some(rest) = line.strip_prefix("xvfb-run -a cargo run --release -- ") {
                rest
            } else if let Some(rest) = line.strip_prefix("rasterlab ") {
                let before = &text[..text.lines().take(n).map(|l| l.len() + 1).sum::<usize>()];
                assert!(
                    before.contains("cargo install --path ."),
                    "{name}:{n}: `{line}` needs rasterlab installed, and the page has not said how"
                );
                rest
            } else {
                continue;
            };
            let args = arguments(rest);
            let parsed = Cli::try_parse_from(std::iter::once("rasterlab".to_string()).chain(args));
            if let Err(e) = parsed {
                panic!("{name}:{n}: `{line}` does not parse: {}", e.render());
            }
            checked += 1;
        }
        // And the inline ones, as README's table of stages shows them.
        for (at, _) in text.match_indices("`cargo run --release -- ") {
            let span = &text[at + 1..];
            let span = &span[..span.find('`').unwrap()];
            let rest = span.strip_prefix("cargo run --release -- ").unwrap();
            let parsed = Cli::try_parse_from(
                std::iter::once("rasterlab".to_string()).chain(arguments(rest)),
            );
            if let Err(e) = parsed {
                panic!("{name}: `{span}` does not parse: {}", e.render());
            }
            checked += 1;
        }
    }
    // README alone shows eighteen.
    assert!(checked >= 40, "only {checked} commands found");
}
