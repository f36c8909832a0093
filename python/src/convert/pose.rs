//! Rotations and poses from Python objects: scipy `Rotation`s,
//! quaternions, 3×3 matrices, 4×4 transforms, and stacks of them.

use super::err_for;
use super::shape::{dtype_kind, float_array, numpy, shape_of, shape_text};
use dymsum::glam::{DMat3, DMat4};
use dymsum::{Pose, Rotation};
use numpy::ndarray::ArrayView2;
use numpy::{PyArray2, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;

/// What a pose argument accepts (error messages).
pub(crate) const POSE_FORMS: &str =
    "a 4×4 homogeneous rigid transform, or a rotation about the origin: a \
     scipy.spatial.transform.Rotation, a (4,) quaternion (x, y, z, w) or a 3×3 rotation matrix";

/// What a single-rotation argument accepts (error messages).
pub(crate) const ROTATION_FORMS: &str =
    "a scipy.spatial.transform.Rotation, a (4,) quaternion (x, y, z, w) \
     or a 3×3 rotation matrix";

/// What a list of rotations accepts (error messages).
pub(crate) const ROTATIONS_FORMS: &str =
    "a scipy.spatial.transform.Rotation (one or a stack), (K, 4) \
     quaternions (x, y, z, w), (K, 3, 3) rotation matrices or (K, 4, 4) homogeneous transforms \
     without translation; or one (4,) quaternion or 3×3 matrix";

/// The form of one rotation or pose in an array, by its trailing shape.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Form {
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
pub(crate) fn rotation_probe<'py>(
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
pub(crate) fn transforms(
    arr: &Bound<'_, PyAny>,
    form: Form,
    what: &str,
    name: impl Fn(usize) -> String,
) -> PyResult<Vec<Pose>> {
    let arr = arr
        .cast::<PyArrayDyn<f64>>()
        .map_err(|e| err_for(what, format!("internal error: not a float64 array: {e}")))?
        .try_readonly()
        .map_err(|e| err_for(what, format!("cannot borrow the array: {e}")))?;
    // Read by logical index (C order), whatever the memory layout: in place
    // when the array is C-contiguous, else copied once by its strides.
    let copied: Vec<f64>;
    let flat: &[f64] = match arr.as_slice() {
        Ok(s) if arr.is_c_contiguous() => s,
        _ => {
            copied = arr.as_array().iter().copied().collect();
            &copied
        }
    };
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
pub(crate) fn item_name(form: Form, k: Option<usize>) -> String {
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
pub(crate) fn one_transform(
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
pub(crate) fn single_form(
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

/// The common case read directly from the array: a (4, 4) `float64` array
/// (any memory layout: C- or Fortran-ordered, transposed, sliced or
/// negatively strided, read by its strides) holding a valid rigid
/// transform (`None` otherwise, and the general path reads it, with its
/// error messages). The 16 numbers are copied under the GIL rather than
/// borrowed: numpy's shared-borrow registry costs about 1,000 instructions
/// a call, more than the copy, on every single-pose query.
pub(crate) fn rigid_4x4(obj: &Bound<'_, PyAny>) -> Option<Pose> {
    let arr = obj.cast::<PyArray2<f64>>().ok()?;
    (arr.shape() == [4, 4]).then_some(())?;
    rigid_from_view(arr.to_owned_array().view())
}

/// A rigid transform from a (4, 4) view indexed `[row, column]` (by its
/// strides, never its raw memory order), if it is one.
pub(crate) fn rigid_from_view(m: ArrayView2<'_, f64>) -> Option<Pose> {
    (m.shape() == [4, 4]).then_some(())?;
    let mut rows = [[0.0; 4]; 4];
    for (r, row) in rows.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = m[[r, c]];
        }
    }
    // glam is column-major: the transpose of the row-major rows.
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
    // The common case read directly: a (K, 4, 4) float64 array of valid
    // rigid transforms, in any memory layout (read by its strides: a
    // Fortran-ordered, transposed, sliced or reversed stack is no copy and
    // no list).
    if let Ok(arr) = obj.cast::<numpy::PyArray3<f64>>() {
        if let Ok(ro) = arr.try_readonly() {
            let view = ro.as_array();
            if view.shape()[1..] == [4, 4] {
                let poses: Option<Vec<Pose>> = view.outer_iter().map(rigid_from_view).collect();
                if let Some(p) = poses {
                    return Ok(p);
                }
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
    stack_of(&probe, &shape, form, what, POSE_STACK_FORMS)
}

/// The transforms of an array already probed as one item or a stack of
/// items of `form` (its `shape` read): every item as a pose, named in
/// errors by its index when a stack.
fn stack_of(
    probe: &Bound<'_, PyAny>,
    shape: &[usize],
    form: Form,
    what: &str,
    forms: &str,
) -> PyResult<Vec<Pose>> {
    let tail = form.tail();
    let rank = if shape.len() == tail.len() {
        tail.len()
    } else {
        tail.len() + 1
    };
    let arr = float_array(probe, rank, tail, what, forms)?;
    let stack = rank > tail.len();
    transforms(&arr, form, what, |k| item_name(form, stack.then_some(k)))
}

/// What [`pose_stack`] takes, for error messages.
pub(crate) const POSE_STACK_FORMS: &str =
    "None, a (K, 4, 4) array of homogeneous rigid transforms, a (K, 4) \
     array of quaternions (x, y, z, w), a (K, 3, 3) array of rotation matrices, a scipy Rotation, \
     or one pose";

/// [`pose`], with `None` meaning `current` (for updates: the body stays).
pub(crate) fn pose_or(obj: Option<&Bound<'_, PyAny>>, what: &str, current: Pose) -> PyResult<Pose> {
    match obj {
        Some(o) if !o.is_none() => pose(Some(o), what),
        _ => Ok(current),
    }
}

pub(crate) fn not_rigid_reason(rows: &[[f64; 4]; 4]) -> String {
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

pub(crate) fn rotation_reason(r: DMat3) -> String {
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
    let poses = stack_of(&probe, &shape, form, what, ROTATIONS_FORMS)?;
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
