//! `Polytope`: a convex polytope built once from points or a convex mesh
//! (the class here, its methods in `methods`), and where it came from
//! ([`Origin`]).

mod methods;

pub(crate) use methods::register;

use dymsum::polytope::ConvexityReport;
use dymsum::Polytope;
use numpy::PyArray2;
use pyo3::prelude::*;

/// Where a shape came from and what building it changed.
#[derive(Clone, Debug)]
pub(crate) enum Origin {
    /// The exact hull of a point cloud of this many points.
    Points { count: usize },
    /// A mesh, validated.
    Mesh(ConvexityReport),
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
    pub(crate) vertices: Py<PyArray2<f64>>,
    pub(crate) faces: Py<PyArray2<i64>>,
}
