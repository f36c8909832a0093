//! Robots with joints from Python (issue 37): ``dymsum.Robot`` (a URDF,
//! its kinematics and collision pairs) and ``dymsum.RobotChecker`` (exact
//! configuration checks and certified joint-space motions).

use std::path::PathBuf;

use dymsum::body::Body;
use dymsum::query::{MeshBody, DEFAULT_BUDGET};
use dymsum::robot::{Robot, RobotChecker, RobotError};
use dymsum_io::urdf::load_robot;
use numpy::{IntoPyArray, PyArray1, PyArray3, PyReadonlyArray2};
use pyo3::prelude::*;

use crate::convert::{err_for, value_error, Budget, Tolerance};
use crate::motion::{check_tolerance, motion_error, obstacles_of, PyMotionCheck};

/// A robot's error as Python's: a bad configuration or pair is a
/// ``ValueError`` naming the joint or link; a motion without an answer
/// ``MotionUndecided``; anything else a ``ValueError`` too.
fn robot_error(py: Python<'_>, what: &str, e: RobotError) -> PyErr {
    match e {
        RobotError::Motion(m) => motion_error(py, what, m, None),
        other => err_for(what, other),
    }
}

/// A configuration argument: a sequence of floats.
fn configuration(q: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    q.extract::<Vec<f64>>().map_err(|_| {
        value_error(format!(
            "{what} must be a sequence of floats, one per degree of freedom"
        ))
    })
}

/// Configurations as rows of a (K, dof) array-like of numbers (any dtype
/// NumPy converts to float64, any memory layout).
fn configurations(qs: &Bound<'_, PyAny>, dof: usize) -> PyResult<Vec<Vec<f64>>> {
    let shape_error = || value_error(format!("qs must be a (K, {dof}) array of numbers"));
    let np = qs.py().import("numpy")?;
    let arr = np
        .call_method1("asarray", (qs, "float64"))
        .map_err(|_| shape_error())?;
    let arr = arr
        .extract::<PyReadonlyArray2<'_, f64>>()
        .map_err(|_| shape_error())?;
    let view = arr.as_array();
    if view.ncols() != dof {
        return Err(shape_error());
    }
    Ok(view.rows().into_iter().map(|r| r.to_vec()).collect())
}

/// A robot read from a URDF: links, joints (revolute, continuous,
/// prismatic, fixed; limits; mimics) and each link's collision geometry.
///
/// ``Robot.from_urdf("panda.urdf", srdf="panda.srdf", package_dirs=[root])``
/// gives Panda's 8 degrees of freedom (seven arm joints and the finger
/// joint its twin mimics); ``forward(q)`` each link's 4×4 pose
/// (``python/tests/test_robot.py`` runs this).
#[pyclass(module = "dymsum", name = "Robot")]
pub struct PyRobot {
    pub(crate) inner: Robot,
    deviations: Vec<(String, f64)>,
}

#[pymethods]
impl PyRobot {
    /// Reads the URDF at ``path``; ``srdf`` (a path) removes its disabled
    /// collision pairs; ``package_dirs`` are the roots ``package://``
    /// mesh paths are found under (``ROOT/NAME/REST``). Mesh paths may also
    /// be absolute or relative to the URDF. Spheres, cylinders and
    /// capsules become polytopes that contain them (``deviations``).
    #[staticmethod]
    #[pyo3(signature = (path, srdf = None, package_dirs = None))]
    fn from_urdf(
        py: Python<'_>,
        path: PathBuf,
        srdf: Option<PathBuf>,
        package_dirs: Option<Vec<PathBuf>>,
    ) -> PyResult<PyRobot> {
        let dirs = package_dirs.unwrap_or_default();
        let loaded = py
            .detach(|| load_robot(&path, srdf.as_deref(), &dirs))
            .map_err(|e| err_for("Robot.from_urdf", e))?;
        Ok(PyRobot {
            inner: loaded.robot,
            deviations: loaded.deviations,
        })
    }

    /// The degrees of freedom's joint names, in configuration order.
    #[getter]
    fn joint_names(&self) -> Vec<String> {
        self.inner
            .joint_names()
            .iter()
            .map(|s| s.to_string())
            .collect()
    }

    /// The links' names, in the order of ``forward``'s poses.
    #[getter]
    fn link_names(&self) -> Vec<String> {
        self.inner
            .link_names()
            .iter()
            .map(|s| s.to_string())
            .collect()
    }

    /// The number of degrees of freedom.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.dof()
    }

    /// Each degree of freedom's ``(lower, upper)`` limits, in
    /// ``joint_names`` order (a continuous joint's are infinite): the
    /// bounds of a planner's joint space.
    #[getter]
    fn joint_limits(&self) -> Vec<(f64, f64)> {
        self.inner.joint_limits()
    }

    /// For each link with a sphere, cylinder or capsule: the largest
    /// distance from its polytope to the exact shape.
    #[getter]
    fn deviations(&self) -> Vec<(String, f64)> {
        self.deviations.clone()
    }

    /// The link pairs checked, by name (by default every pair of links
    /// with geometry not joined by a joint, less the SRDF's); settable.
    #[getter]
    fn get_collision_pairs(&self) -> Vec<(String, String)> {
        self.inner.collision_pair_names()
    }

    #[setter]
    fn set_collision_pairs(&mut self, pairs: Vec<(String, String)>) -> PyResult<()> {
        self.inner
            .set_collision_pairs(&pairs)
            .map_err(|e| err_for("Robot.collision_pairs", e))
    }

    /// Each link's pose in the root's frame at configuration ``q``: an
    /// (L, 4, 4) array in ``link_names`` order. A value outside its
    /// joint's limits is a ``ValueError`` naming the joint.
    fn forward<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let q = configuration(q, "q")?;
        let poses = self
            .inner
            .forward(&q)
            .map_err(|e| err_for("Robot.forward", e))?;
        let mut out = Vec::with_capacity(poses.len());
        for p in poses {
            let m = p.to_mat4();
            out.push(
                (0..4)
                    .map(|r| m.row(r).to_array().to_vec())
                    .collect::<Vec<_>>(),
            );
        }
        numpy::PyArray3::from_vec3(py, &out).map_err(|e| value_error(e.to_string()))
    }

    fn __repr__(&self) -> String {
        format!(
            "dymsum.Robot({} links, {} degrees of freedom, {} collision pairs)",
            self.inner.links().len(),
            self.inner.dof(),
            self.inner.collision_pairs().len()
        )
    }
}

/// Exact configuration checks and certified joint-space motions of a
/// robot against itself (its collision pairs) and obstacles (in the root
/// link's frame; any bodies ``MotionChecker`` takes).
#[pyclass(module = "dymsum", name = "RobotChecker", frozen)]
pub struct PyRobotChecker {
    inner: RobotChecker,
    budget: u64,
}

#[pymethods]
impl PyRobotChecker {
    #[new]
    #[pyo3(signature = (robot, obstacles = None, budget = None))]
    fn new(
        py: Python<'_>,
        robot: PyRef<'_, PyRobot>,
        obstacles: Option<&Bound<'_, PyAny>>,
        budget: Option<Budget>,
    ) -> PyResult<Self> {
        let bodies = match obstacles {
            Some(o) => obstacles_of(o)?,
            None => Vec::new(),
        };
        let meshes: Vec<MeshBody> = bodies
            .into_iter()
            .map(|b| match b {
                Body::Convex(u) => MeshBody::from_union(&u),
                Body::Mesh(m) => m,
            })
            .collect();
        let model = robot.inner.clone();
        let inner = py
            .detach(|| RobotChecker::new(model, &meshes))
            .map_err(|e| err_for("RobotChecker", e))?;
        let budget = budget.map_or(DEFAULT_BUDGET, |b| b.0).max(1);
        Ok(PyRobotChecker { inner, budget })
    }

    /// Whether the robot at ``q`` touches itself (a pair checked) or an
    /// obstacle, exactly. GIL released.
    fn collides_at(&self, py: Python<'_>, q: &Bound<'_, PyAny>) -> PyResult<bool> {
        let q = configuration(q, "q")?;
        let inner = &self.inner;
        py.detach(|| inner.collides_at(&q))
            .map_err(|e| robot_error(py, "RobotChecker.collides_at", e))
    }

    /// ``collides_at`` for each row of a (K, dof) array (any array-like
    /// of numbers, in any memory layout): a (K,) bool array, in parallel
    /// with the GIL released.
    fn collides_many<'py>(
        &self,
        py: Python<'py>,
        qs: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<bool>>> {
        let rows = configurations(qs, self.inner.robot().dof())?;
        let inner = &self.inner;
        let hits = py
            .detach(|| inner.collides_many(&rows))
            .map_err(|e| robot_error(py, "RobotChecker.collides_many", e))?;
        Ok(hits.into_pyarray(py))
    }

    /// Every contact at ``q``: ``(link, None)`` for a link against the
    /// obstacles, ``(link, other)`` for a pair.
    fn colliding_pairs(
        &self,
        py: Python<'_>,
        q: &Bound<'_, PyAny>,
    ) -> PyResult<Vec<(String, Option<String>)>> {
        let q = configuration(q, "q")?;
        let inner = &self.inner;
        py.detach(|| inner.colliding_pairs(&q))
            .map_err(|e| robot_error(py, "RobotChecker.colliding_pairs", e))
    }

    /// A certified lower bound on the clearance at ``q`` (``0.0`` in
    /// contact; ``inf`` when nothing is checked). GIL released.
    fn distance_at(&self, py: Python<'_>, q: &Bound<'_, PyAny>) -> PyResult<f64> {
        let q = configuration(q, "q")?;
        let inner = &self.inner;
        py.detach(|| inner.distance_at(&q))
            .map_err(|e| robot_error(py, "RobotChecker.distance_at", e))
    }

    /// Checks the straight joint-space motion from ``q0`` to ``q1``: a
    /// ``MotionCheck`` (``free``, or the first contact bracketed within
    /// ``tolerance`` in ``t``), certified. Raises ``MotionUndecided`` for
    /// a grazing motion or a spent budget. GIL released.
    #[pyo3(
        signature = (q0, q1, tolerance = Tolerance(1e-6)),
        text_signature = "($self, q0, q1, tolerance=1e-6)"
    )]
    fn check(
        &self,
        py: Python<'_>,
        q0: &Bound<'_, PyAny>,
        q1: &Bound<'_, PyAny>,
        tolerance: Tolerance,
    ) -> PyResult<PyMotionCheck> {
        check_tolerance(tolerance.0)?;
        let (a, b) = (configuration(q0, "q0")?, configuration(q1, "q1")?);
        let (inner, budget) = (&self.inner, self.budget);
        py.detach(|| inner.check(&a, &b, tolerance.0, budget))
            .map(PyMotionCheck::from_check)
            .map_err(|e| robot_error(py, "RobotChecker.check", e))
    }

    /// A cheap refutation before a certificate: the ``t`` of the first
    /// configuration ``q(k / segments)`` of the straight motion (visited
    /// in bisection order, at most ``most`` of them) at which the robot
    /// collides (exact), or ``None`` when none does (which proves nothing:
    /// ``check`` decides). GIL released.
    #[pyo3(
        signature = (q0, q1, segments, most = 7),
        text_signature = "($self, q0, q1, segments, most=7)"
    )]
    fn sampled_contact(
        &self,
        py: Python<'_>,
        q0: &Bound<'_, PyAny>,
        q1: &Bound<'_, PyAny>,
        segments: usize,
        most: usize,
    ) -> PyResult<Option<f64>> {
        let (a, b) = (configuration(q0, "q0")?, configuration(q1, "q1")?);
        let inner = &self.inner;
        py.detach(|| inner.sampled_contact(&a, &b, segments, most))
            .map_err(|e| robot_error(py, "RobotChecker.sampled_contact", e))
    }

    /// The robot's number of degrees of freedom.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.robot().dof()
    }

    /// The most intervals one motion check examines.
    #[getter]
    fn budget(&self) -> u64 {
        self.budget
    }

    fn __repr__(&self) -> String {
        format!("dymsum.RobotChecker({:?})", self.inner)
    }
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyRobot>()?;
    m.add_class::<PyRobotChecker>()?;
    Ok(())
}
