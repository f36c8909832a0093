//! Conversions between Python objects and dymsum's types, and the mapping of
//! dymsum's errors to Python exceptions.
//!
//! * Layouts: every array is read by its logical indices, never its raw
//!   memory order, so no answer depends on a layout (C- or Fortran-ordered,
//!   transposed, negatively strided, sliced, broadcast, big-endian).
//! * Point arrays: an (N, 3) `float64` C-contiguous array is read in place
//!   (a borrowed view, no copy); any other numeric array-like is converted
//!   once by `numpy.ascontiguousarray(x, dtype=float64)`.
//! * Poses: a `float64` (4, 4) array or (K, 4, 4) stack is read in place by
//!   its strides (`as_array`, any layout); anything else is converted once
//!   to a C-contiguous `float64` array (never through Python lists).
//! * Faces: an (M, k) integer array of any integer dtype (converted once to
//!   C-ordered `int64`, or `uint64` for unsigned dtypes, so an index is
//!   quoted as given), or a sequence of index sequences (polygons of any
//!   size). A body's `(vertices, faces)` with no face is an error
//!   ([`solid_from_parts`]), never the hull of the vertices.
//! * Shapes: a `Polytope`, a model name or mesh file path (a `str` or
//!   `os.PathLike`, as `dymsum.load`), a `(vertices, faces)` pair, any
//!   object with `.vertices` and `.faces` (a trimesh.Trimesh, without
//!   importing trimesh), or an (N, 3) point cloud (its exact convex hull),
//!   also as an object with `.vertices` only (a trimesh.PointCloud).
//! * Rotations, wherever one is taken: a `scipy.spatial.transform.Rotation`
//!   (recognised by its `as_quat`/`as_matrix` methods, so scipy is never
//!   imported), a (4,) quaternion `(x, y, z, w)` (scalar last, as scipy) or
//!   a 3×3 rotation matrix. Poses: `None` (the identity), a 4×4 homogeneous
//!   rigid transform, or any rotation form (about the origin). Lists of
//!   rotations: a Rotation stack, (K, 4), (K, 3, 3) or (K, 4, 4) without
//!   translation.
//! * Errors: invalid input (`None` where a shape is expected included) is
//!   `ValueError` with dymsum's message prefixed by the argument's name; a missing file is `FileNotFoundError`, other
//!   I/O failures `OSError`.

use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyPermissionError, PyValueError};
use pyo3::prelude::*;

/// `ValueError(msg)`.
pub(crate) fn value_error(msg: impl Into<String>) -> PyErr {
    PyValueError::new_err(msg.into())
}

/// `ValueError("{what}: {err}")`.
pub(crate) fn err_for(what: &str, err: impl std::fmt::Display) -> PyErr {
    value_error(format!("{what}: {err}"))
}

/// An I/O error as the matching `OSError` subclass, with dymsum's message.
pub(crate) fn io_error(kind: std::io::ErrorKind, msg: String) -> PyErr {
    match kind {
        std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err(msg),
        std::io::ErrorKind::PermissionDenied => PyPermissionError::new_err(msg),
        _ => PyOSError::new_err(msg),
    }
}

mod args;
mod array;
mod pose;
mod shape;

pub(crate) use args::*;
pub(crate) use array::*;
pub(crate) use pose::*;
pub(crate) use shape::*;
