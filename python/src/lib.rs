//! `dymsum._dymsum`: the Python bindings of dymsum (re-exported by the
//! `dymsum` package).
//!
//! Exact static and dynamic Minkowski sums of convex polytopes, penetration
//! depth and distance, contact tracking and C-obstacle slices, from NumPy
//! arrays. Every long computation (hulls, sums, updates, queries, slices,
//! file I/O) runs with the GIL released; the core types are `Send + Sync`.
//!
//! Conventions (see `convert` for the input rules):
//! * shapes: an (N, 3) point cloud (its exact hull), a `(vertices, faces)`
//!   pair, an object with `.vertices` and `.faces` (trimesh), or a
//!   [`PyPolytope`];
//! * shapes may also be model names or mesh file paths (as `load`);
//! * poses: 4×4 homogeneous rigid transforms (`None` = identity), or a
//!   rotation about the origin: a scipy `Rotation`, a 3×3 matrix, or a
//!   quaternion `(x, y, z, w)`, scalar last, as scipy (see `convert`);
//! * outputs: vertices `float64` (n, 3), faces `int64` (m, 3) fan
//!   triangles, or with `polygons=True` the merged faces as a list of
//!   `int64` arrays;
//! * invalid input raises `ValueError` with dymsum's message.
#![forbid(unsafe_code)]

mod convert;
mod maps;
mod motion;
mod solid;

use convert::{err_for, io_error, value_error, Origin, Shape};
use dymsum::polytope::MeshPolicy;
use dymsum::query::{ConvexPair, Proximity, Slab, SlabCover, TrackerStrategy};
use dymsum::sum::{minkowski_sum_posed, Method};
use dymsum::{CObstacle, ContactTracker, DVec3, DynamicSum, Polytope, Pose, UpdateReport};
use dymsum_io::formats::FormatError;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

fn policy(strict: bool) -> MeshPolicy {
    if strict {
        MeshPolicy::strict()
    } else {
        MeshPolicy::default()
    }
}

fn parse_method(method: &str) -> PyResult<Method> {
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

fn shape_of(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Shape> {
    convert::shape(obj, what, MeshPolicy::default())
}

/// The shapes `a`, `b` and their poses, read in the order of the messages
/// a user sees first: `pose_a`, `pose_b`, then the shapes.
fn two_bodies(
    a: &Bound<'_, PyAny>,
    b: &Bound<'_, PyAny>,
    pose_a: Option<&Bound<'_, PyAny>>,
    pose_b: Option<&Bound<'_, PyAny>>,
) -> PyResult<(Shape, Pose, Shape, Pose)> {
    let pa = convert::pose(pose_a, "pose_a")?;
    let pb = convert::pose(pose_b, "pose_b")?;
    Ok((shape_of(a, "a")?, pa, shape_of(b, "b")?, pb))
}

/// ``(R_a A + t_a) ⊕ (R_b B + t_b)``, exactly: ``(vertices, faces)``.
///
/// ``a`` and ``b`` are shapes (an (N, 3) point cloud, a ``(vertices,
/// faces)`` pair, an object with ``.vertices``/``.faces`` such as a
/// trimesh, a ``Polytope``, or a model name or mesh file path as
/// ``dymsum.load`` takes). ``pose_a``/``pose_b`` are 4×4 homogeneous rigid
/// transforms (``None``: identity), or rotations about the origin: a
/// ``scipy.spatial.transform.Rotation``, a 3×3 matrix or a (4,) quaternion
/// ``(x, y, z, w)`` (scalar last, as scipy);
/// ``dymsum.pose(rotation, translation)`` builds a 4×4 pose. ``method`` is ``"walk"``
/// (output-sensitive, fastest), ``"brute"`` or ``"hull"``; all give the same
/// exact facets. Returns vertices (n, 3) ``float64`` and faces (m, 3)
/// ``int64`` (fan triangles of the merged faces, counter-clockwise seen from
/// outside), or with ``polygons=True`` the merged convex polygon faces as a
/// list of ``int64`` arrays. The GIL is released while computing.
///
/// >>> import numpy as np, dymsum
/// >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
/// >>> v, f = dymsum.minkowski_sum(cube, 2 * cube)
/// >>> v.shape, f.shape, v.min(axis=0).tolist(), v.max(axis=0).tolist()
/// ((8, 3), (12, 3), [0.0, 0.0, 0.0], [3.0, 3.0, 3.0])
/// >>> v, polys = dymsum.minkowski_sum(cube, cube, polygons=True)
/// >>> sorted(len(p) for p in polys)
/// [4, 4, 4, 4, 4, 4]
#[pyfunction]
#[pyo3(signature = (a, b, pose_a = None, pose_b = None, method = "walk", polygons = false))]
fn minkowski_sum<'py>(
    py: Python<'py>,
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    pose_a: Option<&Bound<'py, PyAny>>,
    pose_b: Option<&Bound<'py, PyAny>>,
    method: &str,
    polygons: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let method = parse_method(method)?;
    let (sa, pa, sb, pb) = two_bodies(a, b, pose_a, pose_b)?;
    let mesh = py
        .detach(|| {
            let sum = minkowski_sum_posed(&sa.polytope, pa, &sb.polytope, pb, method)
                .map_err(|e| e.to_string())?;
            sum.try_to_mesh().map_err(|e| e.to_string())
        })
        .map_err(|e| err_for("minkowski_sum", e))?;
    convert::mesh_tuple(py, mesh, polygons)
}

fn report_dict<'py>(
    py: Python<'py>,
    r: &UpdateReport,
    facets: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("fv_errors", r.fv_errors)?;
    d.set_item("ee_errors", r.ee_errors)?;
    d.set_item("errors", r.fv_errors + r.ee_errors)?;
    d.set_item("removed", r.removed.len())?;
    d.set_item("added", r.added.len())?;
    d.set_item("facets", facets)?;
    d.set_item("step_angle", r.step_angle)?;
    d.set_item("recomputed", r.recomputed)?;
    d.set_item("recovered", r.recovered.clone())?;
    Ok(d)
}

/// ``A ⊕ B`` kept up to date while the bodies move (the DYMSUM algorithm):
/// each ``update`` repairs only the facets the rotation changed.
///
/// ``DynamicSum(a, b, pose_a=None, pose_b=None)``: shapes and poses as for
/// ``minkowski_sum`` (4×4 homogeneous rigid transforms, or rotations about
/// the origin: a scipy ``Rotation``, a 3×3 matrix or a (4,) quaternion
/// ``(x, y, z, w)``; ``dymsum.pose`` adds a translation). Updates are exact: after any
/// sequence of updates the facets equal a fresh ``minkowski_sum`` at the
/// same poses. Small steps are fastest; large ones fall back to a fresh
/// static sum automatically.
///
/// >>> import numpy as np, dymsum
/// >>> from scipy.spatial.transform import Rotation
/// >>> rng = np.random.default_rng(1)
/// >>> a, b = rng.normal(size=(50, 3)), rng.normal(size=(40, 3))
/// >>> s = dymsum.DynamicSum(a, b)
/// >>> for k in range(1, 11):
/// ...     report = s.update(dymsum.pose(Rotation.from_rotvec([0, 0, 0.01 * k]).as_quat()))
/// >>> sorted(report)[:3]
/// ['added', 'ee_errors', 'errors']
/// >>> v, f = s.mesh()
#[pyclass(module = "dymsum", name = "DynamicSum", subclass)]
pub struct PyDynamicSum {
    inner: DynamicSum,
}

#[pymethods]
impl PyDynamicSum {
    #[new]
    #[pyo3(signature = (a, b, pose_a = None, pose_b = None))]
    fn new(
        py: Python<'_>,
        a: &Bound<'_, PyAny>,
        b: &Bound<'_, PyAny>,
        pose_a: Option<&Bound<'_, PyAny>>,
        pose_b: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let (sa, pa, sb, pb) = two_bodies(a, b, pose_a, pose_b)?;
        let inner = py
            .detach(|| DynamicSum::new(&sa.polytope, pa, &sb.polytope, pb))
            .map_err(|e| err_for("DynamicSum", e))?;
        Ok(PyDynamicSum { inner })
    }

    /// Moves A to ``pose_a`` and B to ``pose_b`` (4×4 homogeneous rigid
    /// transforms; ``None`` keeps that body where it is) and repairs the sum.
    /// Returns the report, a dict: ``fv_errors`` and ``ee_errors`` (the
    /// errors found and repaired), ``errors`` (their sum), ``removed`` and
    /// ``added`` (facets), ``facets`` (the count after the update),
    /// ``step_angle`` (radians), ``recomputed`` (the step was recomputed from
    /// scratch: large step or many changes), ``recovered`` (``None``, or the
    /// internal inconsistency that made the step recompute: a bug to
    /// report). The GIL is released while updating.
    #[pyo3(signature = (pose_a = None, pose_b = None))]
    fn update<'py>(
        &mut self,
        py: Python<'py>,
        pose_a: Option<&Bound<'py, PyAny>>,
        pose_b: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let pa = convert::pose_or(pose_a, "pose_a", self.inner.pose_p())?;
        let pb = convert::pose_or(pose_b, "pose_b", self.inner.pose_q())?;
        let inner = &mut self.inner;
        let (report, facets) = py.detach(|| {
            let r = inner.set_pose(pa, pb);
            (r, inner.facet_count())
        });
        report_dict(py, &report, facets)
    }

    /// The current sum: ``(vertices, faces)`` as ``minkowski_sum`` returns
    /// it (fan triangles, or polygons with ``polygons=True``).
    #[pyo3(signature = (polygons = false))]
    fn mesh<'py>(&self, py: Python<'py>, polygons: bool) -> PyResult<Bound<'py, PyTuple>> {
        let inner = &self.inner;
        let mesh = py
            .detach(|| inner.try_to_mesh())
            .map_err(|e| err_for("DynamicSum.mesh", e))?;
        convert::mesh_tuple(py, mesh, polygons)
    }

    /// The number of facets (fv + vf + ee pairs; coplanar facets are counted
    /// separately, before merging).
    #[getter]
    fn facet_count(&self) -> usize {
        self.inner.facet_count()
    }

    /// A's current pose, a 4×4 ``float64`` array.
    #[getter]
    fn pose_a<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        convert::pose_array(py, self.inner.pose_p())
    }

    /// B's current pose, a 4×4 ``float64`` array.
    #[getter]
    fn pose_b<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        convert::pose_array(py, self.inner.pose_q())
    }

    fn __repr__(&self) -> String {
        format!("DynamicSum({} facets)", self.inner.facet_count())
    }
}

/// The answer of a proximity query between A and B.
///
/// * ``collides``: the bodies overlap or touch;
/// * ``depth``: the penetration depth, the length of the shortest
///   translation separating them (``0.0`` when apart or touching);
/// * ``distance``: the distance between them (``0.0`` when colliding);
/// * ``normal``: unit (3,) ``float64`` vector from A towards B: when
///   colliding, translating A by ``-depth * normal`` separates the bodies;
///   when apart, the direction from ``point_a`` to ``point_b``;
/// * ``point_a``, ``point_b``: (3,) witness points. Colliding: A's deepest
///   point inside B and B's deepest point inside A, with
///   ``point_a - point_b == depth * normal``; apart: the closest points.
#[pyclass(module = "dymsum", name = "Contact", frozen)]
pub struct PyContact {
    collides: bool,
    depth: f64,
    distance: f64,
    normal: [f64; 3],
    point_a: [f64; 3],
    point_b: [f64; 3],
}

impl PyContact {
    fn from_proximity(p: &Proximity) -> Self {
        match p {
            Proximity::Penetrating(c) => PyContact {
                collides: true,
                depth: c.depth,
                distance: 0.0,
                normal: c.normal.to_array(),
                point_a: c.point_on_a.to_array(),
                point_b: c.point_on_b.to_array(),
            },
            Proximity::Separated(s) => PyContact {
                collides: false,
                depth: 0.0,
                distance: s.distance,
                normal: s.direction.to_array(),
                point_a: s.point_on_a.to_array(),
                point_b: s.point_on_b.to_array(),
            },
        }
    }
}

#[pymethods]
impl PyContact {
    /// The bodies overlap or touch.
    #[getter]
    fn collides(&self) -> bool {
        self.collides
    }
    /// Penetration depth (``0.0`` when apart or touching).
    #[getter]
    fn depth(&self) -> f64 {
        self.depth
    }
    /// Distance (``0.0`` when colliding).
    #[getter]
    fn distance(&self) -> f64 {
        self.distance
    }
    /// Unit (3,) ``float64`` normal from A towards B.
    #[getter]
    fn normal<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        convert::vec3(py, self.normal)
    }
    /// Witness point on A, (3,) ``float64``.
    #[getter]
    fn point_a<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        convert::vec3(py, self.point_a)
    }
    /// Witness point on B, (3,) ``float64``.
    #[getter]
    fn point_b<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        convert::vec3(py, self.point_b)
    }
    fn __repr__(&self) -> String {
        if self.collides {
            format!(
                "Contact(collides=True, depth={}, normal={:?})",
                self.depth, self.normal
            )
        } else {
            format!(
                "Contact(collides=False, distance={}, normal={:?})",
                self.distance, self.normal
            )
        }
    }
}

/// Penetration depth or distance of A and B at their poses: a ``Contact``.
///
/// Exact: GJK and EPA on the support functions of A and B propose the
/// answer, and exact certificates prove it equal to the minimum over every
/// facet of the Minkowski difference ``A ⊕ (−B)`` (no GJK/EPA tolerance);
/// where a certificate cannot be made, every facet is evaluated. A
/// ``Polytope`` keeps what its queries need between calls, so pass
/// ``Polytope`` objects (or use ``contact_many``, ``ContactTracker``) for
/// repeated queries. ``pose_a`` and
/// ``pose_b`` are 4×4 homogeneous rigid transforms (``None``: identity), or
/// (4,) quaternions ``(x, y, z, w)`` (scalar last, as scipy) for a rotation
/// about the origin. The GIL is released while computing.
///
/// >>> import numpy as np, dymsum
/// >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
/// >>> c = dymsum.contact(cube, cube, None, dymsum.pose(translation=[0.75, 0, 0]))
/// >>> c.collides, c.depth, c.normal.tolist()
/// (True, 0.25, [1.0, 0.0, 0.0])
/// >>> dymsum.contact(cube, cube, None, dymsum.pose(translation=[1.5, 0, 0])).distance
/// 0.5
#[pyfunction]
#[pyo3(signature = (a, b, pose_a = None, pose_b = None))]
fn contact(
    py: Python<'_>,
    a: &Bound<'_, PyAny>,
    b: &Bound<'_, PyAny>,
    pose_a: Option<&Bound<'_, PyAny>>,
    pose_b: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyContact> {
    let (sa, pa, sb, pb) = two_bodies(a, b, pose_a, pose_b)?;
    let p = py
        .detach(|| ConvexPair::new(&sa.polytope, &sb.polytope)?.query(pa, pb))
        .map_err(|e| err_for("contact", e))?;
    Ok(PyContact::from_proximity(&p))
}

/// Tracks the contact of A and B over a motion, with exactly the answers of
/// ``contact`` at every frame.
///
/// ``ContactTracker(a, b, pose_a=None, pose_b=None, strategy="auto")``;
/// poses 4×4 homogeneous rigid transforms, or rotations about the origin (a
/// scipy ``Rotation``, a 3×3 matrix, a quaternion ``(x, y, z, w)``).
/// ``strategy="certified"`` answers each frame from support functions
/// warm-started from the last frame, with exact certificates;
/// ``strategy="sum"`` keeps the dynamic sum ``A ⊕ (−B)`` repaired by DYMSUM
/// and evaluates every facet (``last_update`` then reports the repair);
/// ``"auto"`` (the default) times both on the first frames and keeps the
/// faster. Every strategy gives the same answers.
///
/// >>> import numpy as np, dymsum
/// >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float) - 0.5
/// >>> t = dymsum.ContactTracker(cube, cube)
/// >>> [round(t.update(None, dymsum.pose(translation=[x, 0, 0])).depth, 3) for x in (0.5, 0.8, 1.2)]
/// [0.5, 0.2, 0.0]
#[pyclass(module = "dymsum", name = "ContactTracker")]
pub struct PyContactTracker {
    inner: ContactTracker,
}

#[pymethods]
impl PyContactTracker {
    #[new]
    #[pyo3(signature = (a, b, pose_a = None, pose_b = None, strategy = "auto"))]
    fn new(
        py: Python<'_>,
        a: &Bound<'_, PyAny>,
        b: &Bound<'_, PyAny>,
        pose_a: Option<&Bound<'_, PyAny>>,
        pose_b: Option<&Bound<'_, PyAny>>,
        strategy: &str,
    ) -> PyResult<Self> {
        let strategy = match strategy {
            "auto" => TrackerStrategy::Auto,
            "certified" => TrackerStrategy::Certified,
            "sum" => TrackerStrategy::DynamicSum,
            other => {
                return Err(convert::value_error(format!(
                    "ContactTracker: strategy must be \"auto\", \"certified\" or \"sum\", got {other:?}"
                )))
            }
        };
        let (sa, pa, sb, pb) = two_bodies(a, b, pose_a, pose_b)?;
        let inner = py
            .detach(|| {
                let pair = ConvexPair::new(&sa.polytope, &sb.polytope)?;
                ContactTracker::with_strategy(&pair, pa, pb, strategy)
            })
            .map_err(|e| err_for("ContactTracker", e))?;
        Ok(PyContactTracker { inner })
    }

    /// Moves A to ``pose_a`` and B to ``pose_b`` (4×4 homogeneous rigid
    /// transforms; ``None`` keeps that body where it is) and returns the
    /// ``Contact``. The GIL is released while updating.
    #[pyo3(signature = (pose_a = None, pose_b = None))]
    fn update(
        &mut self,
        py: Python<'_>,
        pose_a: Option<&Bound<'_, PyAny>>,
        pose_b: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PyContact> {
        let (now_a, now_b) = self.inner.poses();
        let pa = convert::pose_or(pose_a, "pose_a", now_a)?;
        let pb = convert::pose_or(pose_b, "pose_b", now_b)?;
        let inner = &mut self.inner;
        let p = py
            .detach(|| inner.update(pa, pb))
            .map_err(|e| err_for("ContactTracker.update", e))?;
        Ok(PyContact::from_proximity(&p))
    }

    /// The answer of the last update (or of construction).
    #[getter]
    fn last(&self) -> PyContact {
        PyContact::from_proximity(self.inner.last())
    }

    /// What the last update's dynamic sum repair did (the dict of
    /// ``DynamicSum.update``; with the ``"certified"`` strategy, which keeps
    /// no sum, an empty repair with ``facets == 0``).
    #[getter]
    fn last_update<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let facets = self.inner.sum().map_or(0, |s| s.facet_count());
        report_dict(py, self.inner.last_update(), facets)
    }

    /// The strategy asked for: ``"auto"``, ``"certified"`` or ``"sum"``.
    #[getter]
    fn strategy(&self) -> &'static str {
        strategy_name(self.inner.strategy())
    }

    /// The strategy answering now: ``"certified"`` or ``"sum"`` (an
    /// ``"auto"`` tracker measures both on its first frames and keeps the
    /// faster).
    #[getter]
    fn active_strategy(&self) -> &'static str {
        strategy_name(self.inner.active_strategy())
    }

    /// How the pair's queries were answered: a dict with ``queries``,
    /// ``exhaustive_decisions`` and ``exhaustive_answers`` (the answers a
    /// certificate could not settle, found by the exhaustive exact method
    /// instead).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        stats_dict(py, self.inner.stats())
    }
}

/// A strategy's name in Python.
fn strategy_name(s: TrackerStrategy) -> &'static str {
    match s {
        TrackerStrategy::Auto => "auto",
        TrackerStrategy::Certified => "certified",
        TrackerStrategy::DynamicSum => "sum",
    }
}

/// The dict of a pair's ``QueryStats``.
fn stats_dict<'py>(py: Python<'py>, s: dymsum::QueryStats) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("queries", s.queries)?;
    d.set_item("exhaustive_decisions", s.exhaustive_decisions)?;
    d.set_item("exhaustive_answers", s.exhaustive_answers)?;
    Ok(d)
}

/// The poses of a batch: both stacks of the same length K, or one of them
/// a single pose standing for all K.
fn batch_poses(
    poses_a: Option<&Bound<'_, PyAny>>,
    poses_b: Option<&Bound<'_, PyAny>>,
) -> PyResult<Vec<(Pose, Pose)>> {
    let pa = convert::pose_stack(poses_a, "poses_a")?;
    let pb = convert::pose_stack(poses_b, "poses_b")?;
    let k = match (pa.len(), pb.len()) {
        (m, n) if m == n => m,
        (1, n) => n,
        (m, 1) => m,
        (m, n) => {
            return Err(convert::value_error(format!(
                "poses_a and poses_b: {m} and {n} poses; give the same number, or one pose for all"
            )))
        }
    };
    let at = |v: &[Pose], i: usize| if v.len() == 1 { v[0] } else { v[i] };
    Ok((0..k).map(|i| (at(&pa, i), at(&pb, i))).collect())
}

/// The answers of a batch as arrays (``contact_many``): ``collides`` (K,)
/// ``bool``; ``depth`` and ``distance`` (K,) ``float64``; ``normal``,
/// ``point_a``, ``point_b`` (K, 3) ``float64``; row ``k`` holds what
/// ``contact`` returns for pose ``k`` (the same conventions as
/// ``Contact``).
#[pyclass(module = "dymsum", name = "Contacts", frozen)]
pub struct PyContacts {
    collides: Py<PyArray1<bool>>,
    depth: Py<PyArray1<f64>>,
    distance: Py<PyArray1<f64>>,
    normal: Py<PyArray2<f64>>,
    point_a: Py<PyArray2<f64>>,
    point_b: Py<PyArray2<f64>>,
    len: usize,
}

#[pymethods]
impl PyContacts {
    /// (K,) ``bool``: the bodies overlap or touch.
    #[getter]
    fn collides<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        self.collides.bind(py).clone()
    }
    /// (K,) penetration depths (``0.0`` when apart).
    #[getter]
    fn depth<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.depth.bind(py).clone()
    }
    /// (K,) distances (``0.0`` when colliding).
    #[getter]
    fn distance<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.distance.bind(py).clone()
    }
    /// (K, 3) unit normals from A towards B.
    #[getter]
    fn normal<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.normal.bind(py).clone()
    }
    /// (K, 3) witness points on A.
    #[getter]
    fn point_a<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.point_a.bind(py).clone()
    }
    /// (K, 3) witness points on B.
    #[getter]
    fn point_b<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.point_b.bind(py).clone()
    }
    fn __len__(&self) -> usize {
        self.len
    }
    fn __repr__(&self) -> String {
        format!("Contacts({} poses)", self.len)
    }
}

/// ``contact`` at many poses at once: ``poses_a`` and ``poses_b`` are
/// (K, 4, 4) arrays of homogeneous rigid transforms (or (K, 4) quaternions
/// ``(x, y, z, w)``, (K, 3, 3) matrices, a scipy ``Rotation`` stack), or one
/// pose (``None``: the identity) standing for all K. Returns ``Contacts``,
/// whose arrays hold one row per pose. The GIL is released and the poses
/// are answered in parallel chunks (each chunk warm-started from the pose
/// before), with exactly the answers of ``contact``.
///
/// >>> import numpy as np, dymsum
/// >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
/// >>> poses_b = np.stack([dymsum.pose(translation=[x, 0, 0]) for x in (0.5, 0.75, 1.5)])
/// >>> c = dymsum.contact_many(cube, cube, None, poses_b)
/// >>> c.collides.tolist(), c.depth.tolist(), c.distance.tolist()
/// ([True, True, False], [0.5, 0.25, 0.0], [0.0, 0.0, 0.5])
#[pyfunction]
#[pyo3(signature = (a, b, poses_a = None, poses_b = None))]
fn contact_many(
    py: Python<'_>,
    a: &Bound<'_, PyAny>,
    b: &Bound<'_, PyAny>,
    poses_a: Option<&Bound<'_, PyAny>>,
    poses_b: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyContacts> {
    let (sa, sb) = (shape_of(a, "a")?, shape_of(b, "b")?);
    let poses = batch_poses(poses_a, poses_b)?;
    let answers = py
        .detach(|| ConvexPair::new(&sa.polytope, &sb.polytope)?.query_many(&poses))
        .map_err(|e| err_for("contact_many", e))?;
    let k = answers.len();
    let (mut collides, mut depth, mut distance) = (
        Vec::with_capacity(k),
        Vec::with_capacity(k),
        Vec::with_capacity(k),
    );
    let (mut normal, mut point_a, mut point_b) = (
        Vec::with_capacity(3 * k),
        Vec::with_capacity(3 * k),
        Vec::with_capacity(3 * k),
    );
    for p in &answers {
        let c = PyContact::from_proximity(p);
        collides.push(c.collides);
        depth.push(c.depth);
        distance.push(c.distance);
        normal.extend(c.normal);
        point_a.extend(c.point_a);
        point_b.extend(c.point_b);
    }
    let rows = |v: Vec<f64>| convert::rows_array(py, v, k);
    Ok(PyContacts {
        collides: collides.into_pyarray(py).unbind(),
        depth: depth.into_pyarray(py).unbind(),
        distance: distance.into_pyarray(py).unbind(),
        normal: rows(normal)?.unbind(),
        point_a: rows(point_a)?.unbind(),
        point_b: rows(point_b)?.unbind(),
        len: k,
    })
}

/// Whether A and B overlap or touch at many poses (``poses_a``,
/// ``poses_b`` as ``contact_many`` takes them): a (K,) ``bool`` array. The
/// yes/no answer alone, decided exactly by GJK and its certificates (no
/// depth or distance computed), in parallel with the GIL released.
///
/// >>> import numpy as np, dymsum
/// >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
/// >>> poses_b = np.stack([dymsum.pose(translation=[x, 0, 0]) for x in (0.5, 1.0, 1.5)])
/// >>> dymsum.collides_many(cube, cube, None, poses_b).tolist()
/// [True, True, False]
#[pyfunction]
#[pyo3(signature = (a, b, poses_a = None, poses_b = None))]
fn collides_many<'py>(
    py: Python<'py>,
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    poses_a: Option<&Bound<'py, PyAny>>,
    poses_b: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray1<bool>>> {
    let (sa, sb) = (shape_of(a, "a")?, shape_of(b, "b")?);
    let poses = batch_poses(poses_a, poses_b)?;
    let answers = py
        .detach(|| ConvexPair::new(&sa.polytope, &sb.polytope)?.intersects_many(&poses))
        .map_err(|e| err_for("collides_many", e))?;
    Ok(answers.into_pyarray(py))
}

/// C-obstacle slices: for each orientation ``R`` of the robot, the set of
/// translations ``t`` at which ``R·robot + t`` meets the obstacle, i.e. the
/// convex polytope ``obstacle ⊕ (−R·robot)``, as ``(vertices, faces)``.
///
/// ``rotations`` is a ``scipy.spatial.transform.Rotation`` (one or a
/// stack), a (K, 3, 3) array of rotation matrices, a (K, 4) array of unit
/// quaternions in the order ``(x, y, z, w)`` (scalar last, as
/// ``Rotation.as_quat()``), a (K, 4, 4) array of homogeneous transforms
/// without translation, or one (4,) quaternion or 3×3 matrix. Computed with DYMSUM,
/// one dynamic sum moved from slice to slice (fastest when consecutive
/// orientations are close; exact in any order); ``parallel=True`` splits the orientations into chunks
/// over threads (same result). The GIL is released while computing.
///
/// >>> import numpy as np, dymsum
/// >>> from scipy.spatial.transform import Rotation
/// >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
/// >>> quats = Rotation.from_rotvec(np.outer(np.linspace(0, np.pi / 2, 8), [0, 0, 1])).as_quat()
/// >>> slices = dymsum.cobstacle_slices(cube, 2 * cube, quats)
/// >>> len(slices), slices[0][0].shape
/// (8, (8, 3))
/// >>> len(dymsum.cobstacle_slices(cube, "box:2,1,1", Rotation.from_rotvec([[0, 0, 0.1], [0, 0, 0.2]])))
/// 2
///
/// ``certified=True`` returns instead the K − 1 certified slabs between
/// consecutive rotations (:class:`Slab`): slab ``k`` contains every slice
/// for every rotation on the shortest path from ``rotations[k]`` to
/// ``rotations[k + 1]`` (the turn about one axis between two angles at most
/// π apart, or scipy's ``Slerp`` between them). Consecutive rotations must
/// be at most a half turn apart (``ValueError`` otherwise, and for fewer
/// than two rotations); ``polygons`` does not apply (see ``Slab.mesh``).
///
/// >>> turn = Rotation.from_rotvec(np.outer(np.linspace(0, 2 * np.pi, 17), [0, 0, 1]))
/// >>> slabs = dymsum.cobstacle_slices("box:4,0.2,0.2", "box", turn, certified=True)
/// >>> len(slabs), slabs[0].normals.shape[1], bool(slabs[0].contains([2.0, 0.0, 0.0]))
/// (16, 3, True)
///
/// ``certified=True`` with ``cell_radius=rho`` (radians, ``0 <= rho < π``)
/// returns instead one slab per rotation, for the orientation cell about
/// it: slab ``k`` contains every slice for every rotation within angle
/// ``rho`` of ``rotations[k]``, about any axis (its slice with every face
/// plane pushed out by ``r·rho``, ``r`` the robot's largest distance from
/// its origin, and the rounding terms). ``ValueError`` for a radius out of
/// range, or without ``certified=True``.
///
/// >>> centres = Rotation.from_rotvec([[0, 0, 0], [0, 0.5, 0]])
/// >>> cells = dymsum.cobstacle_slices("box:4,0.2,0.2", "box", centres, certified=True, cell_radius=0.1)
/// >>> len(cells), cells[1].cell_radius, cells[1].rotations.shape
/// (2, 0.1, (1, 4))
#[pyfunction]
#[pyo3(signature = (robot, obstacle, rotations, polygons = false, parallel = false, certified = false, cell_radius = None))]
#[allow(clippy::too_many_arguments)]
fn cobstacle_slices<'py>(
    py: Python<'py>,
    robot: &Bound<'py, PyAny>,
    obstacle: &Bound<'py, PyAny>,
    rotations: &Bound<'py, PyAny>,
    polygons: bool,
    parallel: bool,
    certified: bool,
    cell_radius: Option<f64>,
) -> PyResult<Bound<'py, PyList>> {
    if cell_radius.is_some() && !certified {
        return Err(value_error(
            "cobstacle_slices: cell_radius applies to certified slabs (add certified=True)",
        ));
    }
    let rots = convert::rotations(rotations, "rotations")?;
    let sr = shape_of(robot, "robot")?;
    let so = shape_of(obstacle, "obstacle")?;
    if certified {
        if polygons {
            return Err(value_error(
                "cobstacle_slices: polygons=True applies to slices, not to certified slabs \
                 (use Slab.mesh(polygons=True))",
            ));
        }
        let slabs = py
            .detach(|| {
                let c = CObstacle::new(&sr.polytope, &so.polytope)?;
                match (cell_radius, parallel) {
                    (Some(rho), true) => c.certified_slabs_in_cells_par(&rots, rho),
                    (Some(rho), false) => c.certified_slabs_in_cells(&rots, rho),
                    (None, true) => c.certified_slabs_par(&rots),
                    (None, false) => c.certified_slabs(&rots),
                }
            })
            .map_err(|e| err_for("cobstacle_slices", e))?;
        let out = PyList::empty(py);
        for s in slabs {
            out.append(PySlab::new(py, s)?)?;
        }
        return Ok(out);
    }
    let meshes = py
        .detach(|| {
            let c = CObstacle::new(&sr.polytope, &so.polytope)?;
            if parallel {
                c.slices_par(&rots)
            } else {
                c.slices(&rots).collect()
            }
        })
        .map_err(|e| err_for("cobstacle_slices", e))?;
    let out = PyList::empty(py);
    for m in meshes {
        out.append(convert::mesh_tuple(py, m, polygons)?)?;
    }
    Ok(out)
}

/// A certified C-obstacle slab, from ``cobstacle_slices(...,
/// certified=True)``: the convex region ``{x : normals @ x <= offsets}``
/// that contains every slice ``obstacle ⊕ (−R·robot)`` for every rotation
/// ``R`` on the shortest path between its two end rotations (the hull of
/// the two end slices with every face plane pushed out by the arc's
/// sagitta and the rounding terms, offsets rounded outward). A translation
/// outside it is free at every orientation between the ends. With
/// ``cell_radius=rho``: for every rotation within angle ``rho`` of its
/// centre rotation (the centre's slice, planes pushed out by ``r·rho``).
///
/// >>> import numpy as np, dymsum
/// >>> from scipy.spatial.transform import Rotation
/// >>> ends = Rotation.from_rotvec([[0, 0, 0], [0, 0, np.pi / 8]])
/// >>> (slab,) = dymsum.cobstacle_slices("box:4,0.2,0.2", "box", ends, certified=True)
/// >>> slab.contains(np.array([[2.0, 0.3, 0.0], [3.0, 0.0, 0.0]])).tolist()
/// [True, False]
/// >>> vertices, faces = slab.mesh()
#[pyclass(module = "dymsum", name = "Slab", frozen)]
pub struct PySlab {
    inner: Slab,
    normals: Py<PyArray2<f64>>,
    offsets: Py<PyArray1<f64>>,
}

impl PySlab {
    fn new(py: Python<'_>, slab: Slab) -> PyResult<Self> {
        let flat: Vec<f64> = slab.normals().iter().flat_map(|n| n.to_array()).collect();
        let normals = convert::rows_array(py, flat, slab.len())?;
        let offsets = PyArray1::from_vec(py, slab.offsets().to_vec());
        for a in [normals.as_any(), offsets.as_any()] {
            let kwargs = PyDict::new(py);
            kwargs.set_item("write", false)?;
            a.call_method("setflags", (), Some(&kwargs))?;
        }
        Ok(PySlab {
            inner: slab,
            normals: normals.unbind(),
            offsets: offsets.unbind(),
        })
    }
}

#[pymethods]
impl PySlab {
    /// The unit outward normals, a read-only (M, 3) ``float64`` array (one
    /// per face of the end slices' hull).
    #[getter]
    fn normals<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.normals.bind(py).clone()
    }

    /// The offsets, a read-only (M,) ``float64`` array, rounded outward: the
    /// slab is ``{x : normals @ x <= offsets}``.
    #[getter]
    fn offsets<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.offsets.bind(py).clone()
    }

    /// How far each plane is pushed beyond the end slices' hull: the
    /// sagitta ``r·(1 − cos(δ/2))`` of the turn by ``δ`` (``r`` bounds the
    /// robot's radius) plus the rounding terms; for a cell of radius
    /// ``rho``, ``r·rho`` plus the rounding terms.
    #[getter]
    fn margin(&self) -> f64 {
        self.inner.margin()
    }

    /// The end rotations, a (2, 4) array of quaternions ``(x, y, z, w)``
    /// (scalar last, as scipy); for a cell, its centre, a (1, 4) array.
    #[getter]
    fn rotations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let quats: Vec<[f64; 4]> = match self.inner.cover() {
            SlabCover::Path { from, to, .. } => vec![from.xyzw(), to.xyzw()],
            SlabCover::Cell { centre, .. } => vec![centre.xyzw()],
        };
        let rows = quats.len();
        numpy::ndarray::Array2::from_shape_vec((rows, 4), quats.into_flattened())
            .map(|a| a.into_pyarray(py))
            .map_err(|e| value_error(format!("internal error: {e}")))
    }

    /// An upper bound on the angle between the end rotations (radians);
    /// for a cell, its radius.
    #[getter]
    fn angle(&self) -> f64 {
        match self.inner.cover() {
            SlabCover::Path { angle, .. } => angle,
            SlabCover::Cell { radius, .. } => radius,
        }
    }

    /// The cell's radius (radians) for a slab from ``cell_radius=``;
    /// ``None`` for a slab between two rotations.
    #[getter]
    fn cell_radius(&self) -> Option<f64> {
        match self.inner.cover() {
            SlabCover::Path { .. } => None,
            SlabCover::Cell { radius, .. } => Some(radius),
        }
    }

    /// Whether each point satisfies every ``normals @ x <= offsets``,
    /// decided exactly (no tolerance): a (N,) bool array for (N, 3)
    /// points, a bool for one (3,) point; ``False`` for NaN or infinite
    /// points.
    fn contains<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let np = py.import("numpy")?;
        let arr = np.call_method1("asarray", (points,))?;
        let ndim: usize = arr.getattr("ndim")?.extract()?;
        if ndim == 1 {
            let one =
                convert::float_array(&arr, 1, &[3], "points", "(N, 3) points or one (3,) point")?;
            let v: Vec<f64> = one.call_method0("tolist")?.extract()?;
            let inside = self.inner.contains(DVec3::new(v[0], v[1], v[2]));
            return Ok(pyo3::types::PyBool::new(py, inside).to_owned().into_any());
        }
        let arr = convert::points(&arr, "points")?;
        let rows = convert::rows(&arr, "points")?;
        let slab = &self.inner;
        let inside: Vec<bool> = py.detach(|| {
            rows.iter()
                .map(|&p| slab.contains(DVec3::from(p)))
                .collect()
        });
        Ok(inside.into_pyarray(py).into_any())
    }

    /// ``(vertices, faces)`` of a closed convex mesh that contains the slab
    /// (its vertices those of the half-spaces pushed out by about 2⁻⁴⁰ of
    /// its size, rounded; checked exactly): fan triangles, or with
    /// ``polygons=True`` the maximal faces.
    #[pyo3(signature = (polygons = false))]
    fn mesh<'py>(&self, py: Python<'py>, polygons: bool) -> PyResult<Bound<'py, PyTuple>> {
        let slab = &self.inner;
        let mesh = py
            .detach(|| slab.mesh())
            .map_err(|e| err_for("Slab.mesh", e))?;
        convert::mesh_tuple(py, mesh, polygons)
    }

    /// The number of half-spaces.
    fn __len__(&self) -> usize {
        self.inner.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "Slab({} half-spaces, margin {:.3e})",
            self.inner.len(),
            self.inner.margin()
        )
    }
}

/// A 4×4 homogeneous rigid transform (``float64``) from a rotation and a
/// translation. The rotation (the first argument, named ``quaternion``) is
/// a ``scipy.spatial.transform.Rotation``, a 3×3 rotation matrix, or a
/// unit quaternion in the order ``(x, y, z, w)`` (scalar last, as scipy;
/// renormalised). ``pose()`` is the identity.
///
/// >>> import numpy as np, dymsum
/// >>> dymsum.pose([0, 0, 0, 1], [1, 2, 3])[:3, 3].tolist()
/// [1.0, 2.0, 3.0]
/// >>> quarter_turn_z = np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]])
/// >>> np.allclose(dymsum.pose(quarter_turn_z), dymsum.pose([0, 0, np.sqrt(0.5), np.sqrt(0.5)]))
/// True
#[pyfunction]
#[pyo3(signature = (quaternion = None, translation = None))]
fn pose<'py>(
    py: Python<'py>,
    quaternion: Option<&Bound<'py, PyAny>>,
    translation: Option<[f64; 3]>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let rotation = match quaternion.filter(|q| !q.is_none()) {
        None => dymsum::Rotation::IDENTITY,
        Some(q) => convert::rotation(q, "quaternion")?,
    };
    let t = translation.unwrap_or([0.0; 3]);
    if t.iter().any(|x| !x.is_finite()) {
        return Err(value_error(format!("translation: {t:?} is not finite")));
    }
    convert::pose_array(py, Pose::new(rotation, t.into()))
}

fn path_string(path: &Bound<'_, PyAny>) -> PyResult<String> {
    let os = path.py().import("os")?;
    os.call_method1("fspath", (path,))?.extract()
}

/// Loads a polytope from a mesh file (``.off``, ``.obj``, ``.ply``,
/// ``.stl``; a file without faces is a point cloud, whose hull is taken) or
/// a built-in model name (``"cube"``, ``"ellipse"``, ``"sphere:200"``,
/// ``"tcube:10"``, ... see ``dymsum.models()``).
///
/// Raises ``FileNotFoundError`` for a path that does not exist, ``OSError``
/// when a file cannot be read, and ``ValueError`` for an unknown model name
/// (with the closest name), a file that does not parse, or a non-convex
/// mesh (``strict=True`` also refuses meshes convex only within tolerance).
///
/// >>> import dymsum
/// >>> gs1 = dymsum.load("gs1")
/// >>> gs1.source, gs1.convexity_report["input_triangles"]
/// ('built-in gs1', 80)
#[pyfunction]
#[pyo3(signature = (path_or_model_name, strict = false))]
fn load(
    py: Python<'_>,
    path_or_model_name: &Bound<'_, PyAny>,
    strict: bool,
) -> PyResult<PyPolytope> {
    let spec = path_string(path_or_model_name)?;
    let shape = convert::load_shape(py, &spec, policy(strict), None)?;
    PyPolytope::from_shape(py, shape)
}

/// ``t ⊕ P`` for every triangle ``t``: ``triangles`` (3T, 3) (three rows per
/// triangle), ``points`` (N, 3). Returns T ``(vertices, faces)`` pairs, each
/// the exact hull of the 3N pairwise sums (a triangle plus a convex body),
/// computed in parallel with the GIL released. Used by
/// ``minkowski_sum(..., decomposition="boundary")``.
#[pyfunction]
fn _triangle_sums<'py>(
    py: Python<'py>,
    triangles: &Bound<'py, PyAny>,
    points: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyList>> {
    use rayon::prelude::*;
    let tri = convert::points(triangles, "triangles")?;
    let pts = convert::points(points, "points")?;
    let tri = convert::rows(&tri, "triangles")?;
    let pts = convert::rows(&pts, "points")?;
    if tri.len() % 3 != 0 {
        return Err(value_error(format!(
            "triangles: {} rows, not three per triangle",
            tri.len()
        )));
    }
    let hulls = py.detach(|| {
        tri.par_chunks(3)
            .map(|t| {
                let sums: Vec<[f64; 3]> = t
                    .iter()
                    .flat_map(|a| {
                        pts.iter()
                            .map(move |b| [a[0] + b[0], a[1] + b[1], a[2] + b[2]])
                    })
                    .collect();
                Polytope::from_points(&sums).map(|p| p.to_mesh())
            })
            .collect::<Vec<_>>()
    });
    let out = PyList::empty(py);
    for (k, h) in hulls.into_iter().enumerate() {
        let mesh = h.map_err(|e| err_for(&format!("triangle {k}"), e))?;
        out.append(convert::mesh_tuple(py, mesh, false)?)?;
    }
    Ok(out)
}

/// The bodies of a mesh file, as written, without hulls or checks: a list
/// of ``(name, vertices, faces)`` with vertices (N, 3) ``float64`` and faces
/// (M, 3) ``int64`` (polygons fan-triangulated). An OBJ file gives one body
/// per object (groups of one closed mesh are one body); other formats one
/// body named after the file. Used for non-convex bodies given by path
/// (``minkowski_sum``, ``contact``, ... take them); ``load`` is the convex
/// reader.
///
/// Raises ``FileNotFoundError`` / ``OSError`` when the file cannot be read
/// and ``ValueError`` when it does not parse.
///
/// >>> import dymsum, tempfile, os
/// >>> path = os.path.join(tempfile.mkdtemp(), "two.obj")
/// >>> _ = open(path, "w").write("o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
/// ...                           "o b\nv 5 0 0\nv 6 0 0\nv 5 1 0\nv 5 0 1\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n")
/// >>> [(name, v.shape, f.shape) for name, v, f in dymsum.read_mesh_bodies(path)]
/// [('a', (4, 3), (4, 3)), ('b', (4, 3), (4, 3))]
#[pyfunction]
fn read_mesh_bodies<'py>(
    py: Python<'py>,
    path: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyList>> {
    let spec = path_string(path)?;
    let p = std::path::Path::new(&spec);
    let read = py.detach(
        || -> Result<Vec<(String, dymsum::PolygonMesh)>, FormatError> {
            let is_obj = dymsum_io::formats::Format::from_path(p).ok()
                == Some(dymsum_io::formats::Format::Obj);
            if is_obj {
                dymsum_io::formats::read_obj_objects(p)
            } else {
                let name = p
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default();
                Ok(vec![(name, dymsum_io::formats::read_mesh(p)?)])
            }
        },
    );
    let bodies = read.map_err(|e| {
        let msg = format!("file {spec}: {e}");
        match &e {
            FormatError::Io { source, .. } => io_error(source.kind(), msg),
            _ => value_error(msg),
        }
    })?;
    let out = PyList::empty(py);
    for (name, mesh) in bodies {
        let tri = mesh.triangulated();
        let vertices = convert::vertices_array(py, tri.vertices)?;
        let faces = convert::triangles_array(py, &tri.faces)?;
        out.append((name, vertices, faces))?;
    }
    Ok(out)
}

/// Writes a mesh to ``path`` in the format its extension names (``.off``,
/// ``.obj``, ``.ply`` ASCII, ``.stl`` binary), atomically.
///
/// ``save(path, vertices, faces)`` with vertices (N, 3) and faces an (M, k)
/// integer array or a list of index lists; or ``save(path, shape)`` with a
/// ``Polytope`` (written with its merged polygon faces), a ``(vertices,
/// faces)`` pair or an object with ``.vertices`` and ``.faces``. The mesh is
/// written as given (not checked for convexity). Raises ``ValueError`` for
/// an unknown extension or an invalid mesh (index out of range, NaN), and
/// ``OSError`` when the file cannot be written.
///
/// >>> import numpy as np, dymsum, tempfile, os
/// >>> v, f = dymsum.minkowski_sum(dymsum.load("cube"), dymsum.load("cube"))
/// >>> path = os.path.join(tempfile.mkdtemp(), "sum.off")
/// >>> dymsum.save(path, v, f)
/// >>> dymsum.load(path).vertices.shape
/// (8, 3)
#[pyfunction]
#[pyo3(signature = (path, vertices, faces = None))]
fn save(
    py: Python<'_>,
    path: &Bound<'_, PyAny>,
    vertices: &Bound<'_, PyAny>,
    faces: Option<&Bound<'_, PyAny>>,
) -> PyResult<()> {
    let path = path_string(path)?;
    let mesh = match faces.filter(|f| !f.is_none()) {
        Some(f) => convert::mesh_from_parts(vertices, f, "mesh")?,
        None => {
            if let Ok(p) = vertices.cast::<PyPolytope>() {
                p.get().inner.to_mesh()
            } else if let Some((v, f)) = convert::mesh_parts(vertices)? {
                convert::mesh_from_parts(&v, &f, "mesh")?
            } else {
                return Err(value_error(
                    "save: faces are missing (give save(path, vertices, faces) or save(path, shape))",
                ));
            }
        }
    };
    py.detach(|| dymsum_io::formats::write_mesh(std::path::Path::new(&path), &mesh))
        .map_err(|e| match &e {
            FormatError::Io { source, .. } => io_error(source.kind(), e.to_string()),
            _ => value_error(e.to_string()),
        })
}

/// The names of the built-in models and model families (``"cube"``,
/// ``"tcube:K"``, ``"sphere:N"``, ...), for ``dymsum.load``.
#[pyfunction]
fn models() -> Vec<&'static str> {
    dymsum_io::models::catalogue()
        .iter()
        .map(|m| m.name)
        .collect()
}

/// The extension module; the `dymsum` package re-exports it.
#[pymodule]
fn _dymsum(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyPolytope>()?;
    m.add_class::<PyDynamicSum>()?;
    m.add_class::<PyContact>()?;
    m.add_class::<PyContactTracker>()?;
    m.add_class::<PyContacts>()?;
    m.add_class::<PySlab>()?;
    m.add_function(wrap_pyfunction!(minkowski_sum, m)?)?;
    m.add_function(wrap_pyfunction!(contact, m)?)?;
    m.add_function(wrap_pyfunction!(contact_many, m)?)?;
    m.add_function(wrap_pyfunction!(collides_many, m)?)?;
    m.add_function(wrap_pyfunction!(cobstacle_slices, m)?)?;
    m.add_function(wrap_pyfunction!(pose, m)?)?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(save, m)?)?;
    m.add_function(wrap_pyfunction!(read_mesh_bodies, m)?)?;
    m.add_function(wrap_pyfunction!(_triangle_sums, m)?)?;
    m.add_function(wrap_pyfunction!(models, m)?)?;
    motion::register(m)?;
    maps::register(m)?;
    solid::register(m)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
