//! A body of several convex pieces sharing one frame ([`ConvexUnion`]):
//! the data; its queries (collision, distance, C-obstacle slices) are in
//! `query::union`, and with the feature `union-mesh` its merged sums in
//! `nonconvex`.

use crate::polytope::Polytope;

/// Several convex pieces forming one (possibly non-convex) body.
///
/// An L of two boxes against a unit cube: collision and distance are
/// exact, the penetration depth of a union is refused.
///
/// ```
/// use dymsum::{ConvexUnion, DVec3, Polytope, Pose, QueryError, Rotation};
/// let cuboid = |lo: [f64; 3], hi: [f64; 3]| {
///     let corners: Vec<[f64; 3]> = (0..8)
///         .map(|i| {
///             let pick = |k: usize| if i >> k & 1 == 0 { lo[k] } else { hi[k] };
///             [pick(0), pick(1), pick(2)]
///         })
///         .collect();
///     Polytope::from_points(&corners)
/// };
/// let l_shape = ConvexUnion::new(vec![
///     cuboid([0., 0., 0.], [3., 1., 1.])?,
///     cuboid([0., 1., 0.], [1., 3., 1.])?,
/// ])
/// .ok_or("no pieces")?;
/// let cube = ConvexUnion::new(vec![cuboid([0., 0., 0.], [1., 1., 1.])?]).ok_or("no pieces")?;
/// let at = |x: f64, y: f64| Pose::new(Rotation::IDENTITY, DVec3::new(x, y, 0.0));
/// // In the L's inner corner the cube touches nothing...
/// assert!(!l_shape.collides(Pose::IDENTITY, &cube, at(1.5, 1.5))?);
/// assert_eq!(l_shape.distance(Pose::IDENTITY, &cube, at(1.5, 1.5))?, 0.5);
/// // ...moved onto the long arm it collides.
/// assert!(l_shape.collides(Pose::IDENTITY, &cube, at(2.0, 0.5))?);
/// assert_eq!(
///     l_shape.penetration_depth(Pose::IDENTITY, &cube, at(2.0, 0.5)),
///     Err(QueryError::UnionDepthUnsupported)
/// );
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct ConvexUnion {
    pieces: Vec<Polytope>,
}

impl ConvexUnion {
    /// A union of the given pieces (at least one).
    pub fn new(pieces: Vec<Polytope>) -> Option<ConvexUnion> {
        (!pieces.is_empty()).then_some(ConvexUnion { pieces })
    }
    /// The pieces.
    pub fn pieces(&self) -> &[Polytope] {
        &self.pieces
    }
}

impl From<Polytope> for ConvexUnion {
    fn from(p: Polytope) -> ConvexUnion {
        ConvexUnion::new(vec![p]).expect("one piece")
    }
}
