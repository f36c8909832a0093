//! The Rust half of `dymsum.cobstacle_map` (issue 22 §2): one task, one
//! piece pair × one block of consecutive orientations, computed by DYMSUM
//! with the GIL released; the Python half (`pysrc/dymsum/_maps.py`) splits
//! the map into tasks, runs them on a thread pool or a Dask cluster and
//! assembles the container.

use crate::convert::{self, err_for, value_error};
use dymsum::polytope::MeshPolicy;
use dymsum::CObstacle;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

/// The rotations as (K, 4) quaternions ``(x, y, z, w)``, as dymsum reads
/// them (any form ``cobstacle_slices`` takes).
#[pyfunction]
fn _rotations_xyzw<'py>(
    py: Python<'py>,
    rotations: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let rots = convert::rotations(rotations, "rotations")?;
    let flat: Vec<f64> = rots.iter().flat_map(|r| r.xyzw()).collect();
    let a = PyArray1::from_vec(py, flat);
    a.reshape([rots.len(), 4]).map(|a| a.into_any())
}

/// One task of a map: the slices of ``robot`` (a shape) among ``obstacle``
/// at ``rotations`` ((B, 4) quaternions), as half-spaces
/// ``(plane_counts (B,), normals (N, 3), offsets (N,))`` or meshes
/// ``(vertex_counts (B,), vertices (V, 3), face_counts (B,), corner_counts
/// (F,), corners (C,))``; with ``certified`` the B − 1 slabs between
/// consecutive rotations (half-spaces only).
#[pyfunction]
#[pyo3(signature = (robot, obstacle, rotations, form, certified))]
fn _cobstacle_block<'py>(
    py: Python<'py>,
    robot: &Bound<'py, PyAny>,
    obstacle: &Bound<'py, PyAny>,
    rotations: &Bound<'py, PyAny>,
    form: &str,
    certified: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let rots = convert::rotations(rotations, "rotations")?;
    let r = convert::shape(robot, "robot", MeshPolicy::default())?.polytope;
    let o = convert::shape(obstacle, "obstacle", MeshPolicy::default())?.polytope;
    let what = "cobstacle_map";
    match (form, certified) {
        ("halfspaces", _) => {
            let (counts, normals, offsets) = py
                .detach(|| {
                    let c = CObstacle::new(&r, &o)?;
                    let planes: Vec<(Vec<dymsum::DVec3>, Vec<f64>)> = if certified {
                        c.certified_slabs(&rots)?
                            .into_iter()
                            .map(|s| (s.normals().to_vec(), s.offsets().to_vec()))
                            .collect()
                    } else {
                        c.halfspace_slices(&rots)?
                            .into_iter()
                            .map(|h| h.into_parts())
                            .collect()
                    };
                    let counts: Vec<i64> = planes.iter().map(|p| p.1.len() as i64).collect();
                    let normals: Vec<f64> = planes
                        .iter()
                        .flat_map(|p| p.0.iter().flat_map(|n| n.to_array()))
                        .collect();
                    let offsets: Vec<f64> = planes.into_iter().flat_map(|p| p.1).collect();
                    Ok::<_, dymsum::QueryError>((counts, normals, offsets))
                })
                .map_err(|e| err_for(what, e))?;
            let n = offsets.len();
            PyTuple::new(
                py,
                [
                    PyArray1::from_vec(py, counts).into_any(),
                    convert::rows_array(py, normals, n)?.into_any(),
                    PyArray1::from_vec(py, offsets).into_any(),
                ],
            )
        }
        ("mesh", false) => {
            let meshes = py
                .detach(|| {
                    CObstacle::new(&r, &o)?
                        .slices(&rots)
                        .collect::<Result<Vec<_>, _>>()
                })
                .map_err(|e| err_for(what, e))?;
            let vcounts: Vec<i64> = meshes.iter().map(|m| m.vertices.len() as i64).collect();
            let fcounts: Vec<i64> = meshes.iter().map(|m| m.faces.len() as i64).collect();
            let vertices: Vec<f64> = meshes
                .iter()
                .flat_map(|m| m.vertices.iter().flatten().copied())
                .collect();
            let ccounts: Vec<i64> = meshes
                .iter()
                .flat_map(|m| m.faces.iter().map(|f| f.len() as i64))
                .collect();
            let corners: Vec<i64> = meshes
                .iter()
                .flat_map(|m| m.faces.iter().flatten().map(|&i| i as i64))
                .collect();
            let nv = vertices.len() / 3;
            PyTuple::new(
                py,
                [
                    PyArray1::from_vec(py, vcounts).into_any(),
                    convert::rows_array(py, vertices, nv)?.into_any(),
                    PyArray1::from_vec(py, fcounts).into_any(),
                    PyArray1::from_vec(py, ccounts).into_any(),
                    PyArray1::from_vec(py, corners).into_any(),
                ],
            )
        }
        ("mesh", true) => Err(value_error(
            "cobstacle_map: certified slabs come as half-spaces only (form=\"halfspaces\")",
        )),
        _ => Err(value_error(format!(
            "cobstacle_map: form must be \"halfspaces\" or \"mesh\", got {form:?}"
        ))),
    }
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_rotations_xyzw, m)?)?;
    m.add_function(wrap_pyfunction!(_cobstacle_block, m)?)?;
    Ok(())
}
