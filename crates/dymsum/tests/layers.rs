//! The core's layout cannot decay (issue 27): every path into the crate
//! that non-test code writes (`crate::…`, `crate::{…}`, `super::…`,
//! `self::…`, in `use` lines and inline) is resolved to the file it names,
//! and
//!
//! * no module imports a module of a higher layer (the layers, bottom up:
//!   `kernel`, `error`, `sanity`, `mesh` → `hull` → `polytope` → `solid` → `body` → `gauss`
//!   → `sum` → `dynamic` → `query`, `interop` → `nonconvex`), and nothing
//!   imports through the crate root (`lib.rs`);
//! * no files import each other in a circle (judged file by file, also
//!   within one module).
//!
//! Test modules (`#[cfg(test)] mod … { … }`) and comments are not read.
//! ARCHITECTURE.md draws the same layers.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The layers, bottom up; modules on one line share a layer.
const LAYERS: &[&[&str]] = &[
    &["kernel", "error", "sanity", "mesh"],
    &["hull"],
    &["polytope"],
    &["solid"],
    &["body"],
    &["gauss"],
    &["sum"],
    &["dynamic"],
    &["query", "interop"],
    &["nonconvex"],
    &["robot"],
];

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every `.rs` file under `dir`, relative to `src()`.
fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path.strip_prefix(src()).unwrap().to_path_buf());
        }
    }
}

/// The module path of a file: `query/gjk.rs` → `[query, gjk]`,
/// `query/mod.rs` → `[query]`, `lib.rs` → `[]`.
fn module_of(file: &Path) -> Vec<String> {
    let mut parts: Vec<String> = file
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    let last = parts.pop().unwrap();
    let stem = last.trim_end_matches(".rs");
    if stem != "mod" && stem != "lib" {
        parts.push(stem.to_string());
    }
    parts
}

/// The file of a module path, if the module is a file of its own.
fn file_of(module: &[String], known: &BTreeSet<PathBuf>) -> Option<PathBuf> {
    if module.is_empty() {
        return Some(PathBuf::from("lib.rs"));
    }
    let joined = module.join("/");
    [format!("{joined}.rs"), format!("{joined}/mod.rs")]
        .into_iter()
        .map(PathBuf::from)
        .find(|p| known.contains(p))
}

/// The source without comments, string contents and `#[cfg(test)]` items.
fn code_of(text: &str) -> String {
    // Comments and strings out, keeping line structure.
    let mut out = String::with_capacity(text.len());
    let b: Vec<char> = text.chars().collect();
    let mut i = 0;
    while i < b.len() {
        if b[i] == '/' && b.get(i + 1) == Some(&'/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if b[i] == '/' && b.get(i + 1) == Some(&'*') {
            i += 2;
            while i + 1 < b.len() && !(b[i] == '*' && b[i + 1] == '/') {
                i += 1;
            }
            i += 2;
        } else if b[i] == '"' {
            out.push('"');
            i += 1;
            while i < b.len() && b[i] != '"' {
                if b[i] == '\\' {
                    i += 1;
                }
                i += 1;
            }
            out.push('"');
            i += 1;
        } else if b[i] == '\'' && b.get(i + 2) == Some(&'\'') {
            // A char literal such as '{'.
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    // `#[cfg(test)]` followed by an item with a braced body: drop it.
    let mut code = out;
    while let Some(at) = code.find("#[cfg(test)]") {
        let rest = &code[at..];
        let end = match (rest.find('{'), rest.find(';')) {
            (Some(open), semi) if semi.is_none_or(|s| open < s) => {
                let mut depth = 0;
                let mut close = open;
                for (k, c) in rest[open..].char_indices() {
                    match c {
                        '{' => depth += 1,
                        '}' => {
                            depth -= 1;
                            if depth == 0 {
                                close = open + k;
                                break;
                            }
                        }
                        _ => {}
                    }
                }
                close + 1
            }
            (_, Some(semi)) => semi + 1,
            _ => rest.len(),
        };
        code.replace_range(at..at + end, "");
    }
    code
}

/// The paths a piece of code names, each as its segments (`{…}` groups
/// expanded): `crate::a::{b, c::d}` → `[crate, a, b]`, `[crate, a, c, d]`.
fn paths_in(code: &str) -> Vec<Vec<String>> {
    let chars: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    let mut i = 0;
    while i < chars.len() {
        let starts = ["crate::", "super::", "self::"]
            .iter()
            .find(|s| chars[i..].iter().take(s.len()).copied().eq(s.chars()));
        let preceded = i > 0 && (ident(chars[i - 1]) || chars[i - 1] == ':');
        match starts {
            Some(s) if !preceded => {
                let head = s.trim_end_matches("::").to_string();
                let end = expand(&chars, i + s.len(), vec![head], &mut out);
                i = end;
            }
            _ => i += 1,
        }
    }
    out
}

/// Reads a path tail at `i` after `prefix::`, pushing every full path.
fn expand(chars: &[char], mut i: usize, prefix: Vec<String>, out: &mut Vec<Vec<String>>) -> usize {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    let skip_ws = |i: &mut usize| {
        while *i < chars.len() && chars[*i].is_whitespace() {
            *i += 1;
        }
    };
    let mut path = prefix;
    loop {
        skip_ws(&mut i);
        if i < chars.len() && chars[i] == '{' {
            i += 1;
            loop {
                skip_ws(&mut i);
                if i >= chars.len() || chars[i] == '}' {
                    return i + 1;
                }
                i = expand(chars, i, path.clone(), out);
                skip_ws(&mut i);
                if i < chars.len() && chars[i] == ',' {
                    i += 1;
                }
            }
        }
        let start = i;
        while i < chars.len() && ident(chars[i]) {
            i += 1;
        }
        if i == start {
            // `*`, `self` handled as the module itself.
            if i < chars.len() && chars[i] == '*' {
                i += 1;
            }
            out.push(path);
            return i;
        }
        let word: String = chars[start..i].iter().collect();
        if word != "self" {
            path.push(word);
        }
        if chars[i..].starts_with(&[':', ':']) {
            i += 2;
            continue;
        }
        out.push(path);
        // Skip an `as name`.
        return i;
    }
}

fn layer_of(module: &[String]) -> Option<usize> {
    let top = module.first()?;
    LAYERS.iter().position(|l| l.contains(&top.as_str()))
}

struct House {
    /// file → the files it names.
    edges: BTreeMap<PathBuf, BTreeSet<PathBuf>>,
    /// (file, what it names, why it is wrong)
    problems: Vec<String>,
}

fn read_house() -> House {
    let mut list = Vec::new();
    files(&src(), &mut list);
    let known: BTreeSet<PathBuf> = list.iter().cloned().collect();
    let mut edges: BTreeMap<PathBuf, BTreeSet<PathBuf>> = BTreeMap::new();
    let mut problems = Vec::new();
    for file in &list {
        if file == Path::new("lib.rs") {
            continue;
        }
        let text = std::fs::read_to_string(src().join(file)).unwrap();
        let me = module_of(file);
        let my_layer = layer_of(&me);
        for path in paths_in(&code_of(&text)) {
            // Resolve the head to an absolute module path.
            let mut abs: Vec<String> = match path[0].as_str() {
                "crate" => Vec::new(),
                "self" => me.clone(),
                _ => {
                    let mut m = me.clone();
                    let mut k = 0;
                    // `super::super::…` (a `mod.rs` is its module itself).
                    while k < path.len() && path[k] == "super" {
                        m.pop();
                        k += 1;
                    }
                    m.extend(path[k..].iter().cloned());
                    let target = m;
                    resolve(
                        file,
                        &target,
                        &known,
                        &me,
                        my_layer,
                        &mut edges,
                        &mut problems,
                    );
                    continue;
                }
            };
            abs.extend(path[1..].iter().cloned());
            resolve(file, &abs, &known, &me, my_layer, &mut edges, &mut problems);
        }
    }
    House { edges, problems }
}

fn resolve(
    file: &Path,
    target: &[String],
    known: &BTreeSet<PathBuf>,
    me: &[String],
    my_layer: Option<usize>,
    edges: &mut BTreeMap<PathBuf, BTreeSet<PathBuf>>,
    problems: &mut Vec<String>,
) {
    // The deepest prefix that is a file of its own.
    let mut k = target.len();
    let dest = loop {
        if let Some(f) = file_of(&target[..k], known) {
            break f;
        }
        k -= 1;
    };
    if dest.as_path() == file {
        return;
    }
    let shown = target.join("::");
    if dest == Path::new("lib.rs") {
        problems.push(format!(
            "{}: imports `crate::{shown}` through the crate root (lib.rs)",
            file.display()
        ));
        return;
    }
    if let (Some(mine), Some(theirs)) = (my_layer, layer_of(target)) {
        if theirs > mine {
            problems.push(format!(
                "{} (layer {}) imports `{shown}` of a higher layer ({})",
                file.display(),
                me[0],
                target[0]
            ));
        }
    }
    edges.entry(file.to_path_buf()).or_default().insert(dest);
}

/// Every circle of the file graph (strongly connected components of two
/// or more files).
fn circles(edges: &BTreeMap<PathBuf, BTreeSet<PathBuf>>) -> Vec<Vec<PathBuf>> {
    // Tarjan's algorithm, iteratively simple: small graph, recursion fine.
    struct State<'a> {
        edges: &'a BTreeMap<PathBuf, BTreeSet<PathBuf>>,
        index: BTreeMap<PathBuf, usize>,
        low: BTreeMap<PathBuf, usize>,
        stack: Vec<PathBuf>,
        on: BTreeSet<PathBuf>,
        next: usize,
        out: Vec<Vec<PathBuf>>,
    }
    fn visit(s: &mut State, v: &PathBuf) {
        s.index.insert(v.clone(), s.next);
        s.low.insert(v.clone(), s.next);
        s.next += 1;
        s.stack.push(v.clone());
        s.on.insert(v.clone());
        let succ: Vec<PathBuf> = s
            .edges
            .get(v)
            .map(|e| e.iter().cloned().collect())
            .unwrap_or_default();
        for w in succ {
            if !s.index.contains_key(&w) {
                visit(s, &w);
                let l = s.low[v].min(s.low[&w]);
                s.low.insert(v.clone(), l);
            } else if s.on.contains(&w) {
                let l = s.low[v].min(s.index[&w]);
                s.low.insert(v.clone(), l);
            }
        }
        if s.low[v] == s.index[v] {
            let mut comp = Vec::new();
            loop {
                let w = s.stack.pop().unwrap();
                s.on.remove(&w);
                let done = &w == v;
                comp.push(w);
                if done {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort();
                s.out.push(comp);
            }
        }
    }
    let mut s = State {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        next: 0,
        out: Vec::new(),
    };
    let nodes: Vec<PathBuf> = edges.keys().cloned().collect();
    for v in &nodes {
        if !s.index.contains_key(v) {
            visit(&mut s, v);
        }
    }
    s.out
}

#[test]
fn no_module_imports_a_higher_layer_or_through_the_crate_root() {
    let house = read_house();
    assert!(
        house.problems.is_empty(),
        "{} imports break the layers:\n{}",
        house.problems.len(),
        house.problems.join("\n")
    );
}

#[test]
fn no_files_import_each_other_in_a_circle() {
    let house = read_house();
    let found = circles(&house.edges);
    let shown: Vec<String> = found
        .iter()
        .map(|c| {
            let names: Vec<String> = c.iter().map(|p| p.display().to_string()).collect();
            format!("{} files: {}", c.len(), names.join(", "))
        })
        .collect();
    assert!(found.is_empty(), "circles:\n{}", shown.join("\n"));
}

#[test]
fn every_top_level_module_has_a_layer() {
    let mut list = Vec::new();
    files(&src(), &mut list);
    let tops: BTreeSet<String> = list
        .iter()
        .map(|f| module_of(f))
        .filter_map(|m| m.first().cloned())
        .collect();
    for top in tops {
        assert!(
            layer_of(std::slice::from_ref(&top)).is_some(),
            "module `{top}` has no layer in tests/layers.rs (and ARCHITECTURE.md)"
        );
    }
}

#[test]
fn the_path_reader_reads_groups_inline_paths_and_skips_tests() {
    let code = code_of(
        "use crate::{a::B, c::{d, e::F}};\nfn f() { crate::g::h(); super::i::J; }\n\
         // crate::comment::X\n#[cfg(test)]\nmod tests { use crate::t::T; }\n",
    );
    let paths: Vec<String> = paths_in(&code).iter().map(|p| p.join("::")).collect();
    assert_eq!(
        paths,
        [
            "crate::a::B",
            "crate::c::d",
            "crate::c::e::F",
            "crate::g::h",
            "super::i::J"
        ]
    );
}
