//! Rotations (unit quaternions) and rigid poses.
//!
//! A [`Rotation`] keeps its unit quaternion and the matrix derived from it.
//! Quaternion components within `1e-14` of zero are snapped to zero (then
//! the quaternion is renormalised), and matrix entries within `2^-47` of `0`
//! or `±1` are snapped to those values. So rotations by exact multiples of
//! 90° about coordinate axes — also when composed from many quarter turns,
//! whose rounding errors accumulate — map axis-aligned directions to
//! axis-aligned directions *exactly*, and faces that should become parallel
//! do become exactly parallel (a tie the exact predicates then resolve
//! consistently). The snaps move the rotation by less than `2e-14` rad, the
//! rounding level of composed quaternions; rotations smaller than that are
//! the identity.
//!
//! # The quaternion as given
//! A rotation also keeps the quaternion it was made from, *as given*: not
//! snapped, not normalised (only scaled by a power of two, which is
//! exact), with its sign ([`Rotation::quat_as_given`]). Snapping and the
//! canonical sign (`w ≥ 0`) are right for the rotation itself but erase
//! which way a motion to a nearly opposite orientation turns: a turn by
//! `180° + 1e-12°` about z has `w = −8.6e-15`, snapped to `0`, after which
//! the two arcs tie. The arc of a motion (`query::motion`) is therefore
//! decided from the quaternions as given, by the exact sign of their dot
//! product ([`crate::kernel::predicates::dot4`]). A matrix gives the
//! quaternion glam's `DQuat::from_mat3` converts it to (its largest
//! component positive), a composition the product of the given
//! quaternions, an inverse the conjugate. Equality of rotations compares
//! the rotations (the snapped quaternion and matrix), not the given
//! quaternions.

use glam::{DMat3, DQuat, DVec3};

const SNAP: f64 = 1.0 / (1u64 << 47) as f64;
const QUAT_SNAP: f64 = 1e-14;

#[inline]
fn snap(x: f64) -> f64 {
    if x.abs() < SNAP {
        0.0
    } else if (x - 1.0).abs() < SNAP {
        1.0
    } else if (x + 1.0).abs() < SNAP {
        -1.0
    } else {
        x
    }
}

/// `q` scaled by a power of two (exact unless a component lies more than
/// 2¹⁰⁷⁴ below the largest) so that its largest component is in `[1, 2)`:
/// squaring can then neither overflow nor underflow, and a non-zero finite
/// quaternion is never called zero. `None` for a zero or non-finite `q`.
fn scaled_pow2(q: DQuat) -> Option<DQuat> {
    let m = q.w.abs().max(q.x.abs()).max(q.y.abs()).max(q.z.abs());
    if !m.is_finite() || m == 0.0 {
        return None;
    }
    // Unbiased exponent of m (subnormals count as -1023: the scaled
    // maximum is then at least 2^-51, still safe to square).
    let e = ((m.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    let pow2 = |k: i32| f64::from_bits(((k + 1023) as u64) << 52);
    // Two factors, each within the normal range, for |e| up to 1023.
    let (s1, s2) = (pow2(-(e / 2)), pow2(-(e - e / 2)));
    Some(q * s1 * s2)
}

/// A rotation of 3-space, as a unit quaternion plus its (snapped) matrix,
/// and the quaternion it was given as (module docs).
#[derive(Clone, Copy, Debug)]
pub struct Rotation {
    quat: DQuat,
    matrix: DMat3,
    given: DQuat,
}

impl PartialEq for Rotation {
    /// The same rotation (snapped quaternion and matrix); the quaternions
    /// as given may differ, in sign for instance.
    fn eq(&self, other: &Rotation) -> bool {
        self.quat == other.quat && self.matrix == other.matrix
    }
}

impl Default for Rotation {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Rotation {
    /// The identity.
    pub const IDENTITY: Rotation = Rotation {
        quat: DQuat::IDENTITY,
        matrix: DMat3::IDENTITY,
        given: DQuat::IDENTITY,
    };

    /// From quaternion components `w, x, y, z`; renormalised. Returns `None`
    /// for a zero or non-finite quaternion.
    pub fn from_wxyz(w: f64, x: f64, y: f64, z: f64) -> Option<Rotation> {
        let q = scaled_pow2(DQuat::from_xyzw(x, y, z, w))?;
        let len = q.length();
        if !len.is_finite() || len == 0.0 {
            return None;
        }
        Some(Self::from_unit_quat(q / len, q))
    }

    /// From quaternion components in the order `x, y, z, w` (scalar last, as
    /// glam, parry, ROS and Eigen store them); renormalised. The same as
    /// [`Self::from_wxyz`]`(w, x, y, z)`.
    ///
    /// ```
    /// use dymsum::Rotation;
    /// let h = std::f64::consts::FRAC_1_SQRT_2;
    /// assert_eq!(Rotation::from_xyzw(0.0, 0.0, h, h), Rotation::from_wxyz(h, 0.0, 0.0, h));
    /// assert!(Rotation::from_xyzw(0.0, 0.0, 0.0, 0.0).is_none());
    /// ```
    pub fn from_xyzw(x: f64, y: f64, z: f64, w: f64) -> Option<Rotation> {
        Self::from_wxyz(w, x, y, z)
    }

    /// The unit quaternion's components in the order `x, y, z, w` (scalar
    /// last).
    pub fn xyzw(&self) -> [f64; 4] {
        let [w, x, y, z] = self.wxyz();
        [x, y, z, w]
    }

    /// From a quaternion assumed (close to) unit length; renormalised.
    /// `q` is kept as the quaternion as given.
    pub fn from_quat(q: DQuat) -> Rotation {
        Self::from_unit_quat(q, q)
    }

    /// The quaternion this rotation was given as: not snapped, not
    /// normalised, its sign kept (module docs). The arc of a motion between
    /// two rotations is decided from these.
    pub fn quat_as_given(&self) -> DQuat {
        self.given
    }

    /// The matrix to hand out for this rotation so that converting it
    /// back keeps the arc information: [`Self::matrix`] (snapped, so exact
    /// quarter turns stay exact), except where the snap of tiny quaternion
    /// components erased a non-zero component of the quaternion as given
    /// (a half turn plus `1e-12°` or `1e-300` rad): then the matrix of the
    /// quaternion as given, unsnapped, which stays on its side of the half
    /// turn.
    pub fn matrix_as_given(&self) -> DMat3 {
        let n = self.given.length();
        if !(n.is_finite() && n > 0.0) {
            return self.matrix;
        }
        let unit = self.given / n;
        let erased = unit
            .to_array()
            .iter()
            .any(|&c| c != 0.0 && c.abs() < QUAT_SNAP);
        if erased {
            DMat3::from_quat(unit)
        } else {
            self.matrix
        }
    }

    fn from_unit_quat(q: DQuat, given: DQuat) -> Rotation {
        let snap_q = |c: f64| if c.abs() < QUAT_SNAP { 0.0 } else { c };
        let q = DQuat::from_xyzw(snap_q(q.x), snap_q(q.y), snap_q(q.z), snap_q(q.w));
        // Renormalise, but leave an already unit quaternion bit-identical.
        let n2 = q.length_squared();
        let q = if (n2 - 1.0).abs() <= 4.0 * f64::EPSILON {
            q
        } else {
            q / n2.sqrt()
        };
        // Canonical sign (w >= 0) so equal rotations have equal quaternions.
        let q = if q.w < 0.0 { -q } else { q };
        let m = DMat3::from_quat(q);
        let cols =
            [m.x_axis, m.y_axis, m.z_axis].map(|c| DVec3::new(snap(c.x), snap(c.y), snap(c.z)));
        Rotation {
            quat: q,
            matrix: DMat3::from_cols(cols[0], cols[1], cols[2]),
            given,
        }
    }

    /// Rotation by `angle` radians about `axis` (any non-zero length).
    /// Returns `None` for a zero or non-finite axis or angle.
    pub fn from_axis_angle(axis: DVec3, angle: f64) -> Option<Rotation> {
        let len = axis.length();
        if !len.is_finite() || len == 0.0 || !angle.is_finite() {
            return None;
        }
        let q = DQuat::from_axis_angle(axis / len, angle);
        Some(Self::from_unit_quat(q, q))
    }

    /// From a rotation matrix (orthonormal, determinant +1, within 1e-6).
    /// Returns `None` otherwise.
    pub fn from_matrix(m: DMat3) -> Option<Rotation> {
        let should_be_identity = m.transpose() * m;
        if !m.is_finite()
            || !should_be_identity.abs_diff_eq(DMat3::IDENTITY, 1e-6)
            || (m.determinant() - 1.0).abs() > 1e-6
        {
            return None;
        }
        let q = DQuat::from_mat3(&m);
        Some(Self::from_unit_quat(q, q))
    }

    /// The unit quaternion (with `w >= 0`).
    pub fn quat(&self) -> DQuat {
        self.quat
    }

    /// Components `[w, x, y, z]`.
    pub fn wxyz(&self) -> [f64; 4] {
        [self.quat.w, self.quat.x, self.quat.y, self.quat.z]
    }

    /// The rotation matrix (snapped, see the module docs).
    pub fn matrix(&self) -> DMat3 {
        self.matrix
    }

    /// Rotates a vector.
    #[inline]
    pub fn apply(&self, v: DVec3) -> DVec3 {
        self.matrix * v
    }

    /// `self` followed by `other` (i.e. `other ∘ self`).
    pub fn then(&self, other: &Rotation) -> Rotation {
        let product = other.given * self.given;
        let given = scaled_pow2(product).unwrap_or(product);
        if *other == Rotation::IDENTITY {
            return Rotation { given, ..*self };
        }
        if *self == Rotation::IDENTITY {
            return Rotation { given, ..*other };
        }
        Self::from_unit_quat(other.quat * self.quat, given)
    }

    /// The inverse rotation.
    pub fn inverse(&self) -> Rotation {
        Self::from_unit_quat(self.quat.conjugate(), self.given.conjugate())
    }

    /// Rotation angle in radians, in `[0, π]`.
    pub fn angle(&self) -> f64 {
        // Robust for small angles: 2 atan2(|xyz|, |w|).
        2.0 * self.quat.xyz().length().atan2(self.quat.w.abs())
    }

    /// The angle of the rotation taking `self` to `other` (`other · self⁻¹`).
    pub fn angle_to(&self, other: &Rotation) -> f64 {
        if self == other {
            return 0.0;
        }
        let rel = other.quat * self.quat.conjugate();
        2.0 * rel.xyz().length().atan2(rel.w.abs())
    }
}

/// A rigid pose: `p ↦ R p + t`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pose {
    /// The rotation, applied first.
    pub rotation: Rotation,
    /// The translation, applied after the rotation.
    pub translation: DVec3,
}

impl Pose {
    /// The identity pose.
    pub const IDENTITY: Pose = Pose {
        rotation: Rotation::IDENTITY,
        translation: DVec3::ZERO,
    };

    /// A pose from a rotation and a translation.
    pub fn new(rotation: Rotation, translation: DVec3) -> Pose {
        Pose {
            rotation,
            translation,
        }
    }

    /// Applies the pose to a point.
    #[inline]
    pub fn apply(&self, p: DVec3) -> DVec3 {
        self.rotation.apply(p) + self.translation
    }

    /// From a 4×4 homogeneous rigid transform (column-major glam `DMat4`:
    /// rotation in the upper 3×3 block, translation in the last column, last
    /// row `0, 0, 0, 1`). Returns `None` unless the block is a rotation (see
    /// [`Rotation::from_matrix`]), the last row is exactly `0, 0, 0, 1` and
    /// every entry is finite.
    ///
    /// ```
    /// use dymsum::glam::{DMat4, DQuat};
    /// use dymsum::{DVec3, Pose, Rotation};
    /// let m = DMat4::from_rotation_translation(DQuat::from_rotation_z(0.5), DVec3::new(1.0, 2.0, 3.0));
    /// let pose = Pose::from_mat4(m).unwrap();
    /// let p = DVec3::new(0.3, -0.2, 0.1);
    /// assert!((pose.apply(p) - m.transform_point3(p)).length() < 1e-15);
    /// assert!(Pose::from_mat4(DMat4::from_scale(DVec3::splat(2.0))).is_none());
    /// ```
    pub fn from_mat4(m: glam::DMat4) -> Option<Pose> {
        if !m.is_finite() || m.row(3) != glam::DVec4::new(0.0, 0.0, 0.0, 1.0) {
            return None;
        }
        let rotation = Rotation::from_matrix(glam::DMat3::from_mat4(m))?;
        Some(Pose::new(rotation, m.w_axis.truncate()))
    }

    /// The pose as a 4×4 homogeneous transform (column-major glam `DMat4`).
    pub fn to_mat4(&self) -> glam::DMat4 {
        glam::DMat4::from_rotation_translation(self.rotation.quat(), self.translation)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quaternion_orders_and_homogeneous_matrices() {
        let r = Rotation::from_wxyz(0.9, 0.1, -0.3, 0.2).unwrap();
        let [x, y, z, w] = r.xyzw();
        assert_eq!(Rotation::from_xyzw(x, y, z, w), Some(r));
        assert_eq!(r.wxyz(), [w, x, y, z]);
        let pose = Pose::new(r, DVec3::new(-1.0, 2.5, 1e3));
        let back = Pose::from_mat4(pose.to_mat4()).unwrap();
        assert!((back.translation - pose.translation).length() == 0.0);
        assert!(back.rotation.angle_to(&r) < 1e-12);
        // Not rigid: scaled, sheared, projective, non-finite.
        let mut m = pose.to_mat4();
        m.x_axis.x *= 1.5;
        assert!(Pose::from_mat4(m).is_none());
        let mut m = pose.to_mat4();
        m.x_axis.w = 1e-3;
        assert!(Pose::from_mat4(m).is_none());
        let mut m = pose.to_mat4();
        m.w_axis.x = f64::NAN;
        assert!(Pose::from_mat4(m).is_none());
    }
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn quarter_turn_is_exact() {
        let r = Rotation::from_axis_angle(DVec3::Z, FRAC_PI_2).unwrap();
        assert_eq!(r.apply(DVec3::X), DVec3::Y);
        assert_eq!(r.apply(DVec3::Y), -DVec3::X);
        assert_eq!(r.apply(DVec3::Z), DVec3::Z);
    }

    #[test]
    fn tiny_rotation_is_not_snapped_away() {
        let r = Rotation::from_axis_angle(DVec3::Z, 1e-12).unwrap();
        assert!(r.apply(DVec3::X).y > 0.0);
        assert!((r.angle() - 1e-12).abs() < 1e-20);
    }

    #[test]
    fn composed_quarter_turns_stay_exact() {
        let q = Rotation::from_axis_angle(DVec3::Z, FRAC_PI_2).unwrap();
        let mut r = Rotation::IDENTITY;
        for k in 1..=400 {
            r = r.then(&q);
            let x = r.apply(DVec3::X);
            let expect = [DVec3::X, DVec3::Y, -DVec3::X, -DVec3::Y][k % 4];
            assert_eq!(x, expect, "after {k} quarter turns");
        }
        let s = Rotation::from_axis_angle(DVec3::new(1.0, 2.0, 3.0), 0.7).unwrap();
        assert_eq!(s.then(&Rotation::IDENTITY), s);
        assert_eq!(Rotation::IDENTITY.then(&s), s);
    }

    #[test]
    fn rejects_bad_input() {
        assert!(Rotation::from_wxyz(0.0, 0.0, 0.0, 0.0).is_none());
        assert!(Rotation::from_wxyz(f64::NAN, 0.0, 0.0, 1.0).is_none());
        assert!(Rotation::from_axis_angle(DVec3::ZERO, 1.0).is_none());
    }
}
