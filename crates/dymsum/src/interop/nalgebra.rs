//! Conversions to and from [nalgebra](https://nalgebra.rs) 0.35 (Cargo
//! feature `nalgebra`).
//!
//! nalgebra 0.35 is the version of parry's math stack (glamx 0.3's optional
//! nalgebra; it shares simba 0.10 with parry3d-f64 0.31), and needs Rust
//! 1.89.
//!
//! # What converts to what
//! | from | to | trait |
//! | --- | --- | --- |
//! | [`Rotation`] | `UnitQuaternion<f64>` | `From` |
//! | `UnitQuaternion<f64>`, `Quaternion<f64>` | [`Rotation`] | `TryFrom` |
//! | [`Rotation`] | `Rotation3<f64>` | `From` |
//! | `Rotation3<f64>` | [`Rotation`] | `TryFrom` |
//! | [`Pose`] | `Isometry3<f64>` | `From` |
//! | `Isometry3<f64>` | [`Pose`] | `TryFrom` |
//!
//! The feature also turns on nalgebra's own `convert-glam033` feature, so
//! [`glam::DVec3`] ⇄ `Vector3<f64>` / `Point3<f64>`, `DMat3` ⇄
//! `Matrix3<f64>` and the other glam types convert with nalgebra's `From`
//! impls.
//!
//! # Conventions
//! nalgebra's `Quaternion::new(w, i, j, k)` takes the scalar *first* and
//! stores it last (`coords = [i, j, k, w]`); components are mapped by name
//! (`w` ↔ `w`, `i, j, k` ↔ `x, y, z`). Rotations are active and
//! right-handed (Hamilton product), as in glam. `Isometry3` maps
//! `p ↦ rotation · p + translation`, as [`Pose::apply`] does.
//!
//! # What can fail
//! nalgebra's unit types are unit only up to rounding and can be built
//! unchecked (or normalised from zero, which gives NaN), so conversions into
//! dymsum types are `TryFrom`: [`InteropError::BadQuaternion`] (zero or
//! non-finite; a finite non-unit quaternion is normalised),
//! [`InteropError::NotRotation`] (a `Rotation3` whose matrix is not a
//! rotation within `1e-6`), [`InteropError::NonFiniteTranslation`].
//!
//! ```
//! use dymsum::{DVec3, Pose, Rotation};
//! use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};
//! let r = Rotation::from_axis_angle(DVec3::Z, std::f64::consts::FRAC_PI_2).unwrap();
//! let q = UnitQuaternion::from(r);
//! let x = q * Vector3::x();
//! assert!((x - Vector3::y()).norm() < 1e-15);
//! let from_na = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_2);
//! assert_eq!(Rotation::try_from(from_na).unwrap().apply(DVec3::X), DVec3::Y);
//!
//! let pose = Pose::new(r, DVec3::new(1.0, 0.0, 0.0));
//! let iso = Isometry3::from(pose);
//! let p = iso * Point3::new(1.0, 0.0, 0.0);
//! // Point3 -> DVec3 through nalgebra's convert-glam033; nalgebra rotates by
//! // the quaternion formula, dymsum by its snapped matrix: equal to rounding.
//! assert!((DVec3::from(p) - pose.apply(DVec3::X)).length() < 1e-15);
//! assert_eq!(Pose::try_from(iso).unwrap(), pose);
//! ```

use super::{pose_from_parts, rotation_from_xyzw, InteropError};
use crate::kernel::rotation::Pose;
use crate::kernel::rotation::Rotation;
use ::nalgebra::{Isometry3, Matrix3, Quaternion, Rotation3, Translation3, UnitQuaternion};
use glam::{DMat3, DVec3};

impl From<Rotation> for UnitQuaternion<f64> {
    /// The unit quaternion (`w ≥ 0`), bit for bit (not renormalised).
    fn from(r: Rotation) -> UnitQuaternion<f64> {
        let [w, x, y, z] = r.wxyz();
        UnitQuaternion::new_unchecked(Quaternion::new(w, x, y, z))
    }
}

impl TryFrom<UnitQuaternion<f64>> for Rotation {
    type Error = InteropError;

    /// The rotation of a nalgebra unit quaternion.
    ///
    /// # Errors
    /// [`InteropError::BadQuaternion`] for a zero or non-finite quaternion
    /// (possible through `new_unchecked` or normalising zero).
    fn try_from(q: UnitQuaternion<f64>) -> Result<Rotation, InteropError> {
        Rotation::try_from(q.into_inner())
    }
}

impl TryFrom<Quaternion<f64>> for Rotation {
    type Error = InteropError;

    /// The rotation of a nalgebra quaternion; a non-unit quaternion is
    /// normalised.
    ///
    /// # Errors
    /// [`InteropError::BadQuaternion`] for a zero or non-finite quaternion.
    fn try_from(q: Quaternion<f64>) -> Result<Rotation, InteropError> {
        rotation_from_xyzw([q.i, q.j, q.k, q.w])
    }
}

impl From<Rotation> for Rotation3<f64> {
    /// The rotation matrix ([`Rotation::matrix`]).
    fn from(r: Rotation) -> Rotation3<f64> {
        Rotation3::from_matrix_unchecked(Matrix3::from(r.matrix()))
    }
}

impl TryFrom<Rotation3<f64>> for Rotation {
    type Error = InteropError;

    /// The rotation of a nalgebra rotation matrix ([`Rotation::from_matrix`]).
    ///
    /// # Errors
    /// [`InteropError::NotRotation`] unless the matrix is finite,
    /// orthonormal and of determinant +1 (within `1e-6`).
    fn try_from(r: Rotation3<f64>) -> Result<Rotation, InteropError> {
        Rotation::try_from(DMat3::from(r.into_inner()))
    }
}

impl From<Pose> for Isometry3<f64> {
    /// The isometry with the same unit quaternion and translation.
    fn from(p: Pose) -> Isometry3<f64> {
        let t = p.translation;
        Isometry3::from_parts(Translation3::new(t.x, t.y, t.z), p.rotation.into())
    }
}

impl TryFrom<Isometry3<f64>> for Pose {
    type Error = InteropError;

    /// The pose of a nalgebra isometry; a non-unit quaternion is normalised.
    ///
    /// # Errors
    /// [`InteropError::BadQuaternion`] for a zero or non-finite quaternion,
    /// [`InteropError::NonFiniteTranslation`] for a non-finite translation.
    fn try_from(iso: Isometry3<f64>) -> Result<Pose, InteropError> {
        let (q, t) = (iso.rotation, iso.translation.vector);
        pose_from_parts([q.i, q.j, q.k, q.w], DVec3::new(t.x, t.y, t.z))
    }
}
