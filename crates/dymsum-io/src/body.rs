//! An operand read once and taken as a body: the one loader of the command
//! line and of Python.
//!
//! [`read_operands`] reads what a spec names, each file once: a mesh file
//! (OFF, OBJ, PLY, STL; a file with vertices but no faces is a point
//! cloud), an OBJ file of several separate bodies, a built-in model name,
//! or pieces joined with `+` (`a.off+b.off`). Everything after is done in
//! memory on the [`Operand`]s it returns:
//!
//! * [`body_from`] (and [`load_body`], reading and taking at once): one
//!   mesh file through the core's ladder ([`Body::from_mesh_with`]: convex,
//!   a solid of convex shells, triangles; the hull only when
//!   [`LoadOptions::hull`] asks); an OBJ file of several objects as convex
//!   pieces (or, when one is not a convex body, the whole file through the
//!   ladder); models, point clouds and `+` unions as convex pieces;
//! * [`convex_pieces`]: the operand as convex pieces, for the subcommands
//!   that need them (`dymsum sum`, `cobst`);
//! * [`Operand::polytope`]: one convex body ([`crate::load_polytope`] is
//!   [`read_operand`] then this).
//!
//! A [`Reader`] supplies the bytes: [`Files`] reads the file system, and a
//! caller can count the reads or resolve names of its own (the command
//! line's `-` for standard input).
//!
//! ```
//! use dymsum::body::Rung;
//! use dymsum_io::body::{load_body, LoadOptions, Taken};
//! // Two disjoint unit cubes in one OFF file: a solid of two convex shells.
//! let dir = std::env::temp_dir().join(format!("dymsum-io-body-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir)?;
//! let mut off = String::from("OFF\n16 12 0\n");
//! for dx in [0, 3] {
//!     for i in 0..8 {
//!         off += &format!("{} {} {}\n", dx + (i & 1), (i >> 1) & 1, (i >> 2) & 1);
//!     }
//! }
//! for o in [0, 8] {
//!     for q in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
//!         off += &format!("4 {} {} {} {}\n", o + q[0], o + q[1], o + q[2], o + q[3]);
//!     }
//! }
//! let path = dir.join("two.off");
//! std::fs::write(&path, off)?;
//! let loaded = load_body(path.to_str().unwrap(), &LoadOptions::default())?;
//! assert!(loaded.body.is_convex());
//! assert!(matches!(loaded.taken, Taken::Ladder(ref r) if r.rung == Rung::ConvexShells && r.pieces == 2));
//! // A model name is its polytope; `+` joins pieces.
//! let union = load_body("box+gs1", &LoadOptions::default())?;
//! assert!(matches!(union.taken, Taken::Pieces(2)));
//! std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::path::Path;

use dymsum::body::{Body, BodyOptions, BodyReport, ConvexUnion};
use dymsum::polytope::MeshPolicy;
use dymsum::{PolygonMesh, Polytope, PolytopeError};

use crate::formats::{self, Format, FormatError};
pub use crate::load::body_error_text;
use crate::load::{load_mesh, LoadError, Loaded};
use crate::models::{self, ModelError};

/// Where an operand's data came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SourceKind {
    /// A mesh file: taken exactly unless [`LoadOptions::hull`].
    File,
    /// A built-in model: what its definition says (convex pieces, convex
    /// within tolerance unless [`LoadOptions::strict_models`]).
    Model,
    /// Bytes given in memory (standard input): as a model.
    Bytes,
}

/// What an operand, or one piece of a `+` union, holds once read.
#[derive(Clone, Debug)]
pub enum Content {
    /// One mesh; without faces, a point cloud (its hull is the body).
    Mesh(PolygonMesh),
    /// An OBJ file of several separate bodies
    /// ([`formats::read_obj_objects`]: name and mesh, a point cloud
    /// without faces), and the whole file as one mesh.
    Objects {
        /// The bodies, in the order of their first face.
        objects: Vec<(String, PolygonMesh)>,
        /// The file as one mesh ([`formats::read_mesh_bytes`]).
        whole: PolygonMesh,
    },
}

/// An operand (or one piece of a `+` union) read once.
#[derive(Clone, Debug)]
pub struct Operand {
    /// The spec as given (for a piece, the piece's).
    pub spec: String,
    /// Where it came from, for messages: `file foo.off`, `built-in cube`,
    /// `standard input`.
    pub source: String,
    /// Which kind of source.
    pub kind: SourceKind,
    /// What was read.
    pub content: Content,
}

/// How an operand's meshes are taken.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// Mesh files convex within tolerance are the exact hull of their
    /// vertices (the core ladder's [`BodyOptions::hull`]; for pieces,
    /// [`MeshPolicy::default`]). Off: mesh files are taken exactly (a lone
    /// file by the ladder, pieces under [`MeshPolicy::strict`]).
    pub hull: bool,
    /// Built-in models and bytes must be exactly convex
    /// ([`MeshPolicy::strict`]). Off: [`MeshPolicy::default`] (the models'
    /// definitions are hulls; `cube` is convex within rounding).
    pub strict_models: bool,
}

impl LoadOptions {
    /// The policy under which `kind`'s meshes become convex pieces.
    pub fn policy(&self, kind: SourceKind) -> MeshPolicy {
        let strict = match kind {
            SourceKind::File => !self.hull,
            SourceKind::Model | SourceKind::Bytes => self.strict_models,
        };
        if strict {
            MeshPolicy::strict()
        } else {
            MeshPolicy::default()
        }
    }
}

/// Supplies the bytes [`read_operands_from`] reads.
pub trait Reader {
    /// The bytes of the regular file at `path`, read once. The default
    /// reads it from the file system, bounded and refusing what is not a
    /// regular file ([`crate::atomic::read_regular_file`]).
    ///
    /// # Errors
    /// [`FormatError::Io`] or [`FormatError::NotRegularFile`].
    fn read_file(&mut self, path: &Path) -> Result<Vec<u8>, FormatError> {
        crate::atomic::read_regular_file(path).map_err(FormatError::from)
    }

    /// An operand the caller resolves itself (before files and models), or
    /// `None`: nothing by default. The command line reads `-` from
    /// standard input here ([`read_operand_bytes`]).
    fn resolve(&mut self, _spec: &str) -> Option<Result<Operand, LoadError>> {
        None
    }
}

/// The file system, as [`Reader`]'s defaults read it.
#[derive(Clone, Copy, Debug, Default)]
pub struct Files;

impl Reader for Files {}

/// Reads what `spec` names, each file once: one operand, or for pieces
/// joined with `+` (a spec that is not itself a file) one per piece, in
/// order. See [`read_operands_from`].
///
/// # Errors
/// As [`read_operands_from`].
pub fn read_operands(spec: &str) -> Result<Vec<Operand>, LoadError> {
    read_operands_from(spec, &mut Files)
}

/// [`read_operands`] with the bytes from `reader`. Each piece is resolved
/// as [`read_operand_from`] does.
///
/// # Errors
/// The first piece that cannot be read, as [`read_operand_from`]'s error,
/// wrapped in [`LoadError::Piece`] for a piece of a `+` union.
pub fn read_operands_from(spec: &str, reader: &mut dyn Reader) -> Result<Vec<Operand>, LoadError> {
    if !spec.contains('+') || Path::new(spec).is_file() {
        return Ok(vec![read_operand_from(spec, reader)?]);
    }
    spec.split('+')
        .enumerate()
        .map(|(i, part)| {
            read_operand_from(part.trim(), reader).map_err(|e| LoadError::Piece {
                index: i + 1,
                source: Box::new(e),
            })
        })
        .collect()
}

/// Reads one operand (no `+` splitting), the file once: see
/// [`read_operand_from`].
///
/// # Errors
/// As [`read_operand_from`].
pub fn read_operand(spec: &str) -> Result<Operand, LoadError> {
    read_operand_from(spec, &mut Files)
}

/// Reads one operand with the bytes from `reader`: what
/// [`Reader::resolve`] gives; else an existing file with a mesh extension
/// (format by extension; an OBJ file's separate bodies as
/// [`Content::Objects`] when there are several); else a built-in model
/// ([`models::model`]). A file without a mesh extension that is also a
/// model name resolves to the model.
///
/// # Errors
/// [`LoadError::NotFound`] when `spec` is neither a file nor a model (with
/// the closest model name); [`LoadError::Format`] when the file cannot be
/// read or parsed; [`LoadError::Model`] for a model's bad parameters.
pub fn read_operand_from(spec: &str, reader: &mut dyn Reader) -> Result<Operand, LoadError> {
    if let Some(resolved) = reader.resolve(spec) {
        return resolved;
    }
    let path = Path::new(spec);
    let is_file = path.is_file();
    if is_file && has_mesh_extension(spec) {
        return read_file(spec, path, reader);
    }
    let model = models::model(spec);
    // A directory (or other non-file) that is no model: the reader gives
    // the error.
    if path.exists() && model.is_err() {
        return read_file(spec, path, reader);
    }
    let origin = format!("built-in {}", spec.trim());
    match model {
        Ok(mesh) => Ok(Operand {
            spec: spec.to_string(),
            source: origin,
            kind: SourceKind::Model,
            content: Content::Mesh(mesh),
        }),
        Err(ModelError::Unknown { suggestion, .. }) => Err(LoadError::NotFound {
            spec: spec.to_string(),
            suggestion,
            looks_like_file: looks_like_file(spec),
        }),
        Err(source) => Err(LoadError::Model { origin, source }),
    }
}

/// An operand from mesh bytes already in memory (standard input, a
/// network buffer) in `format`; `origin` labels messages
/// ([`Operand::source`]).
///
/// # Errors
/// [`LoadError::Format`] when the bytes do not parse in `format`.
pub fn read_operand_bytes(
    bytes: &[u8],
    format: Format,
    origin: &str,
) -> Result<Operand, LoadError> {
    let mesh =
        formats::read_mesh_bytes(bytes, format, origin).map_err(|source| LoadError::Format {
            origin: origin.to_string(),
            source,
        })?;
    Ok(Operand {
        spec: origin.to_string(),
        source: origin.to_string(),
        kind: SourceKind::Bytes,
        content: Content::Mesh(mesh),
    })
}

/// The file at `path`, read once: format by extension first (an unknown
/// one is refused before reading), then the bytes, parsed in memory.
fn read_file(spec: &str, path: &Path, reader: &mut dyn Reader) -> Result<Operand, LoadError> {
    let origin = format!("file {spec}");
    let format_err = |source| LoadError::Format {
        origin: origin.clone(),
        source,
    };
    let format = Format::from_path(path).map_err(format_err)?;
    let bytes = reader.read_file(path).map_err(format_err)?;
    let name = path.display().to_string();
    let content = if format == Format::Obj {
        // The same bodies in every command: groups of one closed mesh are
        // one body, a faceless object is a point cloud.
        let mut objects = formats::read_obj_objects_bytes(&bytes, &name).map_err(format_err)?;
        if objects.len() > 1 {
            let whole = formats::read_mesh_bytes(&bytes, format, &name).map_err(format_err)?;
            Content::Objects { objects, whole }
        } else {
            Content::Mesh(objects.pop().map(|(_, m)| m).unwrap_or_default())
        }
    } else {
        Content::Mesh(formats::read_mesh_bytes(&bytes, format, &name).map_err(format_err)?)
    };
    Ok(Operand {
        spec: spec.to_string(),
        source: origin,
        kind: SourceKind::File,
        content,
    })
}

/// Mesh file extensions, for telling a mistyped path from a mistyped name.
const MESH_EXTENSIONS: [&str; 4] = ["off", "obj", "ply", "stl"];

fn has_mesh_extension(spec: &str) -> bool {
    Path::new(spec)
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| MESH_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()))
}

fn looks_like_file(spec: &str) -> bool {
    spec.contains('/') || spec.contains(std::path::MAIN_SEPARATOR) || has_mesh_extension(spec)
}

impl Operand {
    /// The operand as one convex body under `policy` ([`load_mesh`]: a
    /// point cloud is its hull).
    ///
    /// # Errors
    /// [`LoadError::SeveralBodies`] for an OBJ file of several bodies;
    /// [`LoadError::Polytope`] when the mesh is no convex body.
    pub fn polytope(&self, policy: MeshPolicy) -> Result<Loaded, LoadError> {
        match &self.content {
            Content::Mesh(mesh) => load_mesh(mesh.clone(), self.source.clone(), policy),
            Content::Objects { objects, .. } => Err(several_bodies(&self.source, objects)),
        }
    }

    /// [`Operand::polytope`], the mesh moved into the [`Loaded`].
    pub(crate) fn into_polytope(self, policy: MeshPolicy) -> Result<Loaded, LoadError> {
        match self.content {
            Content::Mesh(mesh) => load_mesh(mesh, self.source, policy),
            Content::Objects { objects, .. } => Err(several_bodies(&self.source, &objects)),
        }
    }

    /// The operand as convex pieces under `policy`: one, or one per
    /// object of an OBJ file (a faceless object is its points' hull).
    ///
    /// # Errors
    /// [`LoadError::Polytope`] when the mesh is no convex body;
    /// [`LoadError::Object`] naming the first object that is none.
    pub fn convex_pieces(&self, policy: MeshPolicy) -> Result<Vec<Polytope>, LoadError> {
        let Content::Objects { objects, .. } = &self.content else {
            return Ok(vec![self.polytope(policy)?.polytope]);
        };
        objects
            .iter()
            .map(|(name, mesh)| {
                convex_body(mesh, policy).map_err(|source| LoadError::Object {
                    origin: self.source.clone(),
                    name: name.clone(),
                    source,
                })
            })
            .collect()
    }

    /// The operand's mesh as read: its one mesh, or an OBJ file's whole
    /// mesh.
    pub fn mesh(&self) -> &PolygonMesh {
        match &self.content {
            Content::Mesh(mesh) => mesh,
            Content::Objects { whole, .. } => whole,
        }
    }
}

/// An OBJ file's several bodies where one was needed.
fn several_bodies(origin: &str, objects: &[(String, PolygonMesh)]) -> LoadError {
    LoadError::SeveralBodies {
        origin: origin.to_string(),
        names: objects.iter().map(|(n, _)| n.clone()).collect(),
    }
}

/// A mesh as one convex body: a point cloud's hull, or the mesh under
/// `policy`.
fn convex_body(mesh: &PolygonMesh, policy: MeshPolicy) -> Result<Polytope, PolytopeError> {
    if mesh.faces.is_empty() {
        Polytope::from_points(&mesh.vertices)
    } else {
        Polytope::from_mesh(mesh, policy).map(|(p, _)| p)
    }
}

/// The convex pieces of an operand read by [`read_operands`]: one
/// operand's ([`Operand::convex_pieces`]), or one convex body per piece of
/// a `+` union ([`Operand::polytope`]), each under
/// [`LoadOptions::policy`] for its kind.
///
/// # Errors
/// Those of [`Operand::convex_pieces`], or for a union the first piece's
/// error of [`Operand::polytope`] in [`LoadError::Piece`].
pub fn convex_pieces(parts: &[Operand], options: &LoadOptions) -> Result<Vec<Polytope>, LoadError> {
    if let [one] = parts {
        return one.convex_pieces(options.policy(one.kind));
    }
    parts
        .iter()
        .enumerate()
        .map(|(i, part)| {
            part.polytope(options.policy(part.kind))
                .map(|l| l.polytope)
                .map_err(|e| LoadError::Piece {
                    index: i + 1,
                    source: Box::new(e),
                })
        })
        .collect()
}

/// A body and how it was taken.
#[derive(Debug)]
pub struct LoadedBody {
    /// The body.
    pub body: Body,
    /// How it was taken.
    pub taken: Taken,
}

/// How [`body_from`] took an operand.
#[derive(Debug)]
pub enum Taken {
    /// One mesh file by the core's ladder ([`Body::from_mesh_with`]).
    Ladder(BodyReport),
    /// Convex pieces (this many): a model, a point cloud, bytes, the
    /// objects of an OBJ file, or the pieces of a `+` union.
    Pieces(usize),
    /// An OBJ file of several objects, one of which is no convex body
    /// (`refused`): the whole file by the ladder.
    ObjectsByLadder {
        /// Why the objects were not taken as convex pieces.
        refused: LoadError,
        /// What the ladder did with the whole file.
        report: BodyReport,
    },
}

/// The body of an operand read by [`read_operands`] (no file is read
/// again). One mesh file (with faces) goes through the core's ladder
/// ([`Body::from_mesh_with`], the hull when [`LoadOptions::hull`]); an OBJ
/// file of several objects is their convex pieces, or when one is no
/// convex body the whole file through the ladder; models, point clouds,
/// bytes and `+` unions are convex pieces ([`convex_pieces`]).
///
/// # Errors
/// [`LoadError::Body`] when a mesh file cannot be taken even as triangles
/// (no triangle left after cleaning); those of [`convex_pieces`] (for an
/// OBJ file of several objects, when the whole file cannot be taken
/// either).
pub fn body_from(parts: &[Operand], options: &LoadOptions) -> Result<LoadedBody, LoadError> {
    let ladder = |part: &Operand, mesh: &PolygonMesh| {
        Body::from_mesh_with(mesh, &BodyOptions { hull: options.hull }).map_err(|source| {
            LoadError::Body {
                origin: part.source.clone(),
                faces: mesh.faces.len(),
                source,
            }
        })
    };
    if let [part] = parts {
        if part.kind == SourceKind::File {
            match &part.content {
                Content::Mesh(mesh) if !mesh.faces.is_empty() => {
                    let (body, report) = ladder(part, mesh)?;
                    return Ok(LoadedBody {
                        body,
                        taken: Taken::Ladder(report),
                    });
                }
                Content::Objects { whole, .. } => {
                    let refused = match convex_pieces(parts, options) {
                        Ok(pieces) => return Ok(pieces_body(pieces)),
                        Err(e) => e,
                    };
                    let Ok((body, report)) = ladder(part, whole) else {
                        return Err(refused);
                    };
                    return Ok(LoadedBody {
                        body,
                        taken: Taken::ObjectsByLadder { refused, report },
                    });
                }
                Content::Mesh(_) => {}
            }
        }
    }
    Ok(pieces_body(convex_pieces(parts, options)?))
}

/// Convex pieces (at least one) as a body.
fn pieces_body(pieces: Vec<Polytope>) -> LoadedBody {
    let n = pieces.len();
    LoadedBody {
        body: Body::Convex(ConvexUnion::new(pieces).expect("an operand has a piece")),
        taken: Taken::Pieces(n),
    }
}

/// Reads `spec` once ([`read_operands`]) and takes it as a body
/// ([`body_from`]): what the command line's `query` and `motion` and
/// Python's `MotionChecker` do with a body given by name or path.
///
/// # Errors
/// Those of [`read_operands`] and [`body_from`].
pub fn load_body(spec: &str, options: &LoadOptions) -> Result<LoadedBody, LoadError> {
    body_from(&read_operands(spec)?, options)
}

/// Loads a polytope from a file path or a built-in model name (see the
/// module docs for the order of the look-ups). Never panics.
///
/// # Errors
/// * [`LoadError::NotFound`]: `spec` is neither an existing file nor a
///   built-in model name (with the closest model name, if one is close);
/// * [`LoadError::Format`]: the file cannot be read ([`FormatError::Io`],
///   [`FormatError::NotRegularFile`] for a directory or device) or parsed
///   (the content errors of [`formats::read_mesh_bytes`]);
/// * [`LoadError::SeveralBodies`]: an OBJ file holds more than one separate
///   body;
/// * [`LoadError::Model`]: a model family's parameters are wrong
///   ([`ModelError::BadParameter`]);
/// * [`LoadError::Polytope`]: the mesh or point cloud is not a valid convex
///   body (as [`load_mesh`]).
pub fn load_polytope(spec: &str, policy: MeshPolicy) -> Result<Loaded, LoadError> {
    read_operand(spec)?.into_polytope(policy)
}

/// Loads a polytope from mesh bytes already in memory (standard input, a
/// network buffer) in the given format; `origin` labels errors and
/// [`Loaded::source`] (e.g. `"standard input"`). A mesh without faces is a
/// point cloud, as for files. Never panics.
///
/// # Errors
/// [`LoadError::Format`] when the bytes do not parse in `format` (any
/// content error of [`formats::read_mesh_bytes`]); [`LoadError::Polytope`]
/// when the mesh is not a valid convex body (as [`load_mesh`]).
///
/// ```
/// use dymsum::polytope::MeshPolicy;
/// use dymsum_io::formats::Format;
/// let off = b"OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
/// let loaded = dymsum_io::load_polytope_bytes(off, Format::Off, "standard input", MeshPolicy::default()).unwrap();
/// assert_eq!(loaded.polytope.face_count(), 4);
/// ```
pub fn load_polytope_bytes(
    bytes: &[u8],
    format: formats::Format,
    origin: &str,
    policy: MeshPolicy,
) -> Result<Loaded, LoadError> {
    read_operand_bytes(bytes, format, origin)?.into_polytope(policy)
}

#[cfg(test)]
mod tests {
    use super::*;
    use dymsum::body::Rung;
    use dymsum::SolidError;
    use dymsum_testkit::CUBE_QUADS;
    use std::collections::HashMap;
    use std::path::PathBuf;

    /// Reads the file system and counts the reads per path.
    #[derive(Default)]
    struct Counting(HashMap<PathBuf, usize>);

    impl Reader for Counting {
        fn read_file(&mut self, path: &Path) -> Result<Vec<u8>, FormatError> {
            *self.0.entry(path.to_path_buf()).or_default() += 1;
            Files.read_file(path)
        }
    }

    /// Unit cubes at these x offsets in one OFF text; `drop_lid` leaves
    /// out the first cube's top face.
    fn cubes_off(offsets: &[f64], drop_lid: bool) -> String {
        let mut v = String::new();
        let mut f = Vec::new();
        for (k, dx) in offsets.iter().enumerate() {
            for i in 0..8 {
                let c = |b: usize| ((i >> b) & 1) as f64;
                v += &format!("{} {} {}\n", dx + c(0), c(1), c(2));
            }
            for (j, q) in CUBE_QUADS.iter().enumerate() {
                if !(drop_lid && k == 0 && j == 1) {
                    f.push(format!(
                        "4 {}",
                        q.map(|x| (8 * k + x).to_string()).join(" ")
                    ));
                }
            }
        }
        format!(
            "OFF\n{} {} 0\n{v}{}\n",
            8 * offsets.len(),
            f.len(),
            f.join("\n")
        )
    }

    /// A cube in OBJ as object `name` with vertex numbers from `base`.
    fn cube_obj(name: &str, dx: f64, base: usize) -> String {
        let mut t = format!("o {name}\n");
        for i in 0..8 {
            let c = |b: usize| ((i >> b) & 1) as f64;
            t += &format!("v {} {} {}\n", dx + c(0), c(1), c(2));
        }
        for q in CUBE_QUADS {
            t += &format!("f {}\n", q.map(|x| (base + x + 1).to_string()).join(" "));
        }
        t
    }

    #[test]
    fn every_file_is_read_once_whatever_it_becomes() {
        let dir = dymsum_testkit::files::temp_dir("io-body", "read-once");
        let write = |name: &str, text: &str| {
            let p = dir.join(name);
            std::fs::write(&p, text).unwrap();
            p.to_str().unwrap().to_string()
        };
        let convex = write("cube.off", &cubes_off(&[0.0], false));
        let shells = write("two.off", &cubes_off(&[0.0, 3.0], false));
        let open = write("open.off", &cubes_off(&[0.0], true));
        let open_two = write("open_two.off", &cubes_off(&[0.0, 3.0], true));
        let one_obj = write("one.obj", &cube_obj("a", 0.0, 0));
        let objects = write("two.obj", &(cube_obj("a", 0.0, 0) + &cube_obj("b", 3.0, 8)));
        let cloud = write("cloud.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n");
        let union = format!("{convex}+{one_obj}+box");
        let cases: [(&str, Rung, usize); 4] = [
            (&convex, Rung::Convex, 1),
            (&shells, Rung::ConvexShells, 2),
            (&open, Rung::Triangles, 0),
            (&open_two, Rung::Triangles, 0),
        ];
        for (spec, rung, pieces) in cases {
            let mut counting = Counting::default();
            let parts = read_operands_from(spec, &mut counting).unwrap();
            let loaded = body_from(&parts, &LoadOptions::default()).unwrap();
            match loaded.taken {
                Taken::Ladder(r) => assert_eq!((r.rung, r.pieces), (rung, pieces), "{spec}"),
                other => panic!("{spec}: {other:?}"),
            }
            // The subcommands that need convex pieces take the same reading.
            let _ = convex_pieces(&parts, &LoadOptions::default());
            assert_eq!(counting.0.len(), 1, "{spec}");
            assert!(
                counting.0.values().all(|&n| n == 1),
                "{spec}: {:?}",
                counting.0
            );
        }
        for (spec, n) in [(&one_obj, 1), (&objects, 2), (&cloud, 1), (&union, 3)] {
            let mut counting = Counting::default();
            let parts = read_operands_from(spec, &mut counting).unwrap();
            let loaded = body_from(&parts, &LoadOptions::default()).unwrap();
            if spec == &one_obj {
                assert!(matches!(loaded.taken, Taken::Ladder(_)), "{spec}");
            } else {
                assert!(matches!(loaded.taken, Taken::Pieces(k) if k == n), "{spec}");
            }
            assert_eq!(
                convex_pieces(&parts, &LoadOptions::default())
                    .unwrap()
                    .len(),
                n
            );
            let files = if spec == &union { 2 } else { 1 };
            assert_eq!(counting.0.len(), files, "{spec}");
            assert!(
                counting.0.values().all(|&n| n == 1),
                "{spec}: {:?}",
                counting.0
            );
        }
    }

    #[test]
    fn objects_that_are_not_convex_bodies_are_the_whole_file_by_the_ladder() {
        let dir = dymsum_testkit::files::temp_dir("io-body", "objects");
        // Object `b` has no lid: no convex body, so the file is triangles.
        let mut text = cube_obj("a", 0.0, 0) + &cube_obj("b", 3.0, 8);
        text = text.replace("f 13 14 16 15\n", "");
        let path = dir.join("lidless.obj");
        std::fs::write(&path, text).unwrap();
        let loaded = load_body(path.to_str().unwrap(), &LoadOptions::default()).unwrap();
        match loaded.taken {
            Taken::ObjectsByLadder { refused, report } => {
                assert!(matches!(refused, LoadError::Object { ref name, .. } if name == "b"));
                assert!(
                    refused.to_string().contains(", object `b`: open mesh"),
                    "{refused}"
                );
                assert_eq!(report.rung, Rung::Triangles);
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_piece_error_names_the_piece() {
        let err = load_body("box+no_such_model", &LoadOptions::default()).unwrap_err();
        assert!(matches!(err, LoadError::Piece { index: 2, .. }), "{err:?}");
        let msg = err.for_operand("ROBOT");
        assert!(
            msg.starts_with("ROBOT piece 2: `no_such_model` is neither an existing file"),
            "{msg}"
        );
    }

    #[test]
    fn models_are_hulls_unless_strict_and_files_exact_unless_hull() {
        // `cube` is convex only within rounding.
        assert!(load_body("cube", &LoadOptions::default()).is_ok());
        let strict = LoadOptions {
            strict_models: true,
            ..LoadOptions::default()
        };
        let err = load_body("cube", &strict).unwrap_err();
        assert!(matches!(err, LoadError::Polytope { .. }), "{err:?}");
        let o = LoadOptions::default();
        assert!(o.policy(SourceKind::File).strict && !o.policy(SourceKind::Model).strict);
        let hull = LoadOptions {
            hull: true,
            ..LoadOptions::default()
        };
        assert!(!hull.policy(SourceKind::File).strict);
    }

    #[test]
    fn no_triangle_left_is_said_so() {
        let e = SolidError::Empty;
        assert_eq!(
            body_error_text(&e, 3),
            "no triangle is left after cleaning: all 3 faces have zero area (or repeat a vertex)"
        );
    }
}
