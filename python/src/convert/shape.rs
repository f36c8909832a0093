//! Shapes from Python objects: point arrays, faces, meshes, model names
//! and files, `Polytope`s.

use super::args::path_string;
use super::{err_for, io_error, value_error};
use crate::polytope::Origin;
use dymsum::polytope::MeshPolicy;
use dymsum::{PolygonMesh, Polytope};
use dymsum_io::formats::FormatError;
use dymsum_io::load::LoadError;
use numpy::{PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple};

pub(crate) fn numpy(py: Python<'_>) -> PyResult<Bound<'_, PyModule>> {
    py.import("numpy")
}

pub(crate) fn dtype_kind(arr: &Bound<'_, PyAny>) -> PyResult<(char, String)> {
    let dtype = arr.getattr("dtype")?;
    let kind: String = dtype.getattr("kind")?.extract()?;
    Ok((kind.chars().next().unwrap_or('?'), dtype.str()?.to_string()))
}

pub(crate) fn shape_of(arr: &Bound<'_, PyAny>) -> PyResult<Vec<usize>> {
    arr.getattr("shape")?.extract()
}

pub(crate) fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// `obj` as a C-contiguous `float64` array of the given trailing shape
/// (`tail`) and `rank` dimensions: borrowed in place when it already is one,
/// else converted once. Rejects non-numeric dtypes (complex, bool, strings,
/// objects) and wrong shapes with a `ValueError` naming `what`.
pub(crate) fn float_array<'py>(
    obj: &Bound<'py, PyAny>,
    rank: usize,
    tail: &[usize],
    what: &str,
    expected: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let py = obj.py();
    let np = numpy(py)?;
    let arr = if obj.is_instance(&np.getattr("ndarray")?)? {
        obj.clone()
    } else {
        np.call_method1("asarray", (obj,))
            .map_err(|e| err_for(what, format!("expected {expected}: {}", e.value(py))))?
    };
    let (kind, dtype) = dtype_kind(&arr)?;
    if !matches!(kind, 'f' | 'i' | 'u') {
        return Err(err_for(
            what,
            format!("expected {expected} of real numbers, got dtype {dtype}"),
        ));
    }
    let shape = shape_of(&arr)?;
    if shape.len() != rank || !shape.ends_with(tail) {
        return Err(err_for(
            what,
            format!("expected {expected}, got shape {}", shape_text(&shape)),
        ));
    }
    let contiguous: bool = arr.getattr("flags")?.getattr("c_contiguous")?.extract()?;
    if dtype == "float64" && contiguous {
        // Already what dymsum reads: used in place.
        return Ok(arr);
    }
    let kwargs = PyDict::new(py);
    kwargs.set_item("dtype", np.getattr("float64")?)?;
    np.call_method("ascontiguousarray", (arr,), Some(&kwargs))
}

/// An (N, 3) point array, borrowed read-only in place (see [`float_array`]).
pub(crate) fn points<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
) -> PyResult<PyReadonlyArray2<'py, f64>> {
    let arr = float_array(obj, 2, &[3], what, "an (N, 3) array")?;
    let arr = arr.cast_into::<PyArray2<f64>>()?;
    arr.try_readonly()
        .map_err(|e| err_for(what, format!("cannot borrow the array: {e}")))
}

/// The rows of a C-contiguous (N, 3) array (as [`points`] gives), in
/// place. Any other layout is refused (`as_slice` alone would take a
/// Fortran-ordered array's raw memory as rows).
pub(crate) fn rows<'a>(arr: &'a PyReadonlyArray2<'_, f64>, what: &str) -> PyResult<&'a [[f64; 3]]> {
    if !arr.is_c_contiguous() {
        return Err(err_for(what, "internal error: array not C-contiguous"));
    }
    let flat = arr
        .as_slice()
        .map_err(|e| err_for(what, format!("array not contiguous: {e}")))?;
    Ok(flat.as_chunks::<3>().0)
}

/// A face's vertex index as given (any integer, unsigned beyond `i64`
/// included), checked against `0..vertex_count`: the error quotes it as
/// given, never wrapped to another integer.
fn vertex_index(v: i128, face: usize, vertex_count: usize, what: &str) -> PyResult<usize> {
    usize::try_from(v)
        .ok()
        .filter(|&u| u < vertex_count)
        .ok_or_else(|| {
            err_for(
                what,
                format!(
                    "face {face}: vertex index {v} out of range (there are {vertex_count} vertices)"
                ),
            )
        })
}

/// The faces of an (M, k) integer array of any dtype and memory layout:
/// read by logical index after one conversion to a C-contiguous array of
/// `T` (`int64`, or `uint64` for unsigned dtypes, so that an index beyond
/// `2**63` is quoted as given).
fn faces_of_array<T>(
    arr: &Bound<'_, PyAny>,
    dtype: &str,
    vertex_count: usize,
    what: &str,
) -> PyResult<Vec<Vec<usize>>>
where
    T: numpy::Element + Copy + Into<i128>,
{
    let py = arr.py();
    let np = numpy(py)?;
    let kwargs = PyDict::new(py);
    kwargs.set_item("dtype", np.getattr(dtype)?)?;
    let arr = np.call_method("ascontiguousarray", (arr,), Some(&kwargs))?;
    let arr = arr.cast_into::<PyArray2<T>>()?;
    let ro = arr
        .try_readonly()
        .map_err(|e| err_for(what, format!("cannot borrow the array: {e}")))?;
    ro.as_array()
        .outer_iter()
        .enumerate()
        .map(|(i, row)| {
            row.iter()
                .map(|&v| vertex_index(v.into(), i, vertex_count, what))
                .collect()
        })
        .collect()
}

/// Face index lists: an (M, k) integer array (any integer dtype and memory
/// layout) or a sequence of index sequences. Indices must be in
/// `0..vertex_count`; an index out of range is quoted as given.
pub(crate) fn faces(
    obj: &Bound<'_, PyAny>,
    vertex_count: usize,
    what: &str,
) -> PyResult<Vec<Vec<usize>>> {
    let py = obj.py();
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut out = Vec::new();
        for (i, item) in obj.try_iter()?.enumerate() {
            let item = item?;
            let face: PyResult<Vec<i128>> = if item.hasattr("dtype")? {
                let (kind, dtype) = dtype_kind(&item)?;
                if !matches!(kind, 'i' | 'u') {
                    return Err(err_for(
                        what,
                        format!("face {i}: expected integer indices, got dtype {dtype}"),
                    ));
                }
                item.call_method0("tolist")?.extract()
            } else {
                item.extract()
            };
            let face = face.map_err(|e| {
                err_for(
                    what,
                    format!(
                        "face {i}: expected a sequence of integer indices ({})",
                        e.value(py)
                    ),
                )
            })?;
            out.push(
                face.into_iter()
                    .map(|v| vertex_index(v, i, vertex_count, what))
                    .collect::<PyResult<Vec<usize>>>()?,
            );
        }
        return Ok(out);
    }
    let np = numpy(py)?;
    let arr = np.call_method1("asarray", (obj,)).map_err(|e| {
        err_for(
            what,
            format!("expected an (M, k) integer array: {}", e.value(py)),
        )
    })?;
    let (kind, dtype) = dtype_kind(&arr)?;
    let shape = shape_of(&arr)?;
    let empty = shape.contains(&0);
    if !matches!(kind, 'i' | 'u') && !empty {
        return Err(err_for(
            what,
            format!("expected an (M, k) integer array, got dtype {dtype}"),
        ));
    }
    if shape.len() != 2 {
        return Err(err_for(
            what,
            format!(
                "expected an (M, k) integer array, got shape {}",
                shape_text(&shape)
            ),
        ));
    }
    if empty {
        return Ok(Vec::new());
    }
    if kind == 'u' {
        faces_of_array::<u64>(&arr, "uint64", vertex_count, what)
    } else {
        faces_of_array::<i64>(&arr, "int64", vertex_count, what)
    }
}

/// A polytope converted from a Python object.
pub(crate) struct Shape {
    pub(crate) polytope: Polytope,
    pub(crate) origin: Origin,
    pub(crate) source: String,
}

/// A `(vertices, faces)` pair, an object with `.vertices` and `.faces`, or
/// `None` when `obj` is neither.
pub(crate) fn mesh_parts<'py>(
    obj: &Bound<'py, PyAny>,
) -> PyResult<Option<(Bound<'py, PyAny>, Bound<'py, PyAny>)>> {
    if (obj.is_instance_of::<PyTuple>() || obj.is_instance_of::<PyList>()) && obj.len()? == 2 {
        let first = obj.get_item(0)?;
        let np = numpy(obj.py())?;
        let two_d = np
            .call_method1("ndim", (&first,))
            .and_then(|d| d.extract::<usize>())
            .is_ok_and(|d| d == 2);
        if two_d {
            return Ok(Some((first, obj.get_item(1)?)));
        }
    }
    if obj.hasattr("vertices")? && obj.hasattr("faces")? {
        return Ok(Some((obj.getattr("vertices")?, obj.getattr("faces")?)));
    }
    Ok(None)
}

/// A mesh from its Python parts (vertices copied into the mesh).
pub(crate) fn mesh_from_parts(
    vertices: &Bound<'_, PyAny>,
    faces_obj: &Bound<'_, PyAny>,
    what: &str,
) -> PyResult<PolygonMesh> {
    let v = points(vertices, &format!("{what} vertices"))?;
    let verts = rows(&v, what)?.to_vec();
    let f = faces(faces_obj, verts.len(), &format!("{what} faces"))?;
    Ok(PolygonMesh::new(verts, f))
}

/// A mesh that stands for a body (a solid or a surface) from its Python
/// parts: as [`mesh_from_parts`], and an empty face array (shape (0, 3),
/// or an empty list) is a `ValueError` naming `what`, never the convex hull
/// of the vertices.
pub(crate) fn solid_from_parts(
    vertices: &Bound<'_, PyAny>,
    faces_obj: &Bound<'_, PyAny>,
    what: &str,
) -> PyResult<PolygonMesh> {
    let mesh = mesh_from_parts(vertices, faces_obj, what)?;
    if mesh.faces.is_empty() {
        let given = shape_of(faces_obj)
            .map(|s| format!(" (shape {})", shape_text(&s)))
            .unwrap_or_default();
        return Err(err_for(
            &format!("{what} faces"),
            format!(
                "the face array is empty{given}: a (vertices, faces) mesh needs at least one \
                 face (pass the (N, 3) vertices alone for their convex hull)"
            ),
        ));
    }
    Ok(mesh)
}

/// `ValueError` naming `what` when `obj` is `None` where a shape is
/// expected.
pub(crate) fn not_none(obj: &Bound<'_, PyAny>, what: &str, expected: &str) -> PyResult<()> {
    if obj.is_none() {
        return Err(err_for(what, format!("expected {expected}, got None")));
    }
    Ok(())
}

/// What a shape argument accepts (error messages).
pub(crate) const SHAPE_FORMS: &str = "a shape: an (N, 3) point array, a (vertices, faces) pair, \
     an object with .vertices and .faces, a Polytope, or a model name or mesh path";

/// A [`LoadError`] as the matching Python exception: `FileNotFoundError`
/// for a path that does not exist, `OSError` when a file cannot be read,
/// `ValueError` otherwise; prefixed by the argument's name when given.
pub(crate) fn load_error(e: LoadError, what: Option<&str>) -> PyErr {
    let msg = match what {
        Some(w) => format!("{w}: {e}"),
        None => e.to_string(),
    };
    match &e {
        LoadError::NotFound {
            looks_like_file: true,
            ..
        } => io_error(std::io::ErrorKind::NotFound, msg),
        LoadError::Format {
            source: FormatError::Io { source, .. },
            ..
        } => io_error(source.kind(), msg),
        _ => value_error(msg),
    }
}

/// A polytope from a mesh file or a built-in model name (what `dymsum.load`
/// takes), loaded with the GIL released; errors as [`load_error`].
pub(crate) fn load_shape(
    py: Python<'_>,
    spec: &str,
    policy: MeshPolicy,
    what: Option<&str>,
) -> PyResult<Shape> {
    let loaded = py
        .detach(|| dymsum_io::load_polytope(spec, policy))
        .map_err(|e| load_error(e, what))?;
    let origin = match loaded.report {
        Some(r) => Origin::Mesh(r),
        None => Origin::Points {
            count: loaded.input.vertices.len(),
        },
    };
    Ok(Shape {
        polytope: loaded.polytope,
        origin,
        source: loaded.source,
    })
}

/// Any accepted shape as a polytope (see the module docs). The hull is
/// built with the GIL released.
pub(crate) fn shape(obj: &Bound<'_, PyAny>, what: &str, policy: MeshPolicy) -> PyResult<Shape> {
    let py = obj.py();
    not_none(obj, what, SHAPE_FORMS)?;
    if let Ok(p) = obj.cast::<crate::polytope::PyPolytope>() {
        let p = p.get();
        return Ok(Shape {
            polytope: p.inner.clone(),
            origin: p.origin.clone(),
            source: p.source.clone(),
        });
    }
    // A model name or a path (a str or an os.PathLike), as `dymsum.load`.
    if obj.is_instance_of::<PyString>() || obj.hasattr("__fspath__")? {
        let spec = path_string(obj)?;
        return load_shape(py, &spec, policy, Some(what));
    }
    if let Some((v, f)) = mesh_parts(obj)? {
        let mesh = solid_from_parts(&v, &f, what)?;
        let (polytope, report) = py
            .detach(|| Polytope::from_mesh(&mesh, policy))
            .map_err(|e| err_for(what, e))?;
        return Ok(Shape {
            polytope,
            origin: Origin::Mesh(report),
            source: "mesh".into(),
        });
    }
    // An object with `.vertices` but no `.faces` (a trimesh.PointCloud) is a
    // point cloud; anything else must be an (N, 3) array-like.
    let cloud = if obj.hasattr("vertices")? && !obj.is_instance(&numpy(py)?.getattr("ndarray")?)? {
        obj.getattr("vertices")?
    } else {
        obj.clone()
    };
    let arr = points(&cloud, what)?;
    let pts = rows(&arr, what)?;
    let count = pts.len();
    let polytope = py
        .detach(|| Polytope::from_points(pts))
        .map_err(|e| err_for(what, e))?;
    Ok(Shape {
        polytope,
        origin: Origin::Points { count },
        source: "points".into(),
    })
}
