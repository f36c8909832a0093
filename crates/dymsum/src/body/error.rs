//! [`BodyError`]: why a body could not be placed.

/// Why a body could not be placed at a pose.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BodyError {
    /// A vertex placed at the pose is not finite.
    #[error("a vertex placed at the pose is not finite (translation {translation:?})")]
    NotFinite {
        /// The pose's translation.
        translation: [f64; 3],
    },
    /// A convex piece placed at the pose is no longer a polytope (rounding
    /// flattened it).
    #[error("a convex piece placed at the pose is no polytope: {0}")]
    Flattened(String),
}
