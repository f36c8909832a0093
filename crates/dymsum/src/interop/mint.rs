//! Conversions to and from [mint](https://docs.rs/mint) 0.5, the math
//! interchange types (Cargo feature `mint`).
//!
//! # What converts to what
//! | from | to | trait |
//! | --- | --- | --- |
//! | [`Rotation`] | `mint::Quaternion<f64>` | `From` |
//! | `mint::Quaternion<f64>` | [`Rotation`] | `TryFrom` |
//! | [`Rotation`] | `mint::ColumnMatrix3<f64>` | `From` |
//! | `mint::ColumnMatrix3<f64>` | [`Rotation`] | `TryFrom` |
//! | [`Pose`] | `mint::ColumnMatrix4<f64>` | `From` |
//! | `mint::ColumnMatrix4<f64>` | [`Pose`] | `TryFrom` |
//!
//! The feature also turns on glam's own `mint` feature, so
//! [`glam::DVec3`] ⇄ `mint::Vector3<f64>` / `mint::Point3<f64>` and glam's
//! matrices and quaternions convert with glam's `From` impls.
//!
//! # Conventions
//! `mint::Quaternion` names its parts: `v` the vector part `x, y, z`, `s` the
//! scalar `w`; its array form (`[f64; 4]`) is scalar last. Rotations are
//! active and right-handed. `ColumnMatrix4` is the homogeneous transform
//! `p ↦ R p + t` ([`Pose::to_mat4`]): rotation in the upper 3×3 block,
//! translation in the last column. (A `RowMatrix3`/`RowMatrix4` converts to
//! the column form with mint's own `From`, which transposes the storage.)
//!
//! # What can fail
//! mint gives no guarantee that a quaternion is a unit or a matrix a
//! rotation, so conversions into dymsum types are `TryFrom`:
//! [`InteropError::BadQuaternion`] (zero or non-finite; a finite non-unit
//! quaternion is normalised), [`InteropError::NotRotation`],
//! [`InteropError::NotRigid`].
//!
//! ```
//! use dymsum::{DVec3, Pose, Rotation};
//! let h = std::f64::consts::FRAC_1_SQRT_2;
//! // A quarter turn about z, scalar w = h, vector part (0, 0, h).
//! let q = mint::Quaternion { v: mint::Vector3 { x: 0.0, y: 0.0, z: h }, s: h };
//! let r = Rotation::try_from(q).unwrap();
//! assert_eq!(r.apply(DVec3::X), DVec3::Y);
//! assert_eq!(mint::Quaternion::from(r), q);
//! let zero = mint::Quaternion { v: mint::Vector3 { x: 0.0, y: 0.0, z: 0.0 }, s: 0.0 };
//! assert!(Rotation::try_from(zero).is_err());
//!
//! let m: mint::ColumnMatrix4<f64> = Pose::new(r, DVec3::Z).into();
//! assert_eq!(m.w.z, 1.0); // translation in the last column
//! let p: mint::Point3<f64> = DVec3::X.into(); // through glam's mint feature
//! assert_eq!(Pose::try_from(m).unwrap().apply(p.into()), DVec3::new(0.0, 1.0, 1.0));
//! ```

use super::{rotation_from_xyzw, InteropError};
use crate::kernel::rotation::Pose;
use crate::kernel::rotation::Rotation;
use glam::{DMat3, DMat4};

impl From<Rotation> for ::mint::Quaternion<f64> {
    /// The unit quaternion, with `s = w ≥ 0`.
    fn from(r: Rotation) -> ::mint::Quaternion<f64> {
        ::mint::Quaternion::from(r.xyzw())
    }
}

impl TryFrom<::mint::Quaternion<f64>> for Rotation {
    type Error = InteropError;

    /// The rotation of a mint quaternion (`v` the vector part, `s` the
    /// scalar); a non-unit quaternion is normalised.
    ///
    /// # Errors
    /// [`InteropError::BadQuaternion`] for a zero or non-finite quaternion.
    fn try_from(q: ::mint::Quaternion<f64>) -> Result<Rotation, InteropError> {
        rotation_from_xyzw([q.v.x, q.v.y, q.v.z, q.s])
    }
}

impl From<Rotation> for ::mint::ColumnMatrix3<f64> {
    /// The rotation matrix ([`Rotation::matrix`]), column-major.
    fn from(r: Rotation) -> ::mint::ColumnMatrix3<f64> {
        r.matrix().into()
    }
}

impl TryFrom<::mint::ColumnMatrix3<f64>> for Rotation {
    type Error = InteropError;

    /// The rotation of a column-major rotation matrix
    /// ([`Rotation::from_matrix`]).
    ///
    /// # Errors
    /// [`InteropError::NotRotation`] unless the matrix is finite,
    /// orthonormal and of determinant +1 (within `1e-6`).
    fn try_from(m: ::mint::ColumnMatrix3<f64>) -> Result<Rotation, InteropError> {
        Rotation::try_from(DMat3::from(m))
    }
}

impl From<Pose> for ::mint::ColumnMatrix4<f64> {
    /// The homogeneous transform ([`Pose::to_mat4`]), column-major.
    fn from(p: Pose) -> ::mint::ColumnMatrix4<f64> {
        p.to_mat4().into()
    }
}

impl TryFrom<::mint::ColumnMatrix4<f64>> for Pose {
    type Error = InteropError;

    /// The pose of a column-major homogeneous rigid transform
    /// ([`Pose::from_mat4`]).
    ///
    /// # Errors
    /// [`InteropError::NotRigid`] unless the upper 3×3 block is a rotation,
    /// the last row is exactly `0, 0, 0, 1` and every entry is finite.
    fn try_from(m: ::mint::ColumnMatrix4<f64>) -> Result<Pose, InteropError> {
        Pose::try_from(DMat4::from(m))
    }
}
