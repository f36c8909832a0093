//! `dymsum sum P Q -o OUT`: one static Minkowski sum, written as a mesh.

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use clap::Args;
use dymsum::sum::{minkowski_sum_posed, Method};
use dymsum::{DVec3, Pose, Rotation};

use super::{load, short_name};
use crate::stats::{human_us, micros};
use crate::values::{parse_output_path, parse_quaternion, parse_vector, MethodArg};

/// `dymsum sum`.
#[derive(Debug, Args)]
pub struct SumArgs {
    /// First operand P: a mesh file or a built-in model name; `-` reads OFF
    /// from standard input.
    #[arg(value_name = "P")]
    pub p: String,
    /// Second operand Q: as P.
    #[arg(value_name = "Q")]
    pub q: String,
    /// Output mesh; the format follows the extension (.off, .obj, .ply, .stl);
    /// `-` writes OFF to standard output (the summary line then goes to stderr).
    /// A missing folder is created.
    #[arg(short, long, value_name = "OUT", value_parser = parse_output_path)]
    pub output: PathBuf,
    /// Static algorithm.
    #[arg(long, value_enum, default_value_t = MethodArg::Walk)]
    pub method: MethodArg,
    /// Rotate P about the origin by this unit quaternion, scalar first (W,X,Y,Z; renormalised), before summing.
    #[arg(long = "rotate-p-wxyz", alias = "rotate-p", value_name = "W,X,Y,Z",
          value_parser = parse_quaternion, allow_hyphen_values = true)]
    pub rotate_p: Option<Rotation>,
    /// Then translate P by this vector.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vector, allow_hyphen_values = true)]
    pub translate_p: Option<DVec3>,
    /// Refuse meshes that are convex only within tolerance (instead of using their exact hull).
    #[arg(long)]
    pub strict: bool,
}

/// Runs `dymsum sum`.
///
/// # Errors
/// P or Q cannot be loaded ([`super::load`]); the sum fails
/// ([`dymsum::SumError`]: a posed vertex out of range, or a `hull`-method
/// mismatch); its mesh cannot be produced ([`dymsum::sum::MeshError`]);
/// or the output cannot be written.
pub fn run(a: &SumArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    super::stdin_for_one_operand(&[(&a.p, "P"), (&a.q, "Q")])?;
    let p = load(&a.p, "P", a.strict)?;
    let q = load(&a.q, "Q", a.strict)?;
    let pose_p = Pose::new(
        a.rotate_p.unwrap_or(Rotation::IDENTITY),
        a.translate_p.unwrap_or(DVec3::ZERO),
    );
    let method: Method = a.method.into();
    let start = Instant::now();
    let sum = minkowski_sum_posed(&p.polytope, pose_p, &q.polytope, Pose::IDENTITY, method)
        .with_context(|| format!("{} ⊕ {} ({})", a.p, a.q, method.name()))?;
    let elapsed = micros(start.elapsed());
    let with_precision = sum.mesh_with_precision();
    let bent = matches!(&with_precision, Ok(m) if m.hull_fallback);
    let mesh = super::validated(with_precision, "the sum")?;
    // With `-o -` the mesh goes to standard output and the summary to stderr.
    let to_stdout = a.output.as_os_str() == super::STDIO;
    super::write_mesh_or_stdout(&a.output, &mesh, out).context("writing the sum")?;
    let (fv, vf, ee) = sum.counts();
    let mut stderr = std::io::stderr();
    let summary: &mut dyn Write = if to_stdout { &mut stderr } else { out };
    writeln!(
        summary,
        "{} ⊕ {} ({}): {fv} fv + {vf} vf + {ee} ee = {} facets, {} faces after merging{}, {}",
        short_name(&a.p),
        short_name(&a.q),
        method.name(),
        fv + vf + ee,
        mesh.faces.len(),
        if bent {
            " (faces bent by rounding to f64 split)"
        } else {
            ""
        },
        human_us(elapsed),
    )?;
    Ok(())
}
