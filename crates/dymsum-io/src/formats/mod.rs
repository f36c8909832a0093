//! Reading and writing polygon meshes: OFF, OBJ, PLY (ASCII and binary) and
//! STL (ASCII and binary).
//!
//! The exchange type is [`PolygonMesh`]: vertices as `[f64; 3]` and faces as
//! polygons of any size (at least 3 vertices).
//!
//! * The format is chosen by file extension ([`Format::from_path`], case
//!   insensitive: `.off`, `.obj`, `.ply`, `.stl`) or explicitly
//!   ([`write_mesh_with`], [`read_mesh_bytes`], [`write_mesh_bytes`]).
//! * Text formats (OFF, OBJ, ASCII PLY) print every coordinate with Rust's
//!   shortest round-trip representation, so a mesh written and read back has
//!   bit-identical coordinates (including `-0.0`). Binary PLY stores `double`s
//!   and is bit-exact as well.
//! * STL stores `f32` coordinates: writing STL rounds every coordinate to the
//!   nearest `f32` (lossy), and faces are fan-triangulated. Reading STL merges
//!   bit-identical positions into shared vertices so the mesh is closed.
//! * Reading never panics: malformed input gives a [`FormatError`] naming the
//!   source and, where it makes sense, the 1-based line (text formats) or the
//!   byte offset / element index (binary formats).
//!
//! ```
//! use dymsum::PolygonMesh;
//! use dymsum_io::formats::{read_mesh_bytes, write_mesh_bytes, Format};
//! let tri = PolygonMesh::new(
//!     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.1, -0.0]],
//!     vec![vec![0, 1, 2]],
//! );
//! let bytes = write_mesh_bytes(&tri, Format::Off).unwrap();
//! let back = read_mesh_bytes(&bytes, Format::Off, "tri.off").unwrap();
//! assert_eq!(back, tri);
//! ```

use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use dymsum::PolygonMesh;

mod obj;
mod off;
mod ply;
mod stl;

/// Largest number of elements preallocated from a count claimed by a file
/// header. Larger counts are still accepted, but memory then grows only as
/// data is actually read, so a lying header cannot exhaust memory.
pub(crate) const PREALLOC_CAP: usize = 1 << 16;

/// Capacity to reserve for `claimed` elements announced by untrusted input.
pub(crate) fn capped(claimed: usize) -> usize {
    claimed.min(PREALLOC_CAP)
}

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Object File Format (`.off`), text.
    Off,
    /// Wavefront OBJ (`.obj`), text. Only `v` and `f` (and `o`/`g`) are used.
    Obj,
    /// PLY written as ASCII with `double` coordinates. Reading accepts any PLY
    /// encoding (ASCII, binary little or big endian).
    Ply,
    /// PLY written as binary little endian with `double` coordinates. Reading
    /// accepts any PLY encoding.
    PlyBinary,
    /// STL written binary (`f32` coordinates, lossy, triangulated). Reading
    /// accepts ASCII and binary STL.
    Stl,
    /// STL written as ASCII (`f32` coordinates, lossy, triangulated). Reading
    /// accepts ASCII and binary STL.
    StlAscii,
}

impl Format {
    /// All formats, in a fixed order.
    pub const ALL: [Format; 6] = [
        Format::Off,
        Format::Obj,
        Format::Ply,
        Format::PlyBinary,
        Format::Stl,
        Format::StlAscii,
    ];

    /// The format for a path's extension (case insensitive): `.off`, `.obj`,
    /// `.ply` (ASCII PLY for writing) or `.stl` (binary STL for writing).
    ///
    /// # Errors
    /// [`FormatError::UnknownExtension`] when the path has no extension or
    /// another one.
    pub fn from_path(path: &Path) -> Result<Format, FormatError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase());
        match ext.as_deref() {
            Some("off") => Ok(Format::Off),
            Some("obj") => Ok(Format::Obj),
            Some("ply") => Ok(Format::Ply),
            Some("stl") => Ok(Format::Stl),
            _ => Err(FormatError::UnknownExtension {
                path: path.to_path_buf(),
            }),
        }
    }

    /// The usual file extension, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Off => "off",
            Format::Obj => "obj",
            Format::Ply | Format::PlyBinary => "ply",
            Format::Stl | Format::StlAscii => "stl",
        }
    }

    /// A short name, accepted back by [`Format::from_str`]: `off`, `obj`,
    /// `ply`, `ply-binary`, `stl`, `stl-ascii`.
    pub fn name(self) -> &'static str {
        match self {
            Format::Off => "off",
            Format::Obj => "obj",
            Format::Ply => "ply",
            Format::PlyBinary => "ply-binary",
            Format::Stl => "stl",
            Format::StlAscii => "stl-ascii",
        }
    }

    /// Whether writing this format keeps every `f64` coordinate bit-exact
    /// (everything but STL).
    pub fn is_lossless(self) -> bool {
        !matches!(self, Format::Stl | Format::StlAscii)
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Format {
    type Err = String;

    /// Parses a [`Format::name`] (case insensitive; `_` may replace `-`).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let norm = s.to_ascii_lowercase().replace('_', "-");
        Format::ALL
            .into_iter()
            .find(|f| f.name() == norm)
            .ok_or_else(|| {
                format!("unknown mesh format {s:?} (expected off, obj, ply, ply-binary, stl or stl-ascii)")
            })
    }
}

/// Where in the input an error was found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Location {
    /// A 1-based line number of a text format (OFF, OBJ, ASCII PLY, ASCII STL).
    Line(usize),
    /// A byte offset into a binary file.
    Byte(u64),
    /// A 0-based element index in a binary file, e.g. `vertex` 12 or
    /// `triangle` 3.
    Element {
        /// The element kind (`vertex`, `face`, `triangle`, ...).
        kind: String,
        /// 0-based index among elements of that kind.
        index: usize,
    },
    /// The error concerns the input as a whole.
    Whole,
}

impl Location {
    /// The line number, if this is a text line location.
    pub fn line(&self) -> Option<usize> {
        match self {
            Location::Line(l) => Some(*l),
            _ => None,
        }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Line(l) => write!(f, "line {l}"),
            Location::Byte(b) => write!(f, "byte {b}"),
            Location::Element { kind, index } => write!(f, "{kind} #{index}"),
            Location::Whole => f.write_str("file"),
        }
    }
}

/// Errors reading or writing mesh files. Reading never panics; every
/// malformed input maps to one of these.
#[derive(Debug, thiserror::Error)]
pub enum FormatError {
    /// The file could not be opened, read or written. Cause: missing file,
    /// permissions, full disk, a directory given as a file. Fix: check the
    /// path and permissions.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The underlying I/O error.
        source: std::io::Error,
    },

    /// The path names a FIFO, device, socket or directory rather than a
    /// regular file; it is refused before being opened (reading it could
    /// block forever or never end). Fix: copy the data into a mesh file.
    #[error("{}: not a regular file ({kind})", path.display())]
    NotRegularFile {
        /// The path given.
        path: PathBuf,
        /// What it is instead.
        kind: &'static str,
    },

    /// The path's extension is not `.off`, `.obj`, `.ply` or `.stl`. Fix:
    /// rename the file or name the format explicitly
    /// ([`write_mesh_with`], [`read_mesh_bytes`]).
    #[error("{}: unknown mesh file extension (expected .off, .obj, .ply or .stl)", path.display())]
    UnknownExtension {
        /// The path given.
        path: PathBuf,
    },

    /// The input does not follow the format's syntax (bad token, missing
    /// value, wrong keyword, truncated data). Fix: repair the file at the
    /// given location, or re-export it from the tool that made it.
    #[error("{source_name}: {at}: {message}")]
    Parse {
        /// The file name (or the name given to [`read_mesh_bytes`]).
        source_name: String,
        /// Where the problem is.
        at: Location,
        /// What is wrong.
        message: String,
    },

    /// A header count (number of vertices or faces in OFF, PLY or binary
    /// STL) disagrees with the data that follows. Cause: a truncated file, or
    /// extra data after the declared elements. Fix: correct the count in the
    /// header or restore the missing data.
    #[error("{source_name}: {at}: header declares {declared} {what}, but the file has {found}")]
    CountMismatch {
        /// The file name.
        source_name: String,
        /// Where the mismatch became apparent (end of data or the first extra line).
        at: Location,
        /// What was counted (`vertices`, `faces`, `triangles`).
        what: &'static str,
        /// The count the header claims.
        declared: usize,
        /// The number actually present (for excess data, at least this many).
        found: usize,
    },

    /// A face refers to a vertex that does not exist (0-based index after
    /// resolving OBJ's 1-based and negative indices; the raw value as written
    /// is reported). Fix: correct the face or add the missing vertex.
    #[error("{source_name}: {at}: vertex index {index} out of range (the file has {vertex_count} vertices)")]
    BadIndex {
        /// The file name.
        source_name: String,
        /// Where the face is.
        at: Location,
        /// The index as written in the file.
        index: i64,
        /// Number of vertices available.
        vertex_count: usize,
    },

    /// A face has fewer than 3 vertices. Fix: remove the face (points and
    /// edges are not faces) or complete it.
    #[error("{source_name}: {at}: face has {len} vertices, at least 3 are needed")]
    DegenerateFace {
        /// The file name.
        source_name: String,
        /// Where the face is.
        at: Location,
        /// Number of vertices the face has.
        len: usize,
    },

    /// A coordinate is NaN or infinite (or overflows to infinity, like
    /// `1e400`). Fix: correct the coordinate; meshes must be finite.
    #[error("{source_name}: {at}: non-finite coordinate {value}")]
    NonFinite {
        /// The file name.
        source_name: String,
        /// Where the vertex is.
        at: Location,
        /// The offending value as text.
        value: String,
    },

    /// The input contains no vertices at all (an empty file, or a header
    /// declaring zero vertices). Fix: supply a non-empty mesh.
    #[error("{source_name}: no vertices")]
    Empty {
        /// The file name.
        source_name: String,
    },

    /// The file uses a feature this reader does not support (binary OFF,
    /// 4-D OFF, OBJ free-form surfaces, PLY without `x`/`y`/`z`, ...). Fix:
    /// convert the file to a plain polygon mesh.
    #[error("{source_name}: {at}: unsupported: {feature}")]
    Unsupported {
        /// The file name.
        source_name: String,
        /// Where the feature appears.
        at: Location,
        /// What is not supported.
        feature: String,
    },

    /// The mesh given for writing cannot be represented (face index out of
    /// range, face with fewer than 3 vertices, non-finite coordinate,
    /// coordinate outside the `f32` range for STL). Fix: repair the mesh
    /// before writing.
    #[error("cannot write mesh: {reason}")]
    InvalidMesh {
        /// What is wrong.
        reason: String,
    },
}

impl FormatError {
    /// The 1-based line number of the error, for errors located on a text line.
    pub fn line(&self) -> Option<usize> {
        self.location().and_then(Location::line)
    }

    /// Where the error was found, if it concerns a position in the input.
    pub fn location(&self) -> Option<&Location> {
        match self {
            FormatError::Parse { at, .. }
            | FormatError::CountMismatch { at, .. }
            | FormatError::BadIndex { at, .. }
            | FormatError::DegenerateFace { at, .. }
            | FormatError::NonFinite { at, .. }
            | FormatError::Unsupported { at, .. } => Some(at),
            _ => None,
        }
    }

    pub(crate) fn parse(source_name: &str, at: Location, message: impl Into<String>) -> Self {
        FormatError::Parse {
            source_name: source_name.to_string(),
            at,
            message: message.into(),
        }
    }

    pub(crate) fn unsupported(source_name: &str, at: Location, feature: impl Into<String>) -> Self {
        FormatError::Unsupported {
            source_name: source_name.to_string(),
            at,
            feature: feature.into(),
        }
    }
}

/// Reads a mesh, choosing the format by the path's extension.
///
/// # Errors
/// * [`FormatError::UnknownExtension`]: not `.off`, `.obj`, `.ply` or
///   `.stl`;
/// * [`FormatError::Io`]: the file cannot be opened or read (missing,
///   permissions); [`FormatError::NotRegularFile`]: it is a directory, FIFO,
///   socket or device, refused before opening;
/// * the content errors of [`read_mesh_bytes`].
pub fn read_mesh(path: &Path) -> Result<PolygonMesh, FormatError> {
    let format = Format::from_path(path)?;
    let bytes = read_file(path)?;
    read_mesh_bytes(&bytes, format, &path.display().to_string())
}

/// Reads a mesh from memory in the given format. `source_name` only labels
/// errors. For PLY and STL the encoding (ASCII or binary) is detected from the
/// content, so `Ply`/`PlyBinary` and `Stl`/`StlAscii` read alike.
///
/// # Errors
/// Malformed content, labelled with `source_name` and the location:
/// * [`FormatError::Parse`]: a bad token, missing value, wrong keyword or
///   truncated data, at the line or byte offset where it occurs;
/// * [`FormatError::CountMismatch`] (OFF, binary STL): the header's counts
///   disagree with the data;
/// * [`FormatError::BadIndex`] (OFF, OBJ, PLY): a face names a vertex that
///   does not exist; [`FormatError::DegenerateFace`]: a face with fewer
///   than 3 vertices;
/// * [`FormatError::NonFinite`]: a coordinate is NaN or infinite (or
///   overflows, like `1e400`); [`FormatError::Empty`]: no vertices at all;
/// * [`FormatError::Unsupported`]: a feature the reader does not handle
///   (binary or 4-D OFF, OBJ free-form surfaces, PLY without `x`/`y`/`z`).
pub fn read_mesh_bytes(
    bytes: &[u8],
    format: Format,
    source_name: &str,
) -> Result<PolygonMesh, FormatError> {
    match format {
        Format::Off => off::read(bytes, source_name),
        Format::Obj => obj::read(bytes, source_name),
        Format::Ply | Format::PlyBinary => ply::read(bytes, source_name),
        Format::Stl | Format::StlAscii => stl::read(bytes, source_name),
    }
}

/// Reads an OBJ file as its separate bodies, in order of their first face:
/// faces connected through shared vertices form one body whatever their
/// `o` / `g` statements (so per-face groups of one closed mesh are one
/// body), each with only the vertices its faces use, re-indexed from 0 (in
/// file order) and named after the object or group of its first face
/// (`default` before any `o`/`g`). An object or group with vertices but no
/// faces is a point cloud body (its vertices that no face uses, no faces),
/// never dropped. A file with vertices but no faces at all gives one point
/// cloud holding every vertex.
///
/// # Errors
/// * [`FormatError::Io`]: the file cannot be opened or read (missing,
///   permissions); [`FormatError::NotRegularFile`]: it is a directory, FIFO,
///   socket or device, refused before opening;
/// * the OBJ content errors of [`read_mesh_bytes`] (parse errors, bad
///   indices, degenerate faces, non-finite coordinates, no vertices,
///   unsupported statements).
pub fn read_obj_objects(path: &Path) -> Result<Vec<(String, PolygonMesh)>, FormatError> {
    let bytes = read_file(path)?;
    read_obj_objects_bytes(&bytes, &path.display().to_string())
}

/// [`read_obj_objects`] from memory; `source_name` only labels errors.
///
/// # Errors
/// The OBJ content errors of [`read_mesh_bytes`].
pub fn read_obj_objects_bytes(
    bytes: &[u8],
    source_name: &str,
) -> Result<Vec<(String, PolygonMesh)>, FormatError> {
    obj::read_objects(bytes, source_name)
}

/// Writes a mesh, choosing the format by the path's extension (`.ply` is
/// written as ASCII PLY and `.stl` as binary STL; see [`write_mesh_with`]).
///
/// # Errors
/// [`FormatError::UnknownExtension`] for another extension; otherwise
/// those of [`write_mesh_with`].
pub fn write_mesh(path: &Path, mesh: &PolygonMesh) -> Result<(), FormatError> {
    let format = Format::from_path(path)?;
    write_mesh_with(path, mesh, format)
}

/// Writes a mesh in the given format, whatever the path's extension. The
/// file is written atomically ([`crate::atomic::write_atomic`]): on any
/// error an earlier file at `path` is left intact and no partial file is
/// left behind.
///
/// # Errors
/// [`FormatError::InvalidMesh`] when the mesh cannot be encoded (see
/// [`write_mesh_bytes`]; nothing is written then); [`FormatError::Io`]
/// naming `path` when the file cannot be created, written, synced or
/// renamed into place.
pub fn write_mesh_with(path: &Path, mesh: &PolygonMesh, format: Format) -> Result<(), FormatError> {
    let bytes = write_mesh_bytes(mesh, format)?;
    crate::atomic::write_atomic_bytes(path, &bytes).map_err(FormatError::from)
}

/// Encodes a mesh in the given format. Fails with
/// [`FormatError::InvalidMesh`] if a face index is out of range, a face has
/// fewer than 3 vertices, a coordinate is not finite, (STL only) a
/// coordinate overflows `f32`, or (PLY only) there are more than `i32::MAX`
/// vertices.
///
/// # Errors
/// [`FormatError::InvalidMesh`], saying which of the above it is.
pub fn write_mesh_bytes(mesh: &PolygonMesh, format: Format) -> Result<Vec<u8>, FormatError> {
    validate_for_writing(mesh)?;
    if matches!(format, Format::Ply | Format::PlyBinary) && mesh.vertices.len() > i32::MAX as usize
    {
        return Err(FormatError::InvalidMesh {
            reason: format!(
                "{} vertices exceed what PLY `int` indices can address",
                mesh.vertices.len()
            ),
        });
    }
    match format {
        Format::Off => Ok(off::write(mesh)),
        Format::Obj => Ok(obj::write(mesh)),
        Format::Ply => Ok(ply::write_ascii(mesh)),
        Format::PlyBinary => Ok(ply::write_binary_le(mesh)),
        Format::Stl => stl::write_binary(mesh),
        Format::StlAscii => stl::write_ascii(mesh),
    }
}

fn read_file(path: &Path) -> Result<Vec<u8>, FormatError> {
    crate::atomic::read_regular_file(path).map_err(FormatError::from)
}

impl From<crate::atomic::FileError> for FormatError {
    fn from(e: crate::atomic::FileError) -> Self {
        use crate::atomic::FileError;
        match e {
            FileError::Write { path, source } | FileError::Read { path, source } => {
                FormatError::Io { path, source }
            }
            FileError::NotRegular { path, kind } => FormatError::NotRegularFile { path, kind },
        }
    }
}

fn validate_for_writing(mesh: &PolygonMesh) -> Result<(), FormatError> {
    for (i, v) in mesh.vertices.iter().enumerate() {
        if v.iter().any(|c| !c.is_finite()) {
            return Err(FormatError::InvalidMesh {
                reason: format!("vertex {i} has a non-finite coordinate {v:?}"),
            });
        }
    }
    let n = mesh.vertices.len();
    for (j, f) in mesh.faces.iter().enumerate() {
        if f.len() < 3 {
            return Err(FormatError::InvalidMesh {
                reason: format!("face {j} has {} vertices, at least 3 are needed", f.len()),
            });
        }
        if let Some(&bad) = f.iter().find(|&&i| i >= n) {
            return Err(FormatError::InvalidMesh {
                reason: format!("face {j} refers to vertex {bad}, but the mesh has {n} vertices"),
            });
        }
    }
    Ok(())
}

/// Parses one decimal coordinate of a text format: a syntax error gives
/// [`FormatError::Parse`], NaN or infinity [`FormatError::NonFinite`].
pub(crate) fn parse_coord(token: &str, source_name: &str, line: usize) -> Result<f64, FormatError> {
    match token.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(FormatError::NonFinite {
            source_name: source_name.to_string(),
            at: Location::Line(line),
            value: token.to_string(),
        }),
        Err(_) => Err(FormatError::parse(
            source_name,
            Location::Line(line),
            format!("expected a number, found {token:?}"),
        )),
    }
}

/// Appends `x y z` with each coordinate in Rust's shortest round-trip
/// representation (`{}` Display), which parses back to the same bits.
/// The body shared by the OFF and ASCII PLY writers: one vertex a line
/// (shortest round-trip coordinates), then one face a line (its corner count
/// and indices).
pub(crate) fn push_vertices_and_faces(out: &mut String, mesh: &PolygonMesh) {
    use std::fmt::Write as _;
    for v in &mesh.vertices {
        push_coords(out, v);
        out.push('\n');
    }
    for f in &mesh.faces {
        let _ = write!(out, "{}", f.len());
        for i in f {
            let _ = write!(out, " {i}");
        }
        out.push('\n');
    }
}

pub(crate) fn push_coords(out: &mut String, v: &[f64; 3]) {
    use std::fmt::Write;
    let _ = write!(out, "{} {} {}", v[0], v[1], v[2]);
}

/// Splits text into lines (`\n` or `\r\n`), decoding invalid UTF-8 lossily so
/// that garbage bytes give parse errors with correct line numbers.
pub(crate) fn text(bytes: &[u8]) -> std::borrow::Cow<'_, str> {
    String::from_utf8_lossy(bytes)
}

/// Checks a vertex index read from a face list: `Ok` with the index if it
/// lies in `0..vertex_count`, [`FormatError::BadIndex`] at `at` otherwise.
pub(crate) fn vertex_index(
    raw: i64,
    vertex_count: usize,
    source_name: &str,
    at: Location,
) -> Result<usize, FormatError> {
    if raw < 0 || raw as u64 >= vertex_count as u64 {
        return Err(FormatError::BadIndex {
            source_name: source_name.to_string(),
            at,
            index: raw,
            vertex_count,
        });
    }
    Ok(raw as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vertex_index_accepts_exactly_zero_to_count_minus_one() {
        let at = || Location::Line(7);
        assert_eq!(vertex_index(0, 3, "m", at()).unwrap(), 0);
        assert_eq!(vertex_index(2, 3, "m", at()).unwrap(), 2);
        for raw in [3, -1, i64::MIN, i64::MAX] {
            let e = vertex_index(raw, 3, "m", at()).unwrap_err();
            assert!(
                matches!(
                    &e,
                    FormatError::BadIndex { source_name, at: Location::Line(7), index, vertex_count: 3 }
                        if source_name == "m" && *index == raw
                ),
                "raw index {raw}: {e:?}"
            );
        }
        assert!(vertex_index(0, 0, "m", at()).is_err());
    }
}
