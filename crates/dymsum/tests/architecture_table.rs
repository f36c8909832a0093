//! ARCHITECTURE.md cannot drift from the code (issues 27 and 34):
//!
//! * every path of its table "Where to look: questions and files" is a
//!   file, and the table answers the questions readers ask most;
//! * every repository path it names (`crates/…`, `docs/…`, …) exists;
//! * every Rust path it names (`sum::contained`, `commands::cobst::slabs`,
//!   `dymsum_io::load_polytope`, `Validator::collides_at`), in its prose,
//!   tables and diagrams, resolves: a leading part is a module with a file
//!   under `crates/*/src` (`a/b.rs` or `a/b/mod.rs`), the next segment is
//!   a name in that file's code (not its comments: defined or
//!   re-exported), and any further ones are members of that name; a path
//!   starting with a type resolves in the code of the files that declare
//!   or implement the type;
//! * its layer table is `tests/layers.rs`'s `LAYERS`, row by row, and
//!   names every module `lib.rs` declares.
//!
//! The subcommands it names are checked by the CLI's
//! `tests/architecture.rs`.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn architecture() -> String {
    std::fs::read_to_string(root().join("ARCHITECTURE.md")).unwrap()
}

/// The rows of the first table after `heading`, each as its trimmed cells.
fn table_after(text: &str, heading: &str) -> Vec<Vec<String>> {
    let start = text
        .find(heading)
        .unwrap_or_else(|| panic!("ARCHITECTURE.md has no heading {heading:?}"));
    text[start..]
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|row| {
            let cells: Vec<&str> = row.split('|').collect();
            cells[1..cells.len() - 1]
                .iter()
                .map(|c| c.trim().to_string())
                .collect()
        })
        .collect()
}

/// The `code` spans of a piece of Markdown.
fn code_spans(text: &str) -> Vec<String> {
    text.split('`')
        .enumerate()
        .filter(|(i, _)| i % 2 == 1)
        .map(|(_, s)| s.to_string())
        .collect()
}

#[test]
fn every_file_the_question_table_names_exists() {
    let rows = table_after(&architecture(), "## Where to look: questions and files");
    assert!(rows.len() >= 20, "the table has {} rows", rows.len());
    let mut asked = Vec::new();
    for row in &rows {
        let (question, files) = (&row[0], code_spans(&row[1]));
        assert!(!files.is_empty(), "\"{question}\" names no file");
        for file in files {
            assert!(
                root().join(&file).is_file(),
                "ARCHITECTURE.md: \"{question}\" points at {file}, which does not exist"
            );
        }
        asked.push(question.to_lowercase());
    }
    for must in [
        "gjk",
        "epa",
        "penetration depth",
        "dymsum step",
        "winding-number",
        "box tree",
        "motion of convex bodies certified",
        "motion of triangles certified",
    ] {
        assert!(
            asked.iter().any(|q| has_word(q, must)),
            "the table must answer a question about {must}"
        );
    }
}

#[test]
fn every_repository_path_it_names_exists() {
    let text = architecture();
    let mut checked = 0;
    for word in text.split(|c: char| c.is_whitespace() || "`()[],;".contains(c)) {
        let word = word.trim_end_matches(['.', ':']);
        let tops = [
            "crates/",
            "docs/",
            "python/",
            "examples/",
            "scripts/",
            "fuzz/",
        ];
        if tops.iter().any(|t| word.starts_with(t)) {
            assert!(
                root().join(word).exists(),
                "ARCHITECTURE.md names {word}, which does not exist"
            );
            checked += 1;
        }
    }
    assert!(checked >= 40, "only {checked} paths found");
}

/// Crates whose paths ARCHITECTURE.md may name without their code being
/// in this repository.
const EXTERNAL: &[&str] = &["std", "glam", "parry3d_f64", "boolmesh", "clap"];

/// One crate of the workspace: its name in paths and its `src` folder.
struct Crate {
    name: String,
    src: PathBuf,
}

fn crates() -> Vec<Crate> {
    let mut out: Vec<Crate> = std::fs::read_dir(root().join("crates"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("src").is_dir())
        .map(|p| Crate {
            name: p.file_name().unwrap().to_string_lossy().replace('-', "_"),
            src: p.join("src"),
        })
        .collect();
    out.sort_by(|a, b| a.name.cmp(&b.name));
    out
}

/// Every `.rs` file under `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Whether `text` has `word` as a whole identifier.
fn has_word(text: &str, word: &str) -> bool {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    text.match_indices(word).any(|(at, _)| {
        !text[..at].chars().next_back().is_some_and(ident)
            && !text[at + word.len()..].chars().next().is_some_and(ident)
    })
}

/// The file of module `module` (segments) in `src`, if it has one.
fn module_file(src: &Path, module: &[&str]) -> Option<PathBuf> {
    if module.is_empty() {
        return Some(src.join("lib.rs"));
    }
    let joined = module.join("/");
    [format!("{joined}.rs"), format!("{joined}/mod.rs")]
        .into_iter()
        .map(|f| src.join(f))
        .find(|p| p.is_file())
}

/// The code of a file: its lines that are not comments.
fn code(text: &str) -> String {
    text.lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Whether `path` (segments) resolves in crate `c`: some leading part
/// (the longest first; none for a path that names its crate) is a module
/// with a file, the next segment is a name in that file's code (defined
/// or re-exported), and any further ones are members of that name
/// ([`type_path_resolves`]).
fn resolves_in(c: &Crate, path: &[&str], files: &[(PathBuf, String)], crate_named: bool) -> bool {
    let shortest = usize::from(!crate_named);
    (shortest..=path.len()).rev().any(|k| {
        let Some(file) = module_file(&c.src, &path[..k]) else {
            return false;
        };
        match &path[k..] {
            [] => true,
            [name] => has_word(&code(&std::fs::read_to_string(file).unwrap()), name),
            [name, ..] => {
                has_word(&code(&std::fs::read_to_string(file).unwrap()), name)
                    && type_path_resolves(files, &path[k..])
            }
        }
    })
}

/// Whether `Type::name…` resolves: some file declares or implements the
/// type and has the names in its code.
fn type_path_resolves(files: &[(PathBuf, String)], path: &[&str]) -> bool {
    let ty = path[0];
    let declares = |t: &str| {
        ["struct", "enum", "trait", "type", "impl", "for"]
            .iter()
            .any(|k| has_word(t, &format!("{k} {ty}")) || t.contains(&format!("{k} {ty}<")))
    };
    files
        .iter()
        .map(|(_, t)| code(t))
        .filter(|t| declares(t))
        .any(|t| path[1..].iter().all(|n| has_word(&t, n)))
}

/// The Rust paths (`a::b`, at least two segments) anywhere in `text`.
fn rust_paths(text: &str) -> BTreeSet<String> {
    text.split(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
        .map(|w| w.trim_matches(':'))
        .filter(|w| w.contains("::") && !w.contains(":::"))
        .map(str::to_string)
        .collect()
}

#[test]
fn every_rust_path_it_names_resolves() {
    let crates = crates();
    let mut files = Vec::new();
    for c in &crates {
        rust_files(&c.src, &mut files);
    }
    let files: Vec<(PathBuf, String)> = files
        .into_iter()
        .map(|f| {
            let t = std::fs::read_to_string(&f).unwrap();
            (f, t)
        })
        .collect();
    let paths = rust_paths(&architecture());
    assert!(paths.len() >= 40, "only {} Rust paths found", paths.len());
    let mut unresolved = Vec::new();
    for path in &paths {
        let segs: Vec<&str> = path.split("::").collect();
        if EXTERNAL.contains(&segs[0]) {
            continue;
        }
        let ok = if let Some(c) = crates.iter().find(|c| c.name == segs[0]) {
            resolves_in(c, &segs[1..], &files, true)
        } else if segs[0].starts_with(|c: char| c.is_ascii_uppercase()) {
            type_path_resolves(&files, &segs)
        } else {
            crates.iter().any(|c| resolves_in(c, &segs, &files, false))
        };
        if !ok {
            unresolved.push(path.clone());
        }
    }
    assert!(
        unresolved.is_empty(),
        "ARCHITECTURE.md names Rust paths that resolve to no module or item under \
         crates/*/src (or add an external crate to EXTERNAL): {unresolved:?}"
    );
}

/// `tests/layers.rs`'s `LAYERS`, bottom up: the quoted names of each
/// `&[…]` line of the constant.
fn layers_of_the_test() -> Vec<Vec<String>> {
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/layers.rs"))
            .unwrap();
    let start = text
        .find("const LAYERS")
        .expect("tests/layers.rs has LAYERS");
    let body = &text[start..start + text[start..].find("];").unwrap()];
    body.lines()
        .skip(1)
        .filter(|l| l.trim_start().starts_with("&["))
        .map(|l| {
            l.split('"')
                .enumerate()
                .filter(|(i, _)| i % 2 == 1)
                .map(|(_, s)| s.to_string())
                .collect()
        })
        .collect()
}

#[test]
fn the_layer_table_is_the_one_the_layer_test_enforces() {
    let rows = table_after(&architecture(), "## The core's layers");
    let drawn: Vec<Vec<String>> = rows.iter().map(|r| code_spans(&r[1])).collect();
    let numbers: Vec<String> = rows.iter().map(|r| r[0].clone()).collect();
    let expected: Vec<String> = (1..=rows.len()).map(|i| i.to_string()).collect();
    assert_eq!(
        numbers, expected,
        "the layers are numbered bottom up from 1"
    );
    assert_eq!(
        drawn,
        layers_of_the_test(),
        "ARCHITECTURE.md's layer table differs from tests/layers.rs"
    );
    let lib =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs")).unwrap();
    let declared: BTreeSet<String> = lib
        .lines()
        .filter_map(|l| {
            let l = l.trim();
            let rest = l.strip_prefix("pub ").unwrap_or(l);
            let rest = rest.strip_prefix("pub(crate) ").unwrap_or(rest);
            rest.strip_prefix("mod ")?
                .strip_suffix(';')
                .map(str::to_string)
        })
        .collect();
    let in_table: BTreeSet<String> = drawn.into_iter().flatten().collect();
    assert_eq!(
        declared, in_table,
        "the modules lib.rs declares and those of the layer table"
    );
}
