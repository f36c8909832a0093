//! `check_solid`: the core's exact check of a mesh given as a solid, and
//! `_check_closed_mesh`, its check of every merged mesh
//! (`dymsum::solid`), called by `dymsum.nonconvex` before any non-convex
//! sum or decomposition takes a mesh.

use crate::convert::{self, value_error};
use dymsum::solid::check_solid_mesh;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyList;

/// The shells of a mesh given as a solid, as arrays of face indices, each
/// ascending, in the order of their first face. Raises ``ValueError`` with
/// what is wrong and where (faces, edge or vertex in the caller's
/// numbering) unless every shell is closed, consistently oriented,
/// edge- and vertex-manifold, free of zero-area triangles, non-planar
/// faces and of faces listed twice or back to back, crosses itself
/// nowhere, and encloses a positive volume. Every decision is exact (no
/// tolerance); shells may overlap each other (the body is their union).
///
/// >>> import numpy as np, dymsum
/// >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
/// >>> f = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
/// >>> [s.tolist() for s in dymsum._dymsum.check_solid(v, f)]
/// [[0, 1, 2, 3]]
/// >>> dymsum._dymsum.check_solid(v, np.vstack([f, f[:1]]))
/// Traceback (most recent call last):
/// ...
/// ValueError: faces 0 and 4 have the same corners (a face listed twice, or two faces back to back)
#[pyfunction]
fn check_solid<'py>(
    py: Python<'py>,
    vertices: &Bound<'py, PyAny>,
    faces: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyList>> {
    let mesh = convert::mesh_from_parts(vertices, faces, "mesh")?;
    let info = py
        .detach(|| check_solid_mesh(&mesh))
        .map_err(|e| value_error(e.to_string()))?;
    let out = PyList::empty(py);
    for shell in info.shells {
        out.append(PyArray1::from_vec(
            py,
            shell.into_iter().map(|f| f as i64).collect(),
        ))?;
    }
    Ok(out)
}

/// Why ``(vertices, faces)`` is not a closed, oriented 2-manifold of
/// positive volume, or ``None`` when it is: the core's tolerance-free check
/// of every merged mesh (`dymsum::solid::closed::check_closed_mesh`), the
/// one rule for Rust's and Python's non-convex sums.
#[pyfunction]
fn _check_closed_mesh(
    py: Python<'_>,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
) -> PyResult<Option<String>> {
    let mesh = convert::mesh_from_parts(vertices, faces, "mesh")?;
    Ok(py
        .detach(|| dymsum::solid::closed::check_closed_mesh(&mesh))
        .err()
        .map(|e| e.to_string()))
}

/// Registers the solid checks on the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(check_solid, m)?)?;
    m.add_function(wrap_pyfunction!(_check_closed_mesh, m)?)?;
    Ok(())
}
