//! Certified motion checks from Python: `ConvexUnion`, `MotionChecker`,
//! `check_motion`, `check_motions` and the `MotionUndecided` error (the
//! Rust `dymsum::query::motion` module).

use crate::convert::{self, err_for, value_error, Budget, Tolerance};
use crate::polytope::PyPolytope;
use dymsum::body::BodyOptions;
use dymsum::polytope::MeshPolicy;
use dymsum::query::{
    Body, ConvexUnion, MeshReport, MotionCheck, MotionError, Validator, DEFAULT_BUDGET,
    MIN_TOLERANCE,
};
use dymsum::Pose;
use dymsum_io::body::{body_error_text, load_body, LoadOptions};
use numpy::{IntoPyArray, PyArray1};
use pyo3::create_exception;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

create_exception!(
    dymsum,
    MotionUndecided,
    PyRuntimeError,
    "A motion that grazes an obstacle within rounding: neither free nor colliding could be \
     certified (``t_safe``: the last time certified free; ``t``: the end of the undecided \
     interval; ``index``: the motion's index in a batch, else ``None``). A planner should treat \
     the motion as invalid after ``t_safe``."
);

/// A union of convex pieces: a non-convex body given by a convex
/// decomposition (the pieces may overlap).
///
/// ``ConvexUnion(pieces)`` where ``pieces`` is a non-empty sequence of
/// shapes (each an (N, 3) point cloud, a ``(vertices, faces)`` pair, a
/// trimesh, a ``Polytope``, or a model name or mesh path). The motion
/// functions take a ``ConvexUnion`` wherever they take a body or an
/// obstacle, and a single shape as a union of one piece.
///
/// >>> import numpy as np, dymsum
/// >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
/// >>> ell = dymsum.ConvexUnion([cube, cube + [1, 0, 0], cube + [0, 1, 0]])
/// >>> len(ell), ell.pieces[1].vertices.min(axis=0).tolist()
/// (3, [1.0, 0.0, 0.0])
#[pyclass(module = "dymsum", name = "ConvexUnion", frozen)]
pub struct PyConvexUnion {
    pub(crate) inner: ConvexUnion,
    pieces: Py<PyList>,
}

#[pymethods]
impl PyConvexUnion {
    #[new]
    fn new(py: Python<'_>, pieces: &Bound<'_, PyAny>) -> PyResult<Self> {
        if is_single_shape(pieces)? {
            return Err(value_error(
                "ConvexUnion: pieces must be a sequence of shapes (a list of point arrays, \
                 Polytopes, ...), got a single shape; wrap it in a list",
            ));
        }
        let items = pieces.try_iter().map_err(|_| {
            value_error(format!(
                "ConvexUnion: pieces must be a sequence of shapes, got {}",
                type_name(pieces)
            ))
        })?;
        let mut polys = Vec::new();
        let mut objects = Vec::new();
        for (i, item) in items.enumerate() {
            let s = convert::shape(&item?, &format!("pieces[{i}]"), MeshPolicy::default())?;
            polys.push(s.polytope.clone());
            objects.push(Py::new(py, PyPolytope::from_shape(py, s)?)?);
        }
        let inner = ConvexUnion::new(polys)
            .ok_or_else(|| value_error("ConvexUnion: pieces must not be empty"))?;
        Ok(PyConvexUnion {
            inner,
            pieces: PyList::new(py, objects)?.unbind(),
        })
    }

    /// The pieces, a list of ``Polytope`` (a copy of the list).
    #[getter]
    fn pieces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let items: Vec<Bound<'py, PyAny>> = self.pieces.bind(py).iter().collect();
        PyList::new(py, items)
    }

    fn __len__(&self) -> usize {
        self.inner.pieces().len()
    }

    /// Pickles as ``ConvexUnion(pieces)`` (each piece a ``Polytope``).
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyTuple>> {
        let args = pyo3::types::PyTuple::new(py, [self.pieces(py)?])?;
        pyo3::types::PyTuple::new(
            py,
            [py.get_type::<PyConvexUnion>().into_any(), args.into_any()],
        )
    }

    fn __repr__(&self) -> String {
        format!("ConvexUnion({} pieces)", self.inner.pieces().len())
    }
}

/// `obj`'s type name for error messages (`None` for `None`).
fn type_name(obj: &Bound<'_, PyAny>) -> String {
    if obj.is_none() {
        return "None".into();
    }
    obj.get_type()
        .name()
        .map_or_else(|_| "an object".into(), |n| n.to_string())
}

/// Whether `obj` is one shape rather than a sequence of shapes: a
/// `Polytope`, a `ConvexUnion`, a model name or path, a NumPy array (a
/// point cloud), a `(vertices, faces)` pair of arrays, or an object with
/// `.vertices` and `.faces`.
fn is_single_shape(obj: &Bound<'_, PyAny>) -> PyResult<bool> {
    if obj.cast::<PyPolytope>().is_ok()
        || obj.cast::<PyConvexUnion>().is_ok()
        || obj.is_instance_of::<pyo3::types::PyString>()
        || obj.hasattr("__fspath__")?
        || (obj.hasattr("vertices")? && obj.hasattr("faces")?)
        || obj.hasattr("__array_interface__")?
    {
        return Ok(true);
    }
    // A (vertices, faces) pair: two items, the first a 2-D array and the
    // second integer indices (two point clouds are two shapes).
    if let Some((_, faces)) = convert::mesh_parts(obj)? {
        return is_index_array(&faces);
    }
    Ok(false)
}

/// Whether `obj` holds face indices: an integer array, or a (ragged) list
/// of lists of integers.
fn is_index_array(obj: &Bound<'_, PyAny>) -> PyResult<bool> {
    let np = obj.py().import("numpy")?;
    if let Ok(arr) = np.call_method1("asarray", (obj,)) {
        let kind: String = arr.getattr("dtype")?.getattr("kind")?.extract()?;
        // An empty array is no shape: empty faces (refused as such).
        let size: usize = arr.getattr("size")?.extract()?;
        if kind == "i" || kind == "u" || size == 0 {
            return Ok(true);
        }
        if kind != "O" {
            return Ok(false);
        }
    }
    // Ragged polygons: the first item's first index is an integer.
    let first = obj.get_item(0).and_then(|f| f.get_item(0));
    Ok(first.is_ok_and(|i| i.is_instance_of::<pyo3::types::PyInt>()))
}

/// A body or obstacle argument: a `ConvexUnion`; a mesh with faces (a
/// `(vertices, faces)` pair or an object with `.vertices` and `.faces`)
/// taken by the core's ladder ([`Body::from_mesh_with`]: cleaned exactly;
/// one exactly convex solid, or a solid of exactly convex shells, on the
/// convex path; anything else as triangles of any topology); a mesh path or
/// model name by the command line's loader ([`dymsum_io::body::load_body`]:
/// the file read once, a mesh file by the same ladder, an OBJ file of
/// several objects as convex pieces, `a+b` as pieces, a model name or a
/// point cloud as its polytope); or another shape (a `Polytope`, a point
/// array: convex).
fn body_of(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Body> {
    let mut built = build_bodies(obj.py(), vec![body_arg(obj, what)?])?;
    Ok(built.pop().expect("one body asked, one built"))
}

/// A body argument as read from Python (the GIL held): built already, or a
/// mesh's arrays to convert and build ([`build_bodies`]: converted with
/// the GIL held, built with it released).
#[allow(clippy::large_enum_variant)] // a handful per call, moved once
enum BodyArg<'py> {
    Built(Body),
    Mesh {
        vertices: Bound<'py, PyAny>,
        faces: Bound<'py, PyAny>,
        what: String,
    },
}

/// Reads a body argument ([`body_of`]'s forms) without building a mesh.
fn body_arg<'py>(obj: &Bound<'py, PyAny>, what: &str) -> PyResult<BodyArg<'py>> {
    let py = obj.py();
    convert::not_none(obj, what, BODY_FORMS)?;
    if let Ok(u) = obj.cast::<PyConvexUnion>() {
        return Ok(BodyArg::Built(Body::Convex(u.get().inner.clone())));
    }
    if obj.cast::<PyPolytope>().is_err() {
        if let Some((vertices, faces)) = convert::mesh_parts(obj)? {
            return Ok(BodyArg::Mesh {
                vertices,
                faces,
                what: what.to_string(),
            });
        }
        if obj.is_instance_of::<pyo3::types::PyString>() || obj.hasattr("__fspath__")? {
            let spec = convert::path_string(obj)?;
            return py
                .detach(|| load_body(&spec, &LoadOptions::default()))
                .map(|loaded| BodyArg::Built(loaded.body))
                .map_err(|e| convert::load_error(e, Some(what)));
        }
    }
    Ok(BodyArg::Built(Body::Convex(ConvexUnion::from(
        convert::shape(obj, what, MeshPolicy::default())?.polytope,
    ))))
}

/// The bodies of `args`, in order, the meshes among them converted from
/// their arrays (the GIL held) and built by the core's ladder (the GIL
/// released) one at a time; the first error in `args`' order is raised.
///
/// One at a time, although a body and its obstacles of a million
/// triangles each take seconds apiece: each build parallelises its own
/// large steps (the soup's edge chain), while two cleanings side by side
/// peak at twice one's temporaries, which the worker thread's heap then
/// keeps as holes that the trees built next cannot use; and a mesh is
/// converted just before its build and dropped after it. On soups of
/// 10⁴–10⁶ triangles as body and obstacle (`bench_builds.py --memory`),
/// side by side added 1.32–1.38× python-fcl's peak memory; one at a time,
/// with the checker's trees one after the other (`SceneChecker::new`),
/// 0.78–0.83×, for 0.72–0.76× fcl's build time instead of 0.45–0.56×
/// (docs/BENCHMARKS.md, "Builds one at a time").
fn build_bodies(py: Python<'_>, args: Vec<BodyArg<'_>>) -> PyResult<Vec<Body>> {
    args.into_iter()
        .map(|arg| match arg {
            BodyArg::Built(body) => Ok(body),
            BodyArg::Mesh {
                vertices,
                faces,
                what,
            } => {
                let mesh = convert::solid_from_parts(&vertices, &faces, &what)?;
                py.detach(|| Body::from_mesh_with(&mesh, &BodyOptions::default()))
                    .map(|(body, _)| body)
                    .map_err(|e| err_for(&what, body_error_text(&e, mesh.faces.len())))
            }
        })
        .collect()
}

/// What a body argument accepts (error messages).
const BODY_FORMS: &str = "a ConvexUnion or a shape (an (N, 3) point array, a (vertices, faces) \
     pair, an object with .vertices and .faces, a Polytope, or a model name or mesh path)";

/// The obstacles argument: a sequence of bodies, or one.
pub(crate) fn obstacles_of(obj: &Bound<'_, PyAny>) -> PyResult<Vec<Body>> {
    build_bodies(obj.py(), obstacle_args(obj)?)
}

/// Reads an obstacles argument ([`obstacles_of`]) without building its
/// meshes.
fn obstacle_args<'py>(obj: &Bound<'py, PyAny>) -> PyResult<Vec<BodyArg<'py>>> {
    convert::not_none(
        obj,
        "obstacles",
        "a sequence of ConvexUnions or shapes, or one (give [] for none)",
    )?;
    if let Some(placed) = placed_obstacle(obj, "obstacles")? {
        return Ok(vec![BodyArg::Built(placed)]);
    }
    if is_single_shape(obj)? {
        return Ok(vec![body_arg(obj, "obstacles")?]);
    }
    let mut out = Vec::new();
    let items = obj.try_iter().map_err(|_| {
        err_for(
            "obstacles",
            format!(
                "expected a sequence of ConvexUnions or shapes, or one; got {}",
                type_name(obj)
            ),
        )
    })?;
    for (i, item) in items.enumerate() {
        let (item, what) = (item?, format!("obstacles[{i}]"));
        match placed_obstacle(&item, &what)? {
            Some(placed) => out.push(BodyArg::Built(placed)),
            None => out.push(body_arg(&item, &what)?),
        }
    }
    Ok(out)
}

/// An obstacle given in its own frame with its pose: a `(body, pose)` pair
/// whose second item is a pose (a float 4×4 rigid transform, as
/// `dymsum.pose` makes, or a scipy `Rotation`), placed once
/// ([`Body::placed`]); `None` when `obj` is no such pair (a `(vertices,
/// faces)` pair has integer faces).
fn placed_obstacle(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Option<Body>> {
    let is_pair = (obj.is_instance_of::<pyo3::types::PyTuple>()
        || obj.is_instance_of::<pyo3::types::PyList>())
        && obj.len().is_ok_and(|n| n == 2);
    if !is_pair {
        return Ok(None);
    }
    let second = obj.get_item(1)?;
    if !is_pose_like(&second)? {
        return Ok(None);
    }
    let body = body_of(&obj.get_item(0)?, &format!("{what}[0]"))?;
    let pose = convert::pose(Some(&second), &format!("{what}[1]"))?;
    body.placed(pose)
        .map(Some)
        .map_err(|e| err_for(&format!("{what}[1]"), e))
}

/// Whether `obj` is a pose rather than faces: a scipy `Rotation`, or an
/// array of floats of shape (4, 4).
fn is_pose_like(obj: &Bound<'_, PyAny>) -> PyResult<bool> {
    if obj.hasattr("as_quat")? {
        return Ok(true);
    }
    let np = obj.py().import("numpy")?;
    let Ok(arr) = np.call_method1("asarray", (obj,)) else {
        return Ok(false);
    };
    let kind: String = arr.getattr("dtype")?.getattr("kind")?.extract()?;
    let shape: Vec<usize> = arr.getattr("shape")?.extract()?;
    Ok(kind == "f" && shape == [4, 4])
}

/// The validator of `body` against `obstacles`, with its budget.
fn validator(
    py: Python<'_>,
    body: &Bound<'_, PyAny>,
    obstacles: &Bound<'_, PyAny>,
    budget: u64,
    what: &str,
) -> PyResult<Validator> {
    let mut args = vec![body_arg(body, "body")?];
    args.extend(obstacle_args(obstacles)?);
    let mut obstacles = build_bodies(py, args)?;
    let body = obstacles.remove(0);
    Ok(py
        .detach(|| Validator::new(&body, &obstacles))
        .map_err(|e| err_for(what, e))?
        .with_budget(budget))
}

/// A mesh report as a dict.
fn report_dict<'py>(py: Python<'py>, r: MeshReport) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("triangles", r.triangles)?;
    d.set_item("vertices", r.vertices)?;
    d.set_item("merged_vertices", r.merged_vertices)?;
    d.set_item("dropped_zero_area", r.dropped_zero_area)?;
    d.set_item("dropped_duplicates", r.dropped_duplicates)?;
    d.set_item("dropped_back_to_back", r.dropped_back_to_back)?;
    d.set_item("flipped", r.flipped)?;
    d.set_item("inverted", r.inverted)?;
    d.set_item("set_aside", r.set_aside)?;
    d.set_item("split_edges", r.split_edges)?;
    d.set_item("solids", r.solids)?;
    d.set_item("surfaces", r.surfaces)?;
    Ok(d)
}

pub(crate) fn check_tolerance(tolerance: f64) -> PyResult<()> {
    if (MIN_TOLERANCE..1.0).contains(&tolerance) {
        Ok(())
    } else {
        Err(value_error(format!(
            "tolerance must be a finite number in [{MIN_TOLERANCE:e}, 1) (the smallest the \
             search can bracket: it halves intervals down to 2^-48 of the motion), got {tolerance}"
        )))
    }
}

/// The work budget: `None` is the default, else at least one interval.
fn checked_budget(budget: Option<Budget>) -> PyResult<u64> {
    match budget.map(|b| b.0) {
        None => Ok(DEFAULT_BUDGET),
        Some(0) => Err(value_error(
            "budget must be at least 1 (intervals per check; default 4096)",
        )),
        Some(b) => Ok(b),
    }
}

/// A motion error as a Python exception: `MotionUndecided` (with
/// `t_safe`, `t`, `index`) for a grazing motion, `ValueError` otherwise.
pub(crate) fn motion_error(
    py: Python<'_>,
    what: &str,
    e: MotionError,
    index: Option<usize>,
) -> PyErr {
    match e {
        MotionError::Undecided { t_safe, t } => undecided(py, what, &e, t_safe, Some(t), index),
        MotionError::BudgetExhausted { t_safe, .. } => undecided(py, what, &e, t_safe, None, index),
        other => err_for(what, other),
    }
}

/// `MotionUndecided` with its attributes: `t_safe` (every `t ≤ t_safe`
/// certified free), `t` (the end of a grazing interval; `None` when the
/// budget ran out), `index`.
fn undecided(
    py: Python<'_>,
    what: &str,
    e: &MotionError,
    t_safe: f64,
    t: Option<f64>,
    index: Option<usize>,
) -> PyErr {
    let at = index.map_or(String::new(), |k| format!(" (motion {k})"));
    let err = MotionUndecided::new_err(format!("{what}{at}: {e}"));
    let value = err.value(py);
    let _ = value.setattr("t_safe", t_safe);
    let _ = value.setattr("t", t);
    let _ = value.setattr("index", index);
    let _ = value.setattr("budget_exhausted", t.is_none());
    err
}

/// The answer of a motion check.
///
/// * ``free``: no contact at any ``t`` in ``[0, 1]``, certified;
/// * ``t_safe``: the last time certified free (``1.0`` when free, ``None``
///   when the body collides at ``t = 0``): every ``t ≤ t_safe`` is free;
/// * ``t_contact``: a time at which the body touches or overlaps an
///   obstacle (the exact query says so), ``None`` when free;
///   ``t_contact - t_safe`` is at most the tolerance.
///
/// ``bool(check)`` is ``free``.
#[pyclass(module = "dymsum", name = "MotionCheck", frozen)]
pub struct PyMotionCheck {
    free: bool,
    t_safe: Option<f64>,
    t_contact: Option<f64>,
}

impl PyMotionCheck {
    pub(crate) fn from_check(c: MotionCheck) -> Self {
        match c {
            MotionCheck::Free => PyMotionCheck {
                free: true,
                t_safe: Some(1.0),
                t_contact: None,
            },
            MotionCheck::Collides { t_safe, t_contact } => PyMotionCheck {
                free: false,
                t_safe,
                t_contact: Some(t_contact),
            },
        }
    }
}

#[pymethods]
impl PyMotionCheck {
    /// No contact anywhere on the motion (certified).
    #[getter]
    fn free(&self) -> bool {
        self.free
    }
    /// The last time certified free (``1.0`` when free; ``None`` when the
    /// body collides at the start).
    #[getter]
    fn t_safe(&self) -> Option<f64> {
        self.t_safe
    }
    /// A time of contact (``None`` when free).
    #[getter]
    fn t_contact(&self) -> Option<f64> {
        self.t_contact
    }
    fn __bool__(&self) -> bool {
        self.free
    }
    fn __repr__(&self) -> String {
        let opt = |v: Option<f64>| v.map_or("None".to_string(), |x| format!("{x:?}"));
        format!(
            "MotionCheck(free={}, t_safe={}, t_contact={})",
            if self.free { "True" } else { "False" },
            opt(self.t_safe),
            opt(self.t_contact)
        )
    }
}

/// The answers of a batch of motion checks as arrays (``check_motions``):
/// ``free`` (K,) ``bool``; ``t_safe`` and ``t_contact`` (K,) ``float64``,
/// with ``t_safe`` ``1.0`` for a free motion and ``nan`` for one colliding
/// at its start, and ``t_contact`` ``nan`` for a free motion. Row ``k``
/// holds what ``check_motion`` returns for motion ``k``.
#[pyclass(module = "dymsum", name = "MotionChecks", frozen)]
pub struct PyMotionChecks {
    free: Py<PyArray1<bool>>,
    t_safe: Py<PyArray1<f64>>,
    t_contact: Py<PyArray1<f64>>,
    len: usize,
}

#[pymethods]
impl PyMotionChecks {
    /// (K,) ``bool``: the motion is certified free.
    #[getter]
    fn free<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        self.free.bind(py).clone()
    }
    /// (K,) last times certified free (``nan``: colliding at the start).
    #[getter]
    fn t_safe<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.t_safe.bind(py).clone()
    }
    /// (K,) times of contact (``nan``: free).
    #[getter]
    fn t_contact<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.t_contact.bind(py).clone()
    }
    fn __len__(&self) -> usize {
        self.len
    }
    fn __repr__(&self) -> String {
        format!("MotionChecks({} motions)", self.len)
    }
}

fn checks_arrays(py: Python<'_>, answers: &[MotionCheck]) -> PyMotionChecks {
    let k = answers.len();
    let (mut free, mut t_safe, mut t_contact) = (
        Vec::with_capacity(k),
        Vec::with_capacity(k),
        Vec::with_capacity(k),
    );
    for &a in answers {
        let c = PyMotionCheck::from_check(a);
        free.push(c.free);
        t_safe.push(c.t_safe.unwrap_or(f64::NAN));
        t_contact.push(c.t_contact.unwrap_or(f64::NAN));
    }
    PyMotionChecks {
        free: free.into_pyarray(py).unbind(),
        t_safe: t_safe.into_pyarray(py).unbind(),
        t_contact: t_contact.into_pyarray(py).unbind(),
        len: k,
    }
}

/// The motions of a batch: `poses0[k]` to `poses1[k]` (one pose stands
/// for all).
fn motion_pairs(
    poses0: Option<&Bound<'_, PyAny>>,
    poses1: Option<&Bound<'_, PyAny>>,
) -> PyResult<Vec<(Pose, Pose)>> {
    let a = convert::pose_stack(poses0, "poses0")?;
    let b = convert::pose_stack(poses1, "poses1")?;
    let k = match (a.len(), b.len()) {
        (m, n) if m == n => m,
        (1, n) => n,
        (m, 1) => m,
        (m, n) => {
            return Err(value_error(format!(
                "poses0 and poses1: {m} and {n} poses; give the same number, or one pose for all"
            )))
        }
    };
    let at = |v: &[Pose], i: usize| if v.len() == 1 { v[0] } else { v[i] };
    Ok((0..k).map(|i| (at(&a, i), at(&b, i))).collect())
}

/// Checks many motions, reporting the first failure with its index.
fn check_batch(
    py: Python<'_>,
    checker: &Validator,
    motions: &[(Pose, Pose)],
    tolerance: f64,
    what: &str,
) -> PyResult<PyMotionChecks> {
    let answers = py.detach(|| checker.check_many(motions, tolerance));
    match answers {
        Ok(a) => Ok(checks_arrays(py, &a)),
        Err(_) => {
            // Find the failing motion (in order) to name it.
            for (k, &(a, b)) in motions.iter().enumerate() {
                if let Err(e) = py.detach(|| checker.check(a, b, tolerance)) {
                    return Err(motion_error(py, what, e, Some(k)));
                }
            }
            Err(value_error(format!("{what}: a check failed")))
        }
    }
}

/// A body and its obstacles prepared for many certified motion checks (a
/// planner's motion validator).
///
/// ``MotionChecker(body, obstacles)``: ``body`` a ``ConvexUnion`` or one
/// shape, in its own frame; ``obstacles`` a sequence of ``ConvexUnion``s or
/// shapes (or one), placed in the world frame. A triangle mesh of any
/// topology (a ``(vertices, faces)`` pair, a trimesh object or a mesh file:
/// open, double-sided, non-manifold, unwelded) is taken as it comes,
/// cleaned exactly: each connected component a solid (closed and
/// consistently oriented: contact includes lying inside it) or a surface
/// (contact means touching a triangle); ``info`` says which path was taken
/// and what the cleaning did, ``collides_many`` and ``distance_at`` check
/// many poses and give the clearance. ``check(pose0, pose1)``
/// checks the straight motion between two poses: translation linear,
/// rotation by slerp along the shorter arc (exactly OMPL's SE(2) and SE(3)
/// interpolation). The arc is decided from the rotations as given: the
/// exact sign of the dot product of their quaternions (a scipy
/// ``Rotation`` or a quaternion as passed; a matrix converted to a
/// quaternion), the second negated when it is negative, kept at exactly
/// zero (docs/LIMITS.md). ``budget``: the most intervals one check
/// examines (default 4096) before it raises ``MotionUndecided`` with the
/// certified ``t_safe``: a deterministic cap on the work of a grazing
/// motion. The GIL is released while checking.
///
/// A bar turning about its centre past a small block: both end poses and
/// the halfway pose are free, the motion is not.
///
/// >>> import numpy as np, dymsum
/// >>> from scipy.spatial.transform import Rotation
/// >>> def cuboid(lo, hi):
/// ...     return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])], float)
/// >>> bar = cuboid([-2, -0.05, -0.05], [2, 0.05, 0.05])
/// >>> block = cuboid([1.7, 0.6, -1], [1.9, 0.8, 1])
/// >>> turn = lambda deg: dymsum.pose(Rotation.from_euler("z", deg, degrees=True))
/// >>> checker = dymsum.MotionChecker(bar, [block])
/// >>> [checker.collides_at(turn(d)) for d in (0, 45, 90)]
/// [False, False, False]
/// >>> c = checker.check(turn(0), turn(90), tolerance=1e-6)
/// >>> c.free, c.t_contact - c.t_safe <= 1e-6, checker.collides_at(turn(90 * c.t_contact))
/// (False, True, True)
/// >>> checker.check(turn(-90), turn(-1)).free
/// True
#[pyclass(module = "dymsum", name = "MotionChecker", frozen)]
pub struct PyMotionChecker {
    inner: Validator,
}

#[pymethods]
impl PyMotionChecker {
    #[new]
    #[pyo3(signature = (body, obstacles, budget = None))]
    fn new(
        py: Python<'_>,
        body: &Bound<'_, PyAny>,
        obstacles: &Bound<'_, PyAny>,
        budget: Option<Budget>,
    ) -> PyResult<Self> {
        let budget = checked_budget(budget)?;
        let inner = validator(py, body, obstacles, budget, "MotionChecker")?;
        Ok(PyMotionChecker { inner })
    }

    /// How the bodies were taken: ``{"path": "convex"}`` when every body is
    /// convex pieces, else ``{"path": "triangles", "body": {...},
    /// "obstacles": {...}}`` with what the exact cleaning changed and found
    /// (``triangles``, ``vertices``, ``merged_vertices``,
    /// ``dropped_zero_area``, ``dropped_duplicates``,
    /// ``dropped_back_to_back``, ``flipped``, ``solids``, ``surfaces``).
    #[getter]
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        match &self.inner {
            Validator::Convex(_) => d.set_item("path", "convex")?,
            Validator::Mesh(c) => {
                d.set_item("path", "triangles")?;
                d.set_item("body", report_dict(py, c.body().report())?)?;
                d.set_item("obstacles", report_dict(py, c.scene().report())?)?;
            }
        }
        Ok(d)
    }

    /// The clearance of the body at ``pose`` from the obstacles (for
    /// OMPL's clearance objectives): ``0.0`` when it touches or overlaps
    /// one; else the exact distance on the convex path, or, for triangles,
    /// the least triangle–triangle distance rounded down (a certified
    /// lower bound within rounding of it). GIL released.
    #[pyo3(signature = (pose = None))]
    fn distance_at(&self, py: Python<'_>, pose: Option<&Bound<'_, PyAny>>) -> PyResult<f64> {
        let p = convert::pose(pose, "pose")?;
        let inner = &self.inner;
        py.detach(|| inner.distance_at(p))
            .map_err(|e| err_for("MotionChecker.distance_at", e))
    }

    /// Whether the body collides at each of K poses ((K, 4, 4) homogeneous
    /// rigid transforms, or any pose stack ``contact_many`` takes): a (K,)
    /// ``bool`` array, each exactly ``collides_at``. Checked in parallel
    /// with the GIL released.
    fn collides_many<'py>(
        &self,
        py: Python<'py>,
        poses: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<bool>>> {
        let poses = convert::pose_stack(Some(poses), "poses")?;
        let inner = &self.inner;
        let hits = py
            .detach(|| inner.collides_many(&poses))
            .map_err(|e| err_for("MotionChecker.collides_many", e))?;
        Ok(hits.into_pyarray(py))
    }

    /// The most intervals one check examines (``budget=`` at construction).
    #[getter]
    fn budget(&self) -> u64 {
        self.inner.budget()
    }

    /// The intervals examined by all checks so far (the work the budget
    /// counts).
    #[getter]
    fn steps(&self) -> u64 {
        self.inner.steps()
    }

    /// How the containment tests of all queries so far decided their
    /// points (triangles only; ``None`` on the convex path): a dict with
    /// ``by_grid``, ``by_segment`` (from the point decided before),
    /// ``by_ray``, ``segment_fallbacks`` (segments that met an edge or a
    /// plane and gave way to a ray) and ``plane_cull_fallbacks`` (listed
    /// triangles a float bound could not place against the corners' box,
    /// placed by exact signs; every method is exact), ``bodies_by_grid``
    /// (state checks one body's grid decided whole: the other body lay in
    /// its cells, all classified alike) and ``bodies_by_region`` (state
    /// checks one point decided: no triangle of one body came near the
    /// other's box).
    #[getter]
    fn containment_stats<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Validator::Mesh(c) = &self.inner else {
            return Ok(None);
        };
        let s = c.containment_stats();
        let d = PyDict::new(py);
        d.set_item("by_grid", s.by_grid)?;
        d.set_item("by_segment", s.by_segment)?;
        d.set_item("by_ray", s.by_ray)?;
        d.set_item("segment_fallbacks", s.segment_fallbacks)?;
        d.set_item("plane_cull_fallbacks", s.plane_cull_fallbacks)?;
        d.set_item("bodies_by_grid", s.bodies_by_grid)?;
        d.set_item("bodies_by_region", s.bodies_by_region)?;
        Ok(Some(d))
    }

    /// A cheap refutation before a certificate: the ``t`` of the first
    /// pose at ``k / segments`` (``0 < k < segments``) of the motion from
    /// ``pose0`` to ``pose1`` (the poses ``check`` checks), visited in
    /// bisection order and at most ``most`` of them, at which the body
    /// collides (exact), or ``None`` when none does (which proves nothing:
    /// ``check`` decides). GIL released.
    #[pyo3(
        signature = (pose0, pose1, segments, most = 7),
        text_signature = "($self, pose0, pose1, segments, most=7)"
    )]
    fn sampled_contact(
        &self,
        py: Python<'_>,
        pose0: Option<&Bound<'_, PyAny>>,
        pose1: Option<&Bound<'_, PyAny>>,
        segments: usize,
        most: usize,
    ) -> PyResult<Option<f64>> {
        let p0 = convert::pose(pose0, "pose0")?;
        let p1 = convert::pose(pose1, "pose1")?;
        let inner = &self.inner;
        py.detach(|| inner.sampled_contact(p0, p1, segments, most))
            .map_err(|e| err_for("MotionChecker.sampled_contact", e))
    }

    /// Checks the motion from ``pose0`` to ``pose1`` (4×4 homogeneous rigid
    /// transforms, or rotations about the origin), with the bracket
    /// ``t_contact - t_safe`` no wider than ``tolerance`` (in ``t``): a
    /// ``MotionCheck``. Raises ``MotionUndecided`` for a motion grazing an
    /// obstacle within rounding or one that used up the budget.
    #[pyo3(
        signature = (pose0, pose1, tolerance = Tolerance(1e-6)),
        text_signature = "($self, pose0, pose1, tolerance=1e-6)"
    )]
    fn check(
        &self,
        py: Python<'_>,
        pose0: Option<&Bound<'_, PyAny>>,
        pose1: Option<&Bound<'_, PyAny>>,
        tolerance: Tolerance,
    ) -> PyResult<PyMotionCheck> {
        let tolerance = tolerance.0;
        check_tolerance(tolerance)?;
        let p0 = convert::pose(pose0, "pose0")?;
        let p1 = convert::pose(pose1, "pose1")?;
        let inner = &self.inner;
        py.detach(|| inner.check(p0, p1, tolerance))
            .map(PyMotionCheck::from_check)
            .map_err(|e| motion_error(py, "MotionChecker.check", e, None))
    }

    /// ``check`` for many motions: ``poses0`` and ``poses1`` are (K, 4, 4)
    /// arrays (or any pose stack ``contact_many`` takes; one pose stands
    /// for all). Returns ``MotionChecks``. Checked in parallel with the GIL
    /// released.
    #[pyo3(
        signature = (poses0, poses1, tolerance = Tolerance(1e-6)),
        text_signature = "($self, poses0, poses1, tolerance=1e-6)"
    )]
    fn check_many(
        &self,
        py: Python<'_>,
        poses0: Option<&Bound<'_, PyAny>>,
        poses1: Option<&Bound<'_, PyAny>>,
        tolerance: Tolerance,
    ) -> PyResult<PyMotionChecks> {
        let tolerance = tolerance.0;
        check_tolerance(tolerance)?;
        let motions = motion_pairs(poses0, poses1)?;
        check_batch(
            py,
            &self.inner,
            &motions,
            tolerance,
            "MotionChecker.check_many",
        )
    }

    /// Whether the body at ``pose`` touches or overlaps an obstacle
    /// (exact): a state validity check.
    #[pyo3(signature = (pose = None))]
    fn collides_at(&self, py: Python<'_>, pose: Option<&Bound<'_, PyAny>>) -> PyResult<bool> {
        let p = convert::pose(pose, "pose")?;
        let inner = &self.inner;
        py.detach(|| inner.collides_at(p))
            .map_err(|e| err_for("MotionChecker.collides_at", e))
    }

    fn __repr__(&self) -> String {
        format!("{:?}", self.inner)
    }
}

/// Checks the straight motion of ``body`` from ``pose0`` to ``pose1``
/// against ``obstacles``, certified: a ``MotionCheck``. Never by sampling:
/// ``free`` means no contact at any instant; otherwise every
/// ``t ≤ t_safe`` is certified free and the body touches or overlaps an
/// obstacle at ``t_contact``, with ``t_contact - t_safe ≤ tolerance``.
///
/// ``body`` is a ``ConvexUnion`` or one shape (in its own frame);
/// ``obstacles`` a sequence of ``ConvexUnion``s or shapes (or one), in the
/// world frame. Poses are 4×4 homogeneous rigid transforms; the translation
/// moves linearly and the rotation by slerp along the shorter arc (OMPL's
/// SE(2)/SE(3) interpolation). Build a ``MotionChecker`` for many checks.
/// The arc is decided from the rotations as given (exact sign of the
/// quaternions' dot product). Raises ``MotionUndecided`` for a motion
/// grazing an obstacle within rounding or one that examined ``budget``
/// intervals (default 4096) without a decision. The GIL is released while
/// checking.
///
/// A box sliding through a wall 0.002 thick:
///
/// >>> import numpy as np, dymsum
/// >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float) - 0.5
/// >>> wall = np.array([[x, y, z] for x in (4.999, 5.001) for y in (-5, 5) for z in (-5, 5)], float)
/// >>> c = dymsum.check_motion(cube, [wall], None, dymsum.pose(translation=[10, 0, 0]))
/// >>> c.free, round(c.t_contact, 4)
/// (False, 0.4499)
/// >>> dymsum.check_motion(cube, [wall], None, dymsum.pose(translation=[0, 3, 0])).free
/// True
#[pyfunction]
#[pyo3(
    signature = (body, obstacles, pose0, pose1, tolerance = Tolerance(1e-6), budget = None),
    text_signature = "(body, obstacles, pose0, pose1, tolerance=1e-6, budget=None)"
)]
pub fn check_motion(
    py: Python<'_>,
    body: &Bound<'_, PyAny>,
    obstacles: &Bound<'_, PyAny>,
    pose0: Option<&Bound<'_, PyAny>>,
    pose1: Option<&Bound<'_, PyAny>>,
    tolerance: Tolerance,
    budget: Option<Budget>,
) -> PyResult<PyMotionCheck> {
    let tolerance = tolerance.0;
    check_tolerance(tolerance)?;
    let budget = checked_budget(budget)?;
    let p0 = convert::pose(pose0, "pose0")?;
    let p1 = convert::pose(pose1, "pose1")?;
    let checker = validator(py, body, obstacles, budget, "check_motion")?;
    py.detach(|| checker.check(p0, p1, tolerance))
        .map(PyMotionCheck::from_check)
        .map_err(|e| motion_error(py, "check_motion", e, None))
}

/// ``check_motion`` for many motions: ``poses0`` and ``poses1`` are
/// (K, 4, 4) arrays of homogeneous rigid transforms (or any pose stack
/// ``contact_many`` takes; one pose stands for all), motion ``k`` going
/// from ``poses0[k]`` to ``poses1[k]``. Returns ``MotionChecks`` (arrays
/// ``free``, ``t_safe``, ``t_contact``). Checked in parallel with the GIL
/// released; a grazing motion raises ``MotionUndecided`` naming its index.
///
/// >>> import numpy as np, dymsum
/// >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float) - 0.5
/// >>> wall = np.array([[x, y, z] for x in (4.999, 5.001) for y in (-5, 5) for z in (-5, 5)], float)
/// >>> ends = np.stack([dymsum.pose(translation=t) for t in ([10, 0, 0], [0, 3, 0], [4, 0, 0])])
/// >>> dymsum.check_motions(cube, [wall], None, ends).free.tolist()
/// [False, True, True]
#[pyfunction]
#[pyo3(
    signature = (body, obstacles, poses0, poses1, tolerance = Tolerance(1e-6), budget = None),
    text_signature = "(body, obstacles, poses0, poses1, tolerance=1e-6, budget=None)"
)]
pub fn check_motions(
    py: Python<'_>,
    body: &Bound<'_, PyAny>,
    obstacles: &Bound<'_, PyAny>,
    poses0: Option<&Bound<'_, PyAny>>,
    poses1: Option<&Bound<'_, PyAny>>,
    tolerance: Tolerance,
    budget: Option<Budget>,
) -> PyResult<PyMotionChecks> {
    let tolerance = tolerance.0;
    check_tolerance(tolerance)?;
    let budget = checked_budget(budget)?;
    let motions = motion_pairs(poses0, poses1)?;
    let checker = validator(py, body, obstacles, budget, "check_motions")?;
    check_batch(py, &checker, &motions, tolerance, "check_motions")
}

/// Whether the triangles of meshes ``a`` at ``pose_a`` and ``b`` at
/// ``pose_b`` touch (exact, surfaces only: no containment), as FCL's
/// mesh–mesh ``collide`` answers: the tests' referee between dymsum's
/// contact and FCL's. Private.
#[pyfunction]
#[pyo3(signature = (a, pose_a, b, pose_b))]
fn _surfaces_touch(
    py: Python<'_>,
    a: &Bound<'_, PyAny>,
    pose_a: Option<&Bound<'_, PyAny>>,
    b: &Bound<'_, PyAny>,
    pose_b: Option<&Bound<'_, PyAny>>,
) -> PyResult<bool> {
    let mesh = |obj: &Bound<'_, PyAny>, what: &str| -> PyResult<dymsum::PolygonMesh> {
        let (v, f) = convert::mesh_parts(obj)?
            .ok_or_else(|| value_error(format!("{what}: expected (vertices, faces)")))?;
        convert::solid_from_parts(&v, &f, what)
    };
    let (ma, mb) = (mesh(a, "a")?, mesh(b, "b")?);
    let (pa, pb) = (
        convert::pose(pose_a, "pose_a")?,
        convert::pose(pose_b, "pose_b")?,
    );
    py.detach(|| dymsum::query::surfaces_touch(&ma, pa, &mb, pb))
        .map_err(|e| err_for("_surfaces_touch", e))
}

/// Registers the motion classes and functions on the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyConvexUnion>()?;
    m.add_class::<PyMotionCheck>()?;
    m.add_class::<PyMotionChecks>()?;
    m.add_class::<PyMotionChecker>()?;
    m.add("MotionUndecided", m.py().get_type::<MotionUndecided>())?;
    m.add_function(wrap_pyfunction!(check_motion, m)?)?;
    m.add_function(wrap_pyfunction!(check_motions, m)?)?;
    m.add_function(wrap_pyfunction!(_surfaces_touch, m)?)?;
    Ok(())
}
