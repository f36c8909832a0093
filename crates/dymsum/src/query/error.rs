//! Why a query failed ([`QueryError`]), why a motion check failed
//! ([`MotionError`]), and bad input to a slab computation ([`SlabError`]).

use crate::polytope::PolytopeError;
use crate::query::interval_search::{Stop, MIN_TOLERANCE};
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

/// Why a motion check failed ([`crate::query::Checker::check`]): never a
/// guess, each says what is known.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MotionError {
    /// The tolerance is not a finite number in `[MIN_TOLERANCE, 1)`.
    #[error(
        "the tolerance must be a finite number in [{min:e}, 1) (the smallest the search can \
         bracket: it halves intervals down to 2^-48 of the motion), got {0}",
        min = MIN_TOLERANCE
    )]
    Tolerance(f64),
    /// The search examined its whole budget of intervals
    /// ([`crate::query::Checker::budget`]) without a decision: every
    /// `t ≤ t_safe` is certified free, nothing is known after it.
    #[error(
        "undecided: the check used its budget of {steps} intervals; every t <= {t_safe} is \
         certified free, after it nothing is decided (raise the budget, or treat the motion \
         as not free)"
    )]
    BudgetExhausted {
        /// The last time certified free (`0` when only the start is).
        t_safe: f64,
        /// The budget that was used up.
        steps: u64,
    },
    /// An exact query failed (posed coordinates beyond `f64`).
    #[error(transparent)]
    Query(#[from] QueryError),
    /// Between `t_safe` and `t` the body comes within rounding of an
    /// obstacle without a decidable contact (a grazing motion): neither
    /// free nor colliding can be certified.
    #[error(
        "undecided: between t = {t_safe} and t = {t} the body comes within rounding of an \
         obstacle without touching it at a checked time (a grazing motion)"
    )]
    Undecided {
        /// The last time certified free.
        t_safe: f64,
        /// The end of the undecided interval.
        t: f64,
    },
}

impl MotionError {
    /// [`MotionError::Tolerance`] unless `tolerance` is in
    /// `[MIN_TOLERANCE, 1)` (a NaN is not).
    pub(crate) fn check_tolerance(tolerance: f64) -> Result<(), MotionError> {
        if (MIN_TOLERANCE..1.0).contains(&tolerance) {
            Ok(())
        } else {
            Err(MotionError::Tolerance(tolerance))
        }
    }

    /// What a stopped interval search (`query::interval_search`) reports,
    /// for a check of budget `budget`.
    pub(crate) fn from_stop(stop: Stop<QueryError>, budget: u64) -> MotionError {
        match stop {
            Stop::Budget { t_safe } => MotionError::BudgetExhausted {
                t_safe,
                steps: budget,
            },
            Stop::Undecided { t_safe, t } => MotionError::Undecided { t_safe, t },
            Stop::Failed(e) => MotionError::Query(e),
        }
    }
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
