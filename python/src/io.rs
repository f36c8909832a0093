//! Poses and files: `pose`, `load`, `save`, `read_mesh_bodies`, `models`.

use crate::convert;
use crate::convert::policy;
use crate::convert::{io_error, path_string, value_error, Translation};
use crate::polytope::PyPolytope;
use dymsum::Pose;
use dymsum_io::formats::FormatError;
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::PyList;

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
pub(crate) fn pose<'py>(
    py: Python<'py>,
    quaternion: Option<&Bound<'py, PyAny>>,
    translation: Option<Translation>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let rotation = match quaternion.filter(|q| !q.is_none()) {
        None => dymsum::Rotation::IDENTITY,
        Some(q) => convert::rotation(q, "quaternion")?,
    };
    let t = translation.map_or([0.0; 3], |t| t.0);
    if t.iter().any(|x| !x.is_finite()) {
        return Err(value_error(format!("translation: {t:?} is not finite")));
    }
    convert::pose_array(py, Pose::new(rotation, t.into()))
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
pub(crate) fn load(
    py: Python<'_>,
    path_or_model_name: &Bound<'_, PyAny>,
    strict: bool,
) -> PyResult<PyPolytope> {
    let spec = path_string(path_or_model_name)?;
    let shape = convert::load_shape(py, &spec, policy(strict), None)?;
    PyPolytope::from_shape(py, shape)
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
pub(crate) fn read_mesh_bodies<'py>(
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
pub(crate) fn save(
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
pub(crate) fn models() -> Vec<&'static str> {
    dymsum_io::models::catalogue()
        .iter()
        .map(|m| m.name)
        .collect()
}

/// Registers this module's classes and functions on the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(pose, m)?)?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(save, m)?)?;
    m.add_function(wrap_pyfunction!(read_mesh_bodies, m)?)?;
    m.add_function(wrap_pyfunction!(models, m)?)?;
    Ok(())
}
