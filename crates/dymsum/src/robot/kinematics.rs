//! Forward kinematics: each link's pose in the root's frame, composed in
//! floats joint by joint (`parent ∘ origin ∘ motion(value)`). The checks
//! are exact for the link meshes at these poses as computed.

use glam::DVec3;

use super::error::RobotError;
use super::model::{JointKind, Robot, Value};
use crate::kernel::rotation::{Pose, Rotation};

/// `a ∘ b`: `b` first, then `a`.
pub fn compose(a: &Pose, b: &Pose) -> Pose {
    Pose::new(b.rotation.then(&a.rotation), a.apply(b.translation))
}

/// The inverse pose.
pub fn inverse(a: &Pose) -> Pose {
    let r = a.rotation.inverse();
    Pose::new(r, -r.apply(a.translation))
}

impl Robot {
    /// The joints' values for configuration `q`, checked: one finite value
    /// per degree of freedom, revolute and prismatic joints within their
    /// limits (continuous joints take any angle); mimic joints follow.
    ///
    /// # Errors
    /// [`RobotError::BadConfiguration`] naming the joint.
    pub fn joint_values(&self, q: &[f64]) -> Result<Vec<f64>, RobotError> {
        if q.len() != self.dofs.len() {
            return Err(RobotError::BadConfiguration(format!(
                "{} values given for {} degrees of freedom ({})",
                q.len(),
                self.dofs.len(),
                self.joint_names().join(", ")
            )));
        }
        for (k, (&j, &v)) in self.dofs.iter().zip(q).enumerate() {
            let joint = &self.joints[j].spec;
            if !v.is_finite() {
                return Err(RobotError::BadConfiguration(format!(
                    "value {k} (joint {:?}) is not finite",
                    joint.name
                )));
            }
            if let JointKind::Revolute { lower, upper } | JointKind::Prismatic { lower, upper } =
                joint.kind
            {
                if v < lower || v > upper {
                    return Err(RobotError::BadConfiguration(format!(
                        "joint {:?} at {v} is outside its limits [{lower}, {upper}]",
                        joint.name
                    )));
                }
            }
        }
        Ok(self
            .joints
            .iter()
            .map(|j| match j.value {
                Value::None => 0.0,
                Value::Dof(d) => q[d],
                Value::Mimic(d, m, o) => m * q[d] + o,
            })
            .collect())
    }

    /// Each link's pose in the root's frame at configuration `q` (one value
    /// per degree of freedom, [`Robot::joint_names`] order; radians or
    /// metres), in [`Robot::link_names`] order.
    ///
    /// # Errors
    /// [`RobotError::BadConfiguration`] for a wrong length, a value that is
    /// not finite or outside a joint's limits (naming the joint), or a
    /// pose that is not finite.
    pub fn forward(&self, q: &[f64]) -> Result<Vec<Pose>, RobotError> {
        let values = self.joint_values(q)?;
        let mut poses = vec![Pose::IDENTITY; self.links.len()];
        for (joint, &v) in self.joints.iter().zip(&values) {
            let motion = match joint.spec.kind {
                JointKind::Fixed => Pose::IDENTITY,
                JointKind::Revolute { .. } | JointKind::Continuous => {
                    let turn = Rotation::from_axis_angle(joint.axis, v).ok_or_else(|| {
                        RobotError::BadConfiguration(format!(
                            "joint {:?} takes the value {v}, which is not finite (a mimic \
                             overflowing?)",
                            joint.spec.name
                        ))
                    })?;
                    Pose::new(turn, DVec3::ZERO)
                }
                JointKind::Prismatic { .. } => Pose::new(Rotation::IDENTITY, joint.axis * v),
            };
            let at = compose(&compose(&poses[joint.parent], &joint.spec.origin), &motion);
            if !at.translation.is_finite() {
                return Err(RobotError::BadConfiguration(format!(
                    "the pose of link {:?} is not finite",
                    self.links[joint.child].name
                )));
            }
            poses[joint.child] = at;
        }
        Ok(poses)
    }
}
