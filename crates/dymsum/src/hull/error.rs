//! The hull's error: why a hull could not be built.

/// Why a hull could not be built: the input spans less than three dimensions.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum HullError {
    /// Fewer than four points were given. Fix: give at least four points not
    /// all in one plane.
    #[error("too few points: {count} given, a 3-D hull needs at least 4")]
    TooFewPoints {
        /// How many points were given.
        count: usize,
    },
    /// All points are the same point.
    #[error("all {count} points coincide")]
    AllCoincident {
        /// How many points were given.
        count: usize,
    },
    /// All points lie on one line.
    #[error("all {count} points are collinear")]
    AllCollinear {
        /// How many points were given.
        count: usize,
    },
    /// All points lie in one plane (a flat shape has no volume).
    #[error("all {count} points are coplanar (the shape is flat)")]
    AllCoplanar {
        /// How many points were given.
        count: usize,
    },
}
