//! One module per subcommand. Each takes its parsed arguments and the
//! output stream and returns `anyhow::Result`; errors are bad *input*
//! (exit 1), with messages naming the operand and the cause.

pub mod animate;
pub mod bench;
pub mod cobst;
pub mod demo;
pub mod info;
pub mod models;
pub mod query;
pub mod render;
pub mod sum;

use std::io::Write;

use anyhow::anyhow;
use dymsum::polytope::MeshPolicy;
use dymsum_io::{load_polytope, Loaded};

use crate::cli::Command;

/// Runs one subcommand, writing its report to `out`.
pub fn run(command: Command, out: &mut dyn Write) -> anyhow::Result<()> {
    match command {
        Command::Sum(a) => sum::run(&a, out),
        Command::Info(a) => info::run(&a, out),
        Command::Models => models::run(out),
        Command::Animate(a) => animate::run(&a, out),
        Command::Demo(a) => demo::run(&a, out),
        Command::Bench(a) => bench::run(&a, out),
        Command::Render(a) => render::run(&a, out),
        Command::Cobst(a) => cobst::run(&a, out),
        Command::Query(a) => query::run(&a, out),
    }
}

/// The mesh policy for the `--strict` flag.
pub fn policy(strict: bool) -> MeshPolicy {
    if strict {
        MeshPolicy::strict()
    } else {
        MeshPolicy::default()
    }
}

/// Loads operand `operand` (`"P"`, `"Q"`, `"input"`) from a file or model
/// name, with an error message like
/// `P (file cube_open.off): open mesh: edge (3, 7) borders only one face`.
pub fn load(spec: &str, operand: &str, strict: bool) -> anyhow::Result<Loaded> {
    load_polytope(spec, policy(strict)).map_err(|e| anyhow!(e.for_operand(operand)))
}

/// The validated mesh of a sum, with a warning on stderr when its
/// coordinates are coarse relative to its size. Errors keep their type, so
/// an internal one ([`dymsum::sum::MeshError::is_internal`]) exits with 3.
pub fn validated(
    mesh: Result<dymsum::sum::SumMesh, dymsum::sum::MeshError>,
    what: &str,
) -> anyhow::Result<dymsum::PolygonMesh> {
    let m = mesh.map_err(|e| anyhow::Error::new(e).context(format!("the mesh of {what}")))?;
    if m.precision.is_coarse() {
        eprintln!(
            "warning: {what}: coordinates lose precision: {}",
            m.precision
        );
    }
    Ok(m.mesh)
}

/// A short display name for an operand: the model name, or the file name.
pub fn short_name(spec: &str) -> String {
    let path = std::path::Path::new(spec);
    if path.is_file() {
        path.file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_else(|| spec.to_string())
    } else {
        spec.trim().to_string()
    }
}
