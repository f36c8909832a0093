//! The robot layer's error.

use crate::query::{MotionError, QueryError};

/// What can go wrong building a robot or checking a configuration; each
/// variant names the element at fault.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RobotError {
    /// The links and joints do not form one tree (a loop, a link with two
    /// parent joints, a joint naming a missing link, two roots, a name
    /// used twice).
    #[error("the robot is not a tree: {0}")]
    NotATree(String),
    /// A joint is malformed (a zero axis, limits out of order, a mimic of
    /// a missing or mimicking joint, a non-finite origin).
    #[error("joint {joint:?}: {reason}")]
    BadJoint {
        /// The joint's name.
        joint: String,
        /// What is wrong.
        reason: String,
    },
    /// A configuration of the wrong length, not finite, or outside a
    /// joint's limits.
    #[error("configuration: {0}")]
    BadConfiguration(String),
    /// A link's collision geometry could not be taken as a body.
    #[error("link {link:?}: {reason}")]
    BadLink {
        /// The link's name.
        link: String,
        /// What is wrong.
        reason: String,
    },
    /// A collision pair names a missing link or a link twice.
    #[error("collision pair: {0}")]
    BadPair(String),
    /// A motion check gave no answer: a tolerance out of range, a grazing
    /// motion (undecided) or a spent budget ([`MotionError`]).
    #[error(transparent)]
    Motion(MotionError),
    /// A check failed ([`QueryError`], e.g. coordinates beyond `f64`).
    #[error(transparent)]
    Query(#[from] QueryError),
}
