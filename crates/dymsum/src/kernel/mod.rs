//! The exact-predicate kernel: every combinatorial decision in dymsum goes
//! through this small interface.
//!
//! * [`predicates::orient`]: the exact side of a point relative to a plane
//!   through three points (Shewchuk's adaptive `orient3d`).
//! * [`predicates::det3`]: the exact sign of the determinant of three float
//!   vectors (directions on the Gaussian sphere).
//! * [`predicates::sos_det3`]: the same with Simulation of Simplicity, the one
//!   consistent tie-breaking rule for exact degeneracies between two Gaussian
//!   maps. Never returns zero for three distinct indices.
//! * `dd`: double-double arithmetic, the filters' second stage.
//! * `exact`: exact dyadic arithmetic behind the filters.
//! * [`rotation`]: unit quaternions, rotation matrices and rigid poses.

pub(crate) mod bounds;
pub(crate) mod dd;
pub(crate) mod exact;
pub mod predicates;
pub mod rotation;
pub(crate) mod separation;
#[cfg(test)]
pub(crate) mod test_rng;

pub use predicates::Sign;
