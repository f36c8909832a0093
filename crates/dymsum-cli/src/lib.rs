//! The `dymsum` command-line tool, as a library so its parts can be tested
//! and reused (the binary in `main.rs` only calls [`main`]).
//!
//! Its subcommands, one module each under [`commands`] (each owns its
//! clap arguments; bad inputs exit 1 with a message naming the operand):
//!
//! * `dymsum sum` ([`commands::sum`]): P ⊕ Q, written as a mesh (unions and
//!   non-convex meshes as one closed mesh).
//! * `dymsum info` ([`commands::info`]): a polytope's counts, volume, and
//!   what validation changed.
//! * `dymsum models` ([`commands::models`]): the built-in models, listed or
//!   written to a file.
//! * `dymsum completions` ([`commands::completions`]): a shell completion
//!   script.
//! * `dymsum animate` ([`commands::animate`]): P turned by the paper's
//!   random motion, P ⊕ Q kept up to date by DYMSUM.
//! * `dymsum demo` ([`commands::demo`]): DYMSUM against the static sums on
//!   built-in models.
//! * `dymsum bench` ([`commands::bench`]): the paper's experiments (Table 1,
//!   Fig. 4, Fig. 5).
//! * `dymsum render` ([`commands::render`]): a picture of P ⊕ Q (SVG or
//!   PNG), optionally with the facets a further turn changes.
//! * `dymsum cobst` ([`commands::cobst`]): C-obstacle slices, one per
//!   orientation, or certified slabs ([`commands::cobst::slabs`]).
//! * `dymsum query` ([`commands::query`]): collision, penetration depth and
//!   distance of a robot at given poses.
//! * `dymsum motion` ([`commands::motion`]): whether a straight motion
//!   touches the obstacle, certified.
//!
//! The other modules:
//!
//! * [`cli`]: the top-level parser, the subcommand list and its dispatch
//!   (usage errors exit 2).
//! * [`values`]: the flag value parsers several subcommands share.
//! * [`commands::solid`]: the one loader of bodies (convex, unions, meshes
//!   of convex shells, decompositions, triangles).
//! * [`random_motion`]: the paper's random motion of P, for `bench`, `demo`
//!   and `animate` (not the `motion` subcommand).
//! * [`progress`]: the progress bar; [`stats`]: timing summaries.
#![forbid(unsafe_code)]
#![warn(clippy::missing_errors_doc, clippy::missing_panics_doc)]

pub mod cli;
pub mod commands;
pub mod progress;
pub mod random_motion;
pub mod stats;
pub mod values;

use std::io::{self, Write};
use std::process::ExitCode;

use clap::Parser;

/// Parses the process arguments, runs the subcommand and returns the exit
/// code: 0 on success, 1 for bad input (the message goes to stderr), 2 for
/// usage errors (clap prints them and exits), 3 for internal errors (an
/// output mesh failed its exact validation: a bug, never written).
pub fn main() -> ExitCode {
    init_logging();
    let cli = cli::Cli::parse();
    let stdout = io::stdout();
    let mut out = stdout.lock();
    match cli.command.run(&mut out).and_then(|()| Ok(out.flush()?)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) if is_internal(&e) => {
            let _ = writeln!(io::stderr(), "internal error: {}", error_text(&e));
            ExitCode::from(3)
        }
        Err(e) => {
            let _ = writeln!(io::stderr(), "error: {}", error_text(&e));
            ExitCode::from(1)
        }
    }
}

/// `true` when the error is a bug in dymsum (an invalid output mesh), exit 3.
fn is_internal(e: &anyhow::Error) -> bool {
    use dymsum::query::QueryError;
    use dymsum::sum::MeshError;
    e.chain().any(|c| {
        c.downcast_ref::<MeshError>().is_some_and(MeshError::is_internal)
            || matches!(c.downcast_ref::<QueryError>(), Some(QueryError::Mesh(m)) if m.is_internal())
    })
}

/// The error and its causes joined by `": "`, each said once: a cause whose
/// text the message so far already ends with (an OS error that a
/// `"{path}: {source}"` error also carries as its source) is not repeated.
pub fn error_text(e: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in e.chain() {
        let c = cause.to_string();
        if text.is_empty() {
            text = c;
        } else if !text.ends_with(&c) {
            text.push_str(": ");
            text.push_str(&c);
        }
    }
    text
}

/// `true` when the error is a closed stdout (`dymsum models | head`).
fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.downcast_ref::<io::Error>()
            .is_some_and(|e| e.kind() == io::ErrorKind::BrokenPipe)
    })
}

/// The README's Rust code blocks, compiled and run by `cargo test --doc`
/// (with the other Markdown guides below: `tests/docs.rs` checks that
/// every file under `docs/` with a `rust` block is listed here).
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

/// The Rust code blocks of docs/RUST.md, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/RUST.md")]
pub struct RustGuideDoctests;

/// Diagnostics on stderr, `RUST_LOG`-style and off by default:
/// `RUST_LOG=debug dymsum sum ...` shows what was loaded and how validation
/// and the output mesh went; `RUST_LOG=dymsum_cli=trace` adds per-step detail.
fn init_logging() {
    let env = env_logger::Env::default().filter_or("RUST_LOG", "off");
    let _ignored_if_already_set = env_logger::Builder::from_env(env)
        .format_timestamp(None)
        .try_init();
}
