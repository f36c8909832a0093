//! The methods of `Polytope` (its constructor from any shape argument, its
//! arrays, sums and queries).

use super::{Origin, PyPolytope};
use crate::convert;
use crate::convert::{policy, Shape};
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

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
