//! Loading an operand that may be non-convex: one convex body, a union of
//! convex pieces (`a.off+b.off`, an OBJ file with several objects), or a
//! closed non-convex mesh taken apart into convex pieces (its exactly convex
//! components, or a decomposition chosen with `--decomposition`); for the
//! contact checks (`query`, `motion`), any other mesh file as triangles of
//! any topology ([`load_contact_body`]).

use std::path::Path;

use anyhow::anyhow;
use clap::{Args, ValueEnum};
use dymsum::nonconvex::{convex_pieces, Decomposition, DecompositionInfo, UnionMeshError};
use dymsum::query::{Body, ConvexUnion, MeshBody, MeshReport};
use dymsum::{DVec3, PolygonMesh, Polytope, SolidError};

use super::{load, policy, short_name};

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

/// Loads operand `spec` as convex pieces. A convex body or a union of
/// convex pieces loads as for `dymsum query` ([`load_body`]); a mesh file
/// refused only for not being convex is checked exactly to be a solid
/// ([`dymsum::solid::check_solid_mesh`]), then split into its exactly
/// convex shells, or else by `decomposition`.
///
/// # Errors
/// Those of [`load_body`] when the operand is no mesh at all; for a mesh
/// that is not a solid, what is wrong and where, then the fix; for a
/// non-convex solid, the convex loader's message (naming the operand
/// and where the mesh is not convex) followed by
/// [`UnionMeshError::NeedsDecomposition`] (naming `--decomposition vhacd`)
/// or a decomposition failure.
pub fn load_solid(
    spec: &str,
    operand: &str,
    strict: Strictness,
    decomposition: Option<DecompositionArg>,
) -> anyhow::Result<Solid> {
    let refusal = match load_body(spec, operand, strict) {
        Ok(pieces) => {
            let n = pieces.len();
            let method = if n == 1 { "convex" } else { "given" };
            return Ok(Solid {
                pieces,
                info: DecompositionInfo::exact(method, n),
            });
        }
        Err(e) => e,
    };
    let Some(mesh) = mesh_file(spec) else {
        return Err(refusal);
    };
    let d = decomposition.map_or(Decomposition::Components, Decomposition::from);
    match convex_pieces(&mesh, d) {
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
            super::short_name(spec)
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
/// as pieces (`query`, `cobst`, `motion`): as [`load_solid`]; a
/// decomposition, being approximate, is announced on standard error with
/// its volume error (never silently).
///
/// # Errors
/// Those of [`load_solid`].
pub fn load_pieces(
    spec: &str,
    operand: &str,
    strict: Strictness,
    decomposition: Option<DecompositionArg>,
) -> anyhow::Result<Vec<Polytope>> {
    let solid = load_solid(spec, operand, strict, decomposition)?;
    if !solid.info.exact {
        eprintln!(
            "note: {operand} ({}) taken apart by {}",
            super::short_name(spec),
            describe(&solid.info)
        );
    }
    Ok(solid.pieces)
}

/// The mesh of operand `spec` when it is one mesh file with faces (not a
/// union joined with `+`, a model name, standard input or a point cloud).
fn mesh_file(spec: &str) -> Option<PolygonMesh> {
    let path = Path::new(spec);
    if spec.contains('+') || !path.is_file() {
        return None;
    }
    let mesh = dymsum_io::formats::read_mesh(path).ok()?;
    (!mesh.faces.is_empty()).then_some(mesh)
}

/// Loads operand `spec` for the contact checks (`query`, `motion`), taking
/// a mesh file as Python's `MotionChecker` and Rust's
/// [`Body::from_mesh`] take it: cleaned exactly ([`MeshBody::new`]: open,
/// double-sided, non-manifold, touching parts, cavities; what encloses is
/// what has a non-zero winding number), on the convex path when it is one
/// exactly convex solid, as triangles otherwise, announced on standard
/// error with what the cleaning did ([`describe_triangles`]). A mesh convex
/// only within rounding is taken exactly too; with `--hull` it is replaced
/// by the exact hull of its vertices and the deviation is announced.
/// Model names, unions (`a+b`, OBJ objects) and point clouds are convex
/// pieces ([`load_pieces`], mesh files among them taken exactly unless
/// `--hull`); with `--decomposition` a mesh is taken apart or refused,
/// never taken as triangles.
///
/// # Errors
/// Those of [`load_pieces`] when the operand is not one mesh file or a
/// decomposition was asked for; a mesh file that cannot be read; a mesh
/// with no triangle left to take (every face of zero area).
pub fn load_contact_body(spec: &str, operand: &str, options: BodyOptions) -> anyhow::Result<Body> {
    let strict = if options.strict {
        Strictness::Strict
    } else if options.hull {
        Strictness::Tolerant
    } else {
        Strictness::ExactFiles
    };
    let name = short_name(spec);
    if options.decomposition.is_none() && !is_multi_object_obj(spec) {
        if let Some(mesh) = mesh_file(spec) {
            if options.hull {
                if let Ok((hull, r)) = Polytope::from_mesh(&mesh, policy(false)) {
                    if r.replaced_by_hull {
                        eprintln!(
                            "note: {operand} ({name}) replaced by the exact hull of its vertices \
                             (--hull): convex within tolerance, largest deviation {:.3e} \
                             (tolerance {:.3e})",
                            r.max_deviation, r.tolerance
                        );
                    }
                    return Ok(Body::Convex(ConvexUnion::from(hull)));
                }
            }
            let body = MeshBody::new(&mesh).map_err(|e| match e {
                SolidError::Empty => anyhow!(
                    "{operand} (file {name}): no triangle is left after cleaning: all {} faces \
                     have zero area (or repeat a vertex)",
                    mesh.faces.len()
                ),
                e => anyhow!("{operand} (file {name}): {e}"),
            })?;
            let what = describe_triangles(&body.report());
            if body.as_convex().is_none() {
                // A solid of several exactly convex shells is their union
                // (the same set: the convex path, with depth and distance).
                if let Ok((pieces, info)) = convex_pieces(&mesh, Decomposition::Components) {
                    if info.exact && pieces.len() > 1 {
                        eprintln!(
                            "note: {operand} ({name}) taken as {} exactly convex shells (their \
                             union: the same solid as its triangles)",
                            pieces.len()
                        );
                        if let Some(union) = ConvexUnion::new(pieces) {
                            return Ok(Body::Convex(union));
                        }
                    }
                }
            }
            if body.as_convex().is_some() {
                eprintln!(
                    "note: {operand} ({name}) cleaned as triangles ({what}): exactly convex, \
                     taken as one convex piece"
                );
            } else {
                eprintln!("note: {operand} ({name}) taken as triangles ({what})");
            }
            return Ok(Body::Mesh(body));
        }
    }
    let refusal = match load_pieces(spec, operand, strict, options.decomposition) {
        Ok(pieces) => {
            return ConvexUnion::new(pieces)
                .map(Body::Convex)
                .ok_or_else(|| anyhow!("{operand} has no pieces"))
        }
        Err(e) => e,
    };
    if options.decomposition.is_some() {
        return Err(refusal);
    }
    let Some(mesh) = mesh_file(spec) else {
        return Err(refusal);
    };
    let Ok(body) = MeshBody::new(&mesh) else {
        return Err(refusal);
    };
    eprintln!(
        "note: {operand} ({name}) taken as triangles ({})",
        describe_triangles(&body.report())
    );
    Ok(Body::Mesh(body))
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

/// Whether `spec` is an OBJ file of several objects (each a convex piece).
fn is_multi_object_obj(spec: &str) -> bool {
    !obj_names(spec).is_empty()
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

/// Loads a body: one convex polytope, or several pieces (`a+b+c`, or an OBJ
/// file with several objects). Errors name the operand and the piece.
///
/// # Errors
/// An OBJ file that cannot be read or parsed; an object or piece that is
/// not a valid convex body ([`dymsum::PolytopeError`]); or any error of
/// [`super::load`] for a single body or a `+`-separated piece.
pub fn load_body(spec: &str, operand: &str, strict: Strictness) -> anyhow::Result<Vec<Polytope>> {
    let path = Path::new(spec);
    if path.is_file() {
        let strict = strict.for_part(spec);
        let is_obj = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("obj"));
        if is_obj {
            let objects = dymsum_io::formats::read_obj_objects(path)
                .map_err(|e| anyhow!("{operand} (file {}): {e}", short_name(spec)))?;
            if objects.len() > 1 {
                return objects
                    .into_iter()
                    .map(|(name, mesh)| {
                        let poly = if mesh.faces.is_empty() {
                            let pts: Vec<DVec3> =
                                mesh.vertices.iter().map(|&p| DVec3::from(p)).collect();
                            Polytope::from_dvec3s(&pts)
                        } else {
                            Polytope::from_mesh(&mesh, policy(strict)).map(|(p, _)| p)
                        };
                        poly.map_err(|e| {
                            anyhow!(
                                "{operand} (file {}, object `{name}`): {e}",
                                short_name(spec)
                            )
                        })
                    })
                    .collect();
            }
        }
        return Ok(vec![load(spec, operand, strict)?.polytope]);
    }
    if spec.contains('+') {
        return spec
            .split('+')
            .enumerate()
            .map(|(i, part)| {
                let part = part.trim();
                load(
                    part,
                    &format!("{operand} piece {}", i + 1),
                    strict.for_part(part),
                )
                .map(|l| l.polytope)
            })
            .collect();
    }
    Ok(vec![load(spec, operand, strict.for_part(spec))?.polytope])
}

/// Which meshes must be exactly convex to be taken as one convex piece.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strictness {
    /// None: a mesh convex within tolerance is the exact hull of its
    /// vertices (`sum`, `info`, `cobst` without `--strict`).
    Tolerant,
    /// Every mesh (`--strict`).
    Strict,
    /// Mesh files (the contact checks without `--hull`); the built-in
    /// models are what their definitions say (hulls).
    ExactFiles,
}

impl Strictness {
    /// The `--strict` flag of the subcommands that need convex operands.
    pub fn from_flag(strict: bool) -> Strictness {
        if strict {
            Strictness::Strict
        } else {
            Strictness::Tolerant
        }
    }

    /// The strict flag for one operand or `+` piece `spec`.
    fn for_part(self, spec: &str) -> bool {
        match self {
            Strictness::Tolerant => false,
            Strictness::Strict => true,
            Strictness::ExactFiles => Path::new(spec).is_file(),
        }
    }
}

/// Loads one convex body for a subcommand that takes only one (`info`,
/// `render`): as [`super::load`], but a body of several pieces (a union
/// `a+b`, an OBJ file with several objects, a mesh of several convex
/// shells) is refused with the problem first and the fix last, naming the
/// subcommands that take unions.
///
/// # Errors
/// Those of [`super::load`]; a body of several pieces.
pub fn load_single_body(
    spec: &str,
    operand: &str,
    strict: bool,
    subcommand: &str,
) -> anyhow::Result<dymsum_io::Loaded> {
    let error = match load(spec, operand, strict) {
        Ok(loaded) => return Ok(loaded),
        Err(e) => e,
    };
    match load_solid(spec, operand, Strictness::from_flag(strict), None) {
        Ok(solid) if solid.pieces.len() > 1 => Err(anyhow!(
            "{operand} ({}): a body of {} convex pieces{}, and `dymsum {subcommand}` takes one \
             convex body; to use the pieces, run `dymsum sum`, `query`, `motion` or `cobst`, which \
             take unions (pieces joined with `+`, OBJ objects, or a mesh of convex shells), or \
             give one piece",
            short_name(spec),
            solid.pieces.len(),
            obj_names(spec)
        )),
        _ => Err(error),
    }
}

/// ` (`a`, `b`)`: the object names of an OBJ file of several objects, or
/// nothing.
fn obj_names(spec: &str) -> String {
    let path = Path::new(spec);
    let is_obj = path.is_file()
        && path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("obj"));
    match is_obj.then(|| dymsum_io::formats::read_obj_objects(path)) {
        Some(Ok(objects)) if objects.len() > 1 => {
            let names: Vec<String> = objects.iter().map(|(n, _)| format!("`{n}`")).collect();
            format!(" ({})", names.join(", "))
        }
        _ => String::new(),
    }
}
