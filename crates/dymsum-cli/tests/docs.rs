//! The documentation cannot drift from the code (issue 19 §2):
//!
//! * every `console` block of README.md and docs/*.md is run by trycmd, in
//!   a sandbox seeded with the repository's `examples/data/` (the folder
//!   the README tells readers to run them in), and must print what it shows
//!   (`[..]` masks timings and other varying text, a `...` line skips
//!   lines);
//! * every fenced block is of a kind that some test runs (`console` here,
//!   `rust` as doctests of this crate, `python` by
//!   `python/tests/test_docs.py`) or is inert by nature (`text` output,
//!   `toml` configuration, `sh` setup and benchmark recipes), and every file
//!   with `rust` blocks is one of the doctest includes of `src/lib.rs`;
//! * every concrete `dymsum …` command line quoted but not run in the
//!   Markdown files (`sh` blocks, inline code) parses with the current
//!   flags, and every
//!   `cargo … --bench NAME` / `--example NAME` names one that exists.

use std::path::{Path, PathBuf};

use clap::Parser;

/// The repository root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// README.md and docs/*.md, the files whose examples must run.
fn docs() -> Vec<PathBuf> {
    let mut files = vec![root().join("README.md")];
    let mut guides: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    guides.sort();
    files.extend(guides);
    files
}

/// Every Markdown file whose quoted commands must parse.
fn markdown() -> Vec<PathBuf> {
    let mut files = docs();
    files.push(root().join("python/README.md"));
    files.push(root().join("ARCHITECTURE.md"));
    files
}

/// A fenced code block: its info string and its lines.
struct Block {
    info: String,
    lines: Vec<String>,
}

/// The fenced blocks of a Markdown text, and the text outside them.
fn split(text: &str) -> (Vec<Block>, String) {
    let (mut blocks, mut prose) = (Vec::new(), String::new());
    let mut open: Option<Block> = None;
    for line in text.lines() {
        match (&mut open, line.strip_prefix("```")) {
            (None, Some(info)) => {
                open = Some(Block {
                    info: info.trim().to_string(),
                    lines: Vec::new(),
                })
            }
            (Some(_), Some(_)) => blocks.push(open.take().unwrap()),
            (Some(b), None) => b.lines.push(line.to_string()),
            (None, None) => {
                prose.push_str(line);
                prose.push('\n');
            }
        }
    }
    assert!(open.is_none(), "an unclosed code fence");
    (blocks, prose)
}

#[test]
fn console_examples_in_the_docs_run() {
    let dir = dymsum_testkit::files::temp_dir(env!("CARGO_CRATE_NAME"), "console");
    // The files the examples name, shipped where the README says they are.
    let fixtures = root().join("examples/data");
    let cases = trycmd::TestCases::new();
    cases.register_bin("dymsum", Path::new(env!("CARGO_BIN_EXE_dymsum")));
    let mut ran = 0;
    for file in docs() {
        let text = std::fs::read_to_string(&file).unwrap();
        if !split(&text).0.iter().any(|b| b.info == "console") {
            continue;
        }
        // `NAME.md` with `NAME.in/` (the fixtures: the working directory's
        // template) and an empty `NAME.out/` (a sandbox: nothing is written
        // into the repository).
        let name = file.file_stem().unwrap().to_str().unwrap();
        let case = dir.join(format!("{name}.md"));
        std::fs::write(&case, &text).unwrap();
        let input = dir.join(format!("{name}.in"));
        std::fs::create_dir_all(&input).unwrap();
        for f in std::fs::read_dir(&fixtures).unwrap() {
            let f = f.unwrap();
            if !f.file_name().to_string_lossy().starts_with('.') {
                std::fs::copy(f.path(), input.join(f.file_name())).unwrap();
            }
        }
        std::fs::create_dir_all(dir.join(format!("{name}.out"))).unwrap();
        cases.case(&case);
        ran += 1;
    }
    assert!(ran >= 2, "README.md and docs/CLI.md have console examples");
    cases.run();
}

#[test]
fn the_orientation_file_shown_is_the_one_the_examples_use() {
    let shown = std::fs::read_to_string(root().join("docs/CLI.md")).unwrap();
    let used = std::fs::read_to_string(root().join("examples/data/quats.txt")).unwrap();
    assert!(shown.contains(&format!("```text\n{used}```")), "{used}");
}

#[test]
fn every_code_block_is_run_or_inert() {
    let lib =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs")).unwrap();
    for file in markdown() {
        let text = std::fs::read_to_string(&file).unwrap();
        let name = file
            .strip_prefix(root())
            .unwrap_or(&file)
            .display()
            .to_string();
        let blocks = split(&text).0;
        for b in &blocks {
            assert!(
                ["console", "rust", "python", "text", "toml", "sh"].contains(&b.info.as_str()),
                "{name}: a code block of kind `{}` is neither run by a test nor inert \
                 (an unlabelled block would be compiled as Rust): {:?}",
                b.info,
                b.lines.first()
            );
        }
        let has_rust = blocks.iter().any(|b| b.info == "rust");
        let rel = name.replace('\\', "/");
        if has_rust && rel != "python/README.md" {
            assert!(
                lib.contains(&format!("include_str!(\"../../../{rel}\")")),
                "{rel} has rust blocks but is not a doctest include of src/lib.rs"
            );
        }
    }
}

/// The command lines quoted but not run in a Markdown text: lines of `sh`
/// blocks and inline code spans (`console` blocks are run, with their
/// expected exit codes, by `console_examples_in_the_docs_run`).
fn quoted_commands(text: &str) -> Vec<String> {
    let (blocks, prose) = split(text);
    let mut out: Vec<String> = blocks
        .iter()
        .filter(|b| b.info == "sh")
        .flat_map(|b| b.lines.iter().cloned())
        .collect();
    for (i, span) in prose.split('`').enumerate() {
        if i % 2 == 1 {
            out.push(span.to_string());
        }
    }
    out
}

/// A quoted line as `dymsum` arguments, when it is a concrete `dymsum`
/// command (no placeholders such as `FILE` or `[...]`, no pipes).
fn dymsum_args(line: &str) -> Option<Vec<String>> {
    let line = line.split(" #").next().unwrap_or("").trim();
    let rest = [
        "dymsum ",
        "target/release/dymsum ",
        "cargo run --release -p dymsum-cli -- ",
    ]
    .iter()
    .find_map(|p| line.strip_prefix(p))?;
    let args: Vec<String> = rest.split_whitespace().map(str::to_string).collect();
    let placeholder = |a: &String| {
        a.contains("...")
            || a.contains('…')
            || a.contains('[')
            || a.contains('|')
            || a.contains('>')
            || (a.chars().any(|c| c.is_ascii_uppercase())
                && a.chars()
                    .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || ",.:_".contains(c)))
    };
    if args.iter().any(placeholder) {
        return None;
    }
    Some(std::iter::once("dymsum".to_string()).chain(args).collect())
}

#[test]
fn every_quoted_dymsum_command_parses() {
    let mut parsed = 0;
    for file in markdown() {
        let text = std::fs::read_to_string(&file).unwrap();
        for line in quoted_commands(&text) {
            if let Some(args) = dymsum_args(&line) {
                if let Err(e) = dymsum_cli::cli::Cli::try_parse_from(&args) {
                    // `--help` and `--version` "fail" by printing; a command
                    // named in prose (`dymsum info`, `dymsum bench`) may
                    // leave out its required arguments. Unknown flags and
                    // subcommands, bad values and conflicts fail.
                    use clap::error::ErrorKind::{
                        DisplayHelp, DisplayHelpOnMissingArgumentOrSubcommand, DisplayVersion,
                        MissingRequiredArgument,
                    };
                    assert!(
                        matches!(
                            e.kind(),
                            DisplayHelp
                                | DisplayVersion
                                | DisplayHelpOnMissingArgumentOrSubcommand
                                | MissingRequiredArgument
                        ),
                        "{}: `{line}` does not parse:\n{e}",
                        file.display()
                    );
                }
                parsed += 1;
            }
        }
    }
    assert!(parsed >= 10, "only {parsed} commands found");
}

#[test]
fn every_quoted_bench_and_example_exists() {
    let mut checked = 0;
    for file in markdown() {
        let text = std::fs::read_to_string(&file).unwrap();
        for line in quoted_commands(&text) {
            let words: Vec<&str> = line.split_whitespace().collect();
            for w in words.windows(2) {
                let (dir, what) = match w[0] {
                    "--bench" => ("benches", "bench"),
                    "--example" => ("examples", "example"),
                    _ => continue,
                };
                let exists = ["dymsum", "dymsum-bench", "dymsum-cli", "dymsum-io"]
                    .iter()
                    .any(|c| {
                        root()
                            .join(format!("crates/{c}/{dir}/{}.rs", w[1]))
                            .is_file()
                    });
                assert!(
                    exists,
                    "{}: {what} `{}` does not exist",
                    file.display(),
                    w[1]
                );
                checked += 1;
            }
        }
    }
    assert!(checked >= 5, "only {checked} benches and examples found");
}

/// GitHub's anchor of a heading: lower case, spaces as hyphens, other
/// punctuation dropped.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

#[test]
fn every_relative_link_resolves() {
    let mut checked = 0;
    for file in markdown() {
        let text = std::fs::read_to_string(&file).unwrap();
        let prose = split(&text).1;
        for link in prose.split("](").skip(1) {
            let target = link.split(')').next().unwrap_or("");
            if target.starts_with("http") || target.contains(' ') {
                continue;
            }
            let (path, frag) = target.split_once('#').unwrap_or((target, ""));
            let dest = if path.is_empty() {
                file.clone()
            } else {
                file.parent().unwrap().join(path)
            };
            assert!(
                dest.exists(),
                "{}: link to missing `{target}`",
                file.display()
            );
            if !frag.is_empty() {
                let headings: Vec<String> = split(&std::fs::read_to_string(&dest).unwrap())
                    .1
                    .lines()
                    .filter_map(|l| l.strip_prefix('#'))
                    .map(|h| anchor(h.trim_start_matches('#')))
                    .collect();
                assert!(
                    headings.iter().any(|h| h == frag),
                    "{}: no heading `#{frag}` in {}",
                    file.display(),
                    dest.display()
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 20, "only {checked} links found");
}

#[test]
fn the_benchmark_summary_is_on_the_first_screen() {
    // At most eight headline rows first (issue 29), then every figure with
    // its command, date and machine.
    let text = std::fs::read_to_string(root().join("docs/BENCHMARKS.md")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let first_table = lines.iter().position(|l| l.starts_with("| ")).unwrap();
    assert!(
        first_table < 25,
        "the summary table starts on line {first_table}"
    );
    let rows = lines[first_table + 2..]
        .iter()
        .take_while(|l| l.starts_with("| "))
        .count();
    assert!((1..=8).contains(&rows), "{rows} headline rows (at most 8)");
    for column in ["figure", "compared with", "ratio"] {
        assert!(
            lines[first_table].contains(column),
            "headline column `{column}`: {}",
            lines[first_table]
        );
    }
    let full = lines[first_table + 2 + rows..]
        .iter()
        .find(|l| l.starts_with("| "))
        .expect("the table of every figure below the headlines");
    for column in [
        "figure",
        "compared with",
        "ratio",
        "command",
        "date",
        "machine",
    ] {
        assert!(full.contains(column), "summary column `{column}`: {full}");
    }
}
