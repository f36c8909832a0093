//! Conversions between dymsum's math and shape types and those of other
//! crates.
//!
//! # What converts to what
//! Always available (glam is dymsum's own math crate, re-exported as
//! [`crate::glam`]; parry3d-f64 0.31 uses the same glam 0.33, so parry's
//! `Vector` *is* [`glam::DVec3`] and parry's rotation *is* `DQuat`):
//!
//! | from | to | trait |
//! | --- | --- | --- |
//! | [`Rotation`] | `glam::DQuat` | `From` |
//! | `glam::DQuat` | [`Rotation`] | `TryFrom` |
//! | [`Rotation`] | `glam::DMat3` | `From` |
//! | `glam::DMat3` | [`Rotation`] | `TryFrom` |
//! | [`Pose`] | `glam::DMat4` | `From` |
//! | `glam::DMat4` | [`Pose`] | `TryFrom` |
//!
//! Behind optional Cargo features (none is on by default; the crate's
//! `rust-version` holds for the default features, `parry` needs Rust 1.90
//! and `nalgebra` Rust 1.89 for their dependencies):
//!
//! * `parry` (module `interop::parry`, parry3d-f64 0.31): [`Pose`] ⇄
//!   parry's `math::Pose` (its isometry), [`crate::polytope::Polytope`] ⇄
//!   `shape::ConvexPolyhedron`.
//! * `mint` (module `interop::mint`, mint 0.5): [`Rotation`] ⇄
//!   `mint::Quaternion` and `mint::ColumnMatrix3`, [`Pose`] ⇄
//!   `mint::ColumnMatrix4`; vectors and matrices through glam's own `mint`
//!   feature, which this feature turns on (`DVec3` ⇄ `mint::Vector3<f64>` /
//!   `mint::Point3<f64>`).
//! * `nalgebra` (module `interop::nalgebra`, nalgebra 0.35, the version of
//!   parry's math stack): [`Rotation`] ⇄ `UnitQuaternion<f64>` and
//!   `Rotation3<f64>`, [`Pose`] ⇄ `Isometry3<f64>`; vectors, points and
//!   matrices through nalgebra's own `convert-glam033` feature, which this
//!   feature turns on (`DVec3` ⇄ `Vector3<f64>` / `Point3<f64>`).
//!
//! # Conventions (the same in every crate here)
//! * Rotations are *active*: a rotation turns vectors, `v ↦ R v`; a quaternion
//!   `q` acts as `q v q*` (Hamilton product, right-handed). A quarter turn
//!   about `+z` takes `+x` to `+y` in every crate.
//! * A pose maps a point as `p ↦ R p + t`: rotation first, then translation
//!   (the body frame's coordinates to the world frame's), as parry's `Pose`,
//!   nalgebra's `Isometry3` and a homogeneous column-major 4×4 matrix do.
//! * Quaternion component order is never implicit: glam and parry store
//!   `x, y, z, w` (scalar last), nalgebra's `Quaternion::new` takes
//!   `w, i, j, k` (scalar first), mint stores the vector part `v` and the
//!   scalar `s` by name; each conversion maps the components by name.
//! * A [`Rotation`] keeps its quaternion with `w ≥ 0` and snaps components
//!   within `1e-14` of zero (see [`crate::kernel::rotation`]). So
//!   `Rotation → other → Rotation` gives back the same [`Rotation`], bit for
//!   bit, while `other → Rotation → other` gives the same rotation, possibly
//!   as the negated quaternion or moved by less than `2e-14` rad.
//!
//! # What can fail
//! Conversions *into* dymsum types are `TryFrom`, with an [`InteropError`]:
//! a quaternion that is zero or not finite, a matrix that is not a rotation
//! (orthonormal with determinant +1, within `1e-6`, as
//! [`Rotation::from_matrix`]), a 4×4 matrix that is not a rigid transform,
//! a non-finite translation. A quaternion that is finite and non-zero but
//! not of unit length is accepted and normalised (as
//! [`Rotation::from_wxyz`]). Converting a parry shape into a
//! [`crate::polytope::Polytope`] fails with the constructor's own
//! [`crate::polytope::PolytopeError`]. Conversions *out of* dymsum types are `From`,
//! except a polytope into parry's `ConvexPolyhedron`, which parry may
//! refuse ([`InteropError::ParryOutOfRange`] for shapes its float
//! arithmetic cannot represent, [`InteropError::ParryRefused`]).
//!
//! ```
//! use dymsum::glam::{DMat4, DQuat};
//! use dymsum::{DVec3, Pose, Rotation};
//! let r = Rotation::try_from(DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2)).unwrap();
//! assert_eq!(r.apply(DVec3::X), DVec3::Y);
//! assert_eq!(Rotation::try_from(DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0)).unwrap_err(),
//!            dymsum::interop::InteropError::BadQuaternion { xyzw: [0.0; 4] });
//! let pose = Pose::new(r, DVec3::new(1.0, 2.0, 3.0));
//! let m = DMat4::from(pose);
//! assert_eq!(Pose::try_from(m).unwrap().apply(DVec3::X), DVec3::new(1.0, 3.0, 3.0));
//! assert!(Pose::try_from(DMat4::from_scale(DVec3::splat(2.0))).is_err());
//! ```

use crate::kernel::rotation::Pose;
use crate::kernel::rotation::Rotation;
use glam::{DMat3, DMat4, DQuat};

mod error;
pub use error::InteropError;

#[cfg(feature = "mint")]
pub mod mint;
#[cfg(feature = "nalgebra")]
pub mod nalgebra;
#[cfg(feature = "parry")]
pub mod parry;

/// A rotation from quaternion components `x, y, z, w`, checked.
///
/// A quaternion already of unit length (within `4 ε` in squared length) is
/// taken as is, so a round trip through another crate gives back the same
/// [`Rotation`] bit for bit; any other finite non-zero quaternion is
/// normalised without overflow or underflow ([`Rotation::from_xyzw`]).
pub(crate) fn rotation_from_xyzw(xyzw: [f64; 4]) -> Result<Rotation, InteropError> {
    let q = DQuat::from_array(xyzw);
    let bad = InteropError::BadQuaternion { xyzw };
    if !q.is_finite() {
        return Err(bad);
    }
    if (q.length_squared() - 1.0).abs() <= 4.0 * f64::EPSILON {
        return Ok(Rotation::from_quat(q));
    }
    let [x, y, z, w] = xyzw;
    Rotation::from_xyzw(x, y, z, w).ok_or(bad)
}

/// A rotation from a 3×3 matrix, checked ([`Rotation::from_matrix`]).
pub(crate) fn rotation_from_matrix(m: DMat3) -> Result<Rotation, InteropError> {
    Rotation::from_matrix(m).ok_or(InteropError::NotRotation {
        columns: m.to_cols_array_2d(),
    })
}

/// A pose from a rotation's quaternion `x, y, z, w` and a translation,
/// checked.
#[cfg(any(feature = "parry", feature = "nalgebra"))]
pub(crate) fn pose_from_parts(
    xyzw: [f64; 4],
    translation: glam::DVec3,
) -> Result<Pose, InteropError> {
    let rotation = rotation_from_xyzw(xyzw)?;
    if !translation.is_finite() {
        return Err(InteropError::NonFiniteTranslation {
            translation: translation.to_array(),
        });
    }
    Ok(Pose::new(rotation, translation))
}

impl From<Rotation> for DQuat {
    /// The unit quaternion, with `w ≥ 0` ([`Rotation::quat`]).
    fn from(r: Rotation) -> DQuat {
        r.quat()
    }
}

impl TryFrom<DQuat> for Rotation {
    type Error = InteropError;

    /// The rotation of a glam (or parry) quaternion; a non-unit quaternion
    /// is normalised.
    ///
    /// # Errors
    /// [`InteropError::BadQuaternion`] for a zero or non-finite quaternion.
    fn try_from(q: DQuat) -> Result<Rotation, InteropError> {
        rotation_from_xyzw(q.to_array())
    }
}

impl From<Rotation> for DMat3 {
    /// The rotation matrix ([`Rotation::matrix`], snapped).
    fn from(r: Rotation) -> DMat3 {
        r.matrix()
    }
}

impl TryFrom<DMat3> for Rotation {
    type Error = InteropError;

    /// The rotation of a rotation matrix ([`Rotation::from_matrix`]).
    ///
    /// # Errors
    /// [`InteropError::NotRotation`] unless the matrix is finite,
    /// orthonormal and of determinant +1 (within `1e-6`).
    fn try_from(m: DMat3) -> Result<Rotation, InteropError> {
        rotation_from_matrix(m)
    }
}

impl From<Pose> for DMat4 {
    /// The homogeneous transform ([`Pose::to_mat4`]).
    fn from(p: Pose) -> DMat4 {
        p.to_mat4()
    }
}

impl TryFrom<DMat4> for Pose {
    type Error = InteropError;

    /// The pose of a homogeneous rigid transform ([`Pose::from_mat4`]).
    ///
    /// # Errors
    /// [`InteropError::NotRigid`] unless the upper 3×3 block is a rotation,
    /// the last row is exactly `0, 0, 0, 1` and every entry is finite.
    fn try_from(m: DMat4) -> Result<Pose, InteropError> {
        Pose::from_mat4(m).ok_or_else(|| InteropError::NotRigid {
            columns: Box::new(m.to_cols_array_2d()),
        })
    }
}
