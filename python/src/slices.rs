//! C-obstacle slices (`cobstacle_slices`) and certified slabs (`Slab`).

use crate::convert;
use crate::convert::{err_for, value_error};
use crate::sums::shape_of;
use dymsum::query::{Slab, SlabCover};
use dymsum::{CObstacle, DVec3};
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

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
pub(crate) fn cobstacle_slices<'py>(
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

/// Registers this module's classes and functions on the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PySlab>()?;
    m.add_function(wrap_pyfunction!(cobstacle_slices, m)?)?;
    Ok(())
}
