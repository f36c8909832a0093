//! Loading a polytope from a file path or a built-in model name.
//!
//! [`crate::load_polytope`] (in [`crate::body`]) reads `spec` once
//! ([`crate::body::read_operand`]) and takes it as one convex body; this
//! module holds what it returns ([`Loaded`], [`LoadError`]) and
//! [`load_mesh`], which takes a mesh in memory:
//!
//! 1. If `spec` names an existing file, it is read with the reader of its
//!    extension ([`crate::formats::read_mesh_bytes`]). A mesh with faces becomes
//!    a polytope through [`Polytope::from_mesh`] (validated, see
//!    [`dymsum::polytope::build`]); a mesh with no faces is a point cloud and
//!    becomes its convex hull through [`Polytope::from_points`].
//! 2. Otherwise `spec` is looked up with [`crate::models::model`]: `random:N:SEED`
//!    is a point cloud (hull), every other model a mesh.
//! 3. A spec that is neither gives [`LoadError::NotFound`], which says both
//!    things that were tried, and suggests the closest model name.
//!
//! A file without a known extension that is also a model name (a file called
//! `cube` in the current directory, say) resolves to the model: a mesh file
//! must have a `.off`, `.obj`, `.ply` or `.stl` extension anyway. Bodies
//! that are not one convex polytope (triangles, unions) are
//! [`crate::body`]'s.
//!
//! ```
//! use dymsum::polytope::MeshPolicy;
//! use dymsum_io::{load_polytope, LoadError};
//! let gs1 = load_polytope("gs1", MeshPolicy::default()).unwrap();
//! assert_eq!(gs1.source, "built-in gs1");
//! assert_eq!(gs1.input.triangle_count(), 80);
//! let err = load_polytope("elipse", MeshPolicy::default()).unwrap_err();
//! assert!(matches!(err, LoadError::NotFound { .. }));
//! assert!(err.to_string().contains("ellipse"));
//! ```

use dymsum::polytope::{ConvexityReport, MeshPolicy};
use dymsum::{PolygonMesh, Polytope, PolytopeError, SolidError};

use crate::formats::FormatError;
use crate::models::ModelError;

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
    /// An object of an OBJ file of several bodies, taken as convex pieces,
    /// is not a valid convex polytope. Fix: repair or split the object.
    #[error("{origin}, object `{name}`: {source}")]
    Object {
        /// `"file parts.obj"`.
        origin: String,
        /// The object's (or group's) name.
        name: String,
        /// The polytope builder's error.
        #[source]
        source: PolytopeError,
    },
    /// A mesh file could not be taken as a body even as triangles
    /// ([`dymsum::body::Body::from_mesh_with`]: every face of zero area, a
    /// malformed face).
    #[error("{origin}: {}", body_error_text(.source, *.faces))]
    Body {
        /// `"file soup.off"`.
        origin: String,
        /// The mesh's face count.
        faces: usize,
        /// The cleaning's error.
        #[source]
        source: SolidError,
    },
    /// A piece of a union joined with `+` (`a.off+b.off`) could not be
    /// loaded.
    #[error("piece {index}: {source}")]
    Piece {
        /// The piece's place in the union, from 1.
        index: usize,
        /// Its error.
        #[source]
        source: Box<LoadError>,
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
            | LoadError::Polytope { origin, .. }
            | LoadError::Body { origin, .. } => origin.clone(),
            LoadError::Object { origin, name, .. } => format!("{origin}, object `{name}`"),
            LoadError::Piece { source, .. } => source.origin(),
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
            LoadError::Polytope { source, .. } | LoadError::Object { source, .. } => {
                source.to_string()
            }
            LoadError::Body { source, faces, .. } => body_error_text(source, *faces),
            LoadError::Piece { source, .. } => source.cause(),
        }
    }

    /// The message for a named operand: `"P (file foo.off): cause"`, or for a
    /// spec that was not found `"P: cause"` (the cause names the spec); for
    /// a piece of a union, the piece's message as operand `"P piece 2"`.
    pub fn for_operand(&self, operand: &str) -> String {
        match self {
            LoadError::Piece { index, source } => {
                source.for_operand(&format!("{operand} piece {index}"))
            }
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

/// Why a mesh could not be taken as a body, for messages: the
/// [`SolidError`], or for [`SolidError::Empty`] that every one of its
/// `faces` faces has zero area.
pub fn body_error_text(e: &SolidError, faces: usize) -> String {
    match e {
        SolidError::Empty => format!(
            "no triangle is left after cleaning: all {faces} faces have zero area (or repeat a \
             vertex)"
        ),
        e => e.to_string(),
    }
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
    use crate::load_polytope;
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
