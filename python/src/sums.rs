//! Minkowski sums: `minkowski_sum` (static, posed), `DynamicSum` (kept by
//! DYMSUM while the bodies turn) and the triangle sums of the non-convex
//! boundary method.

use crate::convert;
use crate::convert::parse_method;
use crate::convert::{err_for, value_error, Shape};
use dymsum::polytope::MeshPolicy;
use dymsum::sum::minkowski_sum_posed;
use dymsum::{DynamicSum, Polytope, Pose, UpdateReport};
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

pub(crate) fn shape_of(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Shape> {
    convert::shape(obj, what, MeshPolicy::default())
}

/// The shapes `a`, `b` and their poses, read in the order of the messages
/// a user sees first: `pose_a`, `pose_b`, then the shapes.
pub(crate) fn two_bodies(
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
pub(crate) fn minkowski_sum<'py>(
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

pub(crate) fn report_dict<'py>(
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

/// ``t ⊕ P`` for every triangle ``t``: ``triangles`` (3T, 3) (three rows per
/// triangle), ``points`` (N, 3). Returns T ``(vertices, faces)`` pairs, each
/// the exact hull of the 3N pairwise sums (a triangle plus a convex body),
/// computed in parallel with the GIL released. Used by
/// ``minkowski_sum(..., decomposition="boundary")``.
#[pyfunction]
pub(crate) fn _triangle_sums<'py>(
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

/// The indices, in order, of the convex pair sums ``meshes`` (a list of
/// ``(vertices, triangles)``, outward) to keep for their union: every one
/// not certified inside a kept one (`dymsum::sum::contained::uncontained`:
/// exact `orient3d`, the rule Rust's non-convex sums use). The GIL is
/// released while deciding.
#[pyfunction]
pub(crate) fn _uncontained(py: Python<'_>, meshes: &Bound<'_, PyAny>) -> PyResult<Vec<usize>> {
    let mut owned = Vec::new();
    for (k, item) in meshes.try_iter()?.enumerate() {
        let item = item?;
        let what = format!("meshes[{k}]");
        let Some((v, f)) = convert::mesh_parts(&item)? else {
            return Err(value_error(format!("{what}: expected (vertices, faces)")));
        };
        owned.push(convert::mesh_from_parts(&v, &f, &what)?);
    }
    let refs: Vec<&dymsum::PolygonMesh> = owned.iter().collect();
    Ok(py.detach(|| dymsum::sum::contained::uncontained(&refs)))
}

/// Registers this module's classes and functions on the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyDynamicSum>()?;
    m.add_function(wrap_pyfunction!(minkowski_sum, m)?)?;
    m.add_function(wrap_pyfunction!(_triangle_sums, m)?)?;
    m.add_function(wrap_pyfunction!(_uncontained, m)?)?;
    Ok(())
}
