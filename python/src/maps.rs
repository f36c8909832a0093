//! The Rust half of `dymsum.cobstacle_map` (issue 22 §2): one task, one
//! piece pair × one block of consecutive orientations, computed by DYMSUM
//! with the GIL released; the Python half (`pysrc/dymsum/_maps.py` and its
//! `_maps_*` modules) splits the map into tasks, runs them on a thread
//! pool or a Dask cluster and assembles the container.
//!
//! The container's files are dymsum-io's: `_read_cobstacle_map` reads and
//! validates one (`dymsum_io::cmap::read_map`), `_write_cobstacle_map`
//! validates the arrays the same way (`Map::from_arrays`) and writes them
//! atomically (`dymsum_io::atomic::AtomicFile`, `npz::write_npz_to`).

use crate::convert::{self, err_for, io_error, path_string, value_error};
use dymsum::polytope::MeshPolicy;
use dymsum::CObstacle;
use dymsum_io::atomic::{remove_stale_temps_of, AtomicFile, FileError};
use dymsum_io::cmap::{read_map, Map, MapError, FIELDS};
use dymsum_io::npz::{write_npz_to, Array, Data};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArrayDyn};
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};
use std::io::{self, Write};
use std::path::Path;

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

/// The fields of a map container: name → ``(dtype kind, dimensions)``,
/// kind ``"i"`` a signed integer, ``"f"`` float64 or float32, ``"U"``
/// unicode (``dymsum_io::cmap::FIELDS``).
#[pyfunction]
fn _cobstacle_map_fields(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for (name, kind, ndim) in FIELDS {
        out.set_item(name, (kind.to_string(), ndim))?;
    }
    Ok(out)
}

/// The arrays of the map container at ``path``, validated whole first
/// with bounded memory (``dymsum_io::cmap::read_map``): ``ValueError``
/// naming the path (and the field) for a file that is not a valid map or
/// not a regular file, ``OSError`` when it cannot be opened or read.
#[pyfunction]
fn _read_cobstacle_map<'py>(
    py: Python<'py>,
    path: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let p = path_string(path)?;
    let map = py
        .detach(|| read_map(Path::new(&p)))
        .map_err(|e| match &e {
            MapError::Read { source, .. } => io_error(source.kind(), e.to_string()),
            _ => value_error(e.to_string()),
        })?;
    let out = PyDict::new(py);
    for a in map.into_arrays() {
        out.set_item(&a.name, numpy_array(py, a.shape, a.data)?)?;
    }
    Ok(out)
}

/// One array of a map as NumPy's: float64, int64, or unicode strings as
/// ``numpy.array(strings, dtype=str)`` makes them (the longest's width).
fn numpy_array<'py>(py: Python<'py>, shape: Vec<usize>, data: Data) -> PyResult<Bound<'py, PyAny>> {
    match data {
        Data::F64(v) => Ok(PyArray1::from_vec(py, v).reshape(shape)?.into_any()),
        Data::I64(v) => Ok(PyArray1::from_vec(py, v).reshape(shape)?.into_any()),
        Data::Str(v) => {
            let kwargs = PyDict::new(py);
            kwargs.set_item("dtype", "str")?;
            let flat = py
                .import("numpy")?
                .getattr("array")?
                .call((v,), Some(&kwargs))?;
            flat.call_method1("reshape", (PyTuple::new(py, shape)?,))
        }
    }
}

/// The arrays of a Python dict name → array-like, for validation: floats
/// as float64, signed integers as int64, unicode as strings; any other
/// dtype is refused naming the field.
fn arrays_of(arrays: &Bound<'_, PyAny>, path: &str) -> PyResult<Vec<Array>> {
    let np = arrays.py().import("numpy")?;
    let mut out = Vec::new();
    for item in arrays.call_method0("items")?.try_iter()? {
        let (name, value): (String, Bound<'_, PyAny>) = item?.extract()?;
        let a = np.call_method1("asarray", (value,))?;
        let shape: Vec<usize> = a.getattr("shape")?.extract()?;
        let dtype = a.getattr("dtype")?;
        let kind: String = dtype.getattr("kind")?.extract()?;
        let numbers = |dt: &str| np.call_method1("ascontiguousarray", (&a, dt));
        let data = match kind.as_str() {
            // C-contiguous: copied in one go.
            "f" => {
                let v: PyReadonlyArrayDyn<'_, f64> = numbers("float64")?.extract()?;
                Data::F64(
                    v.as_slice()
                        .map_or_else(|_| v.as_array().iter().copied().collect(), <[f64]>::to_vec),
                )
            }
            "i" => {
                let v: PyReadonlyArrayDyn<'_, i64> = numbers("int64")?.extract()?;
                Data::I64(
                    v.as_slice()
                        .map_or_else(|_| v.as_array().iter().copied().collect(), <[i64]>::to_vec),
                )
            }
            "U" => Data::Str(
                a.call_method1("reshape", (-1,))?
                    .call_method0("tolist")?
                    .extract()?,
            ),
            _ => {
                let descr: String = dtype.getattr("str")?.extract()?;
                return Err(value_error(format!(
                    "{path}: field '{name}': dtype {descr} is not a signed integer, a float or a unicode string"
                )));
            }
        };
        out.push(Array { name, shape, data });
    }
    Ok(out)
}

/// A Python file object as a Rust writer.
struct PyFile<'a, 'py>(&'a Bound<'py, PyAny>);

impl Write for PyFile<'_, '_> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self
            .0
            .call_method1("write", (PyBytes::new(self.0.py(), buf),))
            .map_err(io::Error::other)?;
        // A buffered file object writes everything and says how much.
        if n.is_none() {
            return Ok(buf.len());
        }
        n.extract::<usize>().map_err(io::Error::other)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.0
            .call_method0("flush")
            .map(drop)
            .map_err(io::Error::other)
    }
}

/// A failed write as Python's exception: an exception the file object
/// raised stays itself (an ``OSError`` gains the path, the original
/// chained), any other error is an ``OSError`` naming the path.
fn write_error(py: Python<'_>, path: &str, e: io::Error) -> PyErr {
    if e.get_ref().is_some_and(|inner| inner.is::<PyErr>()) {
        let inner = e.into_inner().expect("checked above");
        let err = *inner.downcast::<PyErr>().expect("checked above");
        if !err.is_instance_of::<PyOSError>(py) {
            return err;
        }
        let named = PyOSError::new_err(format!("{path}: {}", err.value(py)));
        named.set_cause(py, Some(err));
        return named;
    }
    io_error(e.kind(), format!("{path}: {e}"))
}

fn file_error(e: FileError) -> PyErr {
    let kind = match &e {
        FileError::Write { source, .. } | FileError::Read { source, .. } => source.kind(),
        FileError::NotRegular { .. } => io::ErrorKind::InvalidInput,
    };
    io_error(kind, e.to_string())
}

/// Writes the map of ``arrays`` (a dict of the container's fields) to
/// ``path``: validated first as ``_read_cobstacle_map`` validates a file
/// (``ValueError`` naming the path and the field), then written atomically
/// by dymsum-io: the temporary files of dead writers of ``path`` removed,
/// a fresh temporary file ``.STEM.tmp-PID-N.EXT`` beside it, the archive
/// written through ``open_temp(temporary path)`` (a binary file object,
/// closed here), synced and renamed over ``path``. On any error the
/// temporary file is removed and ``path`` is as it was.
#[pyfunction]
fn _write_cobstacle_map(
    py: Python<'_>,
    path: &Bound<'_, PyAny>,
    arrays: &Bound<'_, PyAny>,
    open_temp: &Bound<'_, PyAny>,
) -> PyResult<()> {
    let p = path_string(path)?;
    let arrays = arrays_of(arrays, &p)?;
    let map = py
        .detach(|| Map::from_arrays(arrays))
        .map_err(|e| value_error(format!("{p}: {e}")))?;
    let target = Path::new(&p);
    // Best effort: a folder that cannot be listed is reported by the write.
    let _ = py.detach(|| remove_stale_temps_of(target));
    let file = AtomicFile::create(target).map_err(file_error)?;
    let f = open_temp.call1((file.temp_path(),))?;
    let written = write_npz_to(&mut PyFile(&f), &map.into_arrays());
    let closed = f.call_method0("close");
    written.map_err(|e| write_error(py, &p, e))?;
    closed.map_err(|e| write_error(py, &p, io::Error::other(e)))?;
    py.detach(|| file.commit()).map_err(file_error)
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_rotations_xyzw, m)?)?;
    m.add_function(wrap_pyfunction!(_cobstacle_block, m)?)?;
    m.add_function(wrap_pyfunction!(_cobstacle_map_fields, m)?)?;
    m.add_function(wrap_pyfunction!(_read_cobstacle_map, m)?)?;
    m.add_function(wrap_pyfunction!(_write_cobstacle_map, m)?)?;
    Ok(())
}
