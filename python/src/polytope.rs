//! `Polytope`: a convex polytope built once from points or a convex mesh,
//! and the mesh policy and method names the other bindings share.

use crate::convert;
use crate::convert::{err_for, Origin, Shape};
use dymsum::polytope::MeshPolicy;
use dymsum::sum::Method;
use dymsum::Polytope;
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

pub(crate) fn policy(strict: bool) -> MeshPolicy {
    if strict {
        MeshPolicy::strict()
    } else {
        MeshPolicy::default()
    }
}

pub(crate) fn parse_method(method: &str) -> PyResult<Method> {
    method.parse::<Method>().map_err(|e| err_for("method", e))
}

/// A convex polytope: the exact convex hull of a point cloud, or a validated
/// convex mesh. Build it once and pass it to every function (parsing and
/// the hull are then done once).
///
/// ``Polytope(a, strict=False)`` where ``a`` is an (N, 3) array of points
/// (their exact convex hull), a ``(vertices, faces)`` pair (faces an (M, k)
/// integer array or a list of index lists), or any object with
/// ``.vertices`` and ``.faces`` (a ``trimesh.Trimesh``). A mesh must be
/// convex; one convex only within a small tolerance is replaced by the exact
/// hull of its vertices (``strict=True`` refuses it instead), and
/// ``convexity_report`` says what happened.
///
/// Raises ``ValueError`` for a wrong shape or dtype, NaN or infinite
/// coordinates, fewer than 4 points, flat input, or a non-convex or open
/// mesh, with dymsum's message.
///
/// >>> import numpy as np, dymsum
/// >>> cube = dymsum.Polytope(np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float))
/// >>> cube.vertices.shape, cube.faces.shape, cube.volume
/// ((8, 3), (12, 3), 1.0)
/// >>> len(cube.polygons)
/// 6
#[pyclass(module = "dymsum", name = "Polytope", frozen)]
pub struct PyPolytope {
    pub(crate) inner: Polytope,
    pub(crate) origin: Origin,
    pub(crate) source: String,
    vertices: Py<PyArray2<f64>>,
    faces: Py<PyArray2<i64>>,
}

impl PyPolytope {
    pub(crate) fn from_shape(py: Python<'_>, s: Shape) -> PyResult<Self> {
        let mesh = s.polytope.to_mesh();
        let vertices = convert::vertices_array(py, mesh.vertices)?;
        let faces = convert::triangles_array(py, &mesh.faces)?;
        for a in [vertices.as_any(), faces.as_any()] {
            let kwargs = PyDict::new(py);
            kwargs.set_item("write", false)?;
            a.call_method("setflags", (), Some(&kwargs))?;
        }
        Ok(PyPolytope {
            inner: s.polytope,
            origin: s.origin,
            source: s.source,
            vertices: vertices.unbind(),
            faces: faces.unbind(),
        })
    }
}

#[pymethods]
impl PyPolytope {
    #[new]
    #[pyo3(signature = (a, strict = false))]
    fn new(py: Python<'_>, a: &Bound<'_, PyAny>, strict: bool) -> PyResult<Self> {
        let s = convert::shape(a, "a", policy(strict))?;
        Self::from_shape(py, s)
    }

    /// Pickles as ``Polytope(vertices)``: the same body (its hull), so
    /// that a map's tasks can be shipped to worker processes.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let args = PyTuple::new(py, [self.vertices.bind(py).clone()])?;
        PyTuple::new(
            py,
            [py.get_type::<PyPolytope>().into_any(), args.into_any()],
        )
    }

    /// The vertices, a read-only (n, 3) ``float64`` array (the same array on
    /// every access: no copy).
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.vertices.bind(py).clone()
    }

    /// The faces fan-triangulated, a read-only (m, 3) ``int64`` array of
    /// indices into ``vertices``, counter-clockwise seen from outside (the
    /// same array on every access).
    #[getter]
    fn faces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<i64>> {
        self.faces.bind(py).clone()
    }

    /// The maximal (merged, convex) polygon faces, a list of ``int64``
    /// arrays, counter-clockwise seen from outside.
    #[getter]
    fn polygons<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let faces: Vec<Vec<usize>> = self
            .inner
            .faces()
            .map(|f| f.iter().map(|&i| i as usize).collect())
            .collect();
        convert::polygons_list(py, &faces)
    }

    /// ``(vertices, faces)``: fan triangles, or with ``polygons=True`` the
    /// maximal polygon faces as a list of ``int64`` arrays.
    #[pyo3(signature = (polygons = false))]
    fn mesh<'py>(&self, py: Python<'py>, polygons: bool) -> PyResult<Bound<'py, PyTuple>> {
        convert::mesh_tuple(py, self.inner.to_mesh(), polygons)
    }

    /// The volume.
    #[getter]
    fn volume(&self) -> f64 {
        self.inner.volume()
    }

    /// Number of vertices.
    #[getter]
    fn vertex_count(&self) -> usize {
        self.inner.vertex_count()
    }

    /// Number of edges.
    #[getter]
    fn edge_count(&self) -> usize {
        self.inner.edge_count()
    }

    /// Number of maximal faces (polygons).
    #[getter]
    fn face_count(&self) -> usize {
        self.inner.face_count()
    }

    /// Where the polytope came from: ``"points"``, ``"mesh"``,
    /// ``"built-in NAME"`` or ``"file PATH"``.
    #[getter]
    fn source(&self) -> &str {
        &self.source
    }

    /// What building the polytope found and changed, as a dict:
    /// ``point_cloud`` (the input had no faces: its exact hull was taken),
    /// ``input_vertices``, ``input_faces``, ``input_triangles``,
    /// ``vertices``, ``faces``, ``exactly_convex``, ``replaced_by_hull``,
    /// ``max_deviation``, ``tolerance``, ``dropped_vertices``,
    /// ``inward_oriented`` (the mesh-only entries are ``None`` for a point
    /// cloud).
    #[getter]
    fn convexity_report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("source", &self.source)?;
        match &self.origin {
            Origin::Points { count } => {
                d.set_item("point_cloud", true)?;
                d.set_item("input_vertices", count)?;
                d.set_item("input_faces", 0)?;
                d.set_item("input_triangles", 0)?;
                d.set_item("vertices", self.inner.vertex_count())?;
                d.set_item("faces", self.inner.face_count())?;
                d.set_item("exactly_convex", py.None())?;
                d.set_item("replaced_by_hull", true)?;
                d.set_item("max_deviation", py.None())?;
                d.set_item("tolerance", py.None())?;
                d.set_item("dropped_vertices", count - self.inner.vertex_count())?;
                d.set_item("inward_oriented", py.None())?;
            }
            Origin::Mesh(r) => {
                d.set_item("point_cloud", false)?;
                d.set_item("input_vertices", r.input_vertices)?;
                d.set_item("input_faces", r.input_faces)?;
                d.set_item("input_triangles", r.input_triangles)?;
                d.set_item("vertices", r.vertices)?;
                d.set_item("faces", r.faces)?;
                d.set_item("exactly_convex", r.exactly_convex)?;
                d.set_item("replaced_by_hull", r.replaced_by_hull)?;
                d.set_item("max_deviation", r.max_deviation)?;
                d.set_item("tolerance", r.tolerance)?;
                d.set_item("dropped_vertices", r.dropped_vertices)?;
                d.set_item("inward_oriented", r.inward_oriented)?;
            }
        }
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "Polytope({} vertices, {} edges, {} faces, volume {}, from {})",
            self.inner.vertex_count(),
            self.inner.edge_count(),
            self.inner.face_count(),
            self.inner.volume(),
            self.source
        )
    }
}

/// Registers this module's classes and functions on the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyPolytope>()?;
    Ok(())
}
