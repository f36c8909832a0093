//! Non-convex bodies as unions of convex pieces.
//!
//! A [`ConvexUnion`] is a list of convex pieces sharing one body frame (one
//! pose moves them all). What is supported, and exactly:
//!
//! * **collision**: two unions collide iff some piece pair does;
//! * **distance** when apart: the minimum over piece pairs (the distance
//!   between unions is the minimum of the pairwise distances);
//! * **C-obstacle slices**: the C-obstacle of a union robot among a union
//!   obstacle is the union of the piece-pair C-obstacles, returned as the
//!   collection of piece-pair sums (not merged into one mesh);
//! * the per-pair contacts, for information.
//!
//! **The penetration depth of a non-convex union** is not the minimum over
//! piece pairs (the translation that separates one pair can push another
//! pair into contact): the true depth needs the boundary of a union of
//! sums. [`ConvexUnion::penetration_depth`] returns
//! [`QueryError::UnionDepthUnsupported`] unless both unions have a single
//! piece, rather than a wrong number; with the feature `union-mesh`,
//! `ConvexUnion::penetration_depth_mesh` (module `nonconvex`) measures it
//! on the merged C-obstacle mesh.

use crate::body::ConvexUnion;
use crate::kernel::rotation::Pose;
use crate::kernel::rotation::Rotation;
use crate::mesh::PolygonMesh;
use crate::query::answer::Contact;
use crate::query::answer::Proximity;
use crate::query::answer::Separation;
use crate::query::cobstacle::slices::CObstacle;
use crate::query::error::QueryError;
use crate::query::pair::ConvexPair;

/// The answer of a union query.
#[derive(Clone, Debug, PartialEq)]
pub enum UnionProximity {
    /// Some piece pair overlaps or touches; the overlapping pairs
    /// `(piece of self, piece of other)` with their contacts.
    Colliding(Vec<((usize, usize), Contact)>),
    /// All pairs apart; the nearest pair and its separation (exact: the
    /// distance between the unions).
    Separated((usize, usize), Separation),
}

impl ConvexUnion {
    /// Collision and distance against `other`, checking every piece pair.
    ///
    /// # Errors
    /// The first error of a piece pair, as [`ConvexPair::new`] (internal
    /// only) and [`ConvexPair::query`]: [`QueryError::Sum`] wrapping
    /// [`crate::error::SumError::OutOfRange`] or [`QueryError::OutOfRange`] when a
    /// posed vertex or an answer overflows `f64`.
    pub fn query(
        &self,
        pose: Pose,
        other: &ConvexUnion,
        other_pose: Pose,
    ) -> Result<UnionProximity, QueryError> {
        let mut hits = Vec::new();
        let mut nearest: Option<((usize, usize), Separation)> = None;
        for (i, a) in self.pieces().iter().enumerate() {
            for (j, b) in other.pieces().iter().enumerate() {
                match ConvexPair::new(a, b)?.query(pose, other_pose)? {
                    Proximity::Penetrating(c) => hits.push(((i, j), c)),
                    Proximity::Separated(s) => {
                        if !nearest.as_ref().is_some_and(|n| s.distance >= n.1.distance) {
                            nearest = Some(((i, j), s));
                        }
                    }
                }
            }
        }
        if !hits.is_empty() {
            return Ok(UnionProximity::Colliding(hits));
        }
        let (ij, s) = nearest.ok_or_else(|| QueryError::Inconsistent("no pieces".into()))?;
        Ok(UnionProximity::Separated(ij, s))
    }

    /// `true` when some piece pair overlaps or touches.
    ///
    /// # Errors
    /// The first error of a piece pair, as [`ConvexPair::new`] (internal
    /// only) and [`ConvexPair::query`]: [`QueryError::Sum`] wrapping
    /// [`crate::error::SumError::OutOfRange`] or [`QueryError::OutOfRange`] when a
    /// posed vertex or an answer overflows `f64`.
    pub fn collides(
        &self,
        pose: Pose,
        other: &ConvexUnion,
        other_pose: Pose,
    ) -> Result<bool, QueryError> {
        for a in self.pieces() {
            for b in other.pieces() {
                if ConvexPair::new(a, b)?.intersects(pose, other_pose)? {
                    return Ok(true);
                }
            }
        }
        Ok(false)
    }

    /// The distance between the unions (`0` when they collide).
    ///
    /// # Errors
    /// As [`ConvexUnion::query`]: the first error of a piece pair, as [`ConvexPair::new`] (internal
    /// only) and [`ConvexPair::query`]: [`QueryError::Sum`] wrapping
    /// [`crate::error::SumError::OutOfRange`] or [`QueryError::OutOfRange`] when a
    /// posed vertex or an answer overflows `f64`.
    pub fn distance(
        &self,
        pose: Pose,
        other: &ConvexUnion,
        other_pose: Pose,
    ) -> Result<f64, QueryError> {
        Ok(match self.query(pose, other, other_pose)? {
            UnionProximity::Colliding(_) => 0.0,
            UnionProximity::Separated(_, s) => s.distance,
        })
    }

    /// The penetration depth: only for single-piece (convex) unions;
    /// otherwise [`QueryError::UnionDepthUnsupported`] (see the module docs;
    /// with the feature `union-mesh`, `penetration_depth_mesh` answers
    /// for unions too).
    ///
    /// # Errors
    /// [`QueryError::UnionDepthUnsupported`] when either union has more than
    /// one piece; otherwise those of [`ConvexPair::penetration_depth`] for
    /// the single pair.
    pub fn penetration_depth(
        &self,
        pose: Pose,
        other: &ConvexUnion,
        other_pose: Pose,
    ) -> Result<Option<Contact>, QueryError> {
        if self.pieces().len() != 1 || other.pieces().len() != 1 {
            return Err(QueryError::UnionDepthUnsupported);
        }
        ConvexPair::new(&self.pieces()[0], &other.pieces()[0])?.penetration_depth(pose, other_pose)
    }

    /// C-obstacle slices of this union as a robot among `obstacle`: for each
    /// orientation, the piece-pair sums `O_j ⊕ (−R·A_i)` ordered by `(i, j)`.
    /// Their union is the slice. Each piece pair is sliced by one dynamic
    /// sum, in parallel over orientations.
    ///
    /// # Errors
    /// The first error of a piece pair, as [`CObstacle::slices_par`]: an
    /// unbuildable slice mesh ([`QueryError::Mesh`]) or an internal error.
    pub fn cobstacle_slices(
        &self,
        obstacle: &ConvexUnion,
        orientations: &[Rotation],
    ) -> Result<Vec<Vec<PolygonMesh>>, QueryError> {
        let mut out: Vec<Vec<PolygonMesh>> = orientations.iter().map(|_| Vec::new()).collect();
        for a in self.pieces() {
            for o in obstacle.pieces() {
                let slices = CObstacle::new(a, o)?.slices_par(orientations)?;
                for (k, m) in slices.into_iter().enumerate() {
                    out[k].push(m);
                }
            }
        }
        Ok(out)
    }
}
