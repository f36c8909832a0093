//! Robots with joints (issue 37, in part): a tree of links and joints as a
//! URDF describes it ([`Robot`]: revolute, continuous, prismatic and fixed
//! joints, limits, mimic joints), forward kinematics, and exact
//! configuration checks against itself and a scene ([`RobotChecker`]),
//! and certified joint-space motions ([`RobotChecker::check`], the
//! soundness argument in [`motion`]).
//! Reading URDF files is `dymsum_io::urdf`'s.

pub mod checker;
pub mod error;
pub mod kinematics;
pub mod model;
pub mod motion;
mod separation;
pub mod shapes;

pub use checker::{LinkContact, RobotChecker};
pub use error::RobotError;
pub use kinematics::{compose, inverse};
pub use model::{JointKind, JointSpec, LinkSpec, Mimic, Robot};
