//! Why a query failed ([`QueryError`]), and bad input to a slab
//! computation ([`SlabError`]).

use crate::polytope::PolytopeError;
use crate::sum::SumError;

/// Why a query failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum QueryError {
    /// The sum could not be computed (an internal error of the sum).
    #[error(transparent)]
    Sum(#[from] SumError),
    /// The reflected body `−B` could not be built (cannot happen for a valid
    /// polytope; reported rather than panicking).
    #[error("reflecting a body failed: {0}")]
    Reflect(#[from] PolytopeError),
    /// An internal invariant failed (a bug: please report the input).
    #[error("internal inconsistency: {0}")]
    Inconsistent(String),
    /// The mesh of a slice could not be produced (see [`crate::sum::MeshError`]).
    #[error(transparent)]
    Mesh(#[from] crate::sum::MeshError),
    /// The exact penetration depth of a non-convex union is not supported:
    /// the minimum over piece pairs is *not* the union's depth (separating
    /// one pair can push it into another). Use [`crate::query::ConvexUnion::collides`],
    /// [`crate::query::ConvexUnion::distance`] or the per-pair contacts instead.
    #[error(
        "penetration depth of a non-convex union of convex pieces is not supported \
         (the minimum over piece pairs is not the union's depth)"
    )]
    UnionDepthUnsupported,
    /// The bodies at their poses are beyond what `f64` holds: a posed
    /// coordinate (`R p + t`) or the answer overflows (magnitudes above
    /// `1.8e308`). Every finite pose whose posed coordinates and answer are
    /// finite is supported, at any scale.
    #[error("outside the supported range: {0}")]
    OutOfRange(String),
    /// Bad input to a certified slab ([`crate::query::Slab`]): the variant names it.
    #[error(transparent)]
    Slab(#[from] SlabError),
}

/// Bad input to a slab computation: each variant names the offending value.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SlabError {
    /// The rotation axis is zero or not finite.
    #[error("the rotation axis {axis:?} is zero or not finite")]
    BadAxis {
        /// The axis given.
        axis: [f64; 3],
    },
    /// An angle is NaN or infinite.
    #[error("angle {index} is {angle}, not a finite number")]
    NonFiniteAngle {
        /// Its position in the list.
        index: usize,
        /// The angle.
        angle: f64,
    },
    /// An angle does not exceed the one before it.
    #[error(
        "angle {index} ({angle}) does not exceed the angle before it ({previous}): \
         the angles must increase strictly"
    )]
    NotIncreasing {
        /// Its position in the list.
        index: usize,
        /// The angle before it.
        previous: f64,
        /// The angle.
        angle: f64,
    },
    /// Two consecutive angles are more than `π` apart: the turn between
    /// them is not a shortest path, and the sagitta bound needs arcs of at
    /// most a half turn. Add angles in between.
    #[error(
        "the step to angle {index} is {step} rad, more than π: a slab covers at most a half \
         turn (add angles in between)"
    )]
    StepTooLarge {
        /// The position of the step's end in the list.
        index: usize,
        /// The step, in radians.
        step: f64,
    },
    /// Fewer than two orientations: a slab lies between two.
    #[error("{count} orientation(s) given: a slab lies between two, so at least 2 are needed")]
    TooFewOrientations {
        /// How many were given.
        count: usize,
    },
    /// The cell radius is negative, NaN, or not below `π`.
    #[error("the cell radius {radius} is not an angle in [0, π)")]
    BadRadius {
        /// The radius given.
        radius: f64,
    },
}
