//! Why a query failed: [`QueryError`].

use crate::polytope::PolytopeError;
use crate::query::cobstacle::slabs::SlabError;
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
    /// one pair can push it into another). Use [`ConvexUnion::collides`],
    /// [`ConvexUnion::distance`] or the per-pair contacts instead.
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
    /// Bad input to a certified slab ([`Slab`]): the variant names it.
    #[error(transparent)]
    Slab(#[from] SlabError),
}
