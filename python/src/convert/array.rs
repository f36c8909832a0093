//! NumPy arrays out: matrices, poses, vertices, triangles, polygons.

use super::value_error;
use dymsum::glam::DMat4;
use dymsum::{PolygonMesh, Pose};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

/// An (rows, cols) array taking over `flat` (no copy; `flat.len()` is
/// `rows · cols` at every call site, and a mismatch is an error, not a panic).
pub(crate) fn matrix<'py, T: numpy::Element>(
    py: Python<'py>,
    flat: Vec<T>,
    shape: (usize, usize),
) -> PyResult<Bound<'py, PyArray2<T>>> {
    Array2::from_shape_vec(shape, flat)
        .map(|a| a.into_pyarray(py))
        .map_err(|e| value_error(format!("internal error: output shape {shape:?}: {e}")))
}

/// A (rows, 3) `float64` array from `3 · rows` values, row by row.
pub(crate) fn rows_array(
    py: Python<'_>,
    flat: Vec<f64>,
    rows: usize,
) -> PyResult<Bound<'_, PyArray2<f64>>> {
    matrix(py, flat, (rows, 3))
}

/// A 4×4 row-major `float64` array of a pose: the rotation block is the
/// matrix of the quaternion as given (`Rotation::matrix_as_given`, not
/// snapped), so that a pose handed back keeps which way a motion to it
/// turns (a half turn plus 1e-300 stays on its side).
pub(crate) fn pose_array<'py>(py: Python<'py>, pose: Pose) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let m = DMat4::from_mat3_translation(pose.rotation.matrix_as_given(), pose.translation);
    let cols = m.transpose().to_cols_array();
    matrix(py, cols.to_vec(), (4, 4))
}

/// A (3,) `float64` array.
pub(crate) fn vec3<'py>(py: Python<'py>, v: [f64; 3]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, v.to_vec())
}

/// An (n, 3) `float64` array that takes over the mesh's vertex buffer (no
/// copy).
pub(crate) fn vertices_array<'py>(
    py: Python<'py>,
    vertices: Vec<[f64; 3]>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = vertices.len();
    matrix(py, vertices.into_flattened(), (n, 3))
}

/// Fan triangles of convex polygon faces, as an (m, 3) `int64` array.
pub(crate) fn triangles_array<'py>(
    py: Python<'py>,
    faces: &[Vec<usize>],
) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let mut flat = Vec::new();
    for f in faces {
        for i in 1..f.len().saturating_sub(1) {
            flat.extend([f[0] as i64, f[i] as i64, f[i + 1] as i64]);
        }
    }
    let m = flat.len() / 3;
    matrix(py, flat, (m, 3))
}

/// Polygon faces as a list of (k,) `int64` arrays.
pub(crate) fn polygons_list<'py>(
    py: Python<'py>,
    faces: &[Vec<usize>],
) -> PyResult<Bound<'py, PyList>> {
    PyList::new(
        py,
        faces
            .iter()
            .map(|f| PyArray1::from_vec(py, f.iter().map(|&i| i as i64).collect())),
    )
}

/// `(vertices, faces)` of a mesh: triangles by default, polygons on request.
pub(crate) fn mesh_tuple<'py>(
    py: Python<'py>,
    mesh: PolygonMesh,
    polygons: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let faces: Bound<'py, PyAny> = if polygons {
        polygons_list(py, &mesh.faces)?.into_any()
    } else {
        triangles_array(py, &mesh.faces)?.into_any()
    };
    let vertices = vertices_array(py, mesh.vertices)?.into_any();
    PyTuple::new(py, [vertices, faces])
}
