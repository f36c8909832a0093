//! The bodies the subcommands take, as arguments and messages over the one
//! loader, `dymsum_io::body` (each operand read once; the command line
//! adds `-` for standard input): one mesh file through the core's ladder
//! (`dymsum::query::Body::from_mesh_with`: convex, a solid of exactly
//! convex shells, triangles; the hull only with `--hull`) for the contact
//! checks (`query`, `motion`: [`load_contact_body`]); convex pieces for the
//! subcommands that need them ([`load_solid`], [`load_pieces`]: one convex
//! body, a union `a.off+b.off`, an OBJ file of several objects, or a
//! closed non-convex mesh taken apart into its exactly convex shells, or
//! by `--decomposition`); one convex body for `info` and `render`
//! ([`load_single_body`]).

use anyhow::anyhow;
use clap::{Args, ValueEnum};
use dymsum::body::{BodyReport, Rung};
use dymsum::nonconvex::{convex_pieces, Decomposition, DecompositionInfo, UnionMeshError};
use dymsum::query::{Body, ConvexUnion, MeshReport};
use dymsum::{Polytope, SolidError};
use dymsum_io::body::{Content, LoadOptions, Operand, Reader, SourceKind, Taken};
use dymsum_io::formats::{Format, FormatError};
use dymsum_io::LoadError;

use super::{short_name, STDIO};

/// A convex decomposition for non-convex meshes, as a command-line value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DecompositionArg {
    /// parry's V-HACD (approximate: its volume error is reported).
    Vhacd,
}

/// How the operands given as meshes are taken, the same for every
/// subcommand that loads bodies (`sum`, `query`, `motion`, `cobst`).
#[derive(Clone, Copy, Debug, Default, Args)]
pub struct BodyOptions {
    /// Refuse meshes that are convex only within tolerance (instead of
    /// taking the exact hull of their vertices). `query` and `motion` take
    /// mesh files exactly anyway (see `--hull`).
    #[arg(long)]
    pub strict: bool,
    /// `query` and `motion`: take a mesh file that is convex only within
    /// tolerance (1e-5 of its box's diagonal) as the exact hull of its
    /// vertices, reporting the deviation on standard error. Without it such
    /// a mesh is taken exactly, as the triangles it is (as Python and Rust
    /// take it). `sum`, `info` and `cobst` need convex operands and take
    /// the hull unless `--strict`.
    #[arg(long, conflicts_with = "strict")]
    pub hull: bool,
    /// Take a non-convex mesh whose connected components are not all
    /// exactly convex apart by this decomposition (approximate: its volume
    /// error against the input is reported, in `sum`'s summary and on
    /// standard error elsewhere). Without it such a mesh is refused;
    /// exactly convex components are always taken as they are.
    #[arg(long, value_enum, value_name = "METHOD")]
    pub decomposition: Option<DecompositionArg>,
}

impl BodyOptions {
    /// How the contact checks (`query`, `motion`) take meshes: mesh files
    /// exactly unless `--hull`, the built-in models as their definitions
    /// say (hulls) unless `--strict`.
    pub fn contact(&self) -> LoadOptions {
        LoadOptions {
            hull: self.hull,
            strict_models: self.strict,
        }
    }
}

/// How the subcommands that need convex operands (`sum`, `animate`,
/// `cobst`, `info`, `render`) take meshes: a mesh convex within tolerance
/// is the exact hull of its vertices, unless `--strict` refuses it.
pub fn convex_operands(strict: bool) -> LoadOptions {
    LoadOptions {
        hull: !strict,
        strict_models: strict,
    }
}

impl From<DecompositionArg> for Decomposition {
    fn from(d: DecompositionArg) -> Decomposition {
        match d {
            DecompositionArg::Vhacd => Decomposition::VHACD,
        }
    }
}

/// An operand's convex pieces and how they were obtained.
#[derive(Debug)]
pub struct Solid {
    /// The convex pieces (at least one).
    pub pieces: Vec<Polytope>,
    /// How: `convex`, `given`, `components` or `vhacd`.
    pub info: DecompositionInfo,
}

impl Solid {
    /// One convex body, taken as it is.
    pub fn is_convex(&self) -> bool {
        self.info.method == "convex"
    }
}

/// The command line's [`Reader`]: files, and `-` as OFF from standard
/// input (once per run).
struct CommandLine<'a> {
    operand: &'a str,
    /// Why standard input could not be read, in the command line's words.
    failure: Option<anyhow::Error>,
}

impl Reader for CommandLine<'_> {
    fn resolve(&mut self, spec: &str) -> Option<Result<Operand, LoadError>> {
        if spec != STDIO {
            return None;
        }
        Some(match super::read_stdin_once(self.operand) {
            Ok(bytes) => dymsum_io::body::read_operand_bytes(&bytes, Format::Off, "standard input"),
            Err(e) => {
                let source = std::io::Error::other(e.to_string());
                self.failure = Some(e);
                Err(LoadError::Format {
                    origin: "standard input".into(),
                    source: FormatError::Io {
                        path: STDIO.into(),
                        source,
                    },
                })
            }
        })
    }
}

/// Reads operand `spec` (`"P"`, `"ROBOT"`) once: a file, a model name, `-`
/// (standard input), or pieces joined with `+`
/// ([`dymsum_io::body::read_operands_from`]).
///
/// # Errors
/// The first piece that cannot be read or found, named with the operand
/// ([`LoadError::for_operand`]), or standard input read twice.
pub fn read(spec: &str, operand: &str) -> anyhow::Result<Vec<Operand>> {
    let mut reader = CommandLine {
        operand,
        failure: None,
    };
    dymsum_io::body::read_operands_from(spec, &mut reader).map_err(|e| {
        reader
            .failure
            .take()
            .unwrap_or_else(|| anyhow!(e.for_operand(operand)))
    })
}

/// Loads operand `spec` as convex pieces ([`read`], then as
/// [`dymsum_io::body::convex_pieces`] takes it under `options`); a mesh
/// file that is not one convex body is checked exactly to be a solid
/// ([`dymsum::solid::check_solid_mesh`]), then split into its exactly
/// convex shells, or else by `decomposition`.
///
/// # Errors
/// Those of [`read`]; for a mesh that is not a solid, what is wrong and
/// where, then the fix; for a non-convex solid, the convex loader's
/// message (naming the operand and where the mesh is not convex) followed
/// by [`UnionMeshError::NeedsDecomposition`] (naming `--decomposition
/// vhacd`) or a decomposition failure.
pub fn load_solid(
    spec: &str,
    operand: &str,
    options: LoadOptions,
    decomposition: Option<DecompositionArg>,
) -> anyhow::Result<Solid> {
    solid_of(&read(spec, operand)?, operand, options, decomposition)
}

/// [`load_solid`] of an operand already read.
fn solid_of(
    parts: &[Operand],
    operand: &str,
    options: LoadOptions,
    decomposition: Option<DecompositionArg>,
) -> anyhow::Result<Solid> {
    let refusal = match dymsum_io::body::convex_pieces(parts, &options) {
        Ok(pieces) => {
            for (i, p) in pieces.iter().enumerate() {
                log::debug!(
                    "{operand} piece {}: {} vertices, {} faces, {} edges",
                    i + 1,
                    p.vertex_count(),
                    p.face_count(),
                    p.edge_count()
                );
            }
            let n = pieces.len();
            let method = if n == 1 { "convex" } else { "given" };
            return Ok(Solid {
                pieces,
                info: DecompositionInfo::exact(method, n),
            });
        }
        Err(e) => anyhow!(e.for_operand(operand)),
    };
    // One mesh file with faces (an OBJ file of several objects as a whole).
    let file = match parts {
        [part] if part.kind == SourceKind::File && !part.mesh().faces.is_empty() => part,
        _ => return Err(refusal),
    };
    let d = decomposition.map_or(Decomposition::Components, Decomposition::from);
    match convex_pieces(file.mesh(), d) {
        Ok((pieces, info)) => Ok(Solid { pieces, info }),
        // An open mesh is no solid at all: the convex loader's message
        // names its open edge; the fix comes last.
        Err(UnionMeshError::Solid(SolidError::OpenEdge { .. })) => Err(anyhow!(
            "{refusal}; fix: close the mesh (every edge must border exactly two faces), or give \
             the body's convex pieces as files joined with `+` or as OBJ objects"
        )),
        // Checked exactly before any shell or decomposition is taken: the
        // problem, where, then the fix.
        Err(UnionMeshError::Solid(e)) => Err(anyhow!(
            "{operand} (file {}): not a solid: {e}; fix: repair the mesh so that each shell is \
             closed, consistently oriented, manifold and crosses itself nowhere, or give its \
             convex pieces as files joined with `+` or as OBJ objects",
            short_name(&file.spec)
        )),
        // No closed solid: the convex loader's message says most, the
        // non-convex reading's reason after it, the fix last.
        Err(UnionMeshError::Input { reason }) => Err(anyhow!(
            "{refusal}; as a non-convex body: {reason}; fix: give a closed mesh, or the body's \
             convex pieces as files joined with `+` or as OBJ objects"
        )),
        // Why it is not convex, then what to do about it.
        Err(e) => Err(anyhow!("{refusal}; {e}")),
    }
}

/// The convex pieces of operand `spec` for the commands that take bodies
/// as pieces (`cobst`): as [`load_solid`]; a decomposition, being
/// approximate, is announced on standard error with its volume error
/// (never silently).
///
/// # Errors
/// Those of [`load_solid`].
pub fn load_pieces(
    spec: &str,
    operand: &str,
    options: LoadOptions,
    decomposition: Option<DecompositionArg>,
) -> anyhow::Result<Vec<Polytope>> {
    let solid = load_solid(spec, operand, options, decomposition)?;
    announce_decomposition(spec, operand, &solid);
    Ok(solid.pieces)
}

/// The note on standard error for pieces taken apart by a decomposition.
fn announce_decomposition(spec: &str, operand: &str, solid: &Solid) {
    if !solid.info.exact {
        eprintln!(
            "note: {operand} ({}) taken apart by {}",
            short_name(spec),
            describe(&solid.info)
        );
    }
}

/// Loads operand `spec` for the contact checks (`query`, `motion`), read
/// once and taken as Python's `MotionChecker` and Rust's
/// `Body::from_mesh_with` take it ([`dymsum_io::body::body_from`]): a mesh
/// file by the core's ladder, cleaned exactly ([`dymsum::query::MeshBody::new`]:
/// open, double-sided, non-manifold, touching parts, cavities; what
/// encloses is what has a non-zero winding number), on the convex path
/// when it is one exactly convex solid or a solid of exactly convex shells
/// (their union), as triangles otherwise, announced on standard error with
/// what the cleaning did ([`describe_triangles`]). A mesh convex only
/// within rounding is taken exactly too; with `--hull` it is replaced by
/// the exact hull of its vertices and the deviation is announced. Model
/// names, unions (`a+b`, OBJ objects) and point clouds are convex pieces
/// (mesh files among them taken exactly unless `--hull`); with
/// `--decomposition` a mesh is taken apart or refused ([`load_pieces`]),
/// never taken as triangles.
///
/// # Errors
/// Those of [`read`]; those of [`load_solid`] with `--decomposition`; a
/// piece that is no convex body; a mesh with no triangle left to take
/// (every face of zero area).
pub fn load_contact_body(spec: &str, operand: &str, options: BodyOptions) -> anyhow::Result<Body> {
    let parts = read(spec, operand)?;
    if options.decomposition.is_some() {
        let solid = solid_of(&parts, operand, options.contact(), options.decomposition)?;
        announce_decomposition(spec, operand, &solid);
        return ConvexUnion::new(solid.pieces)
            .map(Body::Convex)
            .ok_or_else(|| anyhow!("{operand} has no pieces"));
    }
    let loaded = dymsum_io::body::body_from(&parts, &options.contact())
        .map_err(|e| anyhow!(e.for_operand(operand)))?;
    match &loaded.taken {
        Taken::Ladder(report) | Taken::ObjectsByLadder { report, .. } => {
            announce_ladder(operand, &short_name(spec), report);
        }
        Taken::Pieces(_) => {}
    }
    Ok(loaded.body)
}

/// The note on standard error for a mesh file taken by the core's ladder:
/// which rung, and what the cleaning did.
fn announce_ladder(operand: &str, name: &str, r: &BodyReport) {
    let what = r
        .cleaning
        .as_ref()
        .map(describe_triangles)
        .unwrap_or_default();
    match r.rung {
        Rung::Hull => {
            if let Some(h) = r.hull.as_ref().filter(|h| h.replaced_by_hull) {
                eprintln!(
                    "note: {operand} ({name}) replaced by the exact hull of its vertices \
                     (--hull): convex within tolerance, largest deviation {:.3e} (tolerance \
                     {:.3e})",
                    h.max_deviation, h.tolerance
                );
            }
        }
        Rung::Convex => eprintln!(
            "note: {operand} ({name}) cleaned as triangles ({what}): exactly convex, taken as \
             one convex piece"
        ),
        // A solid of several exactly convex shells is their union (the
        // same set: the convex path, with depth and distance).
        Rung::ConvexShells => eprintln!(
            "note: {operand} ({name}) taken as {} exactly convex shells (their union: the same \
             solid as its triangles)",
            r.pieces
        ),
        Rung::Triangles => eprintln!("note: {operand} ({name}) taken as triangles ({what})"),
    }
}

/// The obstacle placed at `pose` (`--obstacle-xyz-wxyz`), or as given.
///
/// # Errors
/// A pose under which a coordinate is not finite ([`Body::placed`]).
pub fn placed(body: Body, pose: Option<dymsum::Pose>) -> anyhow::Result<Body> {
    match pose {
        None => Ok(body),
        Some(p) => body
            .placed(p)
            .map_err(|e| anyhow!("OBSTACLE at --obstacle-xyz-wxyz: {e}")),
    }
}

/// `1 vertex`, `2 vertices`.
fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// What a body of triangles is made of: `2 surfaces, 1 solid`.
pub fn triangle_components(r: &MeshReport) -> String {
    let mut parts = Vec::new();
    if r.surfaces > 0 {
        parts.push(count(r.surfaces, "surface", "surfaces"));
    }
    if r.solids > 0 {
        parts.push(count(r.solids, "solid", "solids"));
    }
    parts.join(", ")
}

/// What a body of triangles is and what cleaning it did, for the note on
/// standard error: `1 surface, 10 triangles; 10 back-to-back triangles
/// dropped, 8 vertices merged` (or `; nothing to clean`).
pub fn describe_triangles(r: &MeshReport) -> String {
    let mut done = Vec::new();
    for (n, what) in [
        (r.dropped_back_to_back, "back-to-back"),
        (r.dropped_duplicates, "duplicate"),
        (r.dropped_zero_area, "zero-area"),
    ] {
        if n > 0 {
            let triangles = count(n, &format!("{what} triangle"), &format!("{what} triangles"));
            done.push(format!("{triangles} dropped"));
        }
    }
    if r.merged_vertices > 0 {
        done.push(format!(
            "{} merged",
            count(r.merged_vertices, "vertex", "vertices")
        ));
    }
    if r.flipped > 0 {
        done.push(format!(
            "{} turned{}",
            count(r.flipped, "triangle", "triangles"),
            if r.inverted {
                " (the input was inward as a whole)"
            } else {
                " outward"
            }
        ));
    }
    if r.split_edges > 0 {
        done.push(format!(
            "{} split at vertices lying on them (T-junctions)",
            count(r.split_edges, "edge", "edges")
        ));
    }
    if r.set_aside > 0 && r.solids > 0 {
        done.push(format!(
            "{} set aside as surface beside the solids (an edge not closed)",
            count(r.set_aside, "triangle", "triangles")
        ));
    }
    if done.is_empty() {
        done.push("nothing to clean".to_string());
    }
    format!(
        "{}, {}; {}",
        triangle_components(r),
        count(r.triangles, "triangle", "triangles"),
        done.join(", ")
    )
}

/// The convex pieces of a contact body ([`load_contact_body`]), or `None`
/// for triangles (a mesh that is one exactly convex solid is its polytope).
pub fn body_pieces(body: &Body) -> Option<Vec<Polytope>> {
    match body {
        Body::Convex(u) => Some(u.pieces().to_vec()),
        Body::Mesh(m) => m.as_convex().map(|p| vec![p.clone()]),
    }
}

/// How an operand's pieces were obtained, for the summary line: `as
/// given`, `convex`, `2 convex components (exact)`, `vhacd: 7 pieces
/// (volume error 0.81%)`.
pub fn describe(info: &DecompositionInfo) -> String {
    match info.method {
        "convex" => "convex".to_string(),
        "given" => format!("{} pieces as given", info.pieces),
        "components" => format!("{} convex components (exact)", info.pieces),
        m => format!(
            "{m}: {} pieces, {} exact (volume error {:.3}%)",
            info.pieces,
            info.convex_components,
            100.0 * info.volume_error.unwrap_or(f64::NAN)
        ),
    }
}

/// Loads one convex body for a subcommand that takes only one (`info`,
/// `render`): read once ([`read`]) and taken as one polytope under
/// `--strict` or not ([`convex_operands`]), but a body of several pieces
/// (a union `a+b`, an OBJ file with several objects, a mesh of several
/// convex shells) is refused with the problem first and the fix last,
/// naming the subcommands that take unions.
///
/// # Errors
/// Those of [`read`]; a mesh or point cloud that is no convex body
/// ([`dymsum_io::LoadError`]); a body of several pieces.
pub fn load_single_body(
    spec: &str,
    operand: &str,
    strict: bool,
    subcommand: &str,
) -> anyhow::Result<dymsum_io::Loaded> {
    let parts = read(spec, operand)?;
    let options = convex_operands(strict);
    let one_body_error = match parts.as_slice() {
        [one] => match one.polytope(options.policy(one.kind)) {
            Ok(loaded) => {
                super::log_loaded(operand, &loaded);
                return Ok(loaded);
            }
            Err(e) => Some(anyhow!(e.for_operand(operand))),
        },
        _ => None,
    };
    match solid_of(&parts, operand, options, None) {
        Ok(solid) if solid.pieces.len() > 1 => Err(anyhow!(
            "{operand} ({}): a body of {} convex pieces{}, and `dymsum {subcommand}` takes one \
             convex body; to use the pieces, run `dymsum sum`, `query`, `motion` or `cobst`, which \
             take unions (pieces joined with `+`, OBJ objects, or a mesh of convex shells), or \
             give one piece",
            short_name(spec),
            solid.pieces.len(),
            object_names(&parts)
        )),
        other => Err(one_body_error
            .or_else(|| other.err())
            .unwrap_or_else(|| anyhow!("{operand}: no convex body"))),
    }
}

/// ` (`a`, `b`)`: the object names of an OBJ file of several objects, or
/// nothing.
fn object_names(parts: &[Operand]) -> String {
    match parts {
        [Operand {
            content: Content::Objects { objects, .. },
            ..
        }] => {
            let names: Vec<String> = objects.iter().map(|(n, _)| format!("`{n}`")).collect();
            format!(" ({})", names.join(", "))
        }
        _ => String::new(),
    }
}
