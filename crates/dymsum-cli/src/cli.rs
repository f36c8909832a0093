//! The command line: the top-level parser and the subcommand list. Each
//! subcommand's arguments live with the subcommand (`commands::*`), the
//! value parsers they share in [`crate::values`].
//!
//! Every flag value is checked by a clap value parser, so a malformed or
//! meaningless value (`--rotate-p-wxyz 1,2`, a NaN, a zero quaternion, an output
//! file with an unknown extension) is a usage error: clap prints it with the
//! usage line and the process exits with code 2. Bad *inputs* (missing
//! files, unknown models, non-convex meshes) are found later and exit 1.

use std::io::Write;

use clap::{CommandFactory, Parser, Subcommand};

use crate::commands::{
    animate, bench, cobst, completions, demo, info, models, motion, query, render, sum,
};

/// Exact static and dynamic Minkowski sums of convex polytopes.
///
/// Operands P and Q are mesh files (.off, .obj, .ply, .stl; a file with no
/// faces is a point cloud, whose hull is taken) or built-in model names
/// (`dymsum models` lists them, e.g. ellipse, gs4, tcube:10, random:1000:7).
#[derive(Debug, Parser)]
#[command(name = "dymsum", version)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Compute P ⊕ Q (P optionally rotated and translated) and write the merged mesh.
    Sum(sum::SumArgs),
    /// Describe a polytope: counts, volume, and what validation changed.
    Info(info::InfoArgs),
    /// List the built-in models, or write one to a file (`--write NAME FILE`).
    Models(models::ModelsArgs),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell).
    Completions(completions::CompletionsArgs),
    /// Turn P under the paper's random motion and keep P ⊕ Q up to date (DYMSUM).
    Animate(animate::AnimateArgs),
    /// The main job on built-in models: DYMSUM vs static sums on ellipse ⊕ gs4.
    Demo(demo::DemoArgs),
    /// Reproduce the paper's experiments: Table 1, Fig. 4 (rotation), Fig. 5 (size).
    Bench(bench::BenchArgs),
    /// Draw P ⊕ Q (SVG or PNG), optionally highlighting the facets a further turn changes.
    Render(render::RenderArgs),
    /// Configuration-space obstacle slices of a translating robot, one per orientation.
    Cobst(cobst::CobstArgs),
    /// Collision, penetration depth and distance of a robot at given poses.
    Query(query::QueryArgs),
    /// Whether a robot moving straight between two poses touches the obstacle (certified).
    Motion(Box<motion::MotionArgs>),
}

impl Command {
    /// Runs the subcommand, writing its report to `out`.
    ///
    /// # Errors
    /// The subcommand's error (see each `commands::*::run`): an operand that
    /// cannot be loaded, an output that cannot be written, or an internal
    /// error; [`crate::main`] turns it into exit code 1, or 3 for an
    /// internal mesh error.
    pub fn run(self, out: &mut dyn Write) -> anyhow::Result<()> {
        match self {
            Command::Sum(a) => sum::run(&a, out),
            Command::Info(a) => info::run(&a, out),
            Command::Models(a) => models::run(&a, out),
            Command::Completions(a) => completions::run(&a, &mut Cli::command(), out),
            Command::Animate(a) => animate::run(&a, out),
            Command::Demo(a) => demo::run(&a, out),
            Command::Bench(a) => bench::run(&a, out),
            Command::Render(a) => render::run(&a, out),
            Command::Cobst(a) => cobst::run(&a, out),
            Command::Query(a) => query::run(&a, out),
            Command::Motion(a) => motion::run(&a, out),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn clap_definition_is_consistent() {
        Cli::command().debug_assert();
    }

    /// Every flag that takes a quaternion (a `W,...` value or a file of
    /// quaternions) says its component order in its name.
    #[test]
    fn every_quaternion_flag_names_its_order() {
        fn walk(c: &clap::Command, seen: &mut Vec<String>) {
            for a in c.get_arguments() {
                let names: Vec<&str> = a
                    .get_value_names()
                    .unwrap_or_default()
                    .iter()
                    .map(|n| n.as_str())
                    .collect();
                let help = a.get_help().map(|h| h.to_string()).unwrap_or_default();
                if names.iter().any(|n| n.contains("W,")) || help.contains("quaternion") {
                    let long = a.get_long().unwrap_or_default();
                    assert!(long.contains("wxyz"), "{} --{long}", c.get_name());
                    seen.push(format!("{} --{long}", c.get_name()));
                }
            }
            for s in c.get_subcommands() {
                walk(s, seen);
            }
        }
        let mut seen = Vec::new();
        walk(&Cli::command(), &mut seen);
        assert_eq!(
            seen,
            [
                "sum --rotate-p-wxyz",
                "render --rotate-p-wxyz",
                "render --highlight-after-wxyz",
                "cobst --orientations-wxyz",
                "query --pose-xyz-wxyz",
                "query --obstacle-xyz-wxyz",
                "motion --from-xyz-wxyz",
                "motion --to-xyz-wxyz",
                "motion --obstacle-xyz-wxyz"
            ]
        );
    }
}
