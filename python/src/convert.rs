//! Conversions between Python objects and dymsum's types, and the mapping of
//! dymsum's errors to Python exceptions.
//!
//! * Point arrays: an (N, 3) `float64` C-contiguous array is read in place
//!   (a borrowed view, no copy); any other numeric array-like is converted
//!   once by `numpy.ascontiguousarray(x, dtype=float64)`.
//! * Faces: an (M, k) integer array, or a sequence of index sequences
//!   (polygons of any size).
//! * Shapes: a `Polytope`, a model name or mesh file path (a `str` or
//!   `os.PathLike`, as `dymsum.load`), a `(vertices, faces)` pair, any
//!   object with `.vertices` and `.faces` (a trimesh.Trimesh, without
//!   importing trimesh), or an (N, 3) point cloud (its exact convex hull),
//!   also as an object with `.vertices` only (a trimesh.PointCloud).
//! * Rotations, wherever one is taken: a `scipy.spatial.transform.Rotation`
//!   (recognised by its `as_quat`/`as_matrix` methods, so scipy is never
//!   imported), a (4,) quaternion `(x, y, z, w)` (scalar last, as scipy) or
//!   a 3×3 rotation matrix. Poses: `None` (the identity), a 4×4 homogeneous
//!   rigid transform, or any rotation form (about the origin). Lists of
//!   rotations: a Rotation stack, (K, 4), (K, 3, 3) or (K, 4, 4) without
//!   translation.
//! * Errors: invalid input is `ValueError` with dymsum's message prefixed
//!   by the argument's name; a missing file is `FileNotFoundError`, other
//!   I/O failures `OSError`.

use dymsum::glam::{DMat3, DMat4};
use dymsum::polytope::{ConvexityReport, MeshPolicy};
use dymsum::{PolygonMesh, Polytope, Pose, Rotation};
use dymsum_io::formats::FormatError;
use dymsum_io::load::LoadError;
use numpy::ndarray::Array2;
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyPermissionError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple};

/// `ValueError(msg)`.
pub(crate) fn value_error(msg: impl Into<String>) -> PyErr {
    PyValueError::new_err(msg.into())
}

/// `ValueError("{what}: {err}")`.
pub(crate) fn err_for(what: &str, err: impl std::fmt::Display) -> PyErr {
    value_error(format!("{what}: {err}"))
}

/// An I/O error as the matching `OSError` subclass, with dymsum's message.
pub(crate) fn io_error(kind: std::io::ErrorKind, msg: String) -> PyErr {
    match kind {
        std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err(msg),
        std::io::ErrorKind::PermissionDenied => PyPermissionError::new_err(msg),
        _ => PyOSError::new_err(msg),
    }
}

fn numpy(py: Python<'_>) -> PyResult<Bound<'_, PyModule>> {
    py.import("numpy")
}

fn dtype_kind(arr: &Bound<'_, PyAny>) -> PyResult<(char, String)> {
    let dtype = arr.getattr("dtype")?;
    let kind: String = dtype.getattr("kind")?.extract()?;
    Ok((kind.chars().next().unwrap_or('?'), dtype.str()?.to_string()))
}

fn shape_of(arr: &Bound<'_, PyAny>) -> PyResult<Vec<usize>> {
    arr.getattr("shape")?.extract()
}

fn shape_text(shape: &[usize]) -> String {
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

/// The rows of a C-contiguous (N, 3) array, in place.
pub(crate) fn rows<'a>(arr: &'a PyReadonlyArray2<'_, f64>, what: &str) -> PyResult<&'a [[f64; 3]]> {
    let flat = arr
        .as_slice()
        .map_err(|e| err_for(what, format!("array not contiguous: {e}")))?;
    Ok(flat.as_chunks::<3>().0)
}

/// Face index lists: an (M, k) integer array or a sequence of index
/// sequences. Indices must be in `0..vertex_count`.
pub(crate) fn faces(
    obj: &Bound<'_, PyAny>,
    vertex_count: usize,
    what: &str,
) -> PyResult<Vec<Vec<usize>>> {
    let py = obj.py();
    let raw: Vec<Vec<i64>> = if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut out = Vec::new();
        for (i, item) in obj.try_iter()?.enumerate() {
            let item = item?;
            let face: PyResult<Vec<i64>> = if item.hasattr("dtype")? {
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
            out.push(face);
        }
        out
    } else {
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
        let kwargs = PyDict::new(py);
        kwargs.set_item("dtype", np.getattr("int64")?)?;
        let arr = np.call_method("ascontiguousarray", (arr,), Some(&kwargs))?;
        let arr = arr.cast_into::<PyArray2<i64>>()?;
        let ro = arr.readonly();
        let flat = ro
            .as_slice()
            .map_err(|e| err_for(what, format!("array not contiguous: {e}")))?;
        flat.chunks(shape[1]).map(<[i64]>::to_vec).collect()
    };
    raw.into_iter()
        .enumerate()
        .map(|(i, f)| {
            f.into_iter()
                .map(|v| {
                    usize::try_from(v)
                        .ok()
                        .filter(|&u| u < vertex_count)
                        .ok_or_else(|| {
                            err_for(
                                what,
                                format!(
                                    "face {i}: vertex index {v} out of range (there are {vertex_count} vertices)"
                                ),
                            )
                        })
                })
                .collect()
        })
        .collect()
}

/// Where a shape came from and what building it changed.
#[derive(Clone, Debug)]
pub(crate) enum Origin {
    /// The exact hull of a point cloud of this many points.
    Points { count: usize },
    /// A mesh, validated.
    Mesh(ConvexityReport),
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
        let mesh = mesh_from_parts(&v, &f, what)?;
        if mesh.faces.is_empty() {
            let count = mesh.vertices.len();
            let polytope = py
                .detach(|| Polytope::from_points(&mesh.vertices))
                .map_err(|e| err_for(what, e))?;
            return Ok(Shape {
                polytope,
                origin: Origin::Points { count },
                source: "points".into(),
            });
        }
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

/// What a pose argument accepts (error messages).
const POSE_FORMS: &str = "a 4×4 homogeneous rigid transform, or a rotation about the origin: a \
     scipy.spatial.transform.Rotation, a (4,) quaternion (x, y, z, w) or a 3×3 rotation matrix";

/// What a single-rotation argument accepts (error messages).
const ROTATION_FORMS: &str = "a scipy.spatial.transform.Rotation, a (4,) quaternion (x, y, z, w) \
     or a 3×3 rotation matrix";

/// What a list of rotations accepts (error messages).
const ROTATIONS_FORMS: &str = "a scipy.spatial.transform.Rotation (one or a stack), (K, 4) \
     quaternions (x, y, z, w), (K, 3, 3) rotation matrices or (K, 4, 4) homogeneous transforms \
     without translation; or one (4,) quaternion or 3×3 matrix";

/// The form of one rotation or pose in an array, by its trailing shape.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Form {
    /// `(4,)`: a quaternion `(x, y, z, w)`, scalar last as scipy.
    Quaternion,
    /// `(3, 3)`: a rotation matrix.
    Matrix,
    /// `(4, 4)`: a homogeneous rigid transform.
    Homogeneous,
}

impl Form {
    fn tail(self) -> &'static [usize] {
        match self {
            Form::Quaternion => &[4],
            Form::Matrix => &[3, 3],
            Form::Homogeneous => &[4, 4],
        }
    }
}

/// A rotation-like argument as an array: a
/// `scipy.spatial.transform.Rotation` (or any object with `as_quat` and
/// `as_matrix`, recognised without importing scipy) gives its quaternions
/// `as_quat()` (scalar last), anything else `numpy.asarray(obj)`.
fn rotation_probe<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
    expected: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let py = obj.py();
    let np = numpy(py)?;
    let is_array = obj.is_instance(&np.getattr("ndarray")?)?;
    let call = if !is_array && obj.hasattr("as_quat")? && obj.hasattr("as_matrix")? {
        obj.call_method0("as_quat")
    } else {
        np.call_method1("asarray", (obj,))
    };
    let arr = call.map_err(|e| err_for(what, format!("expected {expected}: {}", e.value(py))))?;
    let (kind, dtype) = dtype_kind(&arr)?;
    if !matches!(kind, 'f' | 'i' | 'u') {
        return Err(err_for(
            what,
            format!("expected {expected}, got dtype {dtype}"),
        ));
    }
    Ok(arr)
}

/// The rigid transforms in `arr` (shape `[K..] + form.tail()`), each a
/// rotation (and for [`Form::Homogeneous`] a translation). `name(k)` names
/// item `k` in error messages (`"quaternion 3"`, or `"quaternion"` for a
/// single one; empty for a single pose).
fn transforms(
    arr: &Bound<'_, PyAny>,
    form: Form,
    what: &str,
    name: impl Fn(usize) -> String,
) -> PyResult<Vec<Pose>> {
    let flat: Vec<f64> = arr
        .call_method0("ravel")?
        .call_method0("tolist")?
        .extract()?;
    let size: usize = form.tail().iter().product();
    let turn = |r: Rotation| Pose::new(r, dymsum::DVec3::ZERO);
    flat.chunks_exact(size)
        .enumerate()
        .map(|(k, c)| match form {
            Form::Quaternion => {
                let (x, y, z, w) = (c[0], c[1], c[2], c[3]);
                Rotation::from_xyzw(x, y, z, w).map(turn).ok_or_else(|| {
                    err_for(
                        what,
                        format!(
                            "{} (x, y, z, w) = ({x}, {y}, {z}, {w}) is zero or not finite",
                            name(k)
                        ),
                    )
                })
            }
            Form::Matrix => {
                let r = DMat3::from_cols_slice(c).transpose();
                Rotation::from_matrix(r).map(turn).ok_or_else(|| {
                    let reason = rotation_reason(r).replacen(
                        "not a rigid transform: the 3×3 rotation block must be",
                        "not a rotation: it must be",
                        1,
                    );
                    err_for(what, format!("{} is {reason}", name(k)))
                })
            }
            Form::Homogeneous => {
                let mut rows4 = [[0.0; 4]; 4];
                for (r, row) in rows4.iter_mut().enumerate() {
                    row.copy_from_slice(&c[4 * r..4 * r + 4]);
                }
                // glam is column-major: the transpose of the row-major rows.
                let m = DMat4::from_cols_array_2d(&rows4).transpose();
                Pose::from_mat4(m).ok_or_else(|| {
                    let reason = not_rigid_reason(&rows4);
                    match name(k) {
                        n if n.is_empty() => err_for(what, reason),
                        n => err_for(what, format!("{n}: {reason}")),
                    }
                })
            }
        })
        .collect()
}

/// The name of one item of `form` in error messages, `"quaternion"`,
/// `"matrix"` or `"transform"`, followed by ` k` in a stack.
fn item_name(form: Form, k: Option<usize>) -> String {
    let kind = match form {
        Form::Quaternion => "quaternion",
        Form::Matrix => "matrix",
        Form::Homogeneous => "transform",
    };
    match k {
        Some(k) => format!("{kind} {k}"),
        None if form == Form::Homogeneous => String::new(),
        None => kind.to_string(),
    }
}

/// One transform of the given form from `probe` (already an array).
fn one_transform(
    probe: &Bound<'_, PyAny>,
    form: Form,
    what: &str,
    expected: &str,
) -> PyResult<Pose> {
    let tail = form.tail();
    let arr = float_array(probe, tail.len(), tail, what, expected)?;
    let poses = transforms(&arr, form, what, |_| item_name(form, None))?;
    poses
        .into_iter()
        .next()
        .ok_or_else(|| err_for(what, format!("expected {expected}")))
}

/// The shape of a rotation-like array, refusing a stack where one rotation
/// is expected.
fn single_form(
    probe: &Bound<'_, PyAny>,
    what: &str,
    expected: &str,
    homogeneous: bool,
) -> PyResult<Form> {
    let shape = shape_of(probe)?;
    match shape.as_slice() {
        [4] => Ok(Form::Quaternion),
        [3, 3] => Ok(Form::Matrix),
        [4, 4] if homogeneous => Ok(Form::Homogeneous),
        [k, 4] | [k, 3, 3] => Err(err_for(
            what,
            format!(
                "expected one: {expected}; got a stack of {k} (shape {})",
                shape_text(&shape)
            ),
        )),
        _ => Err(err_for(
            what,
            format!("expected {expected}, got shape {}", shape_text(&shape)),
        )),
    }
}

/// A pose: `None` is the identity; a 4×4 homogeneous rigid transform
/// (rotation block orthonormal with determinant +1 within 1e-6, last row
/// exactly `0, 0, 0, 1`, all finite); or a rotation about the origin, as
/// [`rotation`] takes it (a scipy `Rotation`, a (4,) quaternion `(x, y, z,
/// w)`, a 3×3 rotation matrix).
pub(crate) fn pose(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Pose> {
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return Ok(Pose::IDENTITY);
    };
    if let Some(p) = rigid_4x4(obj) {
        return Ok(p);
    }
    let probe = rotation_probe(obj, what, POSE_FORMS)?;
    let form = single_form(&probe, what, POSE_FORMS, true)?;
    one_transform(&probe, form, what, POSE_FORMS)
}

/// The common case read directly from the array's memory: a C-contiguous
/// (4, 4) `float64` array holding a valid rigid transform (`None`
/// otherwise, and the general path reads it, with its error messages).
fn rigid_4x4(obj: &Bound<'_, PyAny>) -> Option<Pose> {
    let arr = obj.cast::<PyArray2<f64>>().ok()?.readonly();
    let flat = arr.as_slice().ok()?;
    (arr.shape() == [4, 4]).then_some(())?;
    rigid_from_rows(flat)
}

/// A rigid transform from 16 row-major values, if it is one.
fn rigid_from_rows(flat: &[f64]) -> Option<Pose> {
    let mut rows = [[0.0; 4]; 4];
    for (r, row) in rows.iter_mut().enumerate() {
        row.copy_from_slice(&flat[4 * r..4 * r + 4]);
    }
    Pose::from_mat4(DMat4::from_cols_array_2d(&rows).transpose())
}

/// One rotation: a `scipy.spatial.transform.Rotation` (a single one), a (4,)
/// quaternion `(x, y, z, w)` (scalar last, as scipy; renormalised) or a 3×3
/// rotation matrix (orthonormal with determinant +1 within 1e-6).
pub(crate) fn rotation(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Rotation> {
    let probe = rotation_probe(obj, what, ROTATION_FORMS)?;
    let form = single_form(&probe, what, ROTATION_FORMS, false)?;
    Ok(one_transform(&probe, form, what, ROTATION_FORMS)?.rotation)
}

/// Poses for a batch: `None` (the identity), one pose in any form [`pose`]
/// takes (a (4, 4) array is one homogeneous transform), or a stack: a
/// (K, 4, 4) array of homogeneous transforms, a (K, 4) array of quaternions
/// `(x, y, z, w)`, a (K, 3, 3) array of rotation matrices, or a scipy
/// `Rotation` stack. One pose stands for every pose of the batch.
pub(crate) fn pose_stack(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Vec<Pose>> {
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return Ok(vec![Pose::IDENTITY]);
    };
    // The common case read directly: a C-contiguous (K, 4, 4) float64
    // array of valid rigid transforms.
    if let Ok(arr) = obj.cast::<numpy::PyArray3<f64>>() {
        let ro = arr.readonly();
        if let (Ok(flat), [_, 4, 4]) = (ro.as_slice(), ro.shape()) {
            let poses: Option<Vec<Pose>> = flat.chunks_exact(16).map(rigid_from_rows).collect();
            if let Some(p) = poses {
                return Ok(p);
            }
        }
    }
    if let Some(p) = rigid_4x4(obj) {
        return Ok(vec![p]);
    }
    let np = numpy(obj.py())?;
    let scipy_like = !obj.is_instance(&np.getattr("ndarray")?)?
        && obj.hasattr("as_quat")?
        && obj.hasattr("as_matrix")?;
    let probe = rotation_probe(obj, what, POSE_STACK_FORMS)?;
    let shape = shape_of(&probe)?;
    // A (4, 4) array is one homogeneous transform here, not 4 quaternions
    // (a scipy Rotation stack gives its quaternions).
    let form = match shape.as_slice() {
        [4] | [_, 4] if scipy_like => Form::Quaternion,
        [4, 4] | [_, 4, 4] => Form::Homogeneous,
        [4] | [_, 4] => Form::Quaternion,
        [3, 3] | [_, 3, 3] => Form::Matrix,
        _ => {
            return Err(err_for(
                what,
                format!(
                    "expected {POSE_STACK_FORMS}, got shape {}",
                    shape_text(&shape)
                ),
            ))
        }
    };
    let tail = form.tail();
    let rank = if shape.len() == tail.len() {
        tail.len()
    } else {
        tail.len() + 1
    };
    let arr = float_array(&probe, rank, tail, what, POSE_STACK_FORMS)?;
    let stack = rank > tail.len();
    transforms(&arr, form, what, |k| item_name(form, stack.then_some(k)))
}

/// What [`pose_stack`] takes, for error messages.
const POSE_STACK_FORMS: &str = "None, a (K, 4, 4) array of homogeneous rigid transforms, a (K, 4) \
     array of quaternions (x, y, z, w), a (K, 3, 3) array of rotation matrices, a scipy Rotation, \
     or one pose";

/// [`pose`], with `None` meaning `current` (for updates: the body stays).
pub(crate) fn pose_or(obj: Option<&Bound<'_, PyAny>>, what: &str, current: Pose) -> PyResult<Pose> {
    match obj {
        Some(o) if !o.is_none() => pose(Some(o), what),
        _ => Ok(current),
    }
}

fn not_rigid_reason(rows: &[[f64; 4]; 4]) -> String {
    if rows.iter().flatten().any(|x| !x.is_finite()) {
        return "not a rigid transform: an entry is NaN or infinite".into();
    }
    if rows[3] != [0.0, 0.0, 0.0, 1.0] {
        return format!(
            "not a rigid transform: the last row is {:?}, expected exactly [0, 0, 0, 1]",
            rows[3]
        );
    }
    let r = DMat3::from_cols_array_2d(&[
        [rows[0][0], rows[1][0], rows[2][0]],
        [rows[0][1], rows[1][1], rows[2][1]],
        [rows[0][2], rows[1][2], rows[2][2]],
    ]);
    rotation_reason(r)
}

fn rotation_reason(r: DMat3) -> String {
    let g = r.transpose() * r - DMat3::IDENTITY;
    let off = g.to_cols_array().iter().fold(0.0f64, |m, x| m.max(x.abs()));
    format!(
        "not a rigid transform: the 3×3 rotation block must be orthonormal with determinant +1 \
         (within 1e-6), but max |RᵀR − I| = {off:.3e} and det R = {:.6} (scaling, shear and \
         reflections are not supported)",
        r.determinant()
    )
}

/// Rotations: a `scipy.spatial.transform.Rotation` (one or a stack), a
/// (K, 4) array of quaternions `(x, y, z, w)` (scalar last, as scipy; a 2-D
/// (4, 4) array is four quaternions), a (K, 3, 3) array of rotation
/// matrices, a (K, 4, 4) array of homogeneous transforms whose translation
/// is zero, or one (4,) quaternion or 3×3 matrix.
pub(crate) fn rotations(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Rotation>> {
    let probe = rotation_probe(obj, what, ROTATIONS_FORMS)?;
    let shape = shape_of(&probe)?;
    let form = match shape.as_slice() {
        [4] | [_, 4] => Form::Quaternion,
        [3, 3] | [_, 3, 3] => Form::Matrix,
        [_, 4, 4] => Form::Homogeneous,
        _ => {
            return Err(err_for(
                what,
                format!(
                    "expected {ROTATIONS_FORMS}, got shape {}",
                    shape_text(&shape)
                ),
            ))
        }
    };
    let tail = form.tail();
    let rank = if shape.len() == tail.len() {
        tail.len()
    } else {
        tail.len() + 1
    };
    let arr = float_array(&probe, rank, tail, what, ROTATIONS_FORMS)?;
    let stack = rank > tail.len();
    let poses = transforms(&arr, form, what, |k| item_name(form, stack.then_some(k)))?;
    poses
        .into_iter()
        .enumerate()
        .map(|(k, p)| {
            if p.translation == dymsum::DVec3::ZERO {
                Ok(p.rotation)
            } else {
                Err(err_for(
                    what,
                    format!(
                        "transform {k} has the translation {:?}: give rotations only (the \
                         slices are the robot turned about its own origin)",
                        p.translation.to_array()
                    ),
                ))
            }
        })
        .collect()
}

/// An (rows, cols) array taking over `flat` (no copy; `flat.len()` is
/// `rows · cols` at every call site, and a mismatch is an error, not a panic).
fn matrix<'py, T: numpy::Element>(
    py: Python<'py>,
    flat: Vec<T>,
    shape: (usize, usize),
) -> PyResult<Bound<'py, PyArray2<T>>> {
    Array2::from_shape_vec(shape, flat)
        .map(|a| a.into_pyarray(py))
        .map_err(|e| value_error(format!("internal error: output shape {shape:?}: {e}")))
}

/// A (rows, 3) `float64` array from `3 · rows` values, row by row.
pub(crate) fn rows_array(
    py: Python<'_>,
    flat: Vec<f64>,
    rows: usize,
) -> PyResult<Bound<'_, PyArray2<f64>>> {
    matrix(py, flat, (rows, 3))
}

/// A 4×4 row-major `float64` array of a pose: the rotation block is the
/// matrix of the quaternion as given (`Rotation::matrix_as_given`, not
/// snapped), so that a pose handed back keeps which way a motion to it
/// turns (a half turn plus 1e-300 stays on its side).
pub(crate) fn pose_array<'py>(py: Python<'py>, pose: Pose) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let m = DMat4::from_mat3_translation(pose.rotation.matrix_as_given(), pose.translation);
    let cols = m.transpose().to_cols_array();
    matrix(py, cols.to_vec(), (4, 4))
}

/// A (3,) `float64` array.
pub(crate) fn vec3<'py>(py: Python<'py>, v: [f64; 3]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, v.to_vec())
}

/// An (n, 3) `float64` array that takes over the mesh's vertex buffer (no
/// copy).
pub(crate) fn vertices_array<'py>(
    py: Python<'py>,
    vertices: Vec<[f64; 3]>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = vertices.len();
    matrix(py, vertices.into_flattened(), (n, 3))
}

/// Fan triangles of convex polygon faces, as an (m, 3) `int64` array.
pub(crate) fn triangles_array<'py>(
    py: Python<'py>,
    faces: &[Vec<usize>],
) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let mut flat = Vec::new();
    for f in faces {
        for i in 1..f.len().saturating_sub(1) {
            flat.extend([f[0] as i64, f[i] as i64, f[i + 1] as i64]);
        }
    }
    let m = flat.len() / 3;
    matrix(py, flat, (m, 3))
}

/// Polygon faces as a list of (k,) `int64` arrays.
pub(crate) fn polygons_list<'py>(
    py: Python<'py>,
    faces: &[Vec<usize>],
) -> PyResult<Bound<'py, PyList>> {
    PyList::new(
        py,
        faces
            .iter()
            .map(|f| PyArray1::from_vec(py, f.iter().map(|&i| i as i64).collect())),
    )
}

/// `(vertices, faces)` of a mesh: triangles by default, polygons on request.
pub(crate) fn mesh_tuple<'py>(
    py: Python<'py>,
    mesh: PolygonMesh,
    polygons: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let faces: Bound<'py, PyAny> = if polygons {
        polygons_list(py, &mesh.faces)?.into_any()
    } else {
        triangles_array(py, &mesh.faces)?.into_any()
    };
    let vertices = vertices_array(py, mesh.vertices)?.into_any();
    PyTuple::new(py, [vertices, faces])
}

/// An argument PyO3 would extract as a Rust number, with an integer beyond
/// the number's range reported as a `ValueError` naming the argument (PyO3
/// raises `OverflowError` there, and passes it on unnamed): `what` is the
/// argument's name, `range` what it takes.
fn number_arg<'a, 'py, T>(obj: Borrowed<'a, 'py, PyAny>, what: &str, range: &str) -> PyResult<T>
where
    T: for<'b> FromPyObject<'b, 'py, Error = PyErr>,
{
    obj.extract::<T>().map_err(|e: PyErr| {
        let py = obj.py();
        if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(py) {
            value_error(format!("{what} must be {range}, got an integer beyond it"))
        } else {
            e
        }
    })
}

/// A motion check's `tolerance` (a float; its range is checked where it is
/// used).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tolerance(pub f64);

impl<'a, 'py> FromPyObject<'a, 'py> for Tolerance {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        number_arg(obj, "tolerance", "a finite number in [2**-38, 1)").map(Tolerance)
    }
}

/// A motion check's work `budget`, in intervals (`None` the default).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Budget(pub u64);

impl<'a, 'py> FromPyObject<'a, 'py> for Budget {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        number_arg(obj, "budget", "an integer in [1, 2**64)").map(Budget)
    }
}

/// A pose's `translation`: three floats.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Translation(pub [f64; 3]);

impl<'a, 'py> FromPyObject<'a, 'py> for Translation {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        number_arg(obj, "translation", "three finite floats").map(Translation)
    }
}

pub(crate) fn path_string(path: &Bound<'_, PyAny>) -> PyResult<String> {
    let os = path.py().import("os")?;
    os.call_method1("fspath", (path,))?.extract()
}
