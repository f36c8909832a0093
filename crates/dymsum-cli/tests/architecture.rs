//! The subcommands cannot drift from their descriptions (issue 34):
//!
//! * every subcommand ARCHITECTURE.md names (`dymsum NAME` in a code span)
//!   is one of the CLI's, and its subcommand table lists every one with
//!   its module, `commands::NAME`, a file of this crate;
//! * the crate doc (`src/lib.rs`) lists every subcommand, one item each.
//!
//! (The Rust paths ARCHITECTURE.md names are checked by the core's
//! `tests/architecture_table.rs`.)

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use clap::CommandFactory;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The CLI's subcommands, from its clap definition.
fn subcommands() -> BTreeSet<String> {
    dymsum_cli::cli::Cli::command()
        .get_subcommands()
        .map(|s| s.get_name().to_string())
        .filter(|n| n != "help")
        .collect()
}

/// The `code` spans of a piece of Markdown.
fn code_spans(text: &str) -> Vec<&str> {
    text.split('`')
        .enumerate()
        .filter(|(i, _)| i % 2 == 1)
        .map(|(_, s)| s)
        .collect()
}

/// The subcommand a span names: `dymsum NAME …` with `NAME` a lower-case
/// word (not a flag, not a placeholder).
fn named_subcommand(span: &str) -> Option<&str> {
    let name = span.strip_prefix("dymsum ")?.split_whitespace().next()?;
    name.chars().all(|c| c.is_ascii_lowercase()).then_some(name)
}

#[test]
fn every_subcommand_architecture_names_exists() {
    let all = subcommands();
    assert!(all.len() >= 11, "{all:?}");
    let text = std::fs::read_to_string(root().join("ARCHITECTURE.md")).unwrap();
    let named: BTreeSet<&str> = code_spans(&text)
        .into_iter()
        .filter_map(named_subcommand)
        .collect();
    for name in &named {
        assert!(
            all.contains(*name),
            "ARCHITECTURE.md names `dymsum {name}`, which is no subcommand of {all:?}"
        );
    }
    // The subcommand table: every subcommand, with its module's file.
    let start = text
        .find("| subcommand | module |")
        .expect("ARCHITECTURE.md has the subcommand table");
    let mut listed = BTreeSet::new();
    for row in text[start..]
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with('|'))
    {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        let name = code_spans(cells[1])
            .first()
            .and_then(|s| named_subcommand(s))
            .unwrap_or_else(|| panic!("a row without a subcommand: {row}"));
        let module = format!("commands::{name}");
        assert!(
            code_spans(cells[2]).contains(&module.as_str()),
            "`dymsum {name}`: its row names not `{module}`: {row}"
        );
        let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/commands");
        assert!(
            src.join(format!("{name}.rs")).is_file() || src.join(name).join("mod.rs").is_file(),
            "`{module}` has no file"
        );
        listed.insert(name.to_string());
    }
    assert_eq!(
        listed, all,
        "ARCHITECTURE.md's subcommand table and the CLI's subcommands"
    );
}

#[test]
fn the_crate_doc_lists_every_subcommand() {
    let lib =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs")).unwrap();
    let doc: String = lib
        .lines()
        .take_while(|l| l.starts_with("//!"))
        .map(|l| format!("{}\n", l.trim_start_matches("//!").trim()))
        .collect();
    let items: BTreeSet<String> = doc
        .lines()
        .filter_map(|l| l.strip_prefix("* `"))
        .filter_map(|l| named_subcommand(l.split('`').next()?))
        .map(str::to_string)
        .collect();
    let all = subcommands();
    assert_eq!(
        items, all,
        "src/lib.rs's crate doc must list every subcommand as an item \
         \"* `dymsum NAME` ([`commands::NAME`]): …\""
    );
    for name in &all {
        assert!(
            doc.contains(&format!("* `dymsum {name}` ([`commands::{name}`]): ")),
            "src/lib.rs's crate doc: the item of `dymsum {name}` links its module"
        );
    }
}
