//! Loading a polytope from a file path or a built-in model name.
//!
//! [`load_polytope`] is what every `dymsum` subcommand does with an operand:
//!
//! 1. If `spec` names an existing file, it is read with
//!    [`formats::read_mesh`] (format by extension). A mesh with faces becomes
//!    a polytope through [`Polytope::from_mesh`] (validated, see
//!    [`dymsum::polytope::build`]); a mesh with no faces is a point cloud and
//!    becomes its convex hull through [`Polytope::from_points`].
//! 2. Otherwise `spec` is looked up with [`models::model`]: `random:N:SEED`
//!    is a point cloud (hull), every other model a mesh.
//! 3. A spec that is neither gives [`LoadError::NotFound`], which says both
//!    things that were tried, and suggests the closest model name.
//!
//! A file without a known extension that is also a model name (a file called
//! `cube` in the current directory, say) resolves to the model: a mesh file
//! must have a `.off`, `.obj`, `.ply` or `.stl` extension anyway.
//!
//! ```
//! use dymsum::polytope::MeshPolicy;
//! use dymsum_io::load::{load_polytope, LoadError};
//! let gs1 = load_polytope("gs1", MeshPolicy::default()).unwrap();
//! assert_eq!(gs1.source, "built-in gs1");
//! assert_eq!(gs1.input.triangle_count(), 80);
//! let err = load_polytope("elipse", MeshPolicy::default()).unwrap_err();
//! assert!(matches!(err, LoadError::NotFound { .. }));
//! assert!(err.to_string().contains("ellipse"));
//! ```

use std::path::Path;

use dymsum::polytope::{ConvexityReport, MeshPolicy};
use dymsum::{PolygonMesh, Polytope, PolytopeError};

use crate::formats::{self, FormatError};
use crate::models::{self, ModelError};

/// A polytope with where it came from and what building it changed.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The convex polytope.
    pub polytope: Polytope,
    /// What [`Polytope::from_mesh`] found and changed; `None` for a point
    /// cloud (the polytope is its hull by definition).
    pub report: Option<ConvexityReport>,
    /// A human description of the origin: `"file foo.off"` or
    /// `"built-in ellipse"`.
    pub source: String,
    /// The mesh as read (for a point cloud: the points, no faces).
    pub input: PolygonMesh,
}

impl Loaded {
    /// `true` when the input was a point cloud (no faces).
    pub fn is_point_cloud(&self) -> bool {
        self.input.faces.is_empty()
    }
}

/// Why an operand could not be loaded. Every variant names the operand's
/// origin ([`LoadError::origin`]) and the cause ([`LoadError::cause`]); the
/// `Display` text is `"{origin}: {cause}"`.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// `spec` is neither an existing file nor a built-in model. Fix: check
    /// the path, or pick a name from `dymsum models`.
    #[error("{}", not_found_text(.spec, .suggestion, *.looks_like_file))]
    NotFound {
        /// The spec as given.
        spec: String,
        /// The closest built-in model name, if one is close.
        suggestion: Option<String>,
        /// The spec looks like a path (has a `/` or a mesh file extension),
        /// so the message leads with "file does not exist".
        looks_like_file: bool,
    },
    /// The file exists but could not be read or parsed.
    #[error("{origin}: {}", format_cause(.source))]
    Format {
        /// `"file foo.off"`.
        origin: String,
        /// The reader's error.
        #[source]
        source: FormatError,
    },
    /// The name is a built-in model family but its parameters are wrong (or
    /// an embedded model is corrupt).
    #[error("{origin}: {source}")]
    Model {
        /// `"built-in tcube:1000"`.
        origin: String,
        /// The model library's error.
        #[source]
        source: ModelError,
    },
    /// An OBJ file holds several separate bodies (objects or groups not
    /// joined by shared vertices, or a point-cloud object next to a mesh),
    /// but one convex body was asked for. Fix: split the file, or use a
    /// command that takes unions (`query`, `cobst`).
    #[error("{origin}: {}", several_bodies_text(.names))]
    SeveralBodies {
        /// `"file parts.obj"`.
        origin: String,
        /// The bodies' object or group names, in file order.
        names: Vec<String>,
    },
    /// The mesh or point cloud is not a valid convex polytope (open,
    /// non-manifold, non-convex, flat, too few points, non-finite, or, under
    /// the strict policy, convex only within tolerance).
    #[error("{origin}: {source}")]
    Polytope {
        /// `"file foo.off"` or `"built-in ellipse"`.
        origin: String,
        /// The polytope builder's error.
        #[source]
        source: PolytopeError,
    },
}

impl LoadError {
    /// Where the operand came from: `"file foo.off"`, `"built-in ellipse"`,
    /// or for [`LoadError::NotFound`] the spec itself in backquotes.
    pub fn origin(&self) -> String {
        match self {
            LoadError::NotFound { spec, .. } => format!("`{spec}`"),
            LoadError::Format { origin, .. }
            | LoadError::Model { origin, .. }
            | LoadError::SeveralBodies { origin, .. }
            | LoadError::Polytope { origin, .. } => origin.clone(),
        }
    }

    /// What went wrong, without the origin (for messages like
    /// `P (file foo.off): open mesh: edge (3, 7) borders only one face`).
    pub fn cause(&self) -> String {
        match self {
            LoadError::NotFound {
                spec,
                suggestion,
                looks_like_file,
            } => not_found_text(spec, suggestion, *looks_like_file),
            LoadError::Format { source, .. } => format_cause(source),
            LoadError::Model { source, .. } => source.to_string(),
            LoadError::SeveralBodies { names, .. } => several_bodies_text(names),
            LoadError::Polytope { source, .. } => source.to_string(),
        }
    }

    /// The message for a named operand: `"P (file foo.off): cause"`, or for a
    /// spec that was not found `"P: cause"` (the cause names the spec).
    pub fn for_operand(&self, operand: &str) -> String {
        match self {
            LoadError::NotFound { .. } => format!("{operand}: {}", self.cause()),
            _ => format!("{operand} ({}): {}", self.origin(), self.cause()),
        }
    }
}

fn not_found_text(spec: &str, suggestion: &Option<String>, looks_like_file: bool) -> String {
    let hint = match suggestion {
        Some(s) => format!("did you mean the model `{s}`? `dymsum models` lists all models"),
        None => "`dymsum models` lists the built-in models".to_string(),
    };
    if looks_like_file {
        format!("file `{spec}` does not exist, and it is not a built-in model name either ({hint})")
    } else {
        format!("`{spec}` is neither an existing file nor a built-in model ({hint})")
    }
}

fn several_bodies_text(names: &[String]) -> String {
    let list: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    format!(
        "the OBJ file holds {} separate bodies ({}), but one convex body is needed \
         (`sum`, `query`, `motion` and `cobst` take unions)",
        names.len(),
        list.join(", ")
    )
}

/// A format error's message without the file name it starts with (the
/// origin already names the file).
fn format_cause(e: &FormatError) -> String {
    match e {
        FormatError::Io { source, .. } => source.to_string(),
        FormatError::NotRegularFile { kind, .. } => format!("not a regular file ({kind})"),
        FormatError::UnknownExtension { .. } => {
            "unknown mesh file extension (expected .off, .obj, .ply or .stl)".to_string()
        }
        FormatError::Parse { at, message, .. } => format!("{at}: {message}"),
        FormatError::CountMismatch {
            at,
            what,
            declared,
            found,
            ..
        } => format!("{at}: header declares {declared} {what}, but the file has {found}"),
        FormatError::BadIndex {
            at,
            index,
            vertex_count,
            ..
        } => format!(
            "{at}: vertex index {index} out of range (the file has {vertex_count} vertices)"
        ),
        FormatError::DegenerateFace { at, len, .. } => {
            format!("{at}: face has {len} vertices, at least 3 are needed")
        }
        FormatError::NonFinite { at, value, .. } => format!("{at}: non-finite coordinate {value}"),
        FormatError::Empty { .. } => "no vertices".to_string(),
        FormatError::Unsupported { at, feature, .. } => format!("{at}: unsupported: {feature}"),
        FormatError::InvalidMesh { .. } => e.to_string(),
    }
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
    let path = Path::new(spec);
    let is_file = path.is_file();
    if is_file && (has_mesh_extension(spec) || models::model(spec).is_err()) {
        return load_file(spec, path, policy);
    }
    if path.exists() && !is_file {
        // A directory (or other non-file) with a name that is not a model:
        // let the reader give the I/O error.
        if models::model(spec).is_err() {
            return load_file(spec, path, policy);
        }
    }
    match models::model(spec) {
        Ok(mesh) => load_mesh(mesh, format!("built-in {}", spec.trim()), policy),
        Err(ModelError::Unknown { suggestion, .. }) => Err(LoadError::NotFound {
            spec: spec.to_string(),
            suggestion,
            looks_like_file: looks_like_file(spec),
        }),
        Err(source) => Err(LoadError::Model {
            origin: format!("built-in {}", spec.trim()),
            source,
        }),
    }
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
    let mesh =
        formats::read_mesh_bytes(bytes, format, origin).map_err(|source| LoadError::Format {
            origin: origin.to_string(),
            source,
        })?;
    load_mesh(mesh, origin.to_string(), policy)
}

fn load_file(spec: &str, path: &Path, policy: MeshPolicy) -> Result<Loaded, LoadError> {
    let origin = format!("file {spec}");
    let format_err = |source| LoadError::Format {
        origin: origin.clone(),
        source,
    };
    let is_obj = formats::Format::from_path(path).ok() == Some(formats::Format::Obj);
    let mesh = if is_obj {
        // The same bodies as `query` and `cobst` see: groups of one closed
        // mesh are one body, a faceless object is a point cloud.
        let mut bodies = formats::read_obj_objects(path).map_err(format_err)?;
        if bodies.len() > 1 {
            return Err(LoadError::SeveralBodies {
                origin,
                names: bodies.into_iter().map(|(n, _)| n).collect(),
            });
        }
        bodies.pop().map(|(_, m)| m).unwrap_or_default()
    } else {
        formats::read_mesh(path).map_err(format_err)?
    };
    load_mesh(mesh, origin, policy)
}

/// Loads a polytope from a mesh already in memory (a built-in model's, or
/// one read elsewhere): a mesh without faces is a point cloud (its hull),
/// otherwise it is validated under `policy`. `source` labels errors and
/// [`Loaded::source`] (e.g. `"built-in ellipse"`).
///
/// # Errors
/// [`LoadError::Polytope`], the only error, when the mesh is not a valid
/// convex body: the [`PolytopeError`] of [`Polytope::from_points`] for a
/// point cloud (too few points, flat, non-finite) or of
/// [`Polytope::from_mesh`] for a mesh (open, non-manifold, not a sphere,
/// non-convex, or under a strict policy convex only within tolerance).
pub fn load_mesh(
    input: PolygonMesh,
    source: String,
    policy: MeshPolicy,
) -> Result<Loaded, LoadError> {
    let result = if input.faces.is_empty() {
        Polytope::from_points(&input.vertices).map(|p| (p, None))
    } else {
        Polytope::from_mesh(&input, policy).map(|(p, r)| (p, Some(r)))
    };
    match result {
        Ok((polytope, report)) => Ok(Loaded {
            polytope,
            report,
            source,
            input,
        }),
        Err(e) => Err(LoadError::Polytope {
            origin: source,
            source: e,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn temp_file(name: &str, contents: &str) -> PathBuf {
        // Removed when the test process exits (issue 29).
        let dir = dymsum_testkit::files::temp_dir("io-load", &name.replace(['.', '/'], "_"));
        let path = dir.join(name);
        std::fs::write(&path, contents).unwrap();
        path
    }

    const CUBE_OFF: &str = "OFF\n8 6 0\n\
        0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n\
        4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";

    #[test]
    fn loads_a_built_in_model() {
        let l = load_polytope("gs4", MeshPolicy::default()).unwrap();
        assert_eq!(l.source, "built-in gs4");
        assert_eq!(l.input.triangle_count(), 500);
        assert!(l.report.is_some());
        assert!(!l.is_point_cloud());
        assert!(l.polytope.sanity_check().is_ok());
    }

    #[test]
    fn loads_a_point_cloud_model_as_its_hull() {
        let l = load_polytope("random:50:3", MeshPolicy::default()).unwrap();
        assert!(l.is_point_cloud());
        assert!(l.report.is_none());
        assert!(l.polytope.vertex_count() >= 4 && l.polytope.vertex_count() <= 50);
    }

    #[test]
    fn loads_a_file() {
        let path = temp_file("cube.off", CUBE_OFF);
        let spec = path.to_str().unwrap();
        let l = load_polytope(spec, MeshPolicy::strict()).unwrap();
        assert_eq!(l.source, format!("file {spec}"));
        assert_eq!(l.polytope.face_count(), 6);
        assert!(l.report.unwrap().exactly_convex);
    }

    #[test]
    fn loads_a_point_cloud_file() {
        let path = temp_file(
            "pts.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0.1 0.1 0.1\n",
        );
        let l = load_polytope(path.to_str().unwrap(), MeshPolicy::default()).unwrap();
        assert!(l.is_point_cloud());
        assert_eq!(l.polytope.vertex_count(), 4);
    }

    #[test]
    fn unknown_name_suggests_a_model() {
        let err = load_polytope("elipse", MeshPolicy::default()).unwrap_err();
        match &err {
            LoadError::NotFound {
                suggestion,
                looks_like_file,
                ..
            } => {
                assert_eq!(suggestion.as_deref(), Some("ellipse"));
                assert!(!looks_like_file);
            }
            other => panic!("unexpected {other:?}"),
        }
        let msg = err.for_operand("P");
        assert!(msg.starts_with("P: `elipse` is neither an existing file nor a built-in model"));
        assert!(msg.contains("did you mean the model `ellipse`"), "{msg}");
    }

    #[test]
    fn missing_file_says_so() {
        for spec in ["no/such/dir/cube.off", "missing_cube.off", "./nothing"] {
            let err = load_polytope(spec, MeshPolicy::default()).unwrap_err();
            assert!(
                matches!(
                    err,
                    LoadError::NotFound {
                        looks_like_file: true,
                        ..
                    }
                ),
                "{spec}: {err:?}"
            );
            assert!(err.to_string().contains("does not exist"), "{err}");
            assert!(err.to_string().contains(spec));
        }
    }

    #[test]
    fn bad_model_parameter_is_a_model_error() {
        let err = load_polytope("tcube:100000", MeshPolicy::default()).unwrap_err();
        assert!(matches!(err, LoadError::Model { .. }), "{err:?}");
        assert!(err.to_string().starts_with("built-in tcube:100000: "));
    }

    #[test]
    fn open_mesh_names_the_file_and_edge() {
        // The cube without its top face.
        let open = CUBE_OFF
            .replace("8 6 0", "8 5 0")
            .replace("4 4 5 6 7\n", "");
        let path = temp_file("open.off", &open);
        let err = load_polytope(path.to_str().unwrap(), MeshPolicy::default()).unwrap_err();
        assert!(matches!(
            err,
            LoadError::Polytope {
                source: PolytopeError::OpenEdge { .. },
                ..
            }
        ));
        let msg = err.for_operand("Q");
        assert!(msg.starts_with(&format!("Q (file {}): open mesh: edge", path.display())));
    }

    #[test]
    fn parse_error_keeps_the_line_but_not_the_file_twice() {
        let path = temp_file(
            "bad.off",
            "OFF\n4 1 0\n0 0 0\n1 0 x\n0 1 0\n0 0 1\n3 0 1 2\n",
        );
        let err = load_polytope(path.to_str().unwrap(), MeshPolicy::default()).unwrap_err();
        assert!(matches!(err, LoadError::Format { .. }));
        let cause = err.cause();
        assert!(cause.starts_with("line 4"), "{cause}");
        assert!(!cause.contains("bad.off"), "{cause}");
    }

    #[test]
    fn strict_refuses_the_rounded_cube_model() {
        let err = load_polytope("cube", MeshPolicy::strict()).unwrap_err();
        assert!(matches!(
            err,
            LoadError::Polytope {
                source: PolytopeError::NotExactlyConvex { .. },
                ..
            }
        ));
        let ok = load_polytope("cube", MeshPolicy::default()).unwrap();
        assert!(ok.report.unwrap().replaced_by_hull);
    }

    #[test]
    fn too_few_and_flat_points() {
        let three = temp_file("three.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        let err = load_polytope(three.to_str().unwrap(), MeshPolicy::default()).unwrap_err();
        assert!(matches!(
            err,
            LoadError::Polytope {
                source: PolytopeError::TooFewPoints { count: 3 },
                ..
            }
        ));
        let flat = temp_file("flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 3 0\n");
        let err = load_polytope(flat.to_str().unwrap(), MeshPolicy::default()).unwrap_err();
        assert!(
            matches!(
                err,
                LoadError::Polytope {
                    source: PolytopeError::Flat(_),
                    ..
                }
            ),
            "{err:?}"
        );
    }

    #[test]
    fn a_directory_is_an_io_error() {
        let path = temp_file("x.off", CUBE_OFF);
        let dir = path.parent().unwrap().to_str().unwrap().to_string();
        let err = load_polytope(&dir, MeshPolicy::default()).unwrap_err();
        assert!(
            matches!(err, LoadError::Format { .. } | LoadError::NotFound { .. }),
            "{err:?}"
        );
    }
}
