//! The error types that several layers share, on the ground floor so that
//! no layer imports a higher one to name them. Each is re-exported where
//! users find it: [`SumError`] and [`MeshError`] as `dymsum::sum::…` (and
//! `dymsum::SumError`), [`MeshDefect`] as `dymsum::sum::validate::MeshDefect`.

/// Why a sum could not be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SumError {
    /// An internal invariant failed (a bug: please report the input).
    #[error("internal inconsistency: {0}")]
    Inconsistent(String),
    /// The hull of rounded pairwise sums disagrees with the exact overlay
    /// (only [`crate::sum::Method::Hull`]; happens when rotation rounding makes faces of
    /// P non-planar). Use [`crate::sum::Method::Walk`].
    #[error("the hull of pairwise sums is inconsistent with the exact overlay: {0} (rounding the rotated vertices bent P's faces; use the walk or brute method)")]
    HullMismatch(String),
    /// An operand's posed vertex (`R p + t`) overflows `f64`: outside the
    /// supported range (every pose whose posed coordinates are finite is
    /// supported, at any scale).
    #[error("{operand}'s posed vertex {vertex} overflows f64 (|coordinate| > 1.8e308); outside the supported range")]
    OutOfRange {
        /// `"P"` or `"Q"`.
        operand: &'static str,
        /// The vertex.
        vertex: usize,
    },
}

/// Why a mesh is not the boundary of a convex polytope with maximal faces.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MeshDefect {
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} is not finite")]
    NonFinite {
        /// The vertex.
        vertex: usize,
    },
    /// A face has fewer than three vertices, repeats one, or names a
    /// vertex that does not exist.
    #[error("face {face} is not a polygon of at least three distinct vertices")]
    BadFace {
        /// The face.
        face: usize,
    },
    /// A directed edge occurs in two faces (inconsistent orientation or a
    /// non-manifold edge).
    #[error("edge ({0}, {1}) used twice in the same direction")]
    EdgeUsedTwice(usize, usize),
    /// A directed edge has no reverse (a hole).
    #[error("edge ({0}, {1}) has no opposite face (the mesh is open)")]
    OpenEdge(usize, usize),
    /// A vertex belongs to no face.
    #[error("vertex {0} belongs to no face")]
    UnusedVertex(usize),
    /// The faces around a vertex form more than one fan.
    #[error("vertex {0} is pinched (its faces form more than one fan)")]
    PinchedVertex(usize),
    /// `V − E + F ≠ 2`.
    #[error("Euler characteristic {0} != 2")]
    Euler(i64),
    /// A face's corner is off the plane of its first three corners.
    #[error("face {face} is not planar (vertex {vertex} is off its plane)")]
    NonPlanarFace {
        /// The face.
        face: usize,
        /// The vertex off the plane.
        vertex: usize,
    },
    /// A face's corner lies on the line of its neighbours (a collinear or
    /// zero-area corner).
    #[error("face {face} has a straight or degenerate corner at vertex {vertex}")]
    CollinearCorner {
        /// The face.
        face: usize,
        /// The corner.
        vertex: usize,
    },
    /// A face turns both ways or winds more than once (a bow-tie).
    #[error("face {face} is not a convex polygon")]
    NonConvexFace {
        /// The face.
        face: usize,
    },
    /// Two faces meet at an edge that is flat, reflex or inward.
    #[error("edge ({0}, {1}) is not strictly convex and outward")]
    NonConvexEdge(usize, usize),
    /// The faces around a vertex do not form a convex cone that winds once:
    /// a neighbour of the vertex lies on or above the plane of one of its
    /// faces that it does not bound (every edge can still be convex, the
    /// faces folding twice around the vertex).
    #[error("vertex {0} is not a convex corner (its faces fold around it more than once)")]
    NonConvexVertex(usize),
}

/// Why the mesh of a sum could not be produced.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// The sum's vertices cannot be told apart in `f64`: after rounding
    /// they are all coincident, collinear or coplanar. Cause: the sum lies
    /// so far from the origin (or is so thin) that the rounding step of its
    /// coordinates is comparable to its size. Fix: move the operands nearer
    /// to the origin (subtract a common offset, add it back outside dymsum).
    #[error(
        "coordinates lose all precision: rounding step {ulp:.3e} against a size of {size:.3e}; the rounded vertices {collapse} (move the operands nearer to the origin)"
    )]
    PrecisionLost {
        /// The rounding step (ulp) of the largest output coordinate.
        ulp: f64,
        /// The size of the sum (sum of the operands' bounding-box diagonals).
        size: f64,
        /// How the rounded vertices collapsed.
        collapse: String,
    },
    /// A vertex of the sum overflows `f64` (an exact vertex sum `p + q`
    /// beyond `±1.8e308`): the sum is outside the supported range.
    #[error("the sum's coordinates overflow f64 (a vertex sum exceeds 1.8e308 in magnitude); outside the supported range")]
    OutOfRange,
    /// The facets could not be merged into faces (a bug: please report the
    /// input).
    #[error("internal error: merging the facets failed: {0}")]
    Merge(String),
    /// The produced mesh failed the exact validity check (a bug: please
    /// report the input). Never written silently.
    #[error("internal error: the merged mesh is invalid: {0}")]
    Invalid(#[from] MeshDefect),
}

impl MeshError {
    /// `true` for a bug in dymsum (as opposed to an input beyond `f64`).
    pub fn is_internal(&self) -> bool {
        !matches!(
            self,
            MeshError::PrecisionLost { .. } | MeshError::OutOfRange
        )
    }
}
