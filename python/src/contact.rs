//! Contact queries: `contact` (depth or distance, exact), `ContactTracker`
//! (frame to frame), and the batches `contact_many` and `collides_many`.

use crate::convert;
use crate::convert::err_for;
use crate::sums::{report_dict, shape_of, two_bodies};
use dymsum::query::{ConvexPair, Proximity, TrackerStrategy};
use dymsum::{ContactTracker, Pose};
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

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
pub(crate) fn contact(
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
    /// instead), ``carried_polytopes`` (penetrations grown from the last
    /// frame's EPA polytope) and ``carried_restarts`` (of those, the ones
    /// that grew a fresh polytope instead).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        stats_dict(py, self.inner.stats())
    }
}

/// A strategy's name in Python.
pub(crate) fn strategy_name(s: TrackerStrategy) -> &'static str {
    match s {
        TrackerStrategy::Auto => "auto",
        TrackerStrategy::Certified => "certified",
        TrackerStrategy::DynamicSum => "sum",
    }
}

/// The dict of a pair's ``QueryStats``.
pub(crate) fn stats_dict<'py>(
    py: Python<'py>,
    s: dymsum::QueryStats,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("queries", s.queries)?;
    d.set_item("exhaustive_decisions", s.exhaustive_decisions)?;
    d.set_item("exhaustive_answers", s.exhaustive_answers)?;
    d.set_item("carried_polytopes", s.carried_polytopes)?;
    d.set_item("carried_restarts", s.carried_restarts)?;
    Ok(d)
}

/// The poses of a batch: both stacks of the same length K, or one of them
/// a single pose standing for all K.
pub(crate) fn batch_poses(
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
pub(crate) fn contact_many(
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
pub(crate) fn collides_many<'py>(
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

/// Registers this module's classes and functions on the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyContact>()?;
    m.add_class::<PyContactTracker>()?;
    m.add_class::<PyContacts>()?;
    m.add_function(wrap_pyfunction!(contact, m)?)?;
    m.add_function(wrap_pyfunction!(contact_many, m)?)?;
    m.add_function(wrap_pyfunction!(collides_many, m)?)?;
    Ok(())
}
