//! `dymsum sum P Q -o OUT`: one static Minkowski sum, written as a mesh.
//!
//! Convex operands give the exact convex sum. An operand that is a union of
//! convex pieces (`a.off+b.off`, an OBJ file with several objects) or a
//! closed non-convex mesh (its exactly convex components, or the pieces of
//! `--decomposition vhacd`) gives the union of the exact piece-pair sums,
//! merged into one closed mesh by `boolmesh` and validated; the summary
//! says how each operand was taken apart and how far a decomposition's
//! pieces are from the input.

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use clap::Args;
use dymsum::sum::{minkowski_sum_posed, Method};
use dymsum::{DVec3, Pose, Rotation};

use super::short_name;
use super::solid::{convex_operands, describe, load_solid, Solid};
use crate::stats::{human_us, micros};
use crate::values::{parse_output_path, parse_quaternion, parse_vector, MethodArg};
use dymsum::nonconvex::{DecompositionInfo, UnionSum};
use dymsum::ConvexUnion;
use serde::Serialize;

/// `dymsum sum`.
#[derive(Debug, Args)]
pub struct SumArgs {
    /// First operand P: a mesh file or a built-in model name; several convex
    /// pieces joined with `+` (`a.off+b.off`), an OBJ file with several
    /// objects, or a mesh of convex shells form a union (a non-convex body);
    /// `-` reads OFF from standard input.
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
    /// How meshes are taken: `--strict`, `--decomposition`.
    #[command(flatten)]
    pub body: super::solid::BodyOptions,
    /// Merge every piece-pair sum, even those certified inside another
    /// (non-convex sums).
    #[arg(long)]
    pub no_cull: bool,
    /// Print the summary as one JSON object: `{"p":..,"q":..,"method":..,
    /// "pieces":[p,q],"pairs":n,"pairs_culled":k,"decomposition":{"p":{..},
    /// "q":{..}},"vertices":v,"faces":f,"volume":x,"shells":s,"genus":g,
    /// "slivers":z,"microseconds":t}` (`slivers`: zero-area triangles the
    /// boolean left) (`decomposition` entries: `method`, `exact`,
    /// `pieces`, `volume_error`...).
    #[arg(long)]
    pub json: bool,
}

/// The `--json` summary.
#[derive(Serialize)]
struct JsonSummary<'a> {
    p: String,
    q: String,
    method: &'static str,
    pieces: [usize; 2],
    pairs: usize,
    pairs_culled: usize,
    decomposition: JsonDecomposition<'a>,
    vertices: usize,
    faces: usize,
    volume: f64,
    shells: usize,
    genus: i64,
    slivers: usize,
    microseconds: f64,
}

#[derive(Serialize)]
struct JsonDecomposition<'a> {
    p: &'a DecompositionInfo,
    q: &'a DecompositionInfo,
}

/// Runs `dymsum sum`.
///
/// # Errors
/// P or Q cannot be loaded ([`super::solid::load_solid`]); the sum fails
/// ([`dymsum::SumError`]: a posed vertex out of range, or a `hull`-method
/// mismatch); its mesh cannot be produced ([`dymsum::sum::MeshError`]);
/// or the output cannot be written.
pub fn run(a: &SumArgs, out: &mut dyn Write) -> anyhow::Result<()> {
    super::stdin_for_one_operand(&[(&a.p, "P"), (&a.q, "Q")])?;
    let p = load_solid(
        &a.p,
        "P",
        convex_operands(a.body.strict),
        a.body.decomposition,
    )?;
    let q = load_solid(
        &a.q,
        "Q",
        convex_operands(a.body.strict),
        a.body.decomposition,
    )?;
    let pose_p = Pose::new(
        a.rotate_p.unwrap_or(Rotation::IDENTITY),
        a.translate_p.unwrap_or(DVec3::ZERO),
    );
    let method: Method = a.method.into();
    if !(p.is_convex() && q.is_convex()) {
        return run_union(a, p, q, pose_p, method, out);
    }
    let start = Instant::now();
    let sum = minkowski_sum_posed(&p.pieces[0], pose_p, &q.pieces[0], Pose::IDENTITY, method)
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
    if a.json {
        let volume = mesh.signed_volume();
        return write_json(
            a,
            &p,
            &q,
            method,
            [1, 0, 0],
            &mesh,
            volume,
            (1, 0, 0),
            elapsed,
            summary,
        );
    }
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

/// The non-convex path: the union of the exact piece-pair sums, merged and
/// validated.
fn run_union(
    a: &SumArgs,
    p: Solid,
    q: Solid,
    pose_p: Pose,
    method: Method,
    out: &mut dyn Write,
) -> anyhow::Result<()> {
    let (np, nq) = (p.pieces.len(), q.pieces.len());
    let pu = ConvexUnion::new(p.pieces.clone()).context("P has no pieces")?;
    let qu = ConvexUnion::new(q.pieces.clone()).context("Q has no pieces")?;
    let start = Instant::now();
    let sum = UnionSum::new(&pu, pose_p, &qu, Pose::IDENTITY, method, !a.no_cull)
        .with_context(|| format!("{} ⊕ {} ({}, union of piece sums)", a.p, a.q, method.name()))?;
    let elapsed = micros(start.elapsed());
    let to_stdout = a.output.as_os_str() == super::STDIO;
    super::write_mesh_or_stdout(&a.output, sum.mesh(), out).context("writing the sum")?;
    let info = sum.info();
    let mut stderr = std::io::stderr();
    let summary: &mut dyn Write = if to_stdout { &mut stderr } else { out };
    if a.json {
        return write_json(
            a,
            &p,
            &q,
            method,
            [np * nq, info.pairs_culled, 0],
            sum.mesh(),
            info.mesh.volume,
            (info.mesh.shells, info.mesh.genus, info.mesh.slivers),
            elapsed,
            summary,
        );
    }
    writeln!(
        summary,
        "{} ⊕ {} ({}): {} ⊕ {}, {} pair sums ({} culled) merged by boolmesh: \
         {} triangles, volume {}, {} shell{}, genus {}; P {}, Q {}; {}",
        short_name(&a.p),
        short_name(&a.q),
        method.name(),
        plural(np, "piece"),
        plural(nq, "piece"),
        info.pairs,
        info.pairs_culled,
        info.mesh.triangles,
        volume_text(info.mesh.volume),
        info.mesh.shells,
        if info.mesh.shells == 1 { "" } else { "s" },
        info.mesh.genus,
        describe(&p.info),
        describe(&q.info),
        human_us(elapsed),
    )?;
    Ok(())
}

/// Writes the `--json` summary. `pairs` is `[pairs, culled, _]`.
#[allow(clippy::too_many_arguments)]
fn write_json(
    a: &SumArgs,
    p: &Solid,
    q: &Solid,
    method: Method,
    pairs: [usize; 3],
    mesh: &dymsum::PolygonMesh,
    volume: f64,
    (shells, genus, slivers): (usize, i64, usize),
    elapsed: f64,
    out: &mut dyn Write,
) -> anyhow::Result<()> {
    let s = JsonSummary {
        p: short_name(&a.p),
        q: short_name(&a.q),
        method: method.name(),
        pieces: [p.pieces.len(), q.pieces.len()],
        pairs: pairs[0],
        pairs_culled: pairs[1],
        decomposition: JsonDecomposition {
            p: &p.info,
            q: &q.info,
        },
        vertices: mesh.vertices.len(),
        faces: mesh.faces.len(),
        volume,
        shells,
        genus,
        slivers,
        microseconds: elapsed,
    };
    writeln!(out, "{}", serde_json::to_string(&s)?)?;
    Ok(())
}

/// A volume with 6 decimals, trailing zeros dropped (`12.375`).
fn volume_text(v: f64) -> String {
    let s = format!("{v:.6}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// `1 piece`, `2 pieces`.
fn plural(n: usize, what: &str) -> String {
    if n == 1 {
        format!("1 {what}")
    } else {
        format!("{n} {what}s")
    }
}
